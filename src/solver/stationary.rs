//! What Newton does where it stops moving: at a stationary point (converged, or stalled at the
//! round-off floor) and after a line search that found no step. Either the state gets its
//! stability verdict (stable on an unshifted factor or up to gauge modes, else unstable or
//! undecided), or a saddle is left along negative curvature and the iterations go on.

use super::newton::{Limits, Newton, Outcome, TRUSTED_RESIDUAL};
use super::problem::NewtonProblem;
use super::regularize::Saddle;

/// Why a stationary point is not called stable although no saddle escape left it.
const UNDECIDED: &str = "stability not decided: the energy's Hessian has negative curvature \
    that the dead moments' non-symmetric stiffness may remove (a dead moment is not \
    conservative for 3-D rotations; the state is an equilibrium, and the energy cannot judge \
    its stability)";

impl Newton {
    /// The verdict at a stationary point (converged, or stalled below the floor): stable on an
    /// unshifted factor, else leave a saddle (Ok: iterate on) or judge its zero modes.
    pub(super) fn at_stationary<P: NewtonProblem>(
        &mut self,
        p: &mut P,
        lim: &Limits,
        (e0, res, qp_shift): (f64, f64, Option<f64>),
        escapes: &mut usize,
    ) -> Result<(), Outcome> {
        let Some(shift) = qp_shift.or_else(|| self.factor_regularized()) else {
            return Err(Outcome::Failed(format!(
                "Hessian could not be regularized (residual {res:.3e})"
            )));
        };
        if shift == 0.0 {
            if lim.judge_stability {
                self.report.stable = self.stable_unshifted(p);
            }
            return Err(settled(res, lim));
        }
        match self.escape_saddle(p, e0) {
            Saddle::ZeroModesOnly => {
                if lim.judge_stability {
                    self.report.stable = self.gauge_modes_only(p);
                }
                Err(settled(res, lim))
            }
            Saddle::Escaped if *escapes < 8 => {
                *escapes += 1;
                self.report.saddle_escapes += 1;
                Ok(())
            }
            Saddle::Undecided => {
                self.report.stable = false;
                self.report.stability_note = Some(UNDECIDED.into());
                Err(settled(res, lim))
            }
            _ => {
                self.report.stable = false;
                Err(settled(res, lim))
            }
        }
    }

    /// Whether the equilibrium whose unshifted Hessian is factored is stable: a singular
    /// Hessian can factor behind a round-off pivot, so near-singular factors are checked for
    /// modes other than the gauges.
    pub(super) fn stable_unshifted<P: NewtonProblem>(&mut self, p: &mut P) -> bool {
        let gauges = p.gauge_modes();
        let singular = self.near_singular(&gauges);
        self.report.zero_modes = 0;
        !singular || self.gauge_modes_only(p)
    }

    /// When no step length passes: energy differences below round-off, or a saddle. Err ends
    /// the iterations with that outcome. `corrected`: `c` holds the step's first correction,
    /// left there by the failed search.
    pub(super) fn after_failed_search<P: NewtonProblem>(
        &mut self,
        p: &mut P,
        (e0, shift, res, floor, corrected): (f64, f64, f64, f64, bool),
        judge: bool,
        escapes: &mut usize,
    ) -> Result<(), Outcome> {
        // Judge the full step by its residual.
        let n = self.d.len();
        for i in 0..n {
            self.trial[i] = self.d[i] + if corrected { self.c[i] } else { 0.0 };
        }
        p.trial_gradient(&self.trial, 1.0, &mut self.g_trial);
        let res_trial = p.relative_residual(&self.g_trial);
        // Only where the Hessian is positive definite (a convex model: reducing the residual
        // approaches a minimum, not a saddle) and the residual is small. (With constraint forces
        // the plain gradient is no residual: never trusted.)
        let trusted = self.on_newton_model(shift) && res < TRUSTED_RESIDUAL;
        let failed =
            || Outcome::Failed(format!("line search failed (relative residual {res:.3e})"));
        if trusted && res_trial < 0.9 * res && p.max_step(&self.trial) >= 1.0 {
            p.accept(&self.trial, 1.0);
            Ok(())
        } else if shift > 0.0 && *escapes < 8 {
            // No descent along the regularized Newton step near a stationary point of an
            // indefinite Hessian: leave along negative curvature instead.
            match self.escape_saddle(p, e0) {
                Saddle::Escaped => {
                    *escapes += 1;
                    self.report.saddle_escapes += 1;
                    Ok(())
                }
                Saddle::ZeroModesOnly if res < floor => {
                    if judge {
                        self.report.stable = self.gauge_modes_only(p);
                    }
                    Err(Outcome::AtFloor)
                }
                _ if res < floor => {
                    self.report.stable = false;
                    Err(Outcome::AtFloor)
                }
                _ => Err(failed()),
            }
        } else if res < floor {
            // Round-off stalled Newton below the floor.
            self.report.stable = shift == 0.0;
            Err(Outcome::AtFloor)
        } else {
            Err(failed())
        }
    }
}

/// The outcome at a stationary point with residual `res`: converged, or at the round-off floor.
pub(super) fn settled(res: f64, lim: &Limits) -> Outcome {
    if res < lim.tolerance {
        Outcome::Converged
    } else {
        Outcome::AtFloor
    }
}
