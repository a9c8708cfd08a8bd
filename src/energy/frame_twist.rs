//! Twisting between a vertex frame and one incident edge over half the edge:
//! E = GJ (m − m̄)² / (2 l̄), l̄ = |ē|/2, with m the angle from the frame's d1 (parallel
//! transported from the frame tangent to the edge tangent) to the edge's m1, about the edge tangent.
//! The reference part (to the edge's reference director u) is unwrapped by 2π from its last
//! accepted value; the edge's own angle enters linearly.

use super::half_stencil::{half_stencil, HALF_STENCIL_MAP};
use super::{reduced_term, Category, Reduced, Term};
use crate::math::vec::{signed_angle, transport};
use crate::math::Real;
use crate::rod::frames::unwrap_angle;
use crate::variables::Port;
use crate::variables::State;

#[derive(Debug, Clone)]
pub struct FrameTwist {
    /// (x_vertex, x_other, θ, ω, α).
    pub vars: [usize; 11],
    pub port: Port,
    pub edge: usize,
    pub sign: f64,
    pub slot: usize,
    pub rest: f64,
    pub voronoi: f64,
    pub gj: f64,
}

impl FrameTwist {
    /// From the reduced variables (x_other − x_vertex, θ, ω, α).
    pub fn reference_twist<T: Real>(&self, st: &State, y: &[T; 8]) -> T {
        let h = half_stencil(st, &self.port, self.edge, self.sign, y);
        let raw = signed_angle(transport(h.tf, h.te, h.d1), h.u, h.te);
        unwrap_angle(raw, st.twist_prev[self.slot])
    }

    pub fn twist<T: Real>(&self, st: &State, y: &[T; 8]) -> T {
        self.reference_twist(st, y) + y[3] * self.sign
    }

    /// Reduced variables of a full local vector.
    pub fn reduced<T: Real>(x: &[T; 11]) -> [T; 8] {
        super::reduce(&HALF_STENCIL_MAP, x)
    }
}

impl Reduced<11, 8> for FrameTwist {
    const MAP: [[(usize, f64); 2]; 8] = HALF_STENCIL_MAP;
    fn eval_reduced<T: Real>(&self, st: &State, y: &[T; 8]) -> T {
        let d = self.twist(st, y) - self.rest;
        d * d * (0.5 * self.gj / self.voronoi)
    }
}

impl Term<11> for FrameTwist {
    const CATEGORY: Category = Category::Twist;
    fn vars(&self) -> &[usize; 11] {
        &self.vars
    }
    fn edge(&self) -> Option<usize> {
        Some(self.edge)
    }
    fn remembered(&self, st: &State) -> Option<(usize, f64)> {
        let y = Self::reduced(&self.gather(&st.q));
        Some((self.slot, self.reference_twist::<f64>(st, &y)))
    }
    fn nearest_turn(&self, st: &State) -> Option<(usize, f64)> {
        let y = Self::reduced(&self.gather(&st.q));
        let (r, m) = (
            self.reference_twist::<f64>(st, &y),
            self.twist::<f64>(st, &y),
        );
        Some((self.slot, super::nearest_turn(r, m, self.rest)))
    }
    reduced_term!(11, 8);
}
