//! The one pipeline every command runs: scene → network → solve → equilibrium → results.
//! Commands differ only in how they solve (plain Newton, or a gridshell's form finding) and in
//! what they add to the measurements; both are passed in.

use std::sync::atomic::{AtomicU64, Ordering};

use crate::io::results::{Results, StageJson};
use crate::network::budget;
use crate::network::equilibrium::Equilibrium;
use crate::network::{build, Network};
use crate::scene::types::DEFAULT_TOLERANCE;
use crate::scene::{FieldError, Scene};
use crate::solver::{NewtonReport, NewtonSettings};

pub struct Solution {
    pub network: Network,
    pub report: NewtonReport,
    pub equilibrium: Equilibrium,
    pub results: Results,
}

/// The memory a solve may take, bytes (`--max-memory`). A limit on the process, like a
/// resource limit, so held once per process rather than passed through every command's job;
/// the library has none unless a caller sets one.
static MEMORY_LIMIT: AtomicU64 = AtomicU64::new(u64::MAX);

/// Sets the memory limit every later [`run`] checks its scene against (`u64::MAX`: none).
pub fn set_memory_limit(bytes: u64) {
    MEMORY_LIMIT.store(bytes, Ordering::Relaxed);
}

/// The memory limit [`run`] checks against (`u64::MAX`: none).
pub fn memory_limit() -> u64 {
    MEMORY_LIMIT.load(Ordering::Relaxed)
}

/// `--time-limit`, seconds, as f64 bits (`u64::MAX`: none): overrides every scene's
/// `solver.time_limit` in [`settings_of`].
static TIME_LIMIT: AtomicU64 = AtomicU64::new(u64::MAX);

/// Sets the time limit that overrides the scenes' own (`None`: theirs).
pub fn set_time_limit(seconds: Option<f64>) {
    TIME_LIMIT.store(seconds.map_or(u64::MAX, f64::to_bits), Ordering::Relaxed);
}

/// The time limit set by [`set_time_limit`], if any.
pub fn time_limit() -> Option<f64> {
    match TIME_LIMIT.load(Ordering::Relaxed) {
        u64::MAX => None,
        bits => Some(f64::from_bits(bits)),
    }
}

/// Builds a validated scene, refused (as a [`FieldError`] on the field that drives its size)
/// when the solve would need more than the memory limit: first from the scene's sizes, before
/// anything is allocated, then from the built network with the factor's fill counted exactly;
/// and refused at the field that causes it when its round-off floor makes a meaningful answer
/// impossible (`network::floor`).
pub fn build_within_limit(
    scene: &Scene,
    ordering: crate::solver::Ordering,
) -> Result<Network, FieldError> {
    let limit = memory_limit();
    if limit != u64::MAX {
        budget::check_scene(scene, limit)?;
    }
    let mut network = build(scene)?;
    // The floor first: one gradient, where the memory check runs a symbolic analysis.
    crate::network::floor::check(scene, &mut network)?;
    if limit != u64::MAX {
        budget::check_network(scene, &network, limit, ordering)?;
    }
    Ok(network)
}

/// The scene's memory lower bound against the limit (`--max-memory`), before anything is built.
pub fn check_scene_memory(scene: &Scene) -> Result<(), FieldError> {
    let limit = memory_limit();
    if limit == u64::MAX {
        return Ok(());
    }
    budget::check_scene(scene, limit)
}

/// The solver settings a scene asks for.
pub fn settings_of(scene: &Scene) -> NewtonSettings {
    NewtonSettings::default()
        .tolerance(scene.solver.tolerance.unwrap_or(DEFAULT_TOLERANCE))
        .automatic_tolerance(scene.solver.tolerance.is_none())
        .time_limit(time_limit().or(scene.solver.time_limit))
        .continuation(continuation(scene.solver.continuation))
        .max_iterations(scene.solver.max_iterations)
        .load_steps(scene.solver.load_steps)
}

fn continuation(c: crate::scene::types::Continuation) -> crate::solver::Continuation {
    match c {
        crate::scene::types::Continuation::Load => crate::solver::Continuation::Load,
        crate::scene::types::Continuation::ArcLength => crate::solver::Continuation::ArcLength,
    }
}

/// Builds a validated scene and solves it with Newton's method and load stepping, stage by
/// stage when it has `stages` (the last stage's solution).
pub fn solve_scene(scene: &Scene, settings: &NewtonSettings) -> Result<Solution, FieldError> {
    solve_stages(scene, settings, |_| {})
}

