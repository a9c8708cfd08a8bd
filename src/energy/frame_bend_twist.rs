//! Bending and twisting of one half-stencil (a vertex frame and one incident edge) in one pass:
//! the sum of [`FrameBend`] and [`FrameTwist`], which build the same two frames.
//!
//! Both energies depend on the port frame (d1, d2, t_f), a function of (ω, α) only, and on the
//! edge's θ = 0 frame (t_e, u, v), a function of the edge vector only, through the scalar
//! products of the two frames ([`FrameDots`], with the port frame as "edge 0" at θ = 0:
//! u⁰ = d1, v⁰ = t_f × d1 = d2). So each frame is differentiated in its own variables (4 and
//! 3), the products and the five intermediates (κb's projections, the reference twist) in those
//! 7, and the energy in (intermediates, θ); [`compose`] chains them exactly. The energies are
//! still reported apart, bending under [`Category::Bend`] and twisting under
//! [`Category::Twist`].

use super::bend_twist_outer::{add_fixed_bend, add_linear_square, add_rotated_bend};
use super::frame_bend::FrameBend;
use super::frame_twist::FrameTwist;
use super::{diff3, same, Category, Term};
use crate::math::dual::{compose, separable_dot};
use crate::math::vec::{dot, scalef};
use crate::math::{Real, HD};
use crate::rod::frames::{
    bend_quadratic, oriented_reference_frame, unwrap_angle, FrameDots, RefFrame,
};
use crate::variables::State;

/// The bending and twisting terms of one half-stencil (same variables, port, edge and sign).
#[derive(Debug, Clone)]
pub struct FrameBendTwist {
    pub bend: FrameBend,
    pub twist: FrameTwist,
}

/// Map from the local variables (x_vertex, x_other, θ, ω, α) to the order the frames are
/// differentiated in: (ω, α, x_other − x_vertex, θ).
const MAP: [[(usize, f64); 2]; 8] = {
    let e = diff3(0, 3);
    [
        same(7),
        same(8),
        same(9),
        same(10),
        e[0],
        e[1],
        e[2],
        same(6),
    ]
};

/// Scalars of the half-stencil both energies are functions of: κb projected on the port frame
/// and on the edge's θ = 0 frame, (κb·d1, κb·d2, κb·u, κb·v), and the reference twist.
type Intermediates<T> = ([T; 4], T);

impl FrameBendTwist {
    pub fn new(bend: FrameBend, twist: FrameTwist) -> Self {
        debug_assert!(bend.vars == twist.vars && bend.edge == twist.edge);
        FrameBendTwist { bend, twist }
    }

    /// The intermediates from the port frame's variables `w_alpha` = (ω, α) and the edge vector
    /// along the stencil; `dot` multiplies a port-frame vector by an edge-frame vector.
    fn intermediates<P: Real, E: Real, T: Real>(
        &self,
        st: &State,
        w_alpha: [P; 4],
        along: [E; 3],
        dot: impl Fn(&[P; 3], &[E; 3]) -> T,
    ) -> Intermediates<T> {
        let b = &self.bend;
        let sign = b.sign;
        let [d1, d2, t] = b
            .port
            .frame(st, [w_alpha[0], w_alpha[1], w_alpha[2]], w_alpha[3]);
        let port = RefFrame {
            t: scalef(t, sign),
            u: d1,
            v: scalef(d2, sign),
        };
        let edge = oriented_reference_frame(&st.edges[b.edge], sign, along);
        let dots = FrameDots::new(&port, &edge, dot);
        let twist = unwrap_angle(dots.reference_twist(), st.twist_prev[self.twist.slot]);
        (dots.binormal_projections(), twist)
    }

    /// (bending, twisting) energy from the intermediates and the edge's angle θ. With
    /// θ' = sign·θ, the frame's curvature is (κb·d2, −κb·d1) and the edge's
    /// (cos θ' κb·v − sin θ' κb·u, −cos θ' κb·u − sin θ' κb·v), as in [`FrameBend`]; the twist is
    /// the reference twist plus θ', as in [`FrameTwist`].
    fn energies_of<T: Real>(&self, (p, reference): Intermediates<T>, theta: T) -> [T; 2] {
        let (b, tw) = (&self.bend, &self.twist);
        let th = theta * b.sign;
        let (s, c) = (th.sin(), th.cos());
        let frame = [p[1], -p[0]];
        let edge = [c * p[3] - s * p[2], -(c * p[2] + s * p[3])];
        let [ei1, ei2] = b.ei;
        let bend = (bend_quadratic(frame, b.rest[0], ei1, ei2)
            + bend_quadratic(edge, b.rest[1], ei1, ei2))
            * (0.25 / b.voronoi);
        let d = reference + th - tw.rest;
        [bend, d * d * (0.5 * tw.gj / tw.voronoi)]
    }

    /// (bending, twisting) energy at the local variables `x`.
    pub fn energies<T: Real>(&self, st: &State, x: &[T; 11]) -> [T; 2] {
        let y = super::reduce(&MAP, x);
        let i = self.intermediates(st, [y[0], y[1], y[2], y[3]], [y[4], y[5], y[6]], |a, b| {
            dot(*a, *b)
        });
        self.energies_of(i, y[7])
    }
}

impl Term<11> for FrameBendTwist {
    super::bend_twist_items!();
    fn edge(&self) -> Option<usize> {
        Some(self.bend.edge)
    }
    /// The port frame is differentiated in (ω, α), the edge frame in the edge vector, their
    /// products in both (block-structured: `separable_dot`), the energy in (intermediates, θ).
    fn derivatives(&self, st: &State, x: &[f64; 11]) -> HD<11> {
        let y = super::reduce(&MAP, x);
        let w_alpha = HD::<4>::vars(&[y[0], y[1], y[2], y[3]]);
        let along = HD::<3>::vars(&[y[4], y[5], y[6]]);
        let (p, r) = self.intermediates(st, w_alpha, along, separable_dot::<4, 3, 7>);
        let inner = [p[0], p[1], p[2], p[3], r];
        // The energy in (projections, reference twist, θ), derivatives by hand.
        let o = [p[0].v, p[1].v, p[2].v, p[3].v, r.v, y[7]];
        let (b, t) = (&self.bend, &self.twist);
        let w = 0.25 / b.voronoi;
        let mut energy = HD::<6>::cst(0.0);
        add_fixed_bend(&mut energy, [0, 1], [o[0], o[1]], b.rest[0], b.ei, w);
        let edge = [o[2], o[3], o[5]];
        add_rotated_bend(&mut energy, [2, 3, 5], edge, b.sign, b.rest[1], b.ei, w);
        let w = 0.5 * t.gj / t.voronoi;
        add_linear_square(&mut energy, [4, 5], [o[4], o[5]], [1.0, b.sign], t.rest, w);
        super::expand(&MAP, &compose::<7, 5, 6, 8>(&inner, &energy))
    }
}
