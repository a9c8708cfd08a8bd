//! Dead nodal force: potential −λ f·x (λ the load factor). Gravity is lumped into these with the
//! node's share of rod mass (half of each adjacent edge's rest length × ρA).

use super::{Category, Term};
use crate::math::Real;
use crate::variables::State;

#[derive(Debug, Clone)]
pub struct PointLoad {
    pub vars: [usize; 3],
    pub force: [f64; 3],
}

impl Term<3> for PointLoad {
    const CATEGORY: Category = Category::External;
    fn vars(&self) -> &[usize; 3] {
        &self.vars
    }
    fn eval<T: Real>(&self, st: &State, x: &[T; 3]) -> T {
        let l = -st.load_factor;
        x[0] * (l * self.force[0]) + x[1] * (l * self.force[1]) + x[2] * (l * self.force[2])
    }
}
