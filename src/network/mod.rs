//! A network of rods: built from a scene ([`build`]), held as a Newton problem ([`Model`]),
//! assembled ([`assembly`]), lent to the solver ([`problem`]), and measured at equilibrium
//! ([`equilibrium`]).

pub mod assembly;
pub mod build;
pub mod contact;
pub mod equilibrium;
pub mod info;
pub mod joint;
pub mod model;
pub mod positions;
pub mod problem;
pub mod projection;
pub mod rest;

pub use build::build;
pub use info::{JointInfo, Network, RodInfo, SupportInfo};
pub use model::Model;
pub use problem::{solve, NetworkProblem};
