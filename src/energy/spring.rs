//! Elastic support (`Spring(stiffness: (k₁, k₂, k₃))`): a node tied to its anchor by three
//! springs along orthonormal axes eᵢ (the world's by default), E = ½ Σ kᵢ (eᵢ·(x − a))². The
//! anchor moves from the node's rest position to its `move_to` with the load factor, like a
//! prescribed motion.

use super::{Category, Term};
use crate::math::Real;
use crate::variables::State;

#[derive(Debug, Clone)]
pub struct Spring {
    pub vars: [usize; 3],
    /// N/m along each axis.
    pub stiffness: [f64; 3],
    /// Orthonormal spring axes.
    pub axes: [[f64; 3]; 3],
    /// Anchor at load factor 0 and 1, m.
    pub anchor: [[f64; 3]; 2],
}

impl Spring {
    /// Where the anchor is at load factor `lambda`.
    pub fn anchor_at(&self, lambda: f64) -> [f64; 3] {
        std::array::from_fn(|k| {
            self.anchor[0][k] + lambda * (self.anchor[1][k] - self.anchor[0][k])
        })
    }

    /// The force the spring exerts on the node at position `x`, N.
    pub fn force(&self, x: [f64; 3], lambda: f64) -> [f64; 3] {
        let a = self.anchor_at(lambda);
        let d: [f64; 3] = std::array::from_fn(|k| x[k] - a[k]);
        let mut f = [0.0; 3];
        for (e, k) in self.axes.iter().zip(self.stiffness) {
            let s = -k * (e[0] * d[0] + e[1] * d[1] + e[2] * d[2]);
            for c in 0..3 {
                f[c] += s * e[c];
            }
        }
        f
    }
}

impl Term<3> for Spring {
    const CATEGORY: Category = Category::Supports;
    fn vars(&self) -> &[usize; 3] {
        &self.vars
    }
    fn eval<T: Real>(&self, st: &State, x: &[T; 3]) -> T {
        let a = self.anchor_at(st.load_factor);
        let mut e = T::cst(0.0);
        for (axis, k) in self.axes.iter().zip(self.stiffness) {
            let mut s = T::cst(0.0);
            for c in 0..3 {
                s += (x[c] - a[c]) * axis[c];
            }
            e += s * s * (0.5 * k);
        }
        e
    }
}
