//! Indentation of a solved structure (`rodnet indent`): the linear stiffness at a point from the
//! Hessian, and the force–depth curve by displacement control on top of the scene's full load.
//!
//! The pushed point is held only along the push when the direction lies along x, y or z (a
//! Roller whose plane moves: a frictionless point indenter), and on the line of the push
//! otherwise (a sticking indenter; the lateral force it needs is reported). The scene's own
//! loads and prescribed motions stay at their full values (`Model::staged`).

use std::time::Instant;

use crate::network::problem::NetworkProblem;
use crate::network::Network;
use crate::scene::types::{Scene, Support, SupportKind};
use crate::solver::path_events::{EventKind, PathEvent};
use crate::solver::problem::ContinuationPath;
use crate::solver::spectrum;
use crate::solver::{NewtonSettings, Ordering};

/// Where and how far to push.
#[derive(Debug, Clone)]
pub struct Push {
    /// The input vertex pushed (a joint's or a rod vertex's).
    pub rod: String,
    pub vertex: usize,
    /// Unit direction of the push.
    pub direction: [f64; 3],
    pub depth: f64,
    /// Displacement-controlled steps to the full depth.
    pub steps: usize,
}

#[derive(Debug, Clone)]
pub struct Curve {
    /// (depth m, force N) from (0, 0), the force the indenter applies along the push.
    pub points: Vec<(f64, f64)>,
    /// The stability of each point of `points`, with the pushed point held.
    pub stability: Vec<PointStability>,
    /// Where the path lost stability: the steps whose solve left an unstable state.
    pub bifurcations: Vec<Bifurcation>,
    /// Largest lateral force the indenter needs (sticking indenter only), N.
    pub lateral: f64,
    /// Frictionless (held along the push only) or sticking (held on its line).
    pub frictionless: bool,
    /// Local maxima of the force (depth, force): where a force-controlled push would snap.
    pub limit_points: Vec<(f64, f64)>,
    /// Where the push passed a bifurcation or snapped, in order; `load_factor` is the depth's
    /// share of the full push.
    pub events: Vec<PathEvent>,
    /// Every step converged; if not, why the curve stops where it does.
    pub complete: bool,
    pub message: Option<String>,
    pub iterations: usize,
    pub seconds: f64,
}

/// The state at one point of the curve, with the pushed point held (what displacement control
/// sees). Both are the solver's own verdicts, free: the lowest eigenvalue at every point would
/// cost an eigen-solve per step (+31 % on the 20-step push of the n = 12, K = 8 dome, +60 % on
/// the shallow arch), so eigenvalues are computed only where stability was lost.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointStability {
    /// The Hessian over the other unknowns is positive definite at the converged state (its
    /// Cholesky factor at convergence; `NewtonReport::stable`).
    pub stable: bool,
    /// The step's solve reached a state that was not stable and left it along negative
    /// curvature (Newton's saddle escapes): the path it continued lost stability within the step.
    pub left_unstable: bool,
}

/// Where the path continued from the previous steps lost stability (a bifurcation, or a fold in
/// depth that displacement control must jump across).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bifurcation {
    /// The step whose solve left the unstable state (its index in the curve's points).
    pub step: usize,
    /// Where that path's lowest eigenvalue reaches zero, extrapolated linearly from the two
    /// points before the step (within the step; the point before when it cannot be), m, and
    /// the force there on that path, N.
    pub depth: f64,
    pub force: f64,
    /// (depth m, lowest eigenvalue N/m) at the points before the step that it comes from.
    pub eigenvalues: [(f64, f64); 2],
}

/// The force per unit displacement of the point along the direction with everything else free,
/// N/m, from the Hessian at the network's current state: 1 / (dᵀH⁻¹d).
pub fn linear_stiffness(
    net: &mut Network,
    node: usize,
    direction: [f64; 3],
) -> Result<f64, String> {
    let u = net.model.unknowns();
    let mut f = vec![0.0; net.model.n_free];
    for (k, &dk) in direction.iter().enumerate() {
        match u.of_node(node, k) {
            Some(i) => f[i] = dk,
            None if dk != 0.0 => {
                return Err(
                    "the point is held by a support along the push: it cannot be pushed".into(),
                )
            }
            None => {}
        }
    }
    let mut p = NetworkProblem::of_network(net);
    let analyses = p.model.analyses.clone();
    let c = spectrum::compliance(&mut p, &f, Ordering::Auto, &analyses)?;
    if c > 0.0 && c.is_finite() {
        Ok(1.0 / c)
    } else {
        Err(format!(
            "the compliance along the push is {c:e}: no stiffness"
        ))
    }
}

