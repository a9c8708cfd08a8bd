//! `rodnet solve --extrapolate`: the scene solved at its own subdivision and at twice it (and,
//! with `--levels 3`, four times it), and the Richardson extrapolate of the solves
//! (docs/convergence.md, "One run extrapolated").
//!
//! With two levels the error is taken to be O(h²), which Discrete Elastic Rods have in general:
//! with the coarse solution x_h and the fine one x_{h/2} at the coarse nodes (node k of the
//! coarse rod is node 2k of the fine one), x_{h/2} + (x_{h/2} − x_h)/3 removes the h² term, and
//! |x_{h/2} − x_h|/3 estimates the fine solution's own error. Where the end-corrected weights
//! leave no h² term (linear frames whose rods end at clamps and joints) the error is O(h³) and
//! that over-corrects; three levels remove the h² and the h³ terms together, whichever
//! dominates, and measure the order. Each finer solve starts from the coarser equilibrium,
//! refined (midpoints inserted), and is Newton at the full loads from there: a few iterations
//! where the coarse path took many.

use std::time::Instant;

use crate::io::results::ExtrapolationJson;
use crate::math::vec::{add, norm, scalef, sub};
use crate::network::initial::RodState;
use crate::pipeline::{self, JobError, Solution};
use crate::scene::Scene;
use crate::solver::NewtonSettings;

/// Order of the discretization error that the two-level extrapolation removes.
pub const ORDER: f64 = 2.0;

/// Solves `scene` as given and with every rod's subdivision doubled; the fine solution is
/// returned with its results' `extrapolation` block filled (two levels).
pub fn solve(scene: &Scene, settings: &NewtonSettings) -> Result<Solution, JobError> {
    solve_levels(scene, settings, 2)
}

/// Solves `scene` at `levels` (2 or 3) subdivisions, ×1, ×2 (and ×4); the finest solution is
/// returned with its results' `extrapolation` block filled. When a coarser solve does not
/// converge it is returned as it is (no extrapolation of a state that is not an equilibrium).
pub fn solve_levels(
    scene: &Scene,
    settings: &NewtonSettings,
    levels: usize,
) -> Result<Solution, JobError> {
    if !(2..=3).contains(&levels) {
        return Err(JobError::Refused(format!(
            "{levels} levels: the extrapolation uses 2 or 3"
        )));
    }
    // A staged scene is solved through its stages at every level, from rest: its last stage is
    // extrapolated (a restart would need every stage's refined state).
    let staged = !scene.stages.is_empty();
    let solve_level = |sc: &Scene, coarser: Option<&Solution>| match coarser {
        _ if staged => pipeline::solve_stages(sc, settings, |_| {}).map_err(JobError::Scene),
        None => pipeline::solve_scene(sc, settings).map_err(JobError::Scene),
        Some(c) => solve_refined(sc, c, settings),
    };
    // A refusal of a refined level (its memory estimate) says which level it is.
    let at_level = |k: usize| {
        move |e: JobError| match e {
            JobError::Scene(mut f) if k > 0 => {
                f.message = format!(
                    "{} (at ×{} the subdivision: level {} of --extrapolate)",
                    f.message,
                    1 << k,
                    k + 1
                );
                JobError::Scene(f)
            }
            e => e,
        }
    };
    // The finest level is the largest: its lower bound is checked before any solve.
    let finest = (1..levels).fold(scene.clone(), |s, _| refined(&s));
    pipeline::check_scene_memory(&finest, settings.memory_limit)
        .map_err(JobError::Scene)
        .map_err(at_level(levels - 1))?;
    let t0 = Instant::now();
    let mut solves = vec![solve_level(scene, None)?];
    let mut level_scene = scene.clone();
    for k in 1..levels {
        let last = solves.last().unwrap();
        if !last.results.converged || !last.results.all_finite() {
            return Ok(solves.pop().unwrap());
        }
        level_scene = refined(&level_scene);
        let next = solve_level(&level_scene, Some(last)).map_err(at_level(k))?;
        solves.push(next);
    }
    let seconds = t0.elapsed().as_secs_f64();
    let mut finest = solves.pop().unwrap();
    if finest.results.converged && finest.results.all_finite() {
        let mut levels: Vec<&Solution> = solves.iter().collect();
        levels.push(&finest);
        let x = extrapolation(scene, &levels, seconds);
        finest.results.extrapolation = Some(x);
    }
    Ok(finest)
}

