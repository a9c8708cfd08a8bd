//! Bending at a vertex between two edges (Bergou et al. 2010):
//! E = Σ_{j∈{0,1}} [EI1ʲ (κ1ʲ − κ̄1ʲ)² + EI2ʲ (κ2ʲ − κ̄2ʲ)²] / (4 l̄), with material curvatures
//! κʲ = (κb·m2ʲ, −κb·m1ʲ) in each edge's material frame and l̄ the rest Voronoi length.
//!
//! The two edges are usually consecutive edges of one rod. They may also belong to two rods that
//! end at a valence-2 rigid joint, in either direction: `signs` orients each edge along the
//! stencil (edge 0 arrives at the vertex, edge 1 leaves it; a reversed edge has tangent −t,
//! frame (m1, −m2) and angle −θ), and each edge keeps its own rigidities.

use super::{v3, Category, Term};
use crate::math::vec::V3;
use crate::math::Real;
use crate::network::state::State;
use crate::rod::frames::{
    bend_quadratic, curvature_binormal, edge_frame, material_curvature, EdgeFrame,
};

/// Frame of edge `e` between `xa` (towards the stencil's start) and `xb`, oriented along the
/// stencil: with sign −1 the rod's edge runs from `xb` to `xa`.
pub fn oriented_frame<T: Real>(
    st: &State,
    e: usize,
    sign: f64,
    xa: V3<T>,
    xb: V3<T>,
    theta: T,
) -> EdgeFrame<T> {
    use crate::math::vec::scalef;
    if sign > 0.0 {
        edge_frame(xa, xb, theta, &st.edges[e])
    } else {
        let f = edge_frame(xb, xa, theta, &st.edges[e]);
        EdgeFrame {
            t: scalef(f.t, -1.0),
            u: f.u,
            m1: f.m1,
            m2: scalef(f.m2, -1.0),
        }
    }
}

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

impl Bend {
    /// Material curvatures (κ1, κ2) in the frames of edge i−1 and edge i.
    pub fn curvatures<T: Real>(&self, st: &State, x: &[T; 11]) -> [[T; 2]; 2] {
        let (x0, x1, x2) = (v3(x, 0), v3(x, 3), v3(x, 6));
        let f0 = oriented_frame(st, self.edges[0], self.signs[0], x0, x1, x[9]);
        let f1 = oriented_frame(st, self.edges[1], self.signs[1], x1, x2, x[10]);
        let kb = curvature_binormal(f0.t, f1.t);
        [
            material_curvature(kb, f0.m1, f0.m2),
            material_curvature(kb, f1.m1, f1.m2),
        ]
    }
}

impl Term<11> for Bend {
    const CATEGORY: Category = Category::Bend;
    fn vars(&self) -> &[usize; 11] {
        &self.vars
    }
    fn eval<T: Real>(&self, st: &State, x: &[T; 11]) -> T {
        let [k0, k1] = self.curvatures(st, x);
        let [[a0, b0], [a1, b1]] = self.ei;
        (bend_quadratic(k0, self.rest[0], a0, b0) + bend_quadratic(k1, self.rest[1], a1, b1))
            * (0.25 / self.voronoi)
    }
}
