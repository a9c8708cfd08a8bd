//! Newton iterations at a fixed continuation parameter.
//!
//! Each iteration factors the exact Hessian with a sparse Cholesky (symbolic analysis reused). If
//! the Hessian is not positive definite, a diagonal shift is added (`regularize.rs`: modified
//! Newton, the step stays a descent direction). A line search on the energy follows along a
//! curve that corrects the step's length error (`step.rs`, `line_search.rs`). At a stationary
//! point whose Hessian is not positive definite, the direction of most negative curvature is
//! followed downhill, so a perfectly straight compressed rod buckles instead of stalling at the
//! saddle.
//!
//! A problem with inequality constraints (contact, bounds) replaces the Cholesky step by a QP
//! with the same shifted Hessian whenever the unconstrained step would violate a linearized
//! constraint (see `qp.rs` and docs/design.md); without constraints nothing of that runs.
//!
//! The path from λ = 0 to 1 (load steps, adaptive sub-steps) is in `continuation.rs`.

use std::time::Instant;

use super::linalg::SparseCholesky;
use super::line_search::{Search, SecondCurve};
use super::problem::{Core, NewtonProblem};
use super::qp::StepQp;
use super::settings::{NewtonReport, NewtonSettings};
use super::stationary::settled;
use super::step::{repair_lengths, Second};

/// Relative residual below which a full Newton step on a positive definite Hessian may be
/// accepted for reducing the residual when the Armijo test cannot resolve the energy change.
pub(super) const TRUSTED_RESIDUAL: f64 = 1e-4;
/// A full, unshifted Newton step at most this large in the unknowns' scales (edge lengths,
/// radians) moves nothing that matters: below the round-off floor, Newton takes it without a
/// line search and stops instead of assembling once more to see round-off stall the residual
/// (and after such a step taken above the floor, it stops at the next iterate below the floor).
/// Quadratic convergence makes the next step of the order of its square; a soft mode's
/// correction, which the residual below the floor cannot see, is a step of its own size (on a
/// slender rod it can move the tip by 1e-9 of the rod's length, thousands of edge lengths
/// times this).
const NEGLIGIBLE_STEP: f64 = 1e-10;
/// Relative residual below which the round-off floor is measured (once per `iterate`): above
/// it, no floor of a sane problem matters, and measuring costs two gradient evaluations.
const FLOOR_CHECK: f64 = 1e-2;

/// An attempt at its cap goes on while the quadratic model's remaining decrease (½·gᵀH⁻¹g) is at
/// most this many times the last iteration's energy decrease: it is converging, and retrying it
/// with a smaller increment would discard that progress (`Newton::converging`).
const CONVERGING_ITERATIONS: f64 = 4.0;
/// A step whose model decrease is below this share of the recent decreases finds the energy
/// converged: what is left is in the residual alone.
const ENERGY_CONVERGED: f64 = 1e-2;

/// An attempt that may be retried gives up after this many steps in a row on which the shift
/// carries more than half the step's curvature: far in an indefinite region, a smaller
/// increment is cheaper.
const INDEFINITE_STEPS: usize = 3;

/// How Newton iterations at one continuation parameter ended.
pub(super) enum Outcome {
    /// Residual below the tolerance.
    Converged,
    /// Round-off stalled Newton below the residual floor but above the tolerance: as close to
    /// equilibrium as floating point allows, but not the tolerance asked for.
    AtFloor,
    /// The iteration budget or the time limit ran out (`cap` or `deadline`).
    Budget(String),
    Failed(String),
    /// A zero-stiffness mode that the loads excite (its description).
    Mechanism(String),
}

/// Limits of one call of `Newton::iterate`.
pub(super) struct Limits {
    pub tolerance: f64,
    pub cap: usize,
    /// Up to this many iterations an attempt that is converging may go past `cap`.
    pub extended_cap: usize,
    pub deadline: Option<Instant>,
    /// Give up after four damped steps in a row (a sub-step that a smaller increment can
    /// retry more cheaply).
    pub retry_on_damping: bool,
    /// Intermediate states only: a full, unregularized Newton step no larger than this (in the
    /// unknowns' scales) ends the attempt after it is taken, without assembling again.
    pub step_tolerance: Option<f64>,
    /// Whether the state the iterations end at is judged for stability (`stable_unshifted`,
    /// `gauge_modes_only`): not a state that only starts the next sub-step of the same path,
    /// whose verdict the final state's replaces. The judgement is a block inverse iteration of
    /// up to 120 solves, on long chains tens of factorizations' worth per sub-step
    /// (docs/performance.md). The saddle escape is still tried: it changes the path.
    pub judge_stability: bool,
}

