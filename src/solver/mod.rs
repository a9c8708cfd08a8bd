//! Newton's method on the total energy, its linear algebra, and its settings.
pub mod arc_length;
pub mod continuation;
pub mod linalg;
pub mod line_search;
mod modes;
pub mod newton;
pub mod path_events;
pub mod pool;
pub mod problem;
pub mod qp;
mod regularize;
pub mod saddle;
pub mod settings;
pub mod spectrum;
mod stationary;
mod step;
pub mod verdict;

pub use continuation::{solve, solve_with};
pub use linalg::Ordering;
pub use problem::NewtonProblem;
pub use settings::{
    ConstraintReport, Continuation, LimitPoint, NewtonReport, NewtonSettings, Progress,
};
