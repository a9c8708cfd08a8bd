//! Form finding from the flat footprint: the rod ends move in continuation steps from the
//! footprint to their equator points.
//!
//! The footprint and its pinned ends are symmetric under z → −z. Once the ends move inward, the
//! flat grid is a saddle between the dome, its mirror image and mixed states: the first
//! continuation sub-step crushes the end edges (only the prescribed ends move), and near the flat
//! saddle the line search finds no energy decrease, or the solver's negative-curvature escape
//! leaves it on a side that is not tied to "up" (measurements in docs/gridshell.md).
//!
//! So the symmetry is broken by the starting state instead. Before the solve, the footprint is
//! bent onto a shallow spherical cap: the node with footprint coordinates (u, v) goes to the
//! point r(u, v) of the Chebyshev net of a sphere of radius `start_cap · R`, rested on z = 0 at
//! its lowest rod end. That net is isometric along its curves, so every rod keeps its length
//! (up to chord versus arc, ~(l/R_cap)²/24 per edge) and every crossing stays a crossing: the
//! start is an upward, unstretched bend of the footprint, not the answer.
//!
//! Two paths lead from there to the hemisphere (`FormPath`):
//! - `CapNets` (default): the ends travel through the same family of isometric bendings. In
//!   each of `load_steps` steps they sit on the net of the sphere whose curvature is the next of
//!   equal steps from 1/(start_cap·R) to 1/R, and the nodes start the step on that net (twist
//!   angles and joint frames carry over from the last equilibrium). Each step is then a plain
//!   equilibration at fixed ends; one that does not converge is halved from the last
//!   equilibrium. The nets are only starting guesses: the shell's equilibrium departs from them
//!   by a few percent of R and Newton finds it.
//! - `Straight`: the ends move on straight lines from the cap's rim to their equator points, by
//!   the solver's adaptive continuation, and nothing but the starting cap uses the analytic net.
//!   Slower, because the first sub-step crushes the end edges while the grid stands still.
//!
//! The last step is the pure problem (ends pinned on the equator, no load), so the path only
//! selects the branch and starts Newton close: the equilibrium does not depend on it
//! (docs/gridshell.md compares cap radii and paths). `start_cap = 1` starts directly from the
//! analytic net of the hemisphere.

use std::time::{Duration, Instant};

use crate::gridshell::chebyshev::HemisphereNet;
use crate::math::vec::{add, normalize, rotation_between, sub};
use crate::network::model::Model;
use crate::network::{Network, NetworkProblem};
use crate::solver::{NewtonReport, NewtonSettings};

/// Radius of the starting cap over R. Larger radii start flatter and need more iterations
/// (see docs/gridshell.md); the equilibrium is the same.
pub const DEFAULT_START_CAP: f64 = 5.0;

/// How the rod ends get from the starting cap to the equator (see the module doc).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FormPath {
    #[default]
    CapNets,
    Straight,
}

pub struct FormFinding {
    pub report: NewtonReport,
    /// Wall time, s.
    pub seconds: f64,
}

/// Form-finds `network` in place. It must be built from a footprint scene of radius `radius`
/// (rods flat in z = 0 with their net parameters as (x, y), ends with `move_to`).
/// `start_cap` ≥ 1 is the starting cap's radius over R (1: the analytic net itself); 0 starts
/// from the flat footprint and moves the ends on straight lines by the solver's continuation
/// (no symmetry breaking: for studies of the solver).
pub fn form_find(
    network: &mut Network,
    settings: &NewtonSettings,
    radius: f64,
    start_cap: f64,
    path: FormPath,
) -> FormFinding {
    let t0 = Instant::now();
    let report = if start_cap > 0.0 && path == FormPath::CapNets {
        cap_path(network, settings, radius, start_cap)
    } else {
        if start_cap > 0.0 {
            onto_cap(&mut network.model, start_cap * radius);
        }
        crate::network::solve(&mut network.model, settings)
    };
    FormFinding {
        report,
        seconds: t0.elapsed().as_secs_f64(),
    }
}

/// Node positions on the Chebyshev net of the sphere of radius `rho` (resting on z = 0 at the
/// lowest node) and the sphere's unit normals there.
fn on_cap(rho: f64, flat: &[[f64; 3]]) -> (CapNodes, CapNodes) {
    let cap = HemisphereNet::new(rho, 1);
    let uv: Vec<[f64; 2]> = flat.iter().map(|x| [x[0], x[1]]).collect();
    let mut pos = cap.points(&uv);
    let normals = pos.iter().map(|&p| normalize(p)).collect();
    let lowest = pos.iter().map(|p| p[2]).fold(f64::INFINITY, f64::min);
    for p in &mut pos {
        p[2] -= lowest;
    }
    (pos, normals)
}

/// Node positions or normals on one cap.
type CapNodes = Vec<[f64; 3]>;

/// Halvings of a cap step that fails to converge before the form finding gives up.
const MAX_CAP_HALVINGS: usize = 12;

