//! The sparse symmetric linear algebra of the solver, behind this facade: a pattern's analysis
//! (`symbolic.rs`: the stored upper triangle and its renumbering, the storage every
//! factorization reads; `ordering.rs`: AMD or the nested dissection), the numeric factorization
//! (`cholesky.rs`, faer's LLᵀ and LDLᵀ) and its solves (`supernodal_solve.rs`, loops over
//! faer's supernodal factor, or faer's own solve: [`SparseCholesky::use_faer_solve`]).
//!
//! Used from outside through:
//! - [`AnalysisCache`]: the analyses a network's solves share, held by its model (no analysis
//!   outlives the caches and factorizations holding it);
//!   [`AnalysisCache::factorization`] gives a [`SparseCholesky`] on the pattern;
//! - [`SparseCholesky`]: values by slot, `factor`/`factor_weighted` (A + shift·W; failure:
//!   [`NotPositiveDefinite`]), `factor_ldlt`, `solve`, products with the matrix;
//! - [`factor_cost`]: the factor's size, work and memory before any numeric allocation
//!   (the memory budget), from the analysis the solve then takes from the same cache;
//! - [`Ordering`], and [`nested_dissection`] for benchmarks of a given order.

mod budget;
mod cache;
mod cholesky;
#[cfg(test)]
mod layout_tests;
mod ordering;
mod supernodal_solve;
mod symbolic;

pub use budget::{factor_cost, FactorCost};
pub use cache::AnalysisCache;
pub use cholesky::{NotPositiveDefinite, SparseCholesky};
pub use ordering::{nested_dissection, Ordering};
