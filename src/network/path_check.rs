//! `rodnet buckle`'s check of its first linear factor along the nonlinear load path: where the
//! lowest eigenvalue of the tangent stiffness reaches zero, and what kind of loss of stability
//! that is: a clean bifurcation of the path, a crossing approached from below, an imperfect
//! bifurcation (a positive minimum), or none at all (a load whose path stays stable: the linear
//! factor is no buckling load).

use super::problem::NetworkProblem;
use super::zero_stiffness::mean_edge;
use super::Network;
use crate::solver::path_events::EventKind;
use crate::solver::problem::{ContinuationPath, Snapshots};
use crate::solver::spectrum;
use crate::solver::{NewtonSettings, Ordering};

/// What the path check found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PathKind {
    /// The path's solve left a saddle between two samples: a clean bifurcation, located where
    /// the escape direction's stiffness crosses zero (`solver::path_events`).
    Bifurcation,
    /// The lowest eigenvalue, falling, extrapolated to zero from below.
    Crossing,
    /// The lowest eigenvalue falls below half its unloaded value and rises again without
    /// crossing zero: the path turns smoothly (an imperfect bifurcation); no critical factor.
    Imperfect,
    /// The lowest eigenvalue does not fall toward zero along the path, or dips by less than
    /// half and rises again: the loads do not make the structure buckle there, and the linear
    /// factor is no buckling load.
    NoBuckling,
    /// A path solve failed or the search ran out of solves: undecided.
    Unresolved,
}

impl PathKind {
    pub fn name(self) -> &'static str {
        match self {
            PathKind::Bifurcation => "bifurcation",
            PathKind::Crossing => "crossing",
            PathKind::Imperfect => "imperfect_bifurcation",
            PathKind::NoBuckling => "no_buckling",
            PathKind::Unresolved => "unresolved",
        }
    }
}

/// Where the lowest eigenvalue of the tangent stiffness crosses zero along the nonlinear load
/// path (the check of a linear factor, or the critical factor where the structure deforms
/// before it buckles).
#[derive(Debug, Clone)]
pub struct PathCritical {
    /// The critical factor on the path (kinds `Bifurcation` and `Crossing`), else None.
    pub factor: Option<f64>,
    pub kind: PathKind,
    /// (load factor, lowest eigenvalue in N/m) at each equilibrium solved on the way.
    pub samples: Vec<(f64, f64)>,
    /// Newton iterations of those solves.
    pub iterations: usize,
    /// Why the search stopped without a crossing (a failed solve, no approach to zero).
    pub note: Option<String>,
}

/// Follows the load path from the rest state toward `guess` (the linear factor), solving the
/// equilibrium at load factors below the crossing and extrapolating the lowest eigenvalue to
/// zero by secants, from below: past the crossing a symmetric structure leaves its path (the
/// solver escapes the saddle) and its eigenvalue rises again. A rise after a fall is taken as
/// such an overshoot: the solve is redone from the last sample with half the increment.
pub fn critical_on_path(net: &mut Network, settings: &NewtonSettings, guess: f64) -> PathCritical {
    let ebar = mean_edge(&net.model);
    let mut p = NetworkProblem::of_network(net);
    let mut out = PathCritical {
        factor: None,
        kind: PathKind::Unresolved,
        samples: Vec::new(),
        iterations: 0,
        note: None,
    };
    match search(&mut p, settings, guess, ebar, &mut out) {
        Ok((kind, f)) => (out.kind, out.factor) = (kind, Some(f)),
        Err((kind, e)) => (out.kind, out.note) = (kind, Some(e)),
    }
    out
}

/// The lowest eigenvalue (N/m) of the problem's Hessian at its current state.
fn lowest(p: &mut NetworkProblem, ebar: f64) -> Result<f64, String> {
    let analyses = p.model.analyses.clone();
    let sp = spectrum::lowest_modes(p, 2, Ordering::Auto, &analyses)?;
    Ok(sp.values.first().copied().unwrap_or(f64::INFINITY) / (ebar * ebar))
}

