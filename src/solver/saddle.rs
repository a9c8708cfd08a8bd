//! Newton's method on the residual alone, for equilibria of any index (`rodnet states`' search
//! for unstable states): steps from an LDLᵀ factorization of the Hessian as it is (indefinite
//! at a saddle), a backtracking line search on ‖g‖² instead of the energy, and no saddle escape.
//! It converges to the equilibrium nearest its start whatever its stability; a symmetric start
//! (a straight column) keeps its symmetry, where the energy-decreasing iteration would leave it.

use super::linalg::AnalysisCache;
use super::newton::Newton;
use super::problem::NewtonProblem;
use super::settings::{NewtonReport, NewtonSettings};
use super::spectrum::newton_for;

/// Iterations before the search gives up: a start that is not already near an equilibrium is
/// not one this search is for.
const MAX_ITERATIONS: usize = 60;
/// Armijo constant of the residual line search.
const DECREASE: f64 = 1e-4;
const MIN_STEP: f64 = 1e-10;
/// Relative residual below which the round-off floor is measured (as `newton.rs` does).
const FLOOR_CHECK: f64 = 1e-2;

/// Converges from the problem's current state at each continuation parameter of `path` in
/// turn, each from the last (one workspace, one symbolic analysis, for the whole path); the
/// report is the last solve's (or the first that did not converge), with the work of all. The
/// pattern's analysis is taken from, or kept in, `analyses`.
pub fn converge_any<P: NewtonProblem>(
    p: &mut P,
    settings: &NewtonSettings,
    path: &[f64],
    analyses: &AnalysisCache,
) -> NewtonReport {
    let mut nt = newton_for(p, settings.ordering, analyses);
    let mut report = NewtonReport::default();
    let (mut iterations, mut factorizations, mut seconds) = (0, 0, 0.0);
    for &lambda in path {
        report = converge_at(p, &mut nt, settings, lambda);
        iterations += report.iterations;
        factorizations += report.factorizations;
        seconds += report.seconds;
        if !report.converged {
            break;
        }
    }
    report.iterations = iterations;
    report.factorizations = factorizations;
    report.seconds = seconds;
    report
}

fn converge_at<P: NewtonProblem>(
    p: &mut P,
    nt: &mut Newton,
    settings: &NewtonSettings,
    lambda: f64,
) -> NewtonReport {
    let t0 = std::time::Instant::now();
    p.set_continuation(lambda);
    let mut report = NewtonReport {
        tolerance: settings.tolerance,
        ..Default::default()
    };
    let mut floor = 0.0;
    loop {
        report.energy = p.assemble(&mut nt.g, Some(&mut nt.chol.values));
        report.residual = p.relative_residual(&nt.g);
        if !report.energy.is_finite() || !report.residual.is_finite() {
            report.message = Some("non-finite energy or residual".into());
            break;
        }
        // Below the residual that rounding the unknowns alone makes, the ‖g‖² line search
        // accepts steps on noise without ending: measure it once the residual is small.
        if floor == 0.0 && report.residual < FLOOR_CHECK {
            floor = p.residual_floor(&nt.g);
        }
        if report.residual <= settings.tolerance.max(floor) {
            report.converged = true;
            report.stopped_at_floor = report.residual > settings.tolerance;
            break;
        }
        if report.iterations >= MAX_ITERATIONS {
            report.message = Some(format!(
                "no equilibrium within {MAX_ITERATIONS} residual-Newton iterations (relative \
                 residual {:.3e})",
                report.residual
            ));
            break;
        }
        report.factorizations += 1;
        if nt.chol.factor_ldlt().is_err() {
            report.message = Some("the Hessian is singular here".into());
            break;
        }
        let mut d: Vec<f64> = nt.g.iter().map(|v| -v).collect();
        nt.chol.solve_ldlt(&mut d);
        let phi0: f64 = nt.g.iter().map(|v| v * v).sum();
        let mut alpha = p.max_step(&d).min(1.0);
        let accepted = loop {
            if alpha < MIN_STEP {
                break false;
            }
            let e = p.trial_gradient(&d, alpha, &mut nt.g_trial);
            let phi: f64 = nt.g_trial.iter().map(|v| v * v).sum();
            if e.is_finite() && phi <= (1.0 - DECREASE * alpha) * phi0 {
                break true;
            }
            alpha *= 0.5;
        };
        if !accepted {
            // At the round-off floor no step lowers the residual: measure it once, then stop
            // there if that is where the iteration is.
            let f = p.residual_floor(&nt.g);
            if floor < 10.0 * f && report.residual <= 10.0 * f {
                floor = 10.0 * f;
                continue;
            }
            report.message = Some(format!(
                "the residual line search stalled at relative residual {:.3e}",
                report.residual
            ));
            break;
        }
        p.accept(&d, alpha);
        report.iterations += 1;
    }
    report.residual_floor = floor;
    super::verdict::meaningful(&mut report);
    report.seconds = t0.elapsed().as_secs_f64();
    report
}
