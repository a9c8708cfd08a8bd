//! Bending at a vertex between two edges (Bergou et al. 2010):
//! E = Σ_{j∈{0,1}} [EI1ʲ (κ1ʲ − κ̄1ʲ)² + EI2ʲ (κ2ʲ − κ̄2ʲ)²] / (4 l̄), with material curvatures
//! κʲ = (κb·m2ʲ, −κb·m1ʲ) in each edge's material frame and l̄ the rest Voronoi length.
//!
//! The two edges are usually consecutive edges of one rod. They may also belong to two rods that
//! end at a valence-2 rigid joint, in either direction: `signs` orients each edge along the
//! stencil (edge 0 arrives at the vertex, edge 1 leaves it; a reversed edge has tangent −t,
//! frame (m1, −m2) and angle −θ), and each edge keeps its own rigidities.

use super::{diff3, same, Category, Reduced, Term};
use crate::math::dual::{compose, separable_dot};
use crate::math::vec::dot;
use crate::math::{Real, HD};
use crate::rod::frames::{bend_quadratic, oriented_reference_frame, FrameDots, RefFrame};
use crate::variables::State;

#[derive(Debug, Clone)]
pub struct Bend {
    /// (x_{i−1}, x_i, x_{i+1}, θ^{i−1}, θ^i).
    pub vars: [usize; 11],
    pub edges: [usize; 2],
    /// +1 where the rod's edge runs along the stencil (see module doc).
    pub signs: [f64; 2],
    pub rest: [[f64; 2]; 2],
    pub voronoi: f64,
    /// (EI1, EI2) of each edge.
    pub ei: [[f64; 2]; 2],
}

/// y = (x₁ − x₀, x₂ − x₁, θ⁰, θ¹).
pub(crate) const STENCIL_MAP: [[(usize, f64); 2]; 8] = {
    let a = diff3(0, 3);
    let b = diff3(3, 6);
    [a[0], a[1], a[2], b[0], b[1], b[2], same(9), same(10)]
};

/// [`super::expand`] for [`STENCIL_MAP`], written out by blocks: with P, Q, R the Hessian's
/// (e⁰, e⁰), (e⁰, e¹), (e¹, e¹) blocks, the positions' blocks are P, Q − P, −Q,
/// P − Q − Qᵀ + R, Q − R, R, and an angle's column (s, t) in (e⁰, e¹) becomes (−s, s − t, t).
/// The assembly's hottest kernel spends less here than in the general map's loops.
#[inline(always)]
pub(crate) fn expand_stencil(r: &HD<8>) -> HD<11> {
    let h = r.hessian();
    let mut out = HD::<11>::cst(r.v);
    for a in 0..3 {
        out.g[a] = -r.g[a];
        out.g[3 + a] = r.g[a] - r.g[3 + a];
        out.g[6 + a] = r.g[3 + a];
        for b in 0..3 {
            let (p, q, qt, rr) = (h[a][b], h[a][3 + b], h[3 + a][b], h[3 + a][3 + b]);
            if a <= b {
                out.h[a][b] = p;
                out.h[3 + a][3 + b] = p - q - qt + rr;
                out.h[6 + a][6 + b] = rr;
            }
            out.h[a][3 + b] = q - p;
            out.h[a][6 + b] = -q;
            out.h[3 + a][6 + b] = q - rr;
        }
        for m in 0..2 {
            let (s, t) = (h[a][6 + m], h[3 + a][6 + m]);
            out.h[a][9 + m] = -s;
            out.h[3 + a][9 + m] = s - t;
            out.h[6 + a][9 + m] = t;
        }
    }
    out.g[9] = r.g[6];
    out.g[10] = r.g[7];
    out.h[9][9] = h[6][6];
    out.h[9][10] = h[6][7];
    out.h[10][10] = h[7][7];
    out
}

impl Bend {
    /// The curvature binormal projected on the θ = 0 directors of both edges,
    /// (κb·u⁰, κb·v⁰, κb·u¹, κb·v¹): the energy depends on the edge vectors only through these.
    fn projections<T: Real>(f0: &RefFrame<T>, f1: &RefFrame<T>) -> [T; 4] {
        FrameDots::new(f0, f1, |a, b| dot(*a, *b)).binormal_projections()
    }

    /// Material curvatures (κ1, κ2) in the frames of edge 0 and edge 1 from the projections and
    /// the two angles: with θ' = sign·θ, κ = (cos θ' κb·v − sin θ' κb·u, −cos θ' κb·u − sin θ' κb·v).
    fn material_curvatures<T: Real>(&self, p: &[T; 4], theta: [T; 2]) -> [[T; 2]; 2] {
        std::array::from_fn(|j| {
            let th = theta[j] * self.signs[j];
            let (s, c) = (th.sin(), th.cos());
            let (a, b) = (p[2 * j], p[2 * j + 1]);
            [c * b - s * a, -(c * a + s * b)]
        })
    }

