//! `states.json` of `rodnet states`: one entry per equilibrium found.

use serde::Serialize;

#[derive(Debug, Clone, Serialize)]
pub struct StateJson {
    /// Total energy, J.
    pub energy: f64,
    /// No negative eigenvalue among the lowest computed, and no zero one but the gauge's.
    pub stable: bool,
    /// Negative eigenvalues among the lowest computed (Morse index; a lower bound when
    /// `index_at_least`).
    pub index: usize,
    pub index_at_least: bool,
    /// The lowest eigenvalue, N/m.
    pub lowest_eigenvalue: f64,
    /// Largest node distance from state 0 (the scene's own), m.
    pub distance_to_first: f64,
    pub converged: bool,
    pub iterations: usize,
    /// "scene" (the scene's own solve) or how it was reached: "state k, mode j, ±amplitude".
    pub found_by: String,
    /// Its results JSON, beside states.json.
    pub results: String,
    /// The earlier state this one is a copy of under a symmetry (a reflection or turn of it).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub symmetric_to: Option<usize>,
}

#[derive(Debug, Clone, Serialize)]
pub struct StatesJson {
    pub states: Vec<StateJson>,
}
