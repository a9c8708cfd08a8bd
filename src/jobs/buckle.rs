//! Linear buckling about a scene's rest state or a stage's equilibrium (`rodnet buckle`).

use crate::network::Network;
use crate::pipeline::{build_for, solve_scene, Limits};
use crate::scene::{FieldError, Scene};
use crate::solver::NewtonSettings;

use super::modes::MODE_AMPLITUDE;

/// Linear buckling of a scene about its rest state (`rodnet buckle`).
pub struct Buckling {
    pub network: Network,
    pub linear: crate::network::stability::LinearBuckling,
    /// The factors, modes and (unless `linear_only`) the first factor checked along the
    /// nonlinear load path, as `rodnet buckle --json` writes them.
    pub json: crate::io::stability::BucklingJson,
}

/// Why a scene has no buckling factors: a field the builder refuses, or the analysis.
pub enum BuckleError {
    Scene(FieldError),
    Analysis(String),
}

/// The `k` lowest critical load factors of a validated scene and their modes, with the first
/// checked along the load path unless `linear_only`. A scene with `stages` is linearized about
/// its equilibrium after the stages before `stage` (default: the last stage), and the factors
/// scale that stage's added loads; `stage` "base" scales the scene's own loads about rest.
pub fn buckle(
    scene: &Scene,
    k: usize,
    linear_only: bool,
    stage: Option<&str>,
    limits: &Limits,
) -> Result<Buckling, BuckleError> {
    use crate::network::stability;
    let t0 = std::time::Instant::now();
    let settings = limits.settings_of(scene);
    let (mut net, about) = erected_for_buckling(scene, stage, &settings)?;
    if net.model.contact.is_some() {
        return Err(BuckleError::Analysis(
            "buckle does not handle contact or bounds yet (remove obstacles and bounds)".into(),
        ));
    }
    let b = stability::buckling(&mut net, k)
        .map_err(|e| BuckleError::Analysis(format!("linear buckling: {e}")))?;
    let rest = stability::rods_now(&net);
    let shapes: Vec<_> = b
        .modes
        .iter()
        .map(|m| stability::mode_shape(&net, m, MODE_AMPLITUDE))
        .collect();
    let path = match b.factors.first() {
        Some(&first) if !linear_only => Some(crate::network::path_check::critical_on_path(
            &mut net, &settings, first,
        )),
        _ => None,
    };
    let mut json = crate::io::stability::BucklingJson::new(&b, &rest, &shapes);
    json.path = path.as_ref().map(Into::into);
    json.about_stage = about;
    json.seconds = t0.elapsed().as_secs_f64();
    Ok(Buckling {
        network: net,
        linear: b,
        json,
    })
}

/// The network `buckle` linearizes, at λ = 0 of the loads it scales, and the name of the stage
/// whose equilibrium that is (None: the rest state of a scene without stages).
fn erected_for_buckling(
    scene: &Scene,
    stage: Option<&str>,
    settings: &NewtonSettings,
) -> Result<(Network, Option<String>), BuckleError> {
    let n = scene.stages.len();
    let scaled = match stage {
        None => n,
        Some(name) => (0..=n)
            .find(|&k| scene.stage_name(k) == name)
            .ok_or_else(|| {
                let names: Vec<&str> = (0..=n).map(|k| scene.stage_name(k)).collect();
                BuckleError::Scene(FieldError::global(
                    "stages",
                    "",
                    format!("--stage {name:?}: the scene has no such stage (it has {names:?})"),
                ))
            })?,
    };
    if scaled == 0 {
        let base = scene.stage(0);
        let net = build_for(&base, settings).map_err(BuckleError::Scene)?;
        return Ok((net, (n > 0).then(|| "rest".to_string())));
    }
    let mut before = scene.clone();
    before.stages.truncate(scaled - 1);
    let sol = solve_scene(&before, settings).map_err(BuckleError::Scene)?;
    let about = scene.stage_name(scaled - 1).to_string();
    if !sol.results.converged {
        return Err(BuckleError::Analysis(format!(
            "the equilibrium after stage {about:?} did not converge ({}): linear buckling \
             needs it",
            sol.report.message.clone().unwrap_or_default()
        )));
    }
    let mut net = build_for(&scene.stage(scaled), settings).map_err(BuckleError::Scene)?;
    crate::network::stage::start_from(&sol.network, &mut net)
        .map_err(|m| BuckleError::Scene(FieldError::global("stages", "", m)))?;
    Ok((net, Some(about)))
}
