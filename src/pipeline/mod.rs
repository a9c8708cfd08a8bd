//! The one pipeline every command runs: scene → network → solve → equilibrium → results.
//! Commands differ only in how they solve (plain Newton, or a gridshell's form finding) and in
//! what they add to the measurements; both are passed in.

pub mod machine;

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

/// How much of the machine a solve may take (`--max-memory`, `--time-limit`): built by each
/// caller (the command line from its options, sweeps and Python from theirs) and passed down
/// as a value; the library has none unless a caller sets them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits {
    /// Bytes a solve may take (`u64::MAX`: none).
    pub memory: u64,
    /// Seconds, overriding every scene's `solver.time_limit` (`None`: theirs).
    pub time: Option<f64>,
}

impl Limits {
    /// No limits: the scenes' own time limits, no memory check.
    pub const NONE: Limits = Limits {
        memory: u64::MAX,
        time: None,
    };

    /// The default limits of a run: half of the memory this process may take
    /// ([`machine::default_max_memory`]), the scenes' own time limits.
    pub fn machine() -> Limits {
        Limits {
            memory: machine::default_max_memory(),
            time: None,
        }
    }

    /// The solver settings a scene asks for, within these limits (the memory limit travels
    /// with them to every build of the pipeline).
    pub fn settings_of(&self, scene: &Scene) -> NewtonSettings {
        NewtonSettings::default()
            .tolerance(scene.solver.tolerance.unwrap_or(DEFAULT_TOLERANCE))
            .automatic_tolerance(scene.solver.tolerance.is_none())
            .time_limit(self.time.or(scene.solver.time_limit))
            .memory_limit(self.memory)
            .continuation(continuation(scene.solver.continuation))
            .max_iterations(scene.solver.max_iterations)
            .load_steps(scene.solver.load_steps)
    }
}

impl Default for Limits {
    fn default() -> Self {
        Limits::NONE
    }
}

/// Builds a validated scene, refused (as a [`FieldError`] on the field that drives its size)
/// when the solve would need more than `memory` bytes (`u64::MAX`: no limit): first from the
/// scene's sizes, before anything is allocated, then from the built network with the factor's
/// fill counted exactly (factored with `ordering`); and refused at the field that causes it when
/// its round-off floor makes a meaningful answer impossible (`network::floor`). Every network
/// built for a solve is built here.
pub fn build_within_limit(
    scene: &Scene,
    ordering: crate::solver::Ordering,
    memory: u64,
) -> Result<Network, FieldError> {
    check_scene_memory(scene, memory)?;
    let mut network = build(scene)?;
    // The floor first: one gradient, where the memory check runs a symbolic analysis.
    crate::network::floor::check(scene, &mut network)?;
    if memory != u64::MAX {
        budget::check_network(scene, &network, memory, ordering)?;
    }
    Ok(network)
}

/// [`build_within_limit`] with the ordering and memory limit of `settings`.
pub fn build_for(scene: &Scene, settings: &NewtonSettings) -> Result<Network, FieldError> {
    build_within_limit(scene, settings.ordering, settings.memory_limit)
}

/// The scene's memory lower bound against `memory` bytes (`u64::MAX`: none), before anything
/// is built.
pub fn check_scene_memory(scene: &Scene, memory: u64) -> Result<(), FieldError> {
    if memory == u64::MAX {
        return Ok(());
    }
    budget::check_scene(scene, memory)
}

/// The solver settings a scene asks for, without limits ([`Limits::settings_of`]).
pub fn settings_of(scene: &Scene) -> NewtonSettings {
    Limits::NONE.settings_of(scene)
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
            let mut network = build_for(&sc, settings)?;
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
    let mut network = build_for(scene, settings).map_err(JobError::Scene)?;
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
    let mut network = build_for(scene, settings)?;
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
    finish_warned(network, scene, report, measure, warnings_of(scene))
}

/// What the scene probably did not mean (`scene::validate::warnings`), as the results list it:
/// `field: message`.
pub fn warnings_of(scene: &Scene) -> Vec<String> {
    crate::scene::validate::warnings(scene)
        .iter()
        .map(|w| format!("{}: {}", w.path(), w.message))
        .collect()
}

/// [`finish`] with the scene's [`warnings_of`] computed once by a caller that finishes several
/// solutions of one scene.
pub fn finish_warned(
    network: Network,
    scene: &Scene,
    report: NewtonReport,
    measure: impl FnOnce(&Network, &mut Equilibrium),
    warnings: Vec<String>,
) -> Solution {
    let mut equilibrium = Equilibrium::compute(&network, scene, &report);
    measure(&network, &mut equilibrium);
    let mut results = Results::new(&equilibrium, &report);
    results.warnings = warnings;
    Solution {
        network,
        report,
        equilibrium,
        results,
    }
}