/// Pushes the point of `solved` (a network of `scene` at its equilibrium) to the full depth.
pub fn push(
    scene: &Scene,
    solved: &Network,
    how: &Push,
    settings: &NewtonSettings,
) -> Result<Curve, String> {
    push_built(scene, solved, how, settings, |s| {
        crate::network::build(s).map_err(|e| e.message)
    })
}

/// [`push`] with the pushed scene's network built by `build` (the pipeline's build within the
/// job's limits), which says why it could not be.
pub fn push_built(
    scene: &Scene,
    solved: &Network,
    how: &Push,
    settings: &NewtonSettings,
    build: impl FnOnce(&Scene) -> Result<Network, String>,
) -> Result<Curve, String> {
    let t0 = Instant::now();
    let node = solved
        .rod(&how.rod)
        .and_then(|r| r.vertex_node(how.vertex))
        .ok_or_else(|| format!("rod \"{}\" has no vertex {}", how.rod, how.vertex))?;
    let axis = axis_of(how.direction);
    let mut staged_scene = scene.clone();
    staged_scene.supports.push(Support {
        rod: how.rod.clone(),
        vertex: how.vertex,
        kind: match axis {
            Some(k) => SupportKind::Roller {
                normal: std::array::from_fn(|j| if j == k { 1.0 } else { 0.0 }),
            },
            None => SupportKind::Pin,
        },
        move_to: None,
        rotate_by: None,
    });
    let mut net =
        build(&staged_scene).map_err(|m| format!("the pushed scene could not be built: {m}"))?;
    if net.model.state.q.len() != solved.model.state.q.len() {
        return Err("the pushed scene's variables differ from the solved scene's".into());
    }
    net.model.state = solved.model.state.clone();
    let x0 = net.model.position(node);
    let held: Vec<usize> = axis.map_or(vec![0, 1, 2], |k| vec![k]);
    net.model.staged = held
        .iter()
        .map(|&k| crate::network::model::Prescribed {
            var: net.model.layout.node_coord(node, k),
            start: x0[k],
            end: x0[k] + how.depth * how.direction[k],
        })
        .collect();
    let mut curve = Curve {
        points: vec![(0.0, 0.0)],
        stability: Vec::new(),
        bifurcations: Vec::new(),
        lateral: 0.0,
        frictionless: axis.is_some(),
        limit_points: Vec::new(),
        events: Vec::new(),
        complete: true,
        message: None,
        iterations: 0,
        seconds: 0.0,
    };
    let steps = how.steps.max(1);
    let mut p = NetworkProblem::of_network(&mut net);
    p.set_continuation(0.0);
    let base = indenter_force(&*p.model, node, how.direction);
    // The solved state held: one eigen-solve (the pushes' own solves say it for the others).
    let solved_stable =
        crate::network::stability::analyse_problem(&mut p, 1).is_ok_and(|st| st.stable);
    curve.stability.push(PointStability {
        stable: solved_stable,
        left_unstable: false,
    });
    // The states of the last two points, for the eigenvalues where stability is lost.
    let mut before: [Option<crate::variables::State>; 2] = [None, Some(p.model.state.clone())];
    for i in 1..=steps {
        p.set_load_range((i - 1) as f64 / steps as f64, i as f64 / steps as f64);
        let r = p.solve(settings);
        curve.iterations += r.iterations;
        if !r.converged {
            curve.complete = false;
            curve.message = Some(format!(
                "no equilibrium at depth {:.6e} m (step {i}/{steps}): {}; the curve stops at the \
                 last converged depth (a snap-back, where depth itself reverses, would need arc \
                 length)",
                how.depth * i as f64 / steps as f64,
                r.message.unwrap_or_default()
            ));
            break;
        }
        let (along, lateral) = indenter_force(&*p.model, node, how.direction);
        curve
            .points
            .push((how.depth * i as f64 / steps as f64, along - base.0));
        curve.lateral = curve.lateral.max(lateral);
        let left_unstable = r.saddle_escapes > 0;
        curve.stability.push(PointStability {
            stable: r.stable,
            left_unstable,
        });
        if left_unstable {
            let now = p.model.state.clone();
            let lowest = before
                .clone()
                .map(|s| s.map_or(f64::NAN, |s| lowest_held(&mut p, s)));
            p.model.state = now;
            let b = bifurcation(&curve, i, lowest);
            curve.events.push(PathEvent {
                kind: EventKind::Bifurcation,
                load_factor: b.depth / how.depth,
                detail: format!(
                    "the pushed path lost stability at depth {:.6e} m, force {:.6e} N",
                    b.depth, b.force
                ),
            });
            curve.bifurcations.push(b);
        } else if let Some(e) = snap_in_step(&curve.points, &r.path_events, (i, steps)) {
            curve.events.push(e);
        }
        before = [before[1].take(), Some(p.model.state.clone())];
    }
    curve.limit_points = maxima(&curve.points);
    curve.seconds = t0.elapsed().as_secs_f64();
    Ok(curve)
}