    /// The projections from the reduced variables (edge vectors along the stencil).
    fn projections_at<T: Real>(&self, st: &State, y: &[T; 8]) -> [T; 4] {
        let f0 =
            oriented_reference_frame(&st.edges[self.edges[0]], self.signs[0], [y[0], y[1], y[2]]);
        let f1 =
            oriented_reference_frame(&st.edges[self.edges[1]], self.signs[1], [y[3], y[4], y[5]]);
        Self::projections(&f0, &f1)
    }

    /// Material curvatures from the reduced variables (edge vectors along the stencil, angles).
    pub fn curvatures<T: Real>(&self, st: &State, y: &[T; 8]) -> [[T; 2]; 2] {
        self.material_curvatures(&self.projections_at(st, y), [y[6], y[7]])
    }

    /// Energy from the projections and the two angles.
    pub(crate) fn energy_of<T: Real>(&self, p: &[T; 4], theta: [T; 2]) -> T {
        let k = self.material_curvatures(p, theta);
        let mut e = T::cst(0.0);
        for j in 0..2 {
            e += bend_quadratic(k[j], self.rest[j], self.ei[j][0], self.ei[j][1]);
        }
        e * (0.25 / self.voronoi)
    }
}

impl Reduced<11, 8> for Bend {
    const MAP: [[(usize, f64); 2]; 8] = STENCIL_MAP;
    fn eval_reduced<T: Real>(&self, st: &State, y: &[T; 8]) -> T {
        self.energy_of(&self.projections_at(st, y), [y[6], y[7]])
    }
}

impl Term<11> for Bend {
    const CATEGORY: Category = Category::Bend;
    fn vars(&self) -> &[usize; 11] {
        &self.vars
    }
    fn edge(&self) -> Option<usize> {
        Some(self.edges[0])
    }
    fn eval<T: Real>(&self, st: &State, x: &[T; 11]) -> T {
        self.eval_reduced(st, &super::reduce(&STENCIL_MAP, x))
    }
    /// Each edge's frame is differentiated in its own 3 variables, their products in the 6 edge
    /// coordinates (block-structured: `separable_dot`), and the energy in (projections, angles);
    /// `compose` chains them exactly.
    fn derivatives(&self, st: &State, x: &[f64; 11]) -> HD<11> {
        let y = super::reduce(&STENCIL_MAP, x);
        let frame = |j: usize| {
            let e = HD::<3>::vars(&[y[3 * j], y[3 * j + 1], y[3 * j + 2]]);
            oriented_reference_frame(&st.edges[self.edges[j]], self.signs[j], e)
        };
        let p = FrameDots::<HD<6>>::new(&frame(0), &frame(1), separable_dot::<3, 3, 6>)
            .binormal_projections();
        let outer_vars = HD::<6>::vars(&[p[0].v, p[1].v, p[2].v, p[3].v, y[6], y[7]]);
        let outer = self.energy_of(
            &[outer_vars[0], outer_vars[1], outer_vars[2], outer_vars[3]],
            [outer_vars[4], outer_vars[5]],
        );
        super::expand(&STENCIL_MAP, &compose::<6, 4, 6, 8>(&p, &outer))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The written-out expansion is the general one for the stencil's map, on derivatives with
    /// every entry set (values of both signs and different sizes).
    #[test]
    fn expand_stencil_is_the_general_expansion() {
        let val = |k: usize| ((k as f64) * 0.731).sin() * 10f64.powi((k % 5) as i32 - 2);
        let mut r = HD::<8>::cst(val(0));
        for i in 0..8 {
            r.g[i] = val(1 + i);
            for j in i..8 {
                r.h[i][j] = val(10 + 8 * i + j);
            }
        }
        let (a, b) = (
            expand_stencil(&r),
            super::super::expand::<11, 8>(&STENCIL_MAP, &r),
        );
        assert_eq!(a.v, b.v);
        let scale = 100.0;
        for i in 0..11 {
            assert!((a.g[i] - b.g[i]).abs() <= 1e-15 * scale, "g{i}");
            for j in i..11 {
                assert!(
                    (a.h[i][j] - b.h[i][j]).abs() <= 1e-15 * scale,
                    "h{i}{j}: {} vs {}",
                    a.h[i][j],
                    b.h[i][j]
                );
            }
        }
    }
}
