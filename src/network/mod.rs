//! Networks of rods: the global state, ports (vertex frames), the DOF map and assembly, and the
//! builder from a scene.
pub mod build;
pub mod contact;
pub mod joint;
pub mod model;
pub mod port;
pub mod positions;
pub mod problem;
pub mod projection;
pub mod rest;
pub mod state;

pub use build::{build, Network};
pub use model::Model;
