//! Bending at an interior vertex between two edges of one rod (Bergou et al. 2010):
//! E = Σ_{j∈{0,1}} [EI1 (κ1ʲ − κ̄1ʲ)² + EI2 (κ2ʲ − κ̄2ʲ)²] / (4 l̄), with material curvatures
//! κʲ = (κb·m2ʲ, −κb·m1ʲ) in each edge's material frame and l̄ the rest Voronoi length.

use super::{v3, Category, Term};
use crate::math::Real;
use crate::network::state::State;
use crate::rod::frames::{bend_quadratic, curvature_binormal, edge_frame, material_curvature};

#[derive(Debug, Clone)]
pub struct Bend {
    /// (x_{i−1}, x_i, x_{i+1}, θ^{i−1}, θ^i).
    pub vars: [usize; 11],
    pub edges: [usize; 2],
    pub rest: [[f64; 2]; 2],
    pub voronoi: f64,
    pub ei: [f64; 2],
}

impl Bend {
    /// Material curvatures (κ1, κ2) in the frames of edge i−1 and edge i.
    pub fn curvatures<T: Real>(&self, st: &State, x: &[T; 11]) -> [[T; 2]; 2] {
        let (x0, x1, x2) = (v3(x, 0), v3(x, 3), v3(x, 6));
        let f0 = edge_frame(x0, x1, x[9], &st.edges[self.edges[0]]);
        let f1 = edge_frame(x1, x2, x[10], &st.edges[self.edges[1]]);
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
        let [a, b] = self.ei;
        (bend_quadratic(k0, self.rest[0], a, b) + bend_quadratic(k1, self.rest[1], a, b))
            * (0.25 / self.voronoi)
    }
}