/// A force drop under displacement control larger than both this many times the step before's
/// change and `DROP_SHARE` of the largest force so far is a jump to another branch: along a
/// smooth curve, neighbouring steps change the force alike (a maximum passed in one step
/// included), however fine the steps.
const DROP_RATIO: f64 = 4.0;
const DROP_SHARE: f64 = 0.05;

/// A snap in step `i` of `steps` (its point the last of `points`): the force drop rule, or a
/// snap that the step's own solve saw (`path_events` of its sub-steps, in the step's fraction).
fn snap_in_step(
    points: &[(f64, f64)],
    solve_events: &[PathEvent],
    (i, steps): (usize, usize),
) -> Option<PathEvent> {
    let n = points.len();
    let (d1, f1) = points[n - 1];
    let (d0, f0) = points[n - 2];
    let before = if n >= 3 {
        (f0 - points[n - 3].1).abs()
    } else {
        0.0
    };
    let largest = points.iter().map(|p| p.1.abs()).fold(0.0, f64::max);
    let drop = f0 - f1;
    if drop > DROP_RATIO * before && drop > DROP_SHARE * largest {
        return Some(PathEvent {
            kind: EventKind::Snap,
            load_factor: i as f64 / steps as f64,
            detail: format!(
                "the force dropped from {f0:.6e} N to {f1:.6e} N between depths {d0:.6e} and \
                 {d1:.6e} m ({:.3e} N the step before): the structure jumped to another branch",
                before
            ),
        });
    }
    solve_events
        .iter()
        .find(|e| e.kind == EventKind::Snap)
        .map(|e| PathEvent {
            kind: EventKind::Snap,
            load_factor: ((i - 1) as f64 + e.load_factor) / steps as f64,
            detail: format!("between depths {d0:.6e} and {d1:.6e} m: {}", e.detail),
        })
}

/// The lowest eigenvalue (N/m) of the held network at `state`.
fn lowest_held(p: &mut NetworkProblem, state: crate::variables::State) -> f64 {
    p.model.state = state;
    crate::network::stability::analyse_problem(p, 1)
        .ok()
        .and_then(|st| st.eigenvalues.first().copied())
        .unwrap_or(f64::NAN)
}

/// Where the path before step `i` lost stability: its lowest eigenvalue `lowest` at the two
/// points before, falling, extrapolated linearly to zero within the step.
fn bifurcation(c: &Curve, i: usize, lowest: [f64; 2]) -> Bifurcation {
    let (d1, f1) = c.points[i - 1];
    let d0 = if i >= 2 { c.points[i - 2].0 } else { f64::NAN };
    let eigenvalues = [(d0, lowest[0]), (d1, lowest[1])];
    let [l0, l1] = lowest;
    if i < 2 || !(l0 > l1 && l1 > 0.0) {
        return Bifurcation {
            step: i,
            depth: d1,
            force: f1,
            eigenvalues,
        };
    }
    let f0 = c.points[i - 2].1;
    let depth = (d1 + l1 * (d1 - d0) / (l0 - l1)).min(c.points[i].0);
    Bifurcation {
        step: i,
        depth,
        force: f1 + (f1 - f0) * (depth - d1) / (d1 - d0),
        eigenvalues,
    }
}

/// The coordinate axis of a direction along x, y or z, if it is one.
fn axis_of(d: [f64; 3]) -> Option<usize> {
    let nz: Vec<usize> = (0..3).filter(|&k| d[k] != 0.0).collect();
    (nz.len() == 1).then(|| nz[0])
}

/// The force the holding support applies to the point (the energy's gradient there), split
/// along the push and across it.
fn indenter_force(m: &crate::network::Model, node: usize, d: [f64; 3]) -> (f64, f64) {
    let mut grad = vec![0.0; m.n_free];
    let mut full = vec![0.0; m.state.q.len()];
    m.assemble(&mut crate::network::assembly::Assembly {
        grad: &mut grad,
        full_grad: Some(&mut full),
        hess: None,
    });
    let r: [f64; 3] = std::array::from_fn(|k| {
        let v = m.layout.node_coord(node, k);
        if m.free[v] == crate::variables::FIXED {
            full[v]
        } else {
            0.0
        }
    });
    let along: f64 = (0..3).map(|k| r[k] * d[k]).sum();
    let lateral: f64 = (0..3)
        .map(|k| (r[k] - along * d[k]).powi(2))
        .sum::<f64>()
        .sqrt();
    (along, lateral)
}

/// Interior local maxima of the force along the curve.
fn maxima(points: &[(f64, f64)]) -> Vec<(f64, f64)> {
    points
        .windows(3)
        .filter(|w| w[1].1 > w[0].1 && w[1].1 >= w[2].1)
        .map(|w| w[1])
        .collect()
}
