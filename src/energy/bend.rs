//! Bending at a vertex between two edges (Bergou et al. 2010):
//! E = Σ_{j∈{0,1}} [EI1ʲ (κ1ʲ − κ̄1ʲ)² + EI2ʲ (κ2ʲ − κ̄2ʲ)²] / (4 l̄), with material curvatures
//! κʲ = (κb·m2ʲ, −κb·m1ʲ) in each edge's material frame and l̄ the rest Voronoi length.
//!
//! The two edges are usually consecutive edges of one rod. They may also belong to two rods that
//! end at a valence-2 rigid joint, in either direction: `signs` orients each edge along the
//! stencil (edge 0 arrives at the vertex, edge 1 leaves it; a reversed edge has tangent −t,
//! frame (m1, −m2) and angle −θ), and each edge keeps its own rigidities.

use super::{diff3, reduced_term, same, Category, Reduced, Term};
use crate::math::vec::V3;
use crate::math::Real;
use crate::network::state::State;
use crate::rod::frames::{
    bend_quadratic, curvature_binormal, material_curvature, oriented_frame_of,
};

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
    /// Material curvatures (κ1, κ2) in the frames of edge 0 and edge 1, from the reduced
    /// variables (edge vectors along the stencil, angles).
    pub fn curvatures<T: Real>(&self, st: &State, y: &[T; 8]) -> [[T; 2]; 2] {
        let e0: V3<T> = [y[0], y[1], y[2]];
        let e1: V3<T> = [y[3], y[4], y[5]];
        let f0 = oriented_frame_of(&st.edges[self.edges[0]], self.signs[0], e0, y[6]);
        let f1 = oriented_frame_of(&st.edges[self.edges[1]], self.signs[1], e1, y[7]);
        let kb = curvature_binormal(f0.t, f1.t);
        [
            material_curvature(kb, f0.m1, f0.m2),
            material_curvature(kb, f1.m1, f1.m2),
        ]
    }
}

/// y = (x₁ − x₀, x₂ − x₁, θ⁰, θ¹).
pub(crate) const STENCIL_MAP: [[(usize, f64); 2]; 8] = {
    let a = diff3(0, 3);
    let b = diff3(3, 6);
    [a[0], a[1], a[2], b[0], b[1], b[2], same(9), same(10)]
};

impl Reduced<11, 8> for Bend {
    const MAP: [[(usize, f64); 2]; 8] = STENCIL_MAP;
    fn eval_reduced<T: Real>(&self, st: &State, y: &[T; 8]) -> T {
        let [k0, k1] = self.curvatures(st, y);
        let [[a0, b0], [a1, b1]] = self.ei;
        (bend_quadratic(k0, self.rest[0], a0, b0) + bend_quadratic(k1, self.rest[1], a1, b1))
            * (0.25 / self.voronoi)
    }
}

impl Term<11> for Bend {
    const CATEGORY: Category = Category::Bend;
    fn vars(&self) -> &[usize; 11] {
        &self.vars
    }
    reduced_term!(11, 8);
}