fn search(
    p: &mut NetworkProblem,
    settings: &NewtonSettings,
    guess: f64,
    ebar: f64,
    out: &mut PathCritical,
) -> Result<(PathKind, f64), (PathKind, String)> {
    let unresolved = |e: String| (PathKind::Unresolved, e);
    p.set_continuation(0.0);
    let mut at = (0.0, lowest(p, ebar).map_err(unresolved)?, p.snapshot());
    out.samples.push((at.0, at.1));
    let mut falling = false;
    let mut next = 0.5 * guess;
    let mut last_root = f64::NAN;
    let horizon = (2.0 * guess).max(1.0);
    for _ in 0..PATH_SOLVES {
        let (lam, f0) = (at.0, at.1);
        p.set_load_range(lam, next);
        let r = p.solve(settings);
        out.iterations += r.iterations;
        if !r.converged {
            return Err(unresolved(format!(
                "the path solve from load factor {lam:.6e} to {next:.6e} did not converge: {}",
                r.message.unwrap_or_default()
            )));
        }
        // The solve left a saddle: the path bifurcated within it, where its event says.
        if let Some(e) = r
            .path_events
            .iter()
            .find(|e| e.kind == EventKind::Bifurcation)
        {
            return Ok((PathKind::Bifurcation, lam + e.load_factor * (next - lam)));
        }
        let f = lowest(p, ebar).map_err(unresolved)?;
        if f <= 0.0 {
            out.samples.push((next, f));
            return Ok((PathKind::Crossing, lam + (next - lam) * f0 / (f0 - f)));
        }
        if falling && f > f0 {
            if next - lam > 1e-4 * lam {
                // Left the path past the crossing: back to the last sample, half the increment.
                p.restore(&at.2);
                next = lam + 0.5 * (next - lam);
                continue;
            }
            // Rising even over the smallest increment: the eigenvalue has a positive minimum.
            // A dip to less than half the unloaded stiffness is a buckling mode the loads
            // soften and the path turns past (imperfect); a shallower one is a stiffness the
            // loads barely touch, no buckling at all.
            let start = out.samples[0].1;
            if f0 > IMPERFECT_DIP * start {
                return Err((
                    PathKind::NoBuckling,
                    format!(
                        "the lowest eigenvalue stays above {IMPERFECT_DIP} of its unloaded value \
                         along the path (from {start:.3e} N/m to at least {f0:.3e} N/m, at load \
                         factor {lam:.6e}, then rising): no buckling there"
                    ),
                ));
            }
            return Err((
                PathKind::Imperfect,
                format!(
                "the lowest eigenvalue falls to {f0:.3e} N/m at load factor {lam:.6e} and rises \
                 again without crossing zero (an imperfect bifurcation: the path turns smoothly)"
            ),
            ));
        }
        out.samples.push((next, f));
        falling = f < f0;
        let root = next - f * (next - lam) / (f - f0);
        at = (next, f, p.snapshot());
        if !(falling && root.is_finite() && root > next) {
            if next >= horizon {
                return Err((
                    PathKind::NoBuckling,
                    format!(
                        "the lowest eigenvalue does not fall toward zero along the path (checked \
                         up to load factor {next:.6e}): no buckling there"
                    ),
                ));
            }
            next = (2.0 * next).min(horizon);
            last_root = f64::NAN;
            continue;
        }
        if (root - last_root).abs() <= 1e-6 * root {
            return Ok((PathKind::Crossing, root));
        }
        last_root = root;
        // A far extrapolation from a nearly flat eigenvalue is not trusted: at most ×4 per solve.
        next = (at.0 + APPROACH * (root - at.0)).min(4.0 * at.0);
    }
    Err(unresolved(format!(
        "no crossing within {PATH_SOLVES} path solves"
    )))
}

/// The share of its unloaded value that the lowest eigenvalue must fall below, before it rises
/// again, for the path to be an imperfect bifurcation rather than no buckling at all.
const IMPERFECT_DIP: f64 = 0.5;

/// Path solves of `critical_on_path` before it gives up.
const PATH_SOLVES: usize = 30;
/// Fraction of the way to the extrapolated crossing that each path solve goes.
const APPROACH: f64 = 0.9;
