//! Scalar automatic differentiation, small-vector helpers and union-find.
pub mod dual;
pub mod union_find;
pub mod vec;

pub use dual::{Real, D1, HD};
pub use union_find::UnionFind;