/// [`solve_scene`], handing each stage's solution to `done` as it completes when another stage
/// follows it (the solution returned is the last stage solved: the scene's last, or the first
/// that did not converge). Each stage starts from the previous one's equilibrium and follows
/// its added loads from zero (`network::stage`).
pub fn solve_stages(
    scene: &Scene,
    settings: &NewtonSettings,
    mut done: impl FnMut(&Solution),
) -> Result<Solution, FieldError> {
    let base = scene.stage(0);
    let mut sol = run(
        &base,
        settings,
        |net, s| crate::network::solve_toward(net, s, scene.solver.buckle_toward),
        |_, _| {},
    )?;
    if scene.stages.is_empty() {
        return Ok(sol);
    }
    let mut stages = Vec::new();
    let mut events = Vec::new();
    for k in 0..=scene.stages.len() {
        if k > 0 {
            let sc = scene.stage(k);
            let mut network = build_within_limit(&sc, settings.ordering)?;
            crate::network::stage::start_from(&sol.network, &mut network)
                .map_err(|m| FieldError::global("stages", "", m))?;
            let own = scene.stages[k - 1].continuation.map(continuation);
            let stage_settings = match own {
                Some(c) => settings.clone().continuation(c),
                None => settings.clone(),
            };
            let report = crate::network::solve(&mut network.model, &stage_settings);
            sol = finish(network, &sc, report, |_, _| {});
        }
        // Each stage's results carry the events of the path so far, named by stage.
        for e in &mut sol.results.path_events {
            e.stage = Some(scene.stage_name(k).to_string());
        }
        events.append(&mut sol.results.path_events);
        sol.results.path_events = events.clone();
        let this = StageJson::of(k, scene.stage_name(k), &sol.results);
        sol.results.stage = Some(this.clone());
        stages.push(this);
        if k == scene.stages.len() || !sol.results.converged {
            break;
        }
        done(&sol);
    }
    sol.results.stages = stages;
    Ok(sol)
}

/// Newton iterations [`solve_scene_from`] gives the start before it solves from rest.
pub const RESTART_ITERATIONS: usize = 200;

/// Why [`solve_scene_from`] or [`states`] could not run.
#[derive(Debug)]
pub enum JobError {
    Scene(FieldError),
    /// What the command asks cannot be done with this scene: an initial state that does not
    /// fit it, a state search on a scene with contact or one whose own solve fails.
    Refused(String),
}

/// Solves a scene from an earlier equilibrium of it (`rodnet solve --initial`): Newton at the
/// full loads and motions from that state. Should Newton fail from there, the scene is solved
/// from rest as usual and the report's message says so.
pub fn solve_scene_from(
    scene: &Scene,
    settings: &NewtonSettings,
    initial: &[crate::network::initial::RodState],
) -> Result<Solution, JobError> {
    solve_scene_from_joints(scene, settings, initial, None)
}

/// [`solve_scene_from`] that also checks the results' joint names (`joints`), when given, against
/// the scene's.
pub fn solve_scene_from_joints(
    scene: &Scene,
    settings: &NewtonSettings,
    initial: &[crate::network::initial::RodState],
    joints: Option<&[String]>,
) -> Result<Solution, JobError> {
    let mut network = build_within_limit(scene, settings.ordering).map_err(JobError::Scene)?;
    let rest = network.model.state.clone();
    crate::network::initial::place(&mut network, initial).map_err(JobError::Refused)?;
    // After the rods: a file of another scene is named by its first rod that does not fit.
    if let Some(names) = joints {
        crate::network::initial::check_joints(&network, names).map_err(JobError::Refused)?;
    }
    // A start that needs more than this is no restart: the solve from rest is then the better
    // path (a start that violates the scene's bounds, a load that changes the shape entirely).
    let budget = settings.max_iterations.min(RESTART_ITERATIONS);
    let direct = crate::network::solve(
        &mut network.model,
        &settings
            .clone()
            .equilibrate_only(true)
            .max_iterations(budget),
    );
    // Out of time: the restart's own state is the answer (a solve from rest would start with
    // no time left).
    let report = if direct.converged || direct.stopped.is_some() {
        direct
    } else {
        network.model.state = rest;
        let mut r =
            crate::network::solve_toward(&mut network, settings, scene.solver.buckle_toward);
        // The failed start's iterations are part of the run's cost.
        r.add_work(&direct);
        let why = direct.message.as_deref().unwrap_or("no convergence");
        r.message = Some(match r.message.take() {
            Some(m) => format!("from the initial state: {why}; solved from rest: {m}"),
            None => format!("from the initial state: {why}; solved from rest instead"),
        });
        r
    };
    Ok(finish(network, scene, report, |_, _| {}))
}

/// Builds a validated scene, solves it with `solve`, measures the equilibrium (then lets
/// `measure` add to it) and forms the results.
pub fn run(
    scene: &Scene,
    settings: &NewtonSettings,
    solve: impl FnOnce(&mut Network, &NewtonSettings) -> NewtonReport,
    measure: impl FnOnce(&Network, &mut Equilibrium),
) -> Result<Solution, FieldError> {
    let mut network = build_within_limit(scene, settings.ordering)?;
    let report = solve(&mut network, settings);
    Ok(finish(network, scene, report, measure))
}

