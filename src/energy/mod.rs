//! Energy terms. Each term is a function of a few local variables behind one interface
//! ([`Term`]): its value comes from `eval::<f64>` and its exact gradient and Hessian from
//! `eval::<HD<N>>`.

pub mod bend;
pub mod frame_bend;
pub mod frame_twist;
pub mod joint_rotation;
pub mod joint_translation;
pub mod point_load;
pub mod stretch;
pub mod torque;
pub mod twist;

use crate::math::Real;
use crate::network::state::State;

/// Where a term's energy is reported in the results.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Category {
    Stretch,
    Bend,
    Twist,
    Joints,
    External,
}

/// A local energy term in `N` variables (indices into [`State::q`]).
pub trait Term<const N: usize>: Sync + Send {
    const CATEGORY: Category;
    fn vars(&self) -> &[usize; N];
    fn eval<T: Real>(&self, st: &State, x: &[T; N]) -> T;

    fn gather(&self, q: &[f64]) -> [f64; N] {
        let v = self.vars();
        std::array::from_fn(|i| q[v[i]])
    }

    fn energy(&self, st: &State) -> f64 {
        self.eval::<f64>(st, &self.gather(&st.q))
    }
}

/// Splits a local variable array into 3-vectors and scalars.
#[inline]
pub(crate) fn v3<T: Copy>(x: &[T], at: usize) -> [T; 3] {
    [x[at], x[at + 1], x[at + 2]]
}
