//! The equilibria pushes along the lowest modes reach (`rodnet states`).

use crate::io::results::Results;
use crate::pipeline::{build_for, finish_warned, warnings_of, JobError};
use crate::scene::Scene;
use crate::solver::NewtonSettings;

/// The equilibria of a scene that pushes along its lowest modes reach (`rodnet states`), each
/// with its results; the first is the scene's own solve.
pub fn states(
    scene: &Scene,
    settings: &NewtonSettings,
    max: usize,
) -> Result<Vec<(crate::network::states::Found, Results)>, JobError> {
    // The states of the last load case: a staged scene's loads all together.
    let scene = &scene.all_stages();
    let mut network = build_for(scene, settings).map_err(JobError::Scene)?;
    if network.model.contact.is_some() {
        return Err(JobError::Refused(
            "states does not handle contact or bounds yet (its eigen-analysis would have to              hold the active constraints)"
                .into(),
        ));
    }
    let rest = network.model.state.clone();
    let first = crate::network::solve_toward(&mut network, settings, scene.solver.buckle_toward);
    if !first.converged {
        let why = first.message.clone().unwrap_or_default();
        return Err(JobError::Refused(format!(
            "the scene's own solve did not converge ({why}): no state to search from"
        )));
    }
    let found = crate::network::states::search(&mut network, settings, first, &rest, max)
        .map_err(JobError::Refused)?;
    let warnings = warnings_of(scene);
    Ok(found
        .into_iter()
        .map(|f| {
            let mut net = network.clone();
            net.model.state = f.state.clone();
            let sol = finish_warned(net, scene, f.report.clone(), |_, _| {}, warnings.clone());
            (f, sol.results)
        })
        .collect())
}
