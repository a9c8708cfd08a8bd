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
