//! Ports: where a rod meets a vertex frame (a clamp, a rigid or hinge joint, an elastic joint's
//! rod side, or a vertex carrying a torque).
//!
//! A vertex frame has a reference rotation Q (in [`State::frames`]) and three increment variables
//! ω; a port adds its rest orientation C relative to the frame and, for hinges, a scissor angle α
//! about the frame's hinge axis n̄:  F = exp(ω̂) · Q · R(n̄, α) · C.
//! Every rod edge at the vertex is attached to F by half-stencils of bending and twisting
//! (`energy::frame_bend`, `energy::frame_twist`) over half the edge's rest length, so
//! the frame acts exactly at the vertex and no bending stencil ever spans a joint.

use super::state::State;
use crate::math::vec::*;
use crate::math::Real;

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
        // Q · R(n̄, α) · c = Q c + sin α · Q (n̄ × c) + (1 − cos α) · Q (n̄ × (n̄ × c)): only the
        // two coefficients vary, so the constant vectors stay plain numbers.
        let (s, v) = (alpha.sin(), -alpha.cos() + 1.0);
        let world = self.rest.map(|c| {
            let nc = cross(self.hinge_axis, c);
            let nnc = cross(self.hinge_axis, nc);
            let [a, b, d] = [c, nc, nnc].map(|x| mat_vec(q, x));
            std::array::from_fn(|i| s * b[i] + v * d[i] + a[i])
        });
        rotate_each(w, world)
    }
}

/// Q x with Q stored as columns.
fn mat_vec(q: &Frame, x: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| q[0][i] * x[0] + q[1][i] * x[1] + q[2][i] * x[2])
}
