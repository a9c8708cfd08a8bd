//! Twisting at an interior vertex: E = GJ (m − m̄)² / (2 l̄), with the discrete twist
//! m = θ^i − θ^{i−1} + r, r the reference twist between the two edges' reference frames
//! (the angle from the space-parallel transport of u^{i−1} to u^i), unwrapped by 2π from its last
//! accepted value so that many full turns accumulate correctly. Edges are oriented along the
//! stencil as in [`super::bend`] (an edge against it contributes −θ), so the stencil also spans a
//! valence-2 rigid joint between two rods; GJ is then the series value over the two half-edges.

use super::bend::STENCIL_MAP;
use super::{Category, Reduced, Term};
use crate::math::dual::{compose, separable_dot};
use crate::math::vec::dot;
use crate::math::{Real, HD};
use crate::rod::frames::{oriented_reference_frame, unwrap_angle, FrameDots};
use crate::variables::State;

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
    /// Reference twist between two θ = 0 frames along the stencil, unwrapped.
    pub(crate) fn reference_twist_of<T: Real>(&self, st: &State, dots: &FrameDots<T>) -> T {
        unwrap_angle(dots.reference_twist(), st.twist_prev[self.slot])
    }

    /// Reference twist from the reduced variables (edge vectors along the stencil, angles).
    pub fn reference_twist<T: Real>(&self, st: &State, y: &[T; 8]) -> T {
        let f0 =
            oriented_reference_frame(&st.edges[self.edges[0]], self.signs[0], [y[0], y[1], y[2]]);
        let f1 =
            oriented_reference_frame(&st.edges[self.edges[1]], self.signs[1], [y[3], y[4], y[5]]);
        self.reference_twist_of(st, &FrameDots::new(&f0, &f1, |a, b| dot(*a, *b)))
    }

    /// Energy from the reference twist and the two angles.
    pub(crate) fn energy_of<T: Real>(&self, reference: T, theta: [T; 2]) -> T {
        let m = reference + theta[1] * self.signs[1] - theta[0] * self.signs[0];
        let d = m - self.rest;
        d * d * (0.5 * self.gj / self.voronoi)
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
        self.energy_of(self.reference_twist(st, y), [y[6], y[7]])
    }
}

impl Term<11> for Twist {
    const CATEGORY: Category = Category::Twist;
    fn vars(&self) -> &[usize; 11] {
        &self.vars
    }
    fn edge(&self) -> Option<usize> {
        Some(self.edges[0])
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
    fn eval<T: Real>(&self, st: &State, x: &[T; 11]) -> T {
        self.eval_reduced(st, &Self::reduced(x))
    }
    /// The reference twist is differentiated in the 6 edge coordinates (each frame in its own
    /// 3), the energy in (reference twist, angles); `compose` chains them exactly.
    fn derivatives(&self, st: &State, x: &[f64; 11]) -> HD<11> {
        let y = Self::reduced(x);
        let frame = |j: usize| {
            let e = HD::<3>::vars(&[y[3 * j], y[3 * j + 1], y[3 * j + 2]]);
            oriented_reference_frame(&st.edges[self.edges[j]], self.signs[j], e)
        };
        let dots = FrameDots::<HD<6>>::new(&frame(0), &frame(1), separable_dot::<3, 3, 6>);
        let r = self.reference_twist_of(st, &dots);
        let [rv, t0, t1] = HD::<3>::vars(&[r.v, y[6], y[7]]);
        let outer = self.energy_of(rv, [t0, t1]);
        super::expand(&STENCIL_MAP, &compose::<6, 1, 3, 8>(&[r], &outer))
    }
}