pub(super) struct Newton {
    pub(super) chol: SparseCholesky,
    /// The step QP, only for problems with constraints.
    pub(super) qp: Option<StepQp>,
    /// Scratch for the KKT stationarity residual (constrained problems only).
    pub(super) r: Vec<f64>,
    /// The current step came from the QP (some constraint would be violated without it).
    pub(super) qp_used: bool,
    pub(super) g: Vec<f64>,
    pub(super) d: Vec<f64>,
    pub(super) c: Vec<f64>,
    /// A second candidate correction (see `corrections`).
    pub(super) c2: Vec<f64>,
    pub(super) trial: Vec<f64>,
    /// Scratch force of the line search's length repair (`step.rs::repair_lengths`) and the
    /// best repaired trial point.
    pub(super) f_repair: Vec<f64>,
    pub(super) c_repaired: Vec<f64>,
    /// Scratch gradient for judging a full step by its residual.
    pub(super) g_trial: Vec<f64>,
    /// Characteristic size s of each unknown (`NewtonProblem::unknown_scales`) and the shift
    /// weights 1/s²: regularizing H + τ·diag(1/s²) is regularizing the Hessian of the
    /// dimensionless unknowns q/s by τ·I, so a scene and its copy scaled in length or modulus
    /// take the same steps. (With a uniform shift, a length scale λ multiplies the position
    /// rows of H by λ and the angle rows by λ³, so the same relative shift would damp angles
    /// and positions differently at every scale; docs/stiff.md section 3.)
    pub(super) scales: Vec<f64>,
    pub(super) weights: Vec<f64>,
    pub(super) shift_memory: f64,
    /// The first saddle escape since it was last taken: its direction (W-normalized) and the
    /// curvature along it (`path_events`: where the path bifurcated).
    pub(super) escaped: Option<(Vec<f64>, f64)>,
    /// The last converged sub-step of the path escaped a saddle.
    pub(super) leaving_path: bool,
    pub(super) report: NewtonReport,
}

/// What `Newton::iterate` carries from one iteration to the next.
struct Tally {
    it: usize,
    escapes: usize,
    damped: usize,
    indefinite: usize,
    last_res: f64,
    /// Scaled size of the last step if it was a full, unshifted Newton step.
    last_step: f64,
    last_energy: f64,
    prev_energy: f64,
    floor: Option<f64>,
}

impl Default for Tally {
    fn default() -> Tally {
        Tally {
            it: 0,
            escapes: 0,
            damped: 0,
            indefinite: 0,
            last_res: f64::INFINITY,
            last_step: f64::INFINITY,
            last_energy: f64::INFINITY,
            prev_energy: f64::INFINITY,
            floor: None,
        }
    }
}

impl Newton {
    pub(super) fn new(chol: SparseCholesky, qp: Option<StepQp>, n: usize) -> Newton {
        let m = qp.is_some();
        Newton {
            chol,
            qp,
            r: vec![0.0; if m { n } else { 0 }],
            qp_used: false,
            g: vec![0.0; n],
            d: vec![0.0; n],
            c: vec![0.0; n],
            c2: vec![0.0; n],
            trial: vec![0.0; n],
            f_repair: vec![0.0; n],
            c_repaired: vec![0.0; n],
            g_trial: vec![0.0; n],
            scales: vec![1.0; n],
            weights: vec![1.0; n],
            shift_memory: 0.0,
            escaped: None,
            leaving_path: false,
            report: NewtonReport::default(),
        }
    }

    /// Newton iterations at the current continuation parameter until convergence, the floor,
    /// failure, or the limits. `step` names the load step in progress callbacks.
    pub(super) fn iterate<P: NewtonProblem>(
        &mut self,
        p: &mut P,
        s: &NewtonSettings,
        lim: &Limits,
        step: usize,
    ) -> Outcome {
        let mut t = Tally::default();
        self.report.stability_note = None;
        loop {
            if let Err(outcome) = self.iteration(p, s, lim, step, &mut t) {
                return outcome;
            }
        }
    }

