//! One solve of a scene from start to results: build, Newton with load steps, collect.

use crate::io::reference;
use crate::io::results::Results;
use crate::network::build::{build, Network};
use crate::scene::{FieldError, Scene};
use crate::solver::{self, NewtonReport, NewtonSettings};

pub struct Solution {
    pub network: Network,
    pub report: NewtonReport,
    pub results: Results,
}

pub fn settings_of(scene: &Scene) -> NewtonSettings {
    NewtonSettings::default()
        .tolerance(scene.solver.tolerance)
        .max_iterations(scene.solver.max_iterations)
        .load_steps(scene.solver.load_steps)
}

/// Builds and solves a validated scene.
pub fn solve_scene(scene: &Scene, settings: &NewtonSettings) -> Result<Solution, FieldError> {
    let mut network = build(scene)?;
    let report = solver::solve(&mut network.model, settings);
    let mut results = Results::collect(&network, &report, scene.target.as_ref());
    results.reference = reference::measure(&network, scene);
    Ok(Solution {
        network,
        report,
        results,
    })
}