/// The refined scene solved from the coarser solution, refined.
fn solve_refined(
    fine_scene: &Scene,
    coarse: &Solution,
    settings: &NewtonSettings,
) -> Result<Solution, JobError> {
    // The restart keeps the turns the coarse angles carry (`Model::nearest_turns`: every
    // discrete twist within half a turn of its rest value, which a refined state of a converged
    // coarse one has).
    let start = refined_state(&crate::io::initial::of_results(&coarse.results));
    pipeline::solve_scene_from(fine_scene, settings, &start)
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

/// Richardson's step for an error of order `p` between a coarser and a finer value (h, h/2).
fn richardson<const N: usize>(coarse: [f64; N], fine: [f64; N], p: f64) -> [f64; N] {
    let gain = 1.0 / (p.exp2() - 1.0);
    std::array::from_fn(|i| fine[i] + gain * (fine[i] - coarse[i]))
}

/// The extrapolate of values at h, h/2 (and h/4): order 2 from two, orders 2 and 3 from three.
/// Returns it and, with three levels, the two-level extrapolate of the finer pair (the
/// difference of the two estimates the extrapolate's own error).
fn extrapolate<const N: usize>(values: &[[f64; N]]) -> ([f64; N], Option<[f64; N]>) {
    match values {
        [a, b] => (richardson(*a, *b, ORDER), None),
        [a, b, c] => {
            let (r1, r2) = (richardson(*a, *b, 2.0), richardson(*b, *c, 2.0));
            (richardson(r1, r2, 3.0), Some(r2))
        }
        _ => unreachable!("2 or 3 levels"),
    }
}

/// The extrapolate at the coarse nodes, with the error estimate of the finest solution.
fn extrapolation(scene: &Scene, levels: &[&Solution], seconds: f64) -> ExtrapolationJson {
    let n = levels.len();
    let finest = levels[n - 1];
    let (mut error, mut own_error): (f64, f64) = (0.0, 0.0);
    // The largest change between consecutive levels, for the observed order.
    let mut change = vec![0.0f64; n - 1];
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    let rods = levels[0]
        .results
        .rods
        .iter()
        .enumerate()
        .map(|(ri, c)| {
            let points = (0..c.points.len())
                .map(|k| {
                    let at: Vec<[f64; 3]> = (0..n)
                        .map(|l| levels[l].results.rods[ri].points[k << l])
                        .collect();
                    for l in 0..n - 1 {
                        change[l] = change[l].max(norm(sub(at[l + 1], at[l])));
                    }
                    let pf = at[n - 1];
                    let (x, finer_pair) = extrapolate(&at);
                    error = error.max(norm(sub(pf, x)));
                    if let Some(r) = finer_pair {
                        own_error = own_error.max(norm(sub(x, r)));
                    }
                    for i in 0..3 {
                        lo[i] = lo[i].min(pf[i]);
                        hi[i] = hi[i].max(pf[i]);
                    }
                    x
                })
                .collect();
            crate::io::results::ExtrapolatedRod {
                name: c.name.clone(),
                points,
            }
        })
        .collect();
    let energies: Vec<[f64; 1]> = levels.iter().map(|s| [s.results.energy.total]).collect();
    let three = n == 3;
    let observed = (three && change[1] > 0.0).then(|| (change[0] / change[1]).log2());
    ExtrapolationJson {
        order: if three { 3.0 } else { ORDER },
        subdivide: scene
            .rods
            .iter()
            .map(|r| [r.subdivide, r.subdivide << (n - 1)])
            .collect(),
        rods,
        error_estimate: error,
        relative_error_estimate: error / norm(sub(hi, lo)).max(f64::MIN_POSITIVE),
        energy: extrapolate(&energies).0[0],
        coarse_iterations: levels[0].results.iterations,
        fine_iterations: finest.results.iterations,
        seconds,
        levels: n,
        middle_iterations: three.then(|| levels[1].results.iterations),
        observed_order: observed.filter(|p| p.is_finite()),
        extrapolate_error_estimate: three.then_some(own_error),
    }
}
