//! Stretching: E = ½ EA (|e|/|ē| − 1)² |ē| per edge.

use super::{diff3, reduced_term, Category, Reduced, Term};
use crate::math::vec::norm;
use crate::math::Real;
use crate::variables::State;

#[derive(Debug, Clone)]
pub struct Stretch {
    /// (x_a, x_b).
    pub vars: [usize; 6],
    /// The global edge it stretches.
    pub edge: usize,
    pub rest_length: f64,
    pub ea: f64,
}

impl Reduced<6, 3> for Stretch {
    const MAP: [[(usize, f64); 2]; 3] = diff3(0, 3);
    fn eval_reduced<T: Real>(&self, _st: &State, e: &[T; 3]) -> T {
        let strain = norm(*e) / self.rest_length - 1.0;
        strain * strain * (0.5 * self.ea * self.rest_length)
    }
}

impl Term<6> for Stretch {
    const CATEGORY: Category = Category::Stretch;
    fn vars(&self) -> &[usize; 6] {
        &self.vars
    }
    fn edge(&self) -> Option<usize> {
        Some(self.edge)
    }
    reduced_term!(6, 3);
}
