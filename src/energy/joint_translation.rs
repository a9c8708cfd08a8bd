//! Translational spring of an elastic joint: E = ½ k |x_rod − p|² between a rod's node and the
//! joint's centre node (both at the same rest position).

use super::{v3, Category, Term};
use crate::math::vec::sub;
use crate::math::Real;
use crate::network::state::State;

#[derive(Debug, Clone)]
pub struct JointTranslation {
    /// (x_rod, p_joint).
    pub vars: [usize; 6],
    /// N/m.
    pub stiffness: f64,
}

impl Term<6> for JointTranslation {
    const CATEGORY: Category = Category::Joints;
    fn vars(&self) -> &[usize; 6] {
        &self.vars
    }
    fn eval<T: Real>(&self, _st: &State, x: &[T; 6]) -> T {
        let d = sub(v3(x, 0), v3(x, 3));
        (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) * (0.5 * self.stiffness)
    }
}
