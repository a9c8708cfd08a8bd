//! Ports: where a rod meets a vertex frame (a clamp, a rigid or hinge joint, an elastic joint's
//! rod side, or a vertex carrying a torque).
//!
//! A vertex frame has a reference rotation Q (in [`State::frames`]) and three increment variables
//! ω; a port adds its rest orientation C relative to the frame and, for hinges, a scissor angle α
//! about the frame's hinge axis n̄:  F = exp(ω̂) · Q · R(n̄, α) · C.
//! Every rod edge at the vertex is attached to F by half-stencils of bending and twisting
//! ([`crate::energy::frame_bend`], [`crate::energy::frame_twist`]) over half the edge's rest length, so
//! the frame acts exactly at the vertex and no bending stencil ever spans a joint.

use crate::math::vec::*;
use crate::math::Real;
use crate::network::state::State;

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Port {
    pub frame: usize,
    /// Rest orientation of the port relative to the frame, as columns (d1, d2, d3 = tangent).
    pub rest: Frame,
    /// Hinge axis in the frame's body coordinates (unused when α is the fixed zero variable).
    pub hinge_axis: [f64; 3],
}

impl Port {
    /// Current port frame (d1, d2, d3) from the frame's increment ω and the hinge angle α.
    pub fn frame<T: Real>(&self, st: &State, w: V3<T>, alpha: T) -> [V3<T>; 3] {
        let q = &st.frames[self.frame].rotation;
        let n = lift(self.hinge_axis);
        std::array::from_fn(|k| {
            let body = rotate_axis(n, alpha, lift(self.rest[k]));
            // Q · body, with Q stored as columns.
            let world = add(
                add(scale(lift(q[0]), body[0]), scale(lift(q[1]), body[1])),
                scale(lift(q[2]), body[2]),
            );
            rotate(w, world)
        })
    }
}

/// The pieces of a half-stencil, oriented away from the vertex: the port frame's
/// (d1, d2, t) and the edge's (t, u, m1, m2), both with their tangent pointing from the vertex
/// into the edge. `sign` is +1 when the rod's edge leaves the vertex and −1 when it arrives.
pub struct HalfStencil<T> {
    pub d1: V3<T>,
    pub d2: V3<T>,
    pub tf: V3<T>,
    pub te: V3<T>,
    pub u: V3<T>,
    pub m1: V3<T>,
    pub m2: V3<T>,
    pub theta: T,
}

/// Map from a half-stencil's local variables (x_vertex, x_other, θ, ω, α) to its reduced ones
/// (x_other − x_vertex, θ, ω, α).
pub(crate) const HALF_STENCIL_MAP: [[(usize, f64); 2]; 8] = {
    use crate::energy::{diff3, same};
    let e = diff3(0, 3);
    [
        e[0],
        e[1],
        e[2],
        same(6),
        same(7),
        same(8),
        same(9),
        same(10),
    ]
};

/// Half-stencil pieces from the reduced variables y = (x_other − x_vertex, θ, ω, α).
pub fn half_stencil<T: Real>(
    st: &State,
    port: &Port,
    edge: usize,
    sign: f64,
    y: &[T; 8],
) -> HalfStencil<T> {
    let f = port.frame(st, [y[4], y[5], y[6]], y[7]);
    let ef = crate::rod::frames::oriented_frame_of(&st.edges[edge], sign, [y[0], y[1], y[2]], y[3]);
    HalfStencil {
        d1: f[0],
        d2: scalef(f[1], sign),
        tf: scalef(f[2], sign),
        te: ef.t,
        u: ef.u,
        m1: ef.m1,
        m2: ef.m2,
        theta: y[3] * sign,
    }
}
