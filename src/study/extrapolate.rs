//! `rodnet solve --extrapolate`: the scene solved at its own subdivision and at twice it, and
//! the Richardson extrapolate of the two (docs/convergence.md, "One run extrapolated").
//!
//! Discrete Elastic Rods converge as h² (tests/robust_solver.rs, docs/convergence.md), so with
//! the coarse solution x_h and the fine one x_{h/2} at the coarse nodes (node k of the coarse rod
//! is node 2k of the fine one), x_{h/2} + (x_{h/2} − x_h)/3 removes the h² term: what is left is
//! of higher order. |x_{h/2} − x_h|/3 estimates the fine solution's own error. The fine solve
//! starts from the coarse equilibrium, refined (midpoints inserted), and is Newton at the full
//! loads from there: a few iterations where the coarse path took many.

use std::time::Instant;

use crate::io::results::ExtrapolationJson;
use crate::math::vec::{add, norm, scalef, sub};
use crate::network::initial::RodState;
use crate::pipeline::{self, JobError, Solution};
use crate::scene::Scene;
use crate::solver::NewtonSettings;

/// Order of the discretization error that the extrapolation removes.
pub const ORDER: f64 = 2.0;

/// Solves `scene` as given and with every rod's subdivision doubled; the fine solution is
/// returned with its results' `extrapolation` block filled. When the coarse solve does not
/// converge it is returned as it is (no extrapolation of a state that is not an equilibrium).
pub fn solve(scene: &Scene, settings: &NewtonSettings) -> Result<Solution, JobError> {
    if !scene.stages.is_empty() {
        return Err(JobError::Refused(
            "a scene with `stages` cannot be extrapolated yet (each stage would need its own \
             pair of solves); remove --extrapolate or the stages"
                .into(),
        ));
    }
    let t0 = Instant::now();
    let coarse = pipeline::solve_scene(scene, settings).map_err(JobError::Scene)?;
    if !coarse.results.converged || !coarse.results.all_finite() {
        return Ok(coarse);
    }
    let fine_scene = refined(scene);
    // A results state holds each reference twist only modulo 2π: a coarse state twisted by
    // more than half a turn between neighbouring frames would restart untwisted, so the fine
    // scene is then solved from rest like the coarse one.
    let wrapped = coarse
        .network
        .model
        .state
        .twist_prev
        .iter()
        .any(|t| t.abs() > std::f64::consts::PI);
    let mut fine = if wrapped {
        pipeline::solve_scene(&fine_scene, settings).map_err(JobError::Scene)?
    } else {
        let start = refined_state(&crate::io::initial::of_results(&coarse.results));
        pipeline::solve_scene_from(&fine_scene, settings, &start)?
    };
    let seconds = t0.elapsed().as_secs_f64();
    if fine.results.converged && fine.results.all_finite() {
        fine.results.extrapolation = Some(extrapolation(scene, &coarse, &fine, seconds));
    }
    Ok(fine)
}

/// The scene with every rod's subdivision doubled (input vertex k stays node k·subdivide, so
/// supports, loads and joints keep their places).
pub fn refined(scene: &Scene) -> Scene {
    let mut s = scene.clone();
    for r in &mut s.rods {
        r.subdivide *= 2;
    }
    s
}

/// The coarse rod states on the doubled subdivision: a midpoint inserted into every edge, each
/// edge's twist angle given to both its halves. (A closed rod's points end with its first
/// node again, so its closing edge is refined like the others.)
pub fn refined_state(coarse: &[RodState]) -> Vec<RodState> {
    coarse
        .iter()
        .map(|r| {
            let mut points = Vec::with_capacity(2 * r.points.len());
            for (k, p) in r.points.iter().enumerate() {
                if k > 0 {
                    points.push(scalef(add(r.points[k - 1], *p), 0.5));
                }
                points.push(*p);
            }
            RodState {
                name: r.name.clone(),
                points,
                twist: r.twist.iter().flat_map(|&t| [t, t]).collect(),
            }
        })
        .collect()
}

/// The extrapolate at the coarse nodes, with the error estimate of the fine solution.
fn extrapolation(
    scene: &Scene,
    coarse: &Solution,
    fine: &Solution,
    seconds: f64,
) -> ExtrapolationJson {
    let gain = 1.0 / (ORDER.exp2() - 1.0);
    let mut error: f64 = 0.0;
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    let rods = coarse
        .results
        .rods
        .iter()
        .zip(&fine.results.rods)
        .map(|(c, f)| {
            let points = c
                .points
                .iter()
                .enumerate()
                .map(|(k, pc)| {
                    let pf = f.points[2 * k];
                    let d = sub(pf, *pc);
                    error = error.max(gain * norm(d));
                    for i in 0..3 {
                        lo[i] = lo[i].min(pf[i]);
                        hi[i] = hi[i].max(pf[i]);
                    }
                    add(pf, scalef(d, gain))
                })
                .collect();
            crate::io::results::ExtrapolatedRod {
                name: c.name.clone(),
                points,
            }
        })
        .collect();
    let (ec, ef) = (coarse.results.energy.total, fine.results.energy.total);
    ExtrapolationJson {
        order: ORDER,
        subdivide: scene
            .rods
            .iter()
            .map(|r| [r.subdivide, 2 * r.subdivide])
            .collect(),
        rods,
        error_estimate: error,
        relative_error_estimate: error / norm(sub(hi, lo)).max(f64::MIN_POSITIVE),
        energy: ef + gain * (ef - ec),
        coarse_iterations: coarse.results.iterations,
        fine_iterations: fine.results.iterations,
        seconds,
    }
}