/// The equilibrium and results of a solved network.
pub fn finish(
    network: Network,
    scene: &Scene,
    report: NewtonReport,
    measure: impl FnOnce(&Network, &mut Equilibrium),
) -> Solution {
    let mut equilibrium = Equilibrium::compute(&network, scene, &report);
    measure(&network, &mut equilibrium);
    let mut results = Results::new(&equilibrium, &report);
    results.warnings = crate::scene::validate::warnings(scene)
        .iter()
        .map(|w| format!("{}: {}", w.path(), w.message))
        .collect();
    Solution {
        network,
        report,
        equilibrium,
        results,
    }
}

/// The lowest `k` eigenmodes at a solved equilibrium (`rodnet solve --modes K`): sets the
/// results' `stability` block and returns the analysis (for mode shapes).
pub fn analyse_modes(
    sol: &mut Solution,
    k: usize,
) -> Result<crate::network::stability::Stability, String> {
    let st = match (&sol.network.model.contact, &sol.equilibrium.constraints) {
        // The modes of the structure with its active set fixed.
        (Some(_), Some(forces)) => {
            let (mut held, _) = crate::network::active_set::hold_active(&sol.network, forces);
            crate::network::stability::analyse(&mut held, k)?
        }
        _ => crate::network::stability::analyse(&mut sol.network, k)?,
    };
    if !st.converged {
        eprintln!(
            "warning: the {k} lowest eigenvalues did not settle within {} rounds (largest \
             relative residual {:.3e}); stability.converged is false",
            st.rounds, st.residual
        );
    }
    sol.results.stability = Some((&st).into());
    Ok(st)
}

/// Mode shapes as OBJ, one object per mode, each displaced by a tenth of the structure's size.
pub fn modes_obj(network: &Network, labels: &[String], modes: &[Vec<f64>]) -> String {
    let shapes: Vec<(String, crate::network::stability::Shape)> = labels
        .iter()
        .zip(modes)
        .map(|(l, m)| {
            (
                l.clone(),
                crate::network::stability::mode_shape(network, m, MODE_AMPLITUDE),
            )
        })
        .collect();
    crate::io::stability::modes_obj("mode shapes", &shapes)
}

/// Largest node motion of a drawn mode shape, over the bounding-box diagonal.
pub const MODE_AMPLITUDE: f64 = 0.1;

/// The equilibria of a scene that pushes along its lowest modes reach (`rodnet states`), each
/// with its results; the first is the scene's own solve.
pub fn states(
    scene: &Scene,
    settings: &NewtonSettings,
    max: usize,
) -> Result<Vec<(crate::network::states::Found, Results)>, JobError> {
    // The states of the last load case: a staged scene's loads all together.
    let scene = &scene.all_stages();
    let mut network = build_within_limit(scene, settings.ordering).map_err(JobError::Scene)?;
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
    Ok(found
        .into_iter()
        .map(|f| {
            let mut net = network.clone();
            net.model.state = f.state.clone();
            let sol = finish(net, scene, f.report.clone(), |_, _| {});
            (f, sol.results)
        })
        .collect())
}

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
) -> Result<Buckling, BuckleError> {
    use crate::network::stability;
    let t0 = std::time::Instant::now();
    let settings = settings_of(scene);
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
        Some(&first) if !linear_only => {
            Some(stability::critical_on_path(&mut net, &settings, first))
        }
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
        let net = build_within_limit(&base, settings.ordering).map_err(BuckleError::Scene)?;
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
    let mut net =
        build_within_limit(&scene.stage(scaled), settings.ordering).map_err(BuckleError::Scene)?;
    crate::network::stage::start_from(&sol.network, &mut net)
        .map_err(|m| BuckleError::Scene(FieldError::global("stages", "", m)))?;
    Ok((net, Some(about)))
}

/// What `rodnet indent` measures: the results as its `--json` writes them, and the curve.
pub struct Indentation {
    pub json: crate::io::indent::IndentJson,
    pub curve: crate::network::indent::Curve,
}

/// Why an indentation has no results.
pub enum IndentError {
    /// A field the builder refuses.
    Scene(FieldError),
    /// The scene's own solve did not converge (its message): nothing was pushed.
    NotConverged(String),
    /// The point to push (`at`), the depth or the direction is not one.
    At(String),
    /// The push could not be set up.
    Push(String),
}