    /// One iteration: assess the iterate, stop at a stationary point or at the limits, factor,
    /// search and accept. Err ends the iterations with that outcome.
    fn iteration<P: NewtonProblem>(
        &mut self,
        p: &mut P,
        s: &NewtonSettings,
        lim: &Limits,
        step: usize,
        t: &mut Tally,
    ) -> Result<(), Outcome> {
        let (e0, res, qp_shift) = self.assess(p, s, step, t.it)?;
        let floor = self.measure_floor(p, lim, res, t);
        // The floor is measured with one pattern of rounding errors: below it, keep
        // iterating while Newton still halves the residual, and stop when round-off stalls it
        // or the last full Newton step moved nothing (`NEGLIGIBLE_STEP`).
        let stalled = res >= 0.5 * t.last_res || t.last_step <= NEGLIGIBLE_STEP;
        t.last_res = res;
        if res < lim.tolerance || (res < floor && stalled) {
            return self.at_stationary(p, lim, (e0, res, qp_shift), &mut t.escapes);
        }
        let at_cap = self.check_limits(lim, t.it, res, floor, stalled)?;
        let shift = self.factor_step(p, lim, (res, floor, qp_shift), t.it)?;
        t.indefinite = if self.shift_share(shift) > 0.5 {
            t.indefinite + 1
        } else {
            0
        };
        let recent = if t.prev_energy.is_finite() {
            (t.prev_energy, 2.0)
        } else {
            (t.last_energy, 1.0)
        };
        if at_cap && !self.converging(e0, recent, shift) {
            return Err(budget(t.it, res, lim));
        }
        t.prev_energy = t.last_energy;
        t.last_energy = e0;
        let small_step = self.search_and_accept(p, lim, (e0, shift, res, floor, qp_shift), t)?;
        t.it += 1;
        self.report.iterations += 1;
        if small_step {
            return Err(Outcome::Converged);
        }
        give_up_on_damping(lim, t, res)
    }

    /// Assembles energy, gradient and Hessian at the iterate and measures its residual; with
    /// constraints, makes the QP step first and returns its shift. Returns (energy, residual,
    /// the QP's shift).
    fn assess<P: NewtonProblem>(
        &mut self,
        p: &mut P,
        s: &NewtonSettings,
        step: usize,
        it: usize,
    ) -> Result<(f64, f64, Option<f64>), Outcome> {
        let e0 = p.assemble(&mut self.g, Some(&mut self.chol.values));
        let mut res = p.relative_residual(&self.g);
        self.report.residual = res;
        self.report.energy = e0;
        if !e0.is_finite() || !res.is_finite() {
            return Err(Outcome::Failed(format!(
                "non-finite energy or residual at iteration {it}"
            )));
        }
        // With constraints the step, and with it the multipliers, comes first: convergence
        // is judged on the KKT stationarity residual g − Jᵀz, not on g.
        let mut qp_shift = None;
        if self.qp.is_some() {
            match self.constrained_step(p) {
                Ok((shift, r)) => {
                    qp_shift = Some(shift);
                    res = r;
                    self.report.residual = res;
                }
                Err(msg) => return Err(Outcome::Failed(format!("{msg} at iteration {it}"))),
            }
        }
        if let Some(cb) = &s.progress {
            cb(step, self.report.iterations, res, e0);
        }
        Ok((e0, res, qp_shift))
    }

    /// The round-off floor, measured once per `iterate` when the residual first comes near
    /// it (or the cap does); 0 until then.
    fn measure_floor<P: Core>(&mut self, p: &mut P, lim: &Limits, res: f64, t: &mut Tally) -> f64 {
        if t.floor.is_none() && (res < FLOOR_CHECK || t.it + 1 >= lim.cap) {
            let f = p.residual_floor(&self.g);
            self.report.residual_floor = f;
            t.floor = Some(f);
        }
        t.floor.unwrap_or(0.0)
    }

    /// The iteration cap and the deadline. Ok(at_cap): the cap is reached above the floor but
    /// the attempt may go on if it is converging (`converging`).
    fn check_limits(
        &self,
        lim: &Limits,
        it: usize,
        res: f64,
        floor: f64,
        stalled: bool,
    ) -> Result<bool, Outcome> {
        if it >= lim.cap && res < floor && (stalled || it >= lim.extended_cap) {
            // Below the round-off floor Newton may still creep; that is as far as it goes.
            return Err(Outcome::AtFloor);
        }
        // Below the floor and still halving the residual, Newton is in its quadratic phase:
        // the residual no longer sees errors along soft modes (on a slender rod, an error of
        // 1e-9 of the tip position is 1e-9 of the force scale), and the step that the cap
        // would cut short is the one that removes them.
        let at_cap = it >= lim.cap && res >= floor;
        if at_cap && (it >= lim.extended_cap || self.qp.is_some()) {
            return Err(budget(it, res, lim));
        }
        if lim.deadline.is_some_and(|t| Instant::now() >= t) {
            return Err(Outcome::Budget(format!(
                "time limit reached after {it} Newton iterations: relative residual {res:.3e}"
            )));
        }
        Ok(at_cap)
    }

