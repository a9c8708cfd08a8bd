//! Twisting at an interior vertex: E = GJ (m − m̄)² / (2 l̄), with the discrete twist
//! m = θ^i − θ^{i−1} + r, r the reference twist between the two edges' reference frames
//! (the angle from the space-parallel transport of u^{i−1} to u^i), unwrapped by 2π from its last
//! accepted value so that many full turns accumulate correctly. Edges are oriented along the
//! stencil as in [`super::bend`] (an edge against it contributes −θ), so the stencil also spans a
//! valence-2 rigid joint between two rods; GJ is then the series value over the two half-edges.

use super::bend::oriented_frame;
use super::{v3, Category, Term};
use crate::math::vec::{signed_angle, transport};
use crate::math::Real;
use crate::network::state::State;
use crate::rod::frames::unwrap_angle;

#[derive(Debug, Clone)]
pub struct Twist {
    /// (x_{i−1}, x_i, x_{i+1}, θ^{i−1}, θ^i).
    pub vars: [usize; 11],
    pub edges: [usize; 2],
    pub signs: [f64; 2],
    /// Index into [`State::twist_prev`].
    pub slot: usize,
    pub rest: f64,
    pub voronoi: f64,
    pub gj: f64,
}

impl Twist {
    pub fn reference_twist<T: Real>(&self, st: &State, x: &[T; 11]) -> T {
        let (x0, x1, x2) = (v3(x, 0), v3(x, 3), v3(x, 6));
        let zero = T::cst(0.0);
        let f0 = oriented_frame(st, self.edges[0], self.signs[0], x0, x1, zero);
        let f1 = oriented_frame(st, self.edges[1], self.signs[1], x1, x2, zero);
        let raw = signed_angle(transport(f0.t, f1.t, f0.u), f1.u, f1.t);
        unwrap_angle(raw, st.twist_prev[self.slot])
    }

    /// Discrete twist m (radians).
    pub fn twist<T: Real>(&self, st: &State, x: &[T; 11]) -> T {
        self.reference_twist(st, x) + x[10] * self.signs[1] - x[9] * self.signs[0]
    }
}

impl Term<11> for Twist {
    const CATEGORY: Category = Category::Twist;
    fn vars(&self) -> &[usize; 11] {
        &self.vars
    }
    fn eval<T: Real>(&self, st: &State, x: &[T; 11]) -> T {
        let d = self.twist(st, x) - self.rest;
        d * d * (0.5 * self.gj / self.voronoi)
    }
}
