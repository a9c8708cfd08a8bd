//! Bending and twisting at a rod's interior vertex in one pass: the sum of [`Bend`] and
//! [`Twist`] of the same stencil, which build the same two edges' reference frames and the same
//! products of them ([`FrameDots`]).
//!
//! The frames are differentiated in their own edge vectors, the products and the five
//! intermediates (κb's projections, the reference twist) in the 6 edge coordinates, and the
//! energy in (intermediates, θ⁰, θ¹); [`compose`] chains them exactly, and one [`super::expand`]
//! returns to the 11 stencil variables. The energies are still reported apart, bending under
//! [`Category::Bend`] and twisting under [`Category::Twist`].

use super::bend::{expand_stencil, Bend, STENCIL_MAP};
use super::bend_twist_outer::{add_linear_square, add_rotated_bend};
use super::twist::Twist;
use super::{Category, Term};
use crate::math::dual::{compose, separable_dot};
use crate::math::vec::dot;
use crate::math::{Real, HD};
use crate::rod::committed_frames::CommittedPair;
use crate::rod::frames::{oriented_reference_frame, unwrap_angle, FrameDots, RefFrame};
use crate::variables::State;

/// The bending and twisting terms of one stencil (same variables, edges and signs).
#[derive(Debug, Clone)]
pub struct BendTwist {
    pub bend: Bend,
    pub twist: Twist,
}

impl BendTwist {
    pub fn new(bend: Bend, twist: Twist) -> Self {
        debug_assert!(bend.vars == twist.vars && bend.edges == twist.edges);
        BendTwist { bend, twist }
    }

    /// Edge `j`'s θ = 0 frame from its vector along the stencil.
    fn frame<T: Real>(&self, st: &State, j: usize, along: [T; 3]) -> RefFrame<T> {
        let b = &self.bend;
        oriented_reference_frame(&st.edges[b.edges[j]], b.signs[j], along)
    }

    /// The energy's derivatives in (six edge coordinates, θ⁰, θ¹) from the frames' products
    /// differentiated in those coordinates: the energy as a function of (κb's projections,
    /// reference twist, θ⁰, θ¹) is differentiated by hand and chained with them.
    #[inline(always)]
    fn composed(&self, p: [HD<6>; 4], r: HD<6>, theta: [f64; 2]) -> HD<8> {
        let o = [p[0].v, p[1].v, p[2].v, p[3].v, r.v, theta[0], theta[1]];
        let (b, t) = (&self.bend, &self.twist);
        let mut energy = HD::<7>::cst(0.0);
        for j in 0..2 {
            let idx = [2 * j, 2 * j + 1, 5 + j];
            let at = idx.map(|i| o[i]);
            add_rotated_bend(
                &mut energy,
                idx,
                at,
                b.signs[j],
                b.rest[j],
                b.ei[j],
                0.25 / b.voronoi,
            );
        }
        let coef = [1.0, -t.signs[0], t.signs[1]];
        let w = 0.5 * t.gj / t.voronoi;
        add_linear_square(&mut energy, [4, 5, 6], [o[4], o[5], o[6]], coef, t.rest, w);
        let inner = [p[0], p[1], p[2], p[3], r];
        compose::<6, 5, 7, 8>(&inner, &energy)
    }

    /// (bending, twisting) energy at the local variables `x`.
    pub fn energies<T: Real>(&self, st: &State, x: &[T; 11]) -> [T; 2] {
        let y = super::reduce(&STENCIL_MAP, x);
        let f0 = self.frame(st, 0, [y[0], y[1], y[2]]);
        let f1 = self.frame(st, 1, [y[3], y[4], y[5]]);
        let dots = FrameDots::new(&f0, &f1, |a, b| dot(*a, *b));
        let theta = [y[6], y[7]];
        [
            self.bend.energy_of(&dots.binormal_projections(), theta),
            self.twist
                .energy_of(self.twist.reference_twist_of(st, &dots), theta),
        ]
    }
}

impl Term<11> for BendTwist {
    super::bend_twist_items!();
    fn edge(&self) -> Option<usize> {
        Some(self.bend.edges[0])
    }
    /// At a committed state (where Newton assembles) the frames' products, the reference twist
    /// and their derivatives come in closed form ([`CommittedPair`]); elsewhere the frames are
    /// differentiated by hyper-dual arithmetic.
    fn derivatives(&self, st: &State, x: &[f64; 11]) -> HD<11> {
        let y = super::reduce(&STENCIL_MAP, x);
        let b = &self.bend;
        let refs = [&st.edges[b.edges[0]], &st.edges[b.edges[1]]];
        let along = [[y[0], y[1], y[2]], [y[3], y[4], y[5]]];
        let theta = [y[6], y[7]];
        let outer = match CommittedPair::new(refs, b.signs, along) {
            Some(pair) => {
                let p = pair.dots().binormal_projections();
                let r = unwrap_angle(pair.reference_twist(), st.twist_prev[self.twist.slot]);
                pair.to_edges(&self.composed(p, r, theta))
            }
            None => {
                let frame = |j: usize| self.frame(st, j, HD::<3>::vars(&along[j]));
                let dots = FrameDots::<HD<6>>::new(&frame(0), &frame(1), separable_dot::<3, 3, 6>);
                let r = self.twist.reference_twist_of(st, &dots);
                self.composed(dots.binormal_projections(), r, theta)
            }
        };
        expand_stencil(&outer)
    }
}
