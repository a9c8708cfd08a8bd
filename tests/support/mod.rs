//! Independent analytic and semi-analytic reference solutions from rod mechanics, for the
//! validation tests.
//!
//! They live with the tests, not in the library, because the tests compare the simulator
//! against them: they must share no code path with the discrete-elastic-rod machinery, and the
//! solver must not be able to call them. Only `std` is used.
//!
//! Two kinds of tools are provided:
//!
//! * closed forms in terms of Legendre elliptic integrals, evaluated through Carlson's
//!   symmetric integrals ([`elliptic`]);
//! * shooting solutions of the planar inextensible elastica, integrated by the fixed-step
//!   Gragg–Bulirsch–Stoer scheme of [`ode`] and solved by [`roots`].
//!
//! Where both exist (cantilever with a tip force, post-buckled Euler strut, heavy elastica
//! shot upwards and downwards) `tests/analytic_references.rs` checks that they agree to 1e-9.
//!
//! All results are dimensionless; each function documents its scaling.

// Every test target that declares `mod support;` compiles all of it but calls only the
// references it checks against; the rest, and the re-exports below, would be reported as dead
// code and unused imports in each of them.
#![allow(dead_code, unused_imports)]

pub mod buckling;
pub mod elastica;
pub mod elliptic;
pub mod hanging;
pub mod heavy;
pub mod linear;
pub mod ode;
pub mod roots;
pub mod shallow_arch;
mod vector;

pub use buckling::{
    euler_buckling_postbuckled, euler_buckling_postbuckled_at_load, euler_critical_load,
    michell_critical_twist, PostBuckled,
};
pub use elastica::{cantilever_shooting, cantilever_tip_load, cantilever_tip_moment, ElasticaTip};
pub use heavy::{heavy_elastica_lifted_end, heavy_elastica_small_deflection, HeavyElastica};
pub use linear::{l_frame_tip_deflection, uniform_twist_torque};
