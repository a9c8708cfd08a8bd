//! `solve_toward`, the solve of every scene: with the scene's `buckle_toward`, which side a
//! symmetric problem leaves its symmetric state toward (the name says "buckle" for the user's
//! sense of leaving a flat state; linear buckling is `solver::spectrum::linear_buckling`).
//!
//! A flat footprint whose ends move inward, or a column under its load, is in equilibrium in its
//! symmetric state all along the path; which way it buckles is decided by round-off. With a
//! direction given, the path is followed under a small dead bias force along it on every free
//! node (the imperfection that selects the branch), saddle escapes are signed toward it, and
//! the bias is then removed and the state equilibrated again at the end of the path: the result
//! is an equilibrium of the unperturbed problem, on the chosen branch.

use crate::network::model::Model;
use crate::network::problem::NetworkProblem;
use crate::network::Network;
use crate::solver::continuation::INTERMEDIATE_TOLERANCE;
use crate::solver::{NewtonReport, NewtonSettings};

/// Total bias force over the force scale: small against the loads that shape the structure,
/// large against round-off, so that it decides the side and nothing else.
const BIAS: f64 = 1e-2;

/// Solves `net`, leaving symmetric states toward `toward` when given.
pub fn solve_toward(
    net: &mut Network,
    settings: &NewtonSettings,
    toward: Option<[f64; 3]>,
) -> NewtonReport {
    let Some(t) = toward else {
        return NetworkProblem::of_network(net).solve(settings);
    };
    let bias = bias_forces(&net.model, t);
    let mut p = NetworkProblem::of_network(net);
    p.set_bias(bias, Some(t));
    // The biased path ends where the bias-free equilibration starts, which converges to the
    // tolerance asked: the path's last sub-step needs only an intermediate sub-step's.
    let loose = settings.tolerance.max(INTERMEDIATE_TOLERANCE);
    let biased = p.solve(&settings.clone().tolerance(loose));
    if !biased.converged && !biased.stopped_at_floor {
        return biased;
    }
    p.set_bias(Vec::new(), Some(t));
    let mut r = p.solve(&settings.clone().equilibrate_only(true));
    r.biased_iterations = biased.iterations;
    r.add_work(&biased);
    r.load_steps = biased.load_steps;
    let mut steps = biased.step_iterations;
    if let Some(last) = steps.last_mut() {
        *last += r.step_iterations.iter().sum::<usize>();
    }
    r.step_iterations = steps;
    r
}

/// The bias: BIAS × force scale along the unit direction, shared equally by the free nodes.
fn bias_forces(model: &Model, toward: [f64; 3]) -> Vec<f64> {
    let len = toward.iter().map(|x| x * x).sum::<f64>().sqrt();
    let u = model.unknowns();
    let nodes: Vec<usize> = (0..model.layout.n_nodes())
        .filter(|&n| (0..3).any(|k| u.of_node(n, k).is_some()))
        .collect();
    let mut b = vec![0.0; model.n_free];
    if nodes.is_empty() {
        return b;
    }
    let per_node = BIAS * model.force_scale / nodes.len() as f64 / len;
    for n in nodes {
        for k in 0..3 {
            if let Some(f) = u.of_node(n, k) {
                b[f] = per_node * toward[k];
            }
        }
    }
    b
}
