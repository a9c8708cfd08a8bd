//! Scalar automatic differentiation and small-vector helpers.
pub mod dual;
pub mod vec;

pub use dual::{Real, D1, HD};
