//! Rotational spring of an elastic joint between one rod's port frame F and the joint frame J
//! (carrying the port's rest orientation C): with R = (J·C)ᵀ F, the relative rotation measure
//! φ = vee(R − Rᵀ)/2 = sin(angle)·axis (in the port's rest axes) and
//! E = ½ Σᵢ kᵢ (φ·aᵢ)² over the bending (t × n), twist (t) and scissor (n) axes aᵢ.
//! φ is smooth, exact to second order in the angle, and bounded; joint rotations in rod networks
//! stay small compared with a radian.

use super::{Category, Term};
use crate::math::vec::*;
use crate::math::Real;
use crate::variables::State;

#[derive(Debug, Clone)]
pub struct JointRotation {
    /// (ω_port, ω_joint).
    pub vars: [usize; 6],
    pub port_frame: usize,
    pub joint_frame: usize,
    /// The port's rest frame in the joint frame's body coordinates (columns).
    pub rest: Frame,
    /// Spring axes in the port's rest body coordinates, and their stiffnesses (N·m/rad).
    pub axes: [[f64; 3]; 3],
    pub stiffness: [f64; 3],
}

impl JointRotation {
    /// Relative rotation measure φ in the port's rest body axes.
    pub fn relative_rotation<T: Real>(&self, st: &State, x: &[T; 6]) -> V3<T> {
        let fq = &st.frames[self.port_frame].rotation;
        let jq = &st.frames[self.joint_frame].rotation;
        let wp = [x[0], x[1], x[2]];
        let wj = [x[3], x[4], x[5]];
        // Both frames carry the port's rest orientation C: exp(ω) Q c_k. At rest both are C and
        // R = I.
        let carry = |q: &Frame, w: V3<T>, c: [f64; 3]| {
            let world = add(
                add(scalef(q[0], c[0]), scalef(q[1], c[1])),
                scalef(q[2], c[2]),
            );
            rotate(w, lift(world))
        };
        let f: [V3<T>; 3] = std::array::from_fn(|k| carry(fq, wp, self.rest[k]));
        let g: [V3<T>; 3] = std::array::from_fn(|k| carry(jq, wj, self.rest[k]));
        let r = |i: usize, j: usize| dot(g[i], f[j]);
        [
            (r(2, 1) - r(1, 2)) * 0.5,
            (r(0, 2) - r(2, 0)) * 0.5,
            (r(1, 0) - r(0, 1)) * 0.5,
        ]
    }
}

impl Term<6> for JointRotation {
    const CATEGORY: Category = Category::Joints;
    fn vars(&self) -> &[usize; 6] {
        &self.vars
    }
    fn eval<T: Real>(&self, st: &State, x: &[T; 6]) -> T {
        let phi = self.relative_rotation(st, x);
        let mut e = T::cst(0.0);
        for i in 0..3 {
            let p = dot(phi, lift(self.axes[i]));
            e += p * p * (0.5 * self.stiffness[i]);
        }
        e
    }
}
