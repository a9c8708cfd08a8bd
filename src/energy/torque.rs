//! Dead torque on a vertex frame: potential −λ T·(ψ + ω), with ψ the frame's accumulated rotation
//! vector and ω its current increment. Its gradient is exactly the dead moment −λT for the spatial
//! increments ω, so equilibria are those of a torque fixed in space; the potential's value is exact
//! for rotations about a fixed axis and a consistent merit function inside each Newton step
//! otherwise (a dead torque is not conservative for general 3-D rotations).

use super::{Category, Term};
use crate::math::Real;
use crate::variables::State;

#[derive(Debug, Clone)]
pub struct Torque {
    /// The frame's ω variables.
    pub vars: [usize; 3],
    pub frame: usize,
    pub torque: [f64; 3],
}

impl Term<3> for Torque {
    const CATEGORY: Category = Category::External;
    fn vars(&self) -> &[usize; 3] {
        &self.vars
    }
    fn eval<T: Real>(&self, st: &State, x: &[T; 3]) -> T {
        let l = -st.load_factor;
        let psi = st.frames[self.frame].accumulated;
        let mut e = T::cst(0.0);
        for k in 0..3 {
            e += (x[k] + psi[k]) * (l * self.torque[k]);
        }
        e
    }
}
