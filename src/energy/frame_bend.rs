//! Bending between a vertex frame (clamp or joint) and one incident edge: a half-stencil over
//! l̄ = |ē|/2 with the frame's tangent as the "previous edge":
//! E = [EI1 (κ1ᶠ − κ̄1ᶠ)² + EI2 (κ2ᶠ − κ̄2ᶠ)² + EI1 (κ1ᵉ − κ̄1ᵉ)² + EI2 (κ2ᵉ − κ̄2ᵉ)²] / (4 l̄),
//! with κb between the frame tangent and the edge tangent (both pointing into the edge), and the
//! material curvatures taken in the frame's and the edge's material frames. The integrated
//! curvature over [0, |e|/2] is the angle between the vertex tangent and the chord, so the clamp
//! or joint acts exactly at the vertex and the discretization stays second order.

use super::half_stencil::{half_stencil, HALF_STENCIL_MAP};
use super::{reduced_term, Category, Reduced, Term};
use crate::math::Real;
use crate::rod::frames::{bend_quadratic, curvature_binormal, material_curvature};
use crate::variables::Port;
use crate::variables::State;

#[derive(Debug, Clone)]
pub struct FrameBend {
    /// (x_vertex, x_other, θ, ω, α).
    pub vars: [usize; 11],
    pub port: Port,
    pub edge: usize,
    pub sign: f64,
    pub rest: [[f64; 2]; 2],
    pub voronoi: f64,
    pub ei: [f64; 2],
}

impl FrameBend {
    /// Material curvatures in the frame's and the edge's frames, from the reduced variables
    /// (x_other − x_vertex, θ, ω, α).
    pub fn curvatures<T: Real>(&self, st: &State, y: &[T; 8]) -> [[T; 2]; 2] {
        let h = half_stencil(st, &self.port, self.edge, self.sign, y);
        let kb = curvature_binormal(h.tf, h.te);
        [
            material_curvature(kb, h.d1, h.d2),
            material_curvature(kb, h.m1, h.m2),
        ]
    }
}

impl Reduced<11, 8> for FrameBend {
    const MAP: [[(usize, f64); 2]; 8] = HALF_STENCIL_MAP;
    fn eval_reduced<T: Real>(&self, st: &State, y: &[T; 8]) -> T {
        let [kf, ke] = self.curvatures(st, y);
        let [a, b] = self.ei;
        (bend_quadratic(kf, self.rest[0], a, b) + bend_quadratic(ke, self.rest[1], a, b))
            * (0.25 / self.voronoi)
    }
}

impl Term<11> for FrameBend {
    const CATEGORY: Category = Category::Bend;
    fn vars(&self) -> &[usize; 11] {
        &self.vars
    }
    fn edge(&self) -> Option<usize> {
        Some(self.edge)
    }
    reduced_term!(11, 8);
}
