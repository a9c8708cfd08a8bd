//! rodnet: Discrete Elastic Rods statics for rod networks and elastic gridshells.
//!
//! Layout: [`rod`] (sections, frames, transport), [`energy`] (one term per file), [`network`]
//! (state, DOF map, assembly, builder), [`solver`] (Newton, sparse Cholesky), [`scene`] (RON format,
//! validation, scenes from OBJ networks), [`io`] (results, exports), [`gridshell`] (Chebyshev nets),
//! [`study`] (convergence under subdivision), [`sweep`] (parameter sweeps), [`cli`] (the `rodnet` commands).

// Numeric kernels index several arrays with one loop variable; iterator chains there hide the
// mathematics without making it safer.
#![allow(clippy::needless_range_loop)]

pub mod cli;
pub mod energy;
pub mod gridshell;
pub mod io;
pub mod jobs;
pub mod math;
pub mod network;
pub mod pipeline;
pub mod rod;
pub mod scene;
pub mod solver;
pub mod study;
pub mod surface;
pub mod sweep;
pub mod variables;