    /// Factors the Hessian with the shift it needs (or takes the QP's step and shift) and puts
    /// the step in `d`; returns the shift. A negligible full step below the floor is taken
    /// here and ends the iterations.
    fn factor_step<P: NewtonProblem>(
        &mut self,
        p: &mut P,
        lim: &Limits,
        (res, floor, qp_shift): (f64, f64, Option<f64>),
        it: usize,
    ) -> Result<f64, Outcome> {
        let Some(shift) = qp_shift.or_else(|| self.factor_regularized()) else {
            return Err(Outcome::Failed(format!(
                "Hessian could not be regularized at iteration {it} (residual {res:.3e})"
            )));
        };
        let newton_own = shift > 0.0 && qp_shift.is_none() && self.indefinite_step(p);
        let shift = if newton_own { 0.0 } else { shift };
        if shift > 0.0 {
            self.report.regularized_iterations += 1;
        }
        if qp_shift.is_none() && !newton_own {
            self.d.iter_mut().zip(&self.g).for_each(|(d, g)| *d = -g);
            let ts = Instant::now();
            self.chol.solve(&mut self.d);
            self.report.factor_seconds += ts.elapsed().as_secs_f64();
            // Below the floor a negligible full step needs no line search, and the next
            // assembly would only show round-off stall the residual: take it and stop, with
            // the stability of the factor just made and the residual before the step.
            if shift == 0.0 && res < floor && self.scaled_step() <= NEGLIGIBLE_STEP {
                p.accept(&self.d, 1.0);
                self.report.iterations += 1;
                if lim.judge_stability {
                    self.report.stable = self.stable_unshifted(p);
                }
                return Err(settled(res, lim));
            }
        }
        Ok(shift)
    }

    /// Corrects the step, searches along it and accepts the point found (or handles a failed
    /// search). Returns whether the step was small enough to end an intermediate attempt
    /// (`Limits::step_tolerance`).
    fn search_and_accept<P: NewtonProblem>(
        &mut self,
        p: &mut P,
        lim: &Limits,
        (e0, shift, res, floor, qp_shift): (f64, f64, f64, f64, Option<f64>),
        t: &mut Tally,
    ) -> Result<bool, Outcome> {
        let curves = self.corrections(p, shift);
        let mut small_step = false;
        t.last_step = f64::INFINITY;
        match self.search(p, (e0, shift, res), curves) {
            Some(alpha) => {
                t.damped = if alpha < 0.5 { t.damped + 1 } else { 0 };
                if alpha == 1.0 && shift == 0.0 && qp_shift.is_none() {
                    t.last_step = self.scaled_step();
                }
                small_step = alpha == 1.0
                    && t.it > 0
                    && shift == 0.0
                    && qp_shift.is_none()
                    && lim.step_tolerance.is_some_and(|s| self.scaled_step() <= s);
            }
            None => {
                let corrected = curves.0;
                let failed = (e0, shift, res, floor, corrected);
                self.after_failed_search(p, failed, lim.judge_stability, &mut t.escapes)?;
            }
        }
        Ok(small_step)
    }

    /// Whether the current step is Newton's own on the unshifted Hessian, without constraint
    /// forces: its quadratic model holds, and the energy's gradient is the residual.
    pub(super) fn on_newton_model(&self, shift: f64) -> bool {
        shift == 0.0 && !self.qp_used
    }

    /// The largest component of the step `d` in the unknowns' scales (edge lengths, radians).
    fn scaled_step(&self) -> f64 {
        self.d
            .iter()
            .zip(&self.scales)
            .map(|(d, s)| (d / s).abs())
            .fold(0.0, f64::max)
    }

