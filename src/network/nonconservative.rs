//! The part of the loads' tangent stiffness that no energy has: dead moments.
//!
//! A frame's unknowns are the spatial rotation increment ω from its committed orientation. A
//! dead moment T does the work T·δθ on a spatial rotation δθ, and δθ = J(ω)·δω with the left
//! Jacobian J(ω) = I + ½ω̂ + O(ω²) of SO(3): its generalized force T + ½T̂ω has the skew
//! derivative ½T̂ at ω = 0. The torque term's potential −T·(ψ + ω) carries only the symmetric
//! part (none), so the Newton matrix is the symmetric part of the tangent and misses ½T̂ on each
//! loaded frame.

use super::model::{Model, FIXED};
use crate::math::vec::{cross, norm};

impl Model {
    /// The 2-norm of the missing skew stiffness in the unknowns divided by their scales
    /// (`unknown_scales`: 1 for angles): the largest frame's ½·λ·|ΣT| (block diagonal).
    pub fn dead_torque_skew(&self) -> f64 {
        // Without allocating (the solver asks at every shifted iteration): each frame's sum is
        // taken at its first torque.
        let torques = &self.terms.torques;
        let lambda = self.state.load_factor;
        let mut largest: f64 = 0.0;
        for (i, t) in torques.iter().enumerate() {
            let first = torques[..i].iter().all(|u| u.frame != t.frame);
            if !first || t.vars.iter().all(|&v| self.free[v] == FIXED) {
                continue;
            }
            let mut sum = [0.0; 3];
            for u in torques[i..].iter().filter(|u| u.frame == t.frame) {
                (0..3).for_each(|k| sum[k] += u.torque[k]);
            }
            largest = largest.max(0.5 * (lambda * norm(sum)).abs());
        }
        largest
    }

    /// S·v for a direction `v` of the free unknowns, S the skew stiffness −½λT̂ of each
    /// loaded frame, in `out`.
    pub fn dead_torque_image(&self, v: &[f64], out: &mut [f64]) {
        let lambda = self.state.load_factor;
        out.fill(0.0);
        for t in &self.terms.torques {
            let at = |k: usize| self.free[t.vars[k]];
            let w: [f64; 3] = std::array::from_fn(|k| {
                if at(k) == FIXED {
                    0.0
                } else {
                    v[at(k) as usize]
                }
            });
            let tw = cross(t.torque, w);
            for k in 0..3 {
                if at(k) != FIXED {
                    out[at(k) as usize] -= 0.5 * lambda * tw[k];
                }
            }
        }
    }
}