fn cap_path(
    network: &mut Network,
    settings: &NewtonSettings,
    radius: f64,
    start_cap: f64,
) -> NewtonReport {
    let mut problem = NetworkProblem::new(&mut network.model);
    let layout = problem.model.layout;
    let flat: CapNodes = problem.model.world_positions();
    let ends: Vec<f64> = problem.model.prescribed.iter().map(|p| p.end).collect();
    let steps = if start_cap > 1.0 {
        settings.load_steps.max(1)
    } else {
        0
    };
    let (k0, k1) = (1.0 / (start_cap * radius), 1.0 / radius);
    let mut total = NewtonReport {
        load_steps: steps.max(1),
        converged: true,
        ..Default::default()
    };
    // Path parameter s ∈ [0, 1] (curvature k0 + s (k1 − k0)); pending targets, nearest last.
    let mut pending: Vec<f64> = (0..=steps)
        .rev()
        .map(|k| k as f64 / steps.max(1) as f64)
        .collect();
    // The last equilibrium's path parameter, net positions and normals.
    let mut done: Option<(f64, CapNodes, CapNodes)> = None;
    let mut halvings = 0;
    let deadline = settings
        .time_limit
        .map(|t| Instant::now() + Duration::from_secs_f64(t.clamp(0.0, 1e9)));
    // After a failure, steps continue from the last equilibrium instead of restarting from a
    // net, so that halving them brings Newton's start closer.
    let mut carry = false;
    while let Some(&s_next) = pending.last() {
        let last = s_next == 1.0;
        let rho = if last {
            radius
        } else {
            1.0 / (k0 + (k1 - k0) * s_next)
        };
        let (pos, normals) = on_cap(rho, &flat);
        let model = &mut *problem.model;
        let saved = model.state.clone();
        let q = &mut model.state.q;
        match (&done, carry) {
            (Some((_, old, _)), true) => {
                for n in 0..layout.n_nodes() {
                    let p = layout.position(q, n);
                    layout.set_position(q, n, add(p, sub(pos[n], old[n])));
                }
            }
            _ => {
                for (n, p) in pos.iter().enumerate() {
                    let o = model.origin;
                    layout.set_position(q, n, [0, 1, 2].map(|k| p[k] - o[k]));
                }
            }
        }
        let from = |n: usize| done.as_ref().map_or([0.0, 0.0, 1.0], |(_, _, nr)| nr[n]);
        turn_frames(model, &from, &normals);
        // The ends sit on this cap for the whole step (the scene's own targets in the last).
        for (p, &end) in model.prescribed.iter_mut().zip(&ends) {
            let x = if last { end } else { model.state.q[p.var] };
            model.state.q[p.var] = x;
            p.start = x;
            p.end = x;
        }
        // Edge reference frames follow the new tangents before the first assembly.
        model.commit();
        // Only the last step is the answer; the others just start the next. An intermediate
        // state stalled at the round-off floor starts the next step well enough.
        let automatic = settings.automatic_tolerance || !last;
        // The time limit holds for the whole form finding, not for each cap step.
        let left = deadline.map(|d| d.saturating_duration_since(Instant::now()).as_secs_f64());
        let step_settings = settings
            .clone()
            .load_steps(1)
            .intermediate(!last)
            .time_limit(left);
        let r = problem.solve(&step_settings.automatic_tolerance(automatic));
        merge(&mut total, &r);
        if r.stopped.is_some() {
            total.message.clone_from(&r.message);
            total.converged = false;
            break;
        }
        if r.converged {
            pending.pop();
            done = Some((s_next, pos, normals));
            continue;
        }
        // A cap step too far for Newton: retry from the last equilibrium through the cap halfway.
        let s_prev = done.as_ref().map(|d| d.0);
        if let (Some(s_prev), true) = (s_prev, halvings < MAX_CAP_HALVINGS) {
            halvings += 1;
            carry = true;
            total.retries += 1;
            problem.model.state = saved;
            pending.push(0.5 * (s_prev + s_next));
            continue;
        }
        let why = r.message.as_deref().unwrap_or("no convergence");
        total.message = Some(format!(
            "form finding stopped on the cap of radius {rho:.4} m (path parameter {s_next:.4}): {why}"
        ));
        total.converged = false;
        break;
    }
    for (p, &end) in problem.model.prescribed.iter_mut().zip(&ends) {
        p.end = end;
    }
    total
}

/// The straight path's start: the footprint bent onto the cap net of radius `rho`, its ends
/// then moved by the solver's continuation from there to the scene's targets.
fn onto_cap(model: &mut Model, rho: f64) {
    let flat: CapNodes = model.world_positions();
    let (pos, normals) = on_cap(rho, &flat);
    for (n, p) in pos.iter().enumerate() {
        model.set_world_position(n, *p);
    }
    turn_frames(model, &|_| [0.0, 0.0, 1.0], &normals);
    for p in &mut model.prescribed {
        p.start = model.state.q[p.var];
    }
    model.commit();
}

/// Turns the joint frames (Rigid, Hinge) from the surface normals `from` to `to`, so that a
/// guess does not twist the rods against them.
pub(crate) fn turn_frames(model: &mut Model, from: &dyn Fn(usize) -> [f64; 3], to: &[[f64; 3]]) {
    model.turn_frames(|m, fb| {
        let node = m.layout.node_of(fb.vars[0]).expect("a port's vertex node");
        rotation_between(from(node), to[node])
    });
}

/// Adds one cap step's solve to the form finding's report (the last step's state fields win).
fn merge(total: &mut NewtonReport, r: &NewtonReport) {
    total.add_work(r);
    total.step_iterations.push(r.iterations);
    total.residual = r.residual;
    total.energy = r.energy;
    total.stable = r.stable;
    total.residual_floor = r.residual_floor;
    total.tolerance = r.tolerance;
    total.stopped_at_floor = r.stopped_at_floor;
    total.stopped.clone_from(&r.stopped);
}
