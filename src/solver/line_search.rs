//! The line search of a Newton step.

use super::problem::NewtonProblem;

/// Backtracking Armijo search along x + αd (+ α²c when a correction is given), from the
/// problem's largest admissible step; with constraints, infeasible trials are backtracked too.
/// The accepted step is left in `trial`. Near convergence the energy decrease falls below
/// round-off; a relative slack of a few ulps lets Newton finish there.
///
/// `trust` = (relative residual, scratch gradient) when the full step is a Newton step on a
/// positive definite Hessian near convergence. If the full step then fails the Armijo test, it
/// is still taken when it halves the residual. The energy's round-off is not a few ulps of the
/// total energy when stiff terms nearly cancel: a stretch energy ½EA(|e|/ē − 1)²ē carries an
/// error of about |N|·ε·X per edge (N the axial force, X the coordinates' size). When the
/// predicted decrease drowns in that noise, backtracking accepts whatever fraction of the step
/// the noise happens to favour and Newton creeps above the round-off floor, for a number of
/// iterations that depends on the last bits of the data; the residual is the reliable judge
/// there (docs/stiff.md section 3, `networks/extreme/nitinol_cross.ron`).
#[allow(clippy::too_many_arguments)]
pub(super) fn line_search<P: NewtonProblem>(
    p: &mut P,
    d: &[f64],
    c: Option<&[f64]>,
    e0: f64,
    slope: f64,
    trial: &mut [f64],
    constrained: bool,
    mut trust: Option<(f64, &mut [f64])>,
) -> Option<f64> {
    let slack = 64.0 * f64::EPSILON * e0.abs();
    let fill = |alpha: f64, trial: &mut [f64]| {
        for i in 0..d.len() {
            trial[i] = alpha * d[i] + c.map_or(0.0, |c| alpha * alpha * c[i]);
        }
    };
    fill(1.0, trial);
    let mut alpha = p.max_step(trial);
    for _ in 0..60 {
        fill(alpha, trial);
        if constrained && !p.feasible(trial) {
            alpha *= 0.5;
            continue;
        }
        let e = p.trial_energy(trial, 1.0);
        if e.is_finite() && e <= e0 + 1e-4 * alpha * slope.min(0.0) + slack {
            return Some(alpha);
        }
        if let Some((res, g)) = trust.take() {
            if alpha == 1.0 && e.is_finite() {
                p.trial_gradient(trial, 1.0, g);
                if p.relative_residual(g) < 0.5 * res {
                    return Some(alpha);
                }
            }
        }
        alpha *= 0.5;
    }
    None
}