/// Solves a validated scene, then pushes the point `at` (a joint's name, `ROD:VERTEX` or
/// `apex`) by `depth` m along `direction` in `steps` displacement-controlled steps: the linear
/// stiffness there, the force–depth curve and its limit points (`rodnet indent`).
pub fn indent(
    sc: &Scene,
    at: &str,
    direction: [f64; 3],
    depth: f64,
    steps: usize,
) -> Result<Indentation, IndentError> {
    use crate::network::indent::{linear_stiffness, push, Push};
    let n = direction.iter().map(|d| d * d).sum::<f64>().sqrt();
    if !(n.is_finite() && n > 1e-150) {
        return Err(IndentError::At(format!(
            "direction must be finite and non-zero, got {direction:?}"
        )));
    }
    let direction = direction.map(|d| d / n);
    if !(depth.is_finite() && depth > 0.0) || steps == 0 {
        return Err(IndentError::At(format!(
            "depth must be a positive length in m and steps at least 1, got {depth} and {steps}"
        )));
    }
    let settings = settings_of(sc);
    let mut sol = solve_scene(sc, &settings).map_err(IndentError::Scene)?;
    if !sol.results.converged {
        return Err(IndentError::NotConverged(
            sol.report.message.clone().unwrap_or_default(),
        ));
    }
    let (rod, vertex, joint) = locate(at, sc, &sol, direction).map_err(IndentError::At)?;
    let Some(node) = sol.network.rod(&rod).and_then(|r| r.vertex_node(vertex)) else {
        return Err(IndentError::At("no such vertex".into()));
    };
    let position = sol.network.model.world_position(node);
    let k = linear_stiffness(&mut sol.network, node, direction);
    let how = Push {
        rod: rod.clone(),
        vertex,
        direction,
        depth,
        steps,
    };
    // The push holds every stage's loads at their full values.
    let curve = push(&sc.all_stages(), &sol.network, &how, &settings).map_err(IndentError::Push)?;
    let (pts, lims) = crate::io::indent::IndentJson::curve_of(&curve);
    let (curve_stability, bifurcations) = crate::io::indent::IndentJson::stability_of(&curve);
    let json = crate::io::indent::IndentJson {
        rod,
        vertex,
        joint,
        position,
        direction,
        depth,
        linear_stiffness: k.as_ref().ok().copied(),
        linear_stiffness_note: k.as_ref().err().cloned(),
        frictionless: curve.frictionless,
        max_lateral_force: curve.lateral,
        curve: pts,
        limit_points: lims,
        curve_stability,
        bifurcations,
        path_events: crate::io::indent::IndentJson::events_of(&curve),
        complete: curve.complete,
        message: curve.message.clone(),
        solve_iterations: sol.report.iterations,
        iterations: curve.iterations,
        seconds: curve.seconds,
    };
    Ok(Indentation { json, curve })
}

/// The pushed point of `rodnet indent --at` as (rod, input vertex, joint name).
fn locate(
    at: &str,
    sc: &Scene,
    sol: &Solution,
    d: [f64; 3],
) -> Result<(String, usize, Option<String>), String> {
    let along = |p: [f64; 3]| p[0] * d[0] + p[1] * d[1] + p[2] * d[2];
    if at == "apex" {
        let net = &sol.network;
        let best = if sc.joints.is_empty() {
            net.rods
                .iter()
                .flat_map(|r| {
                    (0..r.nodes.len().div_ceil(r.subdivide.max(1)))
                        .filter_map(move |v| r.vertex_node(v).map(|n| (r.name.clone(), v, n)))
                })
                .map(|(r, v, n)| (along(net.model.position(n)), r, v, None))
                .min_by(|a, b| a.0.total_cmp(&b.0))
        } else {
            sc.joints
                .iter()
                .filter_map(|j| {
                    let info = net.joints.iter().find(|i| i.name == j.name)?;
                    let (r, v) = j.at[0].clone();
                    Some((
                        along(net.model.position(info.node)),
                        r,
                        v,
                        Some(j.name.clone()),
                    ))
                })
                .min_by(|a, b| a.0.total_cmp(&b.0))
        };
        return best
            .map(|(_, r, v, j)| (r, v, j))
            .ok_or_else(|| "the scene has no vertex to push".into());
    }
    if let Some(j) = sc.joints.iter().find(|j| j.name == at) {
        let (r, v) = j.at[0].clone();
        return Ok((r, v, Some(j.name.clone())));
    }
    if let Some((rod, v)) = at.rsplit_once(':') {
        let v: usize = v
            .parse()
            .map_err(|_| format!("expected ROD:VERTEX with a vertex number, got {at:?}"))?;
        if sc.rods.iter().any(|r| r.name == rod) {
            return Ok((rod.to_string(), v, None));
        }
        return Err(format!("no rod named {rod:?}"));
    }
    Err("expected a joint's name, ROD:VERTEX or apex".into())
}
