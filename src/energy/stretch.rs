//! Stretching: E = ½ EA (|e|/|ē| − 1)² |ē| per edge.

use super::{v3, Category, Term};
use crate::math::vec::{norm, sub};
use crate::math::Real;
use crate::network::state::State;

#[derive(Debug, Clone)]
pub struct Stretch {
    /// (x_a, x_b).
    pub vars: [usize; 6],
    pub rest_length: f64,
    pub ea: f64,
}

impl Term<6> for Stretch {
    const CATEGORY: Category = Category::Stretch;
    fn vars(&self) -> &[usize; 6] {
        &self.vars
    }
    fn eval<T: Real>(&self, _st: &State, x: &[T; 6]) -> T {
        let l = norm(sub(v3(x, 3), v3(x, 0)));
        let strain = l / self.rest_length - 1.0;
        strain * strain * (0.5 * self.ea * self.rest_length)
    }
}
