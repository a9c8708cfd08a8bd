//! Twisting at an interior vertex: E = GJ (m − m̄)² / (2 l̄), with the discrete twist
//! m = θ^i − θ^{i−1} + r, r the reference twist between the two edges' reference frames
//! (the angle from the space-parallel transport of u^{i−1} to u^i), unwrapped by 2π from its last
//! accepted value so that many full turns accumulate correctly. Edges are oriented along the
//! stencil as in [`super::bend`] (an edge against it contributes −θ), so the stencil also spans a
//! valence-2 rigid joint between two rods; GJ is then the series value over the two half-edges.

use super::bend::STENCIL_MAP;
use super::{reduced_term, Category, Reduced, Term};
use crate::math::vec::{signed_angle, transport};
use crate::math::Real;
use crate::network::state::State;
use crate::rod::frames::{oriented_frame_of, unwrap_angle};

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
    /// Reference twist from the reduced variables (edge vectors along the stencil, angles).
    pub fn reference_twist<T: Real>(&self, st: &State, y: &[T; 8]) -> T {
        let zero = T::cst(0.0);
        let f0 = oriented_frame_of(
            &st.edges[self.edges[0]],
            self.signs[0],
            [y[0], y[1], y[2]],
            zero,
        );
        let f1 = oriented_frame_of(
            &st.edges[self.edges[1]],
            self.signs[1],
            [y[3], y[4], y[5]],
            zero,
        );
        let raw = signed_angle(transport(f0.t, f1.t, f0.u), f1.u, f1.t);
        unwrap_angle(raw, st.twist_prev[self.slot])
    }

    /// Discrete twist m (radians) from the reduced variables.
    pub fn twist<T: Real>(&self, st: &State, y: &[T; 8]) -> T {
        self.reference_twist(st, y) + y[7] * self.signs[1] - y[6] * self.signs[0]
    }

    /// Reduced variables of a full local vector.
    pub fn reduced<T: Real>(x: &[T; 11]) -> [T; 8] {
        super::reduce(&STENCIL_MAP, x)
    }
}

impl Reduced<11, 8> for Twist {
    const MAP: [[(usize, f64); 2]; 8] = STENCIL_MAP;
    fn eval_reduced<T: Real>(&self, st: &State, y: &[T; 8]) -> T {
        let d = self.twist(st, y) - self.rest;
        d * d * (0.5 * self.gj / self.voronoi)
    }
}

impl Term<11> for Twist {
    const CATEGORY: Category = Category::Twist;
    fn vars(&self) -> &[usize; 11] {
        &self.vars
    }
    reduced_term!(11, 8);
}
