//! Translational spring of an elastic joint: E = ½ k |x_rod − p|² between a rod's node and the
//! joint's centre node (both at the same rest position).

use super::{diff3, reduced_term, Category, Reduced, Term};
use crate::math::Real;
use crate::variables::State;

#[derive(Debug, Clone)]
pub struct JointTranslation {
    /// (x_rod, p_joint).
    pub vars: [usize; 6],
    /// N/m.
    pub stiffness: f64,
}

impl Reduced<6, 3> for JointTranslation {
    // x_rod − p.
    const MAP: [[(usize, f64); 2]; 3] = diff3(3, 0);
    fn eval_reduced<T: Real>(&self, _st: &State, d: &[T; 3]) -> T {
        (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) * (0.5 * self.stiffness)
    }
}

impl Term<6> for JointTranslation {
    const CATEGORY: Category = Category::Joints;
    fn vars(&self) -> &[usize; 6] {
        &self.vars
    }
    reduced_term!(6, 3);
}