    /// Whether the attempt is converging: the quadratic model's remaining decrease from the
    /// energy `e0` along the step in `d`, ½·|gᵀd|, is at most `CONVERGING_ITERATIONS` times
    /// the mean decrease of the last `its` iterations (from `last_energy`). Two iterations, not
    /// one: near the round-off floor of a very slender rod a single iteration's decrease is
    /// noisy, and one short iteration would have an attempt already close to its equilibrium
    /// judged stalled and retried from a smaller load. The model is trusted where the
    /// shift carries at most a tenth of the step's curvature dᵀ(H + τW)d = −gᵀd; beyond, the
    /// Hessian is indefinite along the step and the model says nothing of the distance left,
    /// unless even the shifted model's decrease is below `ENERGY_CONVERGED` of the recent ones:
    /// then the energy has converged and what is left is in the residual. A very slender rod
    /// near its round-off floor can fail to factor there by round-off alone, and retrying it
    /// from a smaller load discarded an attempt as good as converged.
    fn converging(&self, e0: f64, (last_energy, its): (f64, f64), shift: f64) -> bool {
        let slope: f64 = self.g.iter().zip(&self.d).map(|(a, b)| a * b).sum();
        let decrease = (last_energy - e0) / its;
        let remaining = -0.5 * slope;
        decrease > 0.0
            && (remaining <= ENERGY_CONVERGED * decrease
                || (self.shift_share(shift) <= 0.1
                    && remaining <= CONVERGING_ITERATIONS * decrease))
    }

    /// The share of the step's curvature dᵀ(H + τW)d = −gᵀd that the shift τ carries.
    fn shift_share(&self, shift: f64) -> f64 {
        if shift == 0.0 {
            return 0.0;
        }
        let slope: f64 = self.g.iter().zip(&self.d).map(|(a, b)| a * b).sum();
        let shifted: f64 = shift
            * self
                .d
                .iter()
                .zip(&self.weights)
                .map(|(d, w)| w * d * d)
                .sum::<f64>();
        shifted / -slope
    }

    /// The line search along the step corrected by `c` (if `curves.0`) and `c2`; accepts the
    /// step found.
    fn search<P: NewtonProblem>(
        &mut self,
        p: &mut P,
        (e0, shift, res): (f64, f64, f64),
        curves: (bool, Second),
    ) -> Option<f64> {
        let slope: f64 = self.g.iter().zip(&self.d).map(|(a, b)| a * b).sum();
        // Near convergence on a positive definite Hessian the full Newton step may be judged by
        // its residual when the energy cannot resolve its decrease (see `line_search`).
        let trust = (self.on_newton_model(shift) && res < TRUSTED_RESIDUAL).then_some(res);
        let search = Search {
            d: &self.d,
            first: curves.0.then_some(&self.c[..]),
            e0,
            slope,
            constrained: self.qp.is_some(),
            model_decrease: self.on_newton_model(shift).then_some(0.5 * slope.abs()),
        };
        let repairs = p.repairs_lengths();
        let (chol, f) = (&mut self.chol, &mut self.f_repair[..]);
        let mut repair = |p: &mut P, trial: &mut [f64], alpha: f64| {
            repairs && repair_lengths(p, (&mut *chol, &mut *f), (search.d, slope), alpha, trial)
        };
        let mut second = SecondCurve {
            buf: &mut self.c2,
            state: curves.1,
        };
        let alpha = search.run(
            p,
            (&mut self.trial, &mut self.c_repaired),
            &mut second,
            trust.map(|r| (r, &mut self.g_trial[..])),
            &mut repair,
        )?;
        p.accept(&self.trial, 1.0);
        Some(alpha)
    }
}

/// The iteration budget ran out at iteration `it`.
fn budget(it: usize, res: f64, lim: &Limits) -> Outcome {
    Outcome::Budget(format!(
        "{it} Newton iterations: relative residual {res:.3e} > tolerance {:.1e}",
        lim.tolerance
    ))
}

/// Repeatedly damped or indefinite steps far from the solution: a smaller increment is
/// cheaper (`Limits::retry_on_damping`).
fn give_up_on_damping(lim: &Limits, t: &Tally, res: f64) -> Result<(), Outcome> {
    if t.indefinite >= INDEFINITE_STEPS && lim.retry_on_damping {
        return Err(Outcome::Failed(format!(
            "indefinite Newton steps (residual {res:.3e})"
        )));
    }
    if t.damped >= 4 && lim.retry_on_damping {
        return Err(Outcome::Failed(format!(
            "damped Newton steps (residual {res:.3e})"
        )));
    }
    Ok(())
}
