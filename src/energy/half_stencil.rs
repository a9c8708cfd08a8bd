//! Half-stencils: the bending and twisting coupling between a port's frame and one rod edge at
//! the port's vertex, shared by `frame_bend` and `frame_twist`.

use crate::math::vec::*;
use crate::math::Real;
use crate::variables::{Port, State};

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
    use super::{diff3, same};
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
