//! Rotational elastic support (`Spring(rotational: (k₁, k₂, k₃))`): a vertex frame tied to an
//! anchor frame by three rotational springs. With R the frame's rotation from rest and A(λ) the
//! anchor's (the identity, or turning to `rotate_by` with the load factor), the relative rotation
//! Aᵀ R has the rotation vector φ = θ·axis (its logarithm, in the anchor's axes), and
//! E = ½ Σᵢ kᵢ (φ·aᵢ)² over the spring axes aᵢ (N·m/rad).
//!
//! The logarithm, unlike the bounded sin θ·axis of the elastic joints, keeps E = ½ k θ² for large
//! turns: a support spring may turn a rod end by a radian or more. It is smooth for θ < π: φ is
//! computed as g·v with v = vee(M − Mᵀ)/2 = sin θ·axis and g = θ / sin θ, a smooth function of
//! sin²θ taken from its series near θ = 0, where the square root has no derivatives.

use super::{Category, Term};
use crate::math::vec::*;
use crate::math::Real;
use crate::variables::State;

#[derive(Debug, Clone)]
pub struct RotationalSpring {
    /// The frame's ω variables.
    pub vars: [usize; 3],
    pub frame: usize,
    /// Spring axes in world rest coordinates (orthonormal; they turn with the anchor), and
    /// stiffnesses (N·m/rad).
    pub axes: [[f64; 3]; 3],
    pub stiffness: [f64; 3],
    /// The anchor's rotation vector at load factor 1 (zero: the anchor stays at rest).
    pub rotate_by: [f64; 3],
}

/// Below this sin²θ, θ / sin θ comes from its series (error below 1e-19).
const SERIES_BELOW: f64 = 1e-6;

impl RotationalSpring {
    /// The anchor frame's columns at load factor `lambda`.
    pub fn anchor_at(&self, lambda: f64) -> Frame {
        let w = self.rotate_by.map(|r| lambda * r);
        frame_rotate(w, &[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
    }

    /// Rotation vector of the frame relative to its anchor, in the anchor's axes (the world's
    /// at rest), rad.
    pub fn rotation_vector<T: Real>(&self, st: &State, w: &[T; 3]) -> V3<T> {
        let q = &st.frames[self.frame].rotation;
        let a = self.anchor_at(st.load_factor);
        let r: [V3<T>; 3] = std::array::from_fn(|j| rotate(*w, lift(q[j])));
        // m[i][j] = (A eᵢ)·(R eⱼ): the relative rotation in the anchor's axes.
        let m = |i: usize, j: usize| dot(lift(a[i]), r[j]);
        let v = [
            (m(2, 1) - m(1, 2)) * 0.5,
            (m(0, 2) - m(2, 0)) * 0.5,
            (m(1, 0) - m(0, 1)) * 0.5,
        ];
        let c = (m(0, 0) + m(1, 1) + m(2, 2) - 1.0) * 0.5;
        let s2 = dot(v, v);
        let g = if s2.val() < SERIES_BELOW && c.val() > 0.0 {
            // θ/sin θ = asin(s)/s = 1 + s²/6 + 3s⁴/40 + 5s⁶/112 + … for θ < π/2.
            s2 * (s2 * (s2 * (5.0 / 112.0) + 3.0 / 40.0) + 1.0 / 6.0) + 1.0
        } else {
            let s = s2.sqrt();
            s.atan2(c) / s
        };
        scale(v, g)
    }

    /// The moment the spring exerts on the frame, N·m (world axes).
    pub fn moment(&self, st: &State) -> [f64; 3] {
        let w = self.gather(&st.q);
        let d = self.derivatives(st, &w);
        d.g.map(|g| -g)
    }
}

impl Term<3> for RotationalSpring {
    const CATEGORY: Category = Category::Supports;
    fn vars(&self) -> &[usize; 3] {
        &self.vars
    }
    fn eval<T: Real>(&self, st: &State, x: &[T; 3]) -> T {
        let phi = self.rotation_vector(st, x);
        let mut e = T::cst(0.0);
        for i in 0..3 {
            let p = dot(phi, lift(self.axes[i]));
            e += p * p * (0.5 * self.stiffness[i]);
        }
        e
    }
}
