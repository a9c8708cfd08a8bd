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
use crate::solver::spectrum;
use crate::solver::{NewtonProblem, NewtonSettings, Ordering};

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
    /// Largest lateral force the indenter needs (sticking indenter only), N.
    pub lateral: f64,
    /// Frictionless (held along the push only) or sticking (held on its line).
    pub frictionless: bool,
    /// Local maxima of the force (depth, force): where a force-controlled push would snap.
    pub limit_points: Vec<(f64, f64)>,
    /// Every step converged; if not, why the curve stops where it does.
    pub complete: bool,
    pub message: Option<String>,
    pub iterations: usize,
    pub seconds: f64,
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
    let c = spectrum::compliance(&mut p, &f, Ordering::Auto)?;
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
    let mut net = crate::network::build(&staged_scene)
        .map_err(|e| format!("the pushed scene could not be built: {}", e.message))?;
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
        lateral: 0.0,
        frictionless: axis.is_some(),
        limit_points: Vec::new(),
        complete: true,
        message: None,
        iterations: 0,
        seconds: 0.0,
    };
    let steps = how.steps.max(1);
    let mut p = NetworkProblem::of_network(&mut net);
    p.set_continuation(0.0);
    let base = indenter_force(&*p.model, node, how.direction);
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
    }
    curve.limit_points = maxima(&curve.points);
    curve.seconds = t0.elapsed().as_secs_f64();
    Ok(curve)
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
