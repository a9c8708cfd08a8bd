//! The line search of a Newton step.

use super::problem::{Constraints, Core, LengthRepair, Steps};
use super::step::Second;

/// Backtracking Armijo search along x + αd + α²c for each candidate correction c (or along
/// x + αd when there is none), from the problem's largest admissible step; with constraints,
/// infeasible trials are backtracked too. Each curve's point is tried as it is and, when the
/// `repair` closure moves it (lengths restored beyond second order, `step.rs::repair_lengths`),
/// repaired. At each α the candidate with the lowest energy among those that pass is taken; a
/// later curve must beat an earlier one by a thousandth of the decrease, so that near-ties do
/// not depend on round-off (and scaled copies of a scene take the same path, tests/stiff.rs),
/// and is not tried at all where the first curve's full step agrees with Newton's model;
/// a repaired point need only beat its own curve's plain point (it is the same point with less
/// stretch, and kept only where that lowers the energy: accepted without that comparison,
/// the repair can trade stretch for more bending and twist, and slows Newton). The accepted
/// step is left in `trial` (`kept`: scratch for the best repaired point). Near convergence the
/// energy decrease falls below round-off; a relative slack of a few ulps lets Newton finish
/// there.
///
/// `trust` = (relative residual, scratch gradient) when the full step is a Newton step on a
/// positive definite Hessian near convergence. If the full step then fails the Armijo test, it
/// is still taken when it halves the residual. The energy's round-off is not a few ulps of the
/// total energy when stiff terms nearly cancel: a stretch energy ½EA(|e|/ē − 1)²ē carries an
/// error of about |N|·ε·X per edge (N the axial force, X the coordinates' size). When the
/// predicted decrease drowns in that noise, backtracking accepts whatever fraction of the step
/// the noise happens to favour and Newton creeps above the round-off floor, for a number of
/// iterations that depends on the last bits of the data; the residual is the reliable judge
/// there (docs/stiff.md section 3).
pub(super) struct Search<'a> {
    pub d: &'a [f64],
    /// The first curve's correction (None: a straight line).
    pub first: Option<&'a [f64]>,
    pub e0: f64,
    pub slope: f64,
    pub constrained: bool,
    /// The quadratic model's decrease ½|gᵀd| of a full Newton step on a positive definite
    /// Hessian (None on shifted ones, where the model is not Newton's).
    pub model_decrease: Option<f64>,
}

/// A full step on the first curve (plain or repaired) whose energy decrease agrees with
/// Newton's quadratic model to this share is taken without trying the other curves.
const MODEL_AGREEMENT: f64 = 0.1;

/// The second curve's correction: its buffer and whether it holds one (made on first use when
/// [`Second::Deferred`]).
pub(super) struct SecondCurve<'b> {
    pub buf: &'b mut [f64],
    pub state: Second,
}

impl SecondCurve<'_> {
    /// The correction, made now if it was deferred.
    fn get<P: LengthRepair>(&mut self, p: &mut P, d: &[f64]) -> Option<&[f64]> {
        if self.state == Second::Deferred {
            self.state = if p.step_correction(d, self.buf) {
                Second::Ready
            } else {
                Second::Absent
            };
        }
        (self.state == Second::Ready).then_some(&*self.buf)
    }
}

impl Search<'_> {
    fn fill(&self, c: Option<&[f64]>, alpha: f64, trial: &mut [f64]) {
        for i in 0..self.d.len() {
            trial[i] = alpha * self.d[i] + c.map_or(0.0, |c| alpha * alpha * c[i]);
        }
    }

    /// Largest α ≤ max_step(d) at which the first curve is admissible as a whole.
    fn start<P: Steps>(&self, p: &P, trial: &mut [f64]) -> f64 {
        let mut alpha = p.max_step(self.d);
        for _ in 0..60 {
            self.fill(self.first, alpha, trial);
            let m = p.max_step(trial);
            if m >= 1.0 {
                break;
            }
            alpha *= m.max(0.5);
        }
        alpha
    }

    /// Returns the accepted α (the step is in `trial`), or None.
    pub fn run<P: Core + Steps + LengthRepair + Constraints>(
        &self,
        p: &mut P,
        (trial, kept): (&mut [f64], &mut [f64]),
        second: &mut SecondCurve<'_>,
        mut trust: Option<(f64, &mut [f64])>,
        repair: &mut impl FnMut(&mut P, &mut [f64], f64) -> bool,
    ) -> Option<f64> {
        let slack = 64.0 * f64::EPSILON * self.e0.abs();
        let curves = if second.state == Second::Absent { 1 } else { 2 };
        let mut alpha = self.start(p, trial);
        for _ in 0..60 {
            // (curve, repaired, energy) of the best candidate so far.
            let mut best: Option<(usize, bool, f64)> = None;
            for k in 0..curves {
                // The first curve's best point agrees with the model: skip the others.
                if k > 0 && alpha == 1.0 {
                    let agrees = |(_, _, e): (usize, bool, f64)| {
                        self.model_decrease
                            .is_some_and(|m| ((self.e0 - e) / m - 1.0).abs() <= MODEL_AGREEMENT)
                    };
                    if best.is_some_and(agrees) {
                        break;
                    }
                }
                let c = if k == 0 {
                    self.first
                } else {
                    match second.get(p, self.d) {
                        Some(c) => Some(c),
                        None => break,
                    }
                };
                for repaired in [false, true] {
                    self.fill(c, alpha, trial);
                    if repaired && !repair(p, trial, alpha) {
                        continue;
                    }
                    if (k > 0 || repaired) && p.max_step(trial) < 1.0 {
                        continue;
                    }
                    if self.constrained && !p.feasible(trial) {
                        continue;
                    }
                    let e = p.trial_energy(trial, 1.0);
                    let margin = |bk: usize| if bk == k { 0.0 } else { 1e-3 };
                    if e.is_finite()
                        && e <= self.e0 + 1e-4 * alpha * self.slope.min(0.0) + slack
                        && best.is_none_or(|(bk, _, b)| e < b - margin(bk) * (self.e0 - b).abs())
                    {
                        best = Some((k, repaired, e));
                        if repaired {
                            kept.copy_from_slice(trial);
                        }
                    }
                    if k == 0 && !repaired && best.is_none() {
                        if let Some((res, g)) = trust.take() {
                            if alpha == 1.0 && e.is_finite() {
                                p.trial_gradient(trial, 1.0, g);
                                if p.relative_residual(g) < 0.5 * res {
                                    return Some(alpha);
                                }
                            }
                        }
                    }
                }
            }
            if let Some((k, repaired, _)) = best {
                if repaired {
                    trial.copy_from_slice(kept);
                } else if k == 0 {
                    self.fill(self.first, alpha, trial);
                } else {
                    self.fill(second.get(p, self.d), alpha, trial);
                }
                return Some(alpha);
            }
            alpha *= 0.5;
        }
        None
    }
}
