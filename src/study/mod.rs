//! Studies that solve one problem many times: `rodnet study convergence` (docs/convergence.md).
pub mod convergence;
pub mod extrapolate;
pub mod plot;
pub mod report;
pub mod richardson;
