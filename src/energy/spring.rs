//! Elastic support (`Spring(stiffness: (kx, ky, kz))`): a node tied to its anchor by three
//! springs along the world axes, E = ½ Σ kᵢ (xᵢ − aᵢ)². The anchor moves from the node's rest
//! position to its `move_to` with the load factor, like a prescribed motion.

use super::{Category, Term};
use crate::math::Real;
use crate::variables::State;

#[derive(Debug, Clone)]
pub struct Spring {
    pub vars: [usize; 3],
    /// N/m along x, y, z.
    pub stiffness: [f64; 3],
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
        std::array::from_fn(|k| -self.stiffness[k] * (x[k] - a[k]))
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
        for k in 0..3 {
            let d = x[k] - a[k];
            e += d * d * (0.5 * self.stiffness[k]);
        }
        e
    }
}
