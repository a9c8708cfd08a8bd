//! Newton's method on the total energy with load stepping.
//!
//! Each iteration factors the exact Hessian with a sparse Cholesky (symbolic analysis reused). If
//! the Hessian is not positive definite, a diagonal shift τ·I is added, grown ×10 from a fraction
//! of the last successful shift until the factorization succeeds (modified Newton: the step stays
//! a descent direction). A backtracking line search on the energy (Armijo) follows, capped by the
//! problem's admissible step. At a stationary point whose Hessian is not positive definite, the
//! direction of most negative curvature (inverse iteration with the shifted factor) is followed
//! downhill, so a perfectly straight compressed rod buckles instead of stalling at the saddle.
//!
//! A problem with inequality constraints (contact, bounds) replaces the Cholesky step by a QP
//! with the same shifted Hessian whenever the unconstrained step would violate a linearized
//! constraint (see `qp.rs` and docs/design.md); without constraints nothing of that runs.

use std::time::Instant;

use super::linalg::SparseCholesky;
use super::line_search::line_search;
use super::ordering::factorization;
use super::problem::NewtonProblem;
use super::qp::StepQp;
use super::settings::{ConstraintReport, NewtonReport, NewtonSettings};

/// Newton iterations a continuation sub-step may take before it is retried with a smaller
/// increment (unless the increment is already minimal).
const ATTEMPT_CAP: usize = 8;
/// Smallest continuation increment, as a fraction of the whole load path.
const MIN_INCREMENT: f64 = 1e-5;
/// Residual to which intermediate continuation sub-steps are converged (or the solve's tolerance
/// if looser): their states only start the next sub-step, and a few digits are enough for that;
/// iterating them to round-off would spend iterations on states that are discarded.
pub const INTERMEDIATE_TOLERANCE: f64 = 1e-6;
/// Relative residual below which a full Newton step on a positive definite Hessian may be
/// accepted for reducing the residual when the Armijo test cannot resolve the energy change.
const TRUSTED_RESIDUAL: f64 = 1e-4;

/// What the search for negative curvature at a stationary point found.
enum Saddle {
    /// Only zero-energy modes (rigid rotations, free spin): a minimum up to those modes.
    ZeroModesOnly,
    Escaped,
    /// Negative curvature, but no energy decrease along it within round-off.
    NoDecrease,
}

enum Outcome {
    Converged(usize),
    Failed(String),
}

pub fn solve<P: NewtonProblem>(p: &mut P, s: &NewtonSettings) -> NewtonReport {
    let t0 = Instant::now();
    let n = p.num_free();
    let pairs = p.hessian_pattern();
    let (chol, slots) = factorization(p, n, &pairs, s.ordering);
    p.set_hessian_slots(&slots);
    let steps = s.load_steps.max(1);
    // Only a problem with constraints builds a QP; without, every step is the Cholesky solve.
    let m = p.num_constraints();
    let qp = (m > 0).then(|| StepQp::new(n, m, p.constraint_pattern()));
    let mut st = Newton {
        chol,
        qp,
        r: vec![0.0; if m > 0 { n } else { 0 }],
        qp_used: false,
        g: vec![0.0; n],
        d: vec![0.0; n],
        c: vec![0.0; n],
        trial: vec![0.0; n],
        g_trial: vec![0.0; n],
        scales: vec![1.0; n],
        weights: vec![1.0; n],
        shift_memory: 0.0,
        report: NewtonReport {
            load_steps: steps,
            ..Default::default()
        },
    };
    // Adaptive continuation: each user load step is reached through sub-steps whose increment
    // is quartered on failure and doubles after easy convergence; a secant predictor from the last
    // two converged states starts each sub-step.
    p.unknown_scales(&mut st.scales);
    for (w, s) in st.weights.iter_mut().zip(&st.scales) {
        *w = 1.0 / (s * s);
    }
    let mut lam = 0.0;
    let mut inc = 1.0 / steps as f64;
    let mut prev: Option<(f64, P::Snapshot)> = None;
    // A start that is not in equilibrium at λ = 0 (a form-finding guess; a rest state always is)
    // is equilibrated before the path starts: every sub-step then begins from an equilibrium, and
    // the start's own imbalance is not mistaken for a too-large increment.
    let trivial = p.continuation_is_trivial();
    p.set_continuation(if trivial { 1.0 } else { 0.0 });
    let mut start_iterations = 0;
    if trivial {
        // Nothing moves along the path (a form-finding step with fixed supports and no loads):
        // the solve is the start's equilibration, to the full tolerance.
        match st.iterate(p, s, s.max_iterations, (steps, steps)) {
            Outcome::Converged(_) => st.report.converged = true,
            Outcome::Failed(msg) => st.fail(msg),
        }
        st.report.substeps = 1;
        st.report.step_iterations = vec![st.report.iterations];
    } else if p.assemble(&mut st.g, None).is_finite() && p.relative_residual(&st.g) > s.tolerance {
        let intermediate = s.clone().tolerance(s.tolerance.max(INTERMEDIATE_TOLERANCE));
        let saved = p.snapshot();
        match st.iterate(p, &intermediate, s.max_iterations, (0, steps)) {
            Outcome::Converged(_) => st.report.substeps += 1,
            // Not fatal: the path then starts from the guess itself, as it would without this.
            Outcome::Failed(_) => {
                st.report.retries += 1;
                p.restore(&saved);
            }
        }
        start_iterations = st.report.iterations;
    }
    let first = if trivial { steps + 1 } else { 1 };
    'steps: for k in first..=steps {
        let target = k as f64 / steps as f64;
        // The start's equilibration has its own budget but is reported with the first step.
        let its_before = st.report.iterations;
        let reported_before = its_before - if k == 1 { start_iterations } else { 0 };
        while lam < target {
            let mut next = (lam + inc).min(target);
            if target - next < 0.25 * inc {
                next = target;
            }
            let saved = p.snapshot();
            match &prev {
                Some((lp, snap)) if lam > *lp => {
                    p.extrapolate(snap, ((next - lam) / (lam - lp)).min(2.0));
                    p.set_continuation(next);
                }
                Some(_) => p.set_continuation(next),
                None => st.tangent_predict(p, lam, next),
            }
            let minimal = inc <= MIN_INCREMENT * 1.0001;
            // `max_iterations` bounds the Newton iterations of a whole load step, sub-steps
            // and retries included.
            let remaining = s
                .max_iterations
                .saturating_sub(st.report.iterations - its_before);
            let last_chance = minimal || remaining <= ATTEMPT_CAP;
            let cap = if minimal {
                remaining
            } else {
                ATTEMPT_CAP.min(remaining)
            };
            let tolerance = if next == 1.0 {
                s.tolerance
            } else {
                s.tolerance.max(INTERMEDIATE_TOLERANCE)
            };
            match st.iterate(p, &s.clone().tolerance(tolerance), cap, (k, steps)) {
                Outcome::Converged(its) => {
                    st.report.substeps += 1;
                    prev = Some((lam, saved));
                    lam = next;
                    if its <= 5 {
                        inc = (2.0 * inc).min(1.0 / steps as f64);
                    }
                }
                Outcome::Failed(msg) => {
                    if last_chance {
                        st.fail(msg);
                        st.report
                            .step_iterations
                            .push(st.report.iterations - reported_before);
                        break 'steps;
                    }
                    st.report.retries += 1;
                    p.restore(&saved);
                    inc = (0.25 * inc).max(MIN_INCREMENT);
                }
            }
        }
        st.report
            .step_iterations
            .push(st.report.iterations - reported_before);
        if k == steps {
            st.report.converged = st.report.message.is_none();
        }
    }
    st.report.seconds = t0.elapsed().as_secs_f64();
    st.report.tolerance = s.tolerance;
    if let Some(qp) = &st.qp {
        st.report.constraints = Some(ConstraintReport {
            multipliers: qp.z.clone(),
            qp_solves: qp.solves,
            steps_without_qp: qp.skipped,
            polished_qps: qp.polished,
            inexact_qps: qp.inexact,
            qp_iterations: qp.iterations,
            qp_seconds: qp.seconds,
        });
    }
    st.report
}

struct Newton {
    chol: SparseCholesky,
    /// The step QP, only for problems with constraints.
    qp: Option<StepQp>,
    /// Scratch for the KKT stationarity residual (constrained problems only).
    r: Vec<f64>,
    /// The current step came from the QP (some constraint would be violated without it).
    qp_used: bool,
    g: Vec<f64>,
    d: Vec<f64>,
    c: Vec<f64>,
    trial: Vec<f64>,
    /// Scratch gradient for judging a full step by its residual.
    g_trial: Vec<f64>,
    /// Characteristic size s of each unknown (`NewtonProblem::unknown_scales`) and the shift
    /// weights 1/s²: regularizing H + τ·diag(1/s²) is regularizing the Hessian of the
    /// dimensionless unknowns q/s by τ·I, so a scene and its copy scaled in length or modulus
    /// take the same steps. (With a uniform shift, a length scale λ multiplies the position
    /// rows of H by λ and the angle rows by λ³, so the same relative shift would damp angles
    /// and positions differently at every scale; docs/stiff.md section 3.)
    scales: Vec<f64>,
    weights: Vec<f64>,
    shift_memory: f64,
    report: NewtonReport,
}

impl Newton {
    /// Newton iterations at the current continuation parameter until convergence, failure, or
    /// `cap` iterations.
    fn iterate<P: NewtonProblem>(
        &mut self,
        p: &mut P,
        s: &NewtonSettings,
        cap: usize,
        (step, steps): (usize, usize),
    ) -> Outcome {
        let n = self.g.len();
        let mut it = 0;
        let mut escapes = 0;
        let mut damped = 0;
        let mut last_res = f64::INFINITY;
        loop {
            let e0 = p.assemble(&mut self.g, Some(&mut self.chol.values));
            let mut res = p.relative_residual(&self.g);
            self.report.residual = res;
            self.report.energy = e0;
            if !e0.is_finite() || !res.is_finite() {
                return Outcome::Failed(format!(
                    "non-finite energy or residual at load step {step}/{steps}, iteration {it}"
                ));
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
                    Err(msg) => {
                        return Outcome::Failed(format!(
                            "{msg} at load step {step}/{steps}, iteration {it}"
                        ))
                    }
                }
            }
            if let Some(cb) = &s.progress {
                cb(step, self.report.iterations, res, e0);
            }
            let floor = p.residual_floor();
            self.report.residual_floor = floor;
            // The floor is a worst-case estimate: below it, keep iterating while Newton still
            // halves the residual, and stop when round-off stalls it.
            let stalled = res >= 0.5 * last_res;
            last_res = res;
            if res < s.tolerance || (res < floor && stalled) {
                let Some(shift) = qp_shift.or_else(|| self.factor_regularized()) else {
                    return Outcome::Failed(format!(
                        "Hessian could not be regularized at load step {step}/{steps} (residual {res:.3e})"
                    ));
                };
                if shift == 0.0 {
                    self.report.stable = true;
                    return Outcome::Converged(it);
                }
                match self.escape_saddle(p, e0) {
                    Saddle::ZeroModesOnly => {
                        self.report.stable = true;
                        return Outcome::Converged(it);
                    }
                    Saddle::Escaped if escapes < 8 => {
                        escapes += 1;
                        self.report.saddle_escapes += 1;
                        continue;
                    }
                    _ => {
                        self.report.stable = false;
                        return Outcome::Converged(it);
                    }
                }
            }
            if it >= cap && res < floor {
                // Below the round-off floor Newton may still creep; that is convergence.
                return Outcome::Converged(it);
            }
            if it >= cap {
                return Outcome::Failed(format!(
                    "no convergence in {it} Newton iterations at load step {step}/{steps}: \
                     relative residual {res:.3e} > tolerance {:.1e}",
                    s.tolerance
                ));
            }
            let Some(shift) = qp_shift.or_else(|| self.factor_regularized()) else {
                return Outcome::Failed(format!(
                    "Hessian could not be regularized at load step {step}/{steps}, iteration {it} \
                     (residual {res:.3e})"
                ));
            };
            if shift > 0.0 {
                self.report.regularized_iterations += 1;
            }
            if qp_shift.is_none() {
                for i in 0..n {
                    self.d[i] = -self.g[i];
                }
                let ts = Instant::now();
                self.chol.solve(&mut self.d);
                self.report.factor_seconds += ts.elapsed().as_secs_f64();
            }
            let slope: f64 = self.g.iter().zip(&self.d).map(|(a, b)| a * b).sum();
            let corrected = p.step_correction(&self.d, &mut self.c);
            // Near convergence on a positive definite Hessian the full Newton step may be
            // judged by its residual when the energy cannot resolve its decrease (see
            // `line_search`).
            let trust = (shift == 0.0 && res < TRUSTED_RESIDUAL && !self.qp_used).then_some(res);
            match line_search(
                p,
                &self.d,
                corrected.then_some(&self.c[..]),
                e0,
                slope,
                &mut self.trial,
                self.qp.is_some(),
                trust.map(|r| (r, &mut self.g_trial[..])),
            ) {
                Some(alpha) => {
                    p.accept(&self.trial, 1.0);
                    damped = if alpha < 0.5 { damped + 1 } else { 0 };
                }
                None => {
                    // Energy differences below round-off: judge the full step by its residual.
                    for i in 0..n {
                        self.trial[i] = self.d[i] + if corrected { self.c[i] } else { 0.0 };
                    }
                    let mut gt = std::mem::take(&mut self.c);
                    p.trial_gradient(&self.trial, 1.0, &mut gt);
                    let res_trial = p.relative_residual(&gt);
                    self.c = gt;
                    // Only where the Hessian is positive definite (a convex model: reducing the
                    // residual approaches a minimum, not a saddle) and the residual is small.
                    // (With constraint forces the plain gradient is no residual: never trusted.)
                    let trusted = shift == 0.0 && res < TRUSTED_RESIDUAL && !self.qp_used;
                    if trusted && res_trial < 0.9 * res && p.max_step(&self.trial) >= 1.0 {
                        p.accept(&self.trial, 1.0);
                    } else if shift > 0.0 && escapes < 8 {
                        // No descent along the regularized Newton step near a stationary point
                        // of an indefinite Hessian: leave along negative curvature instead.
                        match self.escape_saddle(p, e0) {
                            Saddle::Escaped => {
                                escapes += 1;
                                self.report.saddle_escapes += 1;
                            }
                            found if res < floor => {
                                self.report.stable = matches!(found, Saddle::ZeroModesOnly);
                                return Outcome::Converged(it);
                            }
                            _ => {
                                return Outcome::Failed(format!(
                                    "line search failed at load step {step}/{steps}, iteration \
                                     {it} (relative residual {res:.3e})"
                                ))
                            }
                        }
                    } else if res < floor {
                        // Round-off stalled Newton below the floor: converged as far as
                        // floating point allows.
                        self.report.stable = shift == 0.0;
                        return Outcome::Converged(it);
                    } else {
                        return Outcome::Failed(format!(
                            "line search failed at load step {step}/{steps}, iteration {it} \
                             (relative residual {res:.3e})"
                        ));
                    }
                }
            }
            it += 1;
            self.report.iterations += 1;
            // Repeatedly damped steps far from the solution: a smaller increment is cheaper.
            if damped >= 4 && cap == ATTEMPT_CAP {
                return Outcome::Failed(format!(
                    "damped Newton steps at load step {step}/{steps} (residual {res:.3e})"
                ));
            }
        }
    }

    /// First sub-step of the path, from an equilibrium at `lam`: moves the free unknowns by the
    /// linear response to the increment, δ = −H⁻¹ (g(λ_next) − g(λ)) at fixed free unknowns, so
    /// that prescribed ends do not start by crushing their first edges. Kept only if it lowers
    /// the energy at `next`. Later sub-steps use the secant through two equilibria instead (a
    /// tangent predictor there leads a strut shortened past buckling onto its straight saddle;
    /// docs/design.md).
    fn tangent_predict<P: NewtonProblem>(&mut self, p: &mut P, lam: f64, next: f64) {
        let n = self.g.len();
        if self.qp.is_some() {
            // The linear response ignores contact and bounds: it could jump through an obstacle.
            p.set_continuation(next);
            return;
        }
        p.set_continuation(lam);
        let e0 = p.assemble(&mut self.g, Some(&mut self.chol.values));
        let factored = e0.is_finite() && self.factor_regularized().is_some();
        p.set_continuation(next);
        if !factored || n == 0 {
            return;
        }
        let e1 = p.assemble(&mut self.d, None);
        for i in 0..n {
            self.d[i] = self.g[i] - self.d[i];
        }
        self.chol.solve(&mut self.d);
        let alpha = p.max_step(&self.d).min(1.0);
        let e = p.trial_energy(&self.d, alpha);
        if e.is_finite() && e < e1 {
            p.accept(&self.d, alpha);
        }
    }

    /// Factors H + τI as for an unconstrained step, then solves the step QP with it at the
    /// current iterate. Returns the shift and the relative stationarity residual.
    fn constrained_step<P: NewtonProblem>(&mut self, p: &mut P) -> Result<(f64, f64), String> {
        let shift = self
            .factor_regularized()
            .ok_or_else(|| "Hessian could not be regularized".to_string())?;
        for i in 0..self.d.len() {
            self.d[i] = -self.g[i];
        }
        let ts = Instant::now();
        self.chol.solve(&mut self.d);
        self.report.factor_seconds += ts.elapsed().as_secs_f64();
        let qp = self.qp.as_mut().expect("constrained problem");
        p.constraints(&mut qp.c, &mut qp.jac);
        // The QP is convex: when the unconstrained minimizer of its model satisfies the
        // linearized constraints, it is the QP's solution, with zero multipliers. Then Clarabel
        // is not needed, and a constraint that is never active leaves every iterate exactly as
        // without it.
        if qp.admits(&self.d) {
            qp.z.fill(0.0);
            qp.skipped += 1;
            self.qp_used = false;
            return Ok((shift, p.relative_residual(&self.g)));
        }
        qp.solve(&mut self.chol, &self.g, &mut self.d)?;
        self.qp_used = true;
        qp.stationarity(&self.g, &mut self.r);
        Ok((shift, p.relative_residual(&self.r)))
    }

    fn fail(&mut self, msg: String) {
        self.report.converged = false;
        self.report.message = Some(msg);
    }

    /// Factors H + τI with the smallest τ of the sequence 0, τ₀, 10τ₀, … that succeeds.
    ///
    /// The unshifted attempt is made at every iteration, even while it keeps failing: skipping
    /// it would save a factorization per indefinite iteration, but the shift would then linger
    /// (it decays ×10 per iteration) and turn Newton's final quadratic convergence linear.
    fn factor_regularized(&mut self) -> Option<f64> {
        let ts = Instant::now();
        let r = self.factor_regularized_inner();
        self.report.factor_seconds += ts.elapsed().as_secs_f64();
        r
    }

    fn factor_regularized_inner(&mut self) -> Option<f64> {
        self.report.factorizations += 1;
        if self.chol.factor(0.0).is_ok() {
            self.shift_memory *= 0.1;
            return Some(0.0);
        }
        let scale = self.scaled_diagonal().max(f64::MIN_POSITIVE);
        let mut tau = (1e-10 * scale).max(0.1 * self.shift_memory);
        while tau < 1e12 * scale {
            self.report.factorizations += 1;
            if self.chol.factor_weighted(tau, &self.weights).is_ok() {
                self.shift_memory = tau;
                return Some(tau);
            }
            tau *= 10.0;
        }
        None
    }

    /// Largest |H_ii|·s_i²: the diagonal scale of the Hessian of the dimensionless unknowns.
    fn scaled_diagonal(&self) -> f64 {
        (0..self.scales.len())
            .map(|i| self.chol.diagonal(i).abs() * self.scales[i] * self.scales[i])
            .fold(0.0, f64::max)
    }

    /// With H + τW factored (W = diag(1/s²)), finds the most negative curvature direction of
    /// H for the dimensionless unknowns q/s by inverse iteration (the generalized eigenproblem
    /// H u = λ W u) and moves downhill along it.
    fn escape_saddle<P: NewtonProblem>(&mut self, p: &mut P, e0: f64) -> Saddle {
        let n = self.g.len();
        if n == 0 {
            return Saddle::ZeroModesOnly;
        }
        let (s, w) = (&self.scales, &self.weights);
        // W-norm: the Euclidean norm of the dimensionless vector.
        let norm_w = |v: &[f64]| v.iter().zip(w).map(|(x, w)| w * x * x).sum::<f64>().sqrt();
        // Deterministic, generic start vector (in dimensionless unknowns).
        let mut v: Vec<f64> = (0..n)
            .map(|i| (1.0 + 0.5 * ((i as f64) * 0.7).sin()) * s[i])
            .collect();
        let mut hv = vec![0.0; n];
        let mut lambda = 0.0;
        for _ in 0..50 {
            let nv = norm_w(&v);
            v.iter_mut().for_each(|x| *x /= nv);
            self.chol.multiply(&v, &mut hv);
            let new_lambda: f64 = v.iter().zip(&hv).map(|(a, b)| a * b).sum();
            let done = (new_lambda - lambda).abs() <= 1e-6 * new_lambda.abs();
            lambda = new_lambda;
            if done {
                break;
            }
            v.iter_mut().zip(w).for_each(|(x, w)| *x *= w);
            self.chol.solve(&mut v);
        }
        let nv = norm_w(&v);
        v.iter_mut().for_each(|x| *x /= nv);
        let scale = self.scaled_diagonal();
        if lambda >= -1e-12 * scale {
            return Saddle::ZeroModesOnly;
        }
        // Deterministic sign: largest dimensionless component positive.
        let imax = (0..n)
            .max_by(|&a, &b| (v[a] / s[a]).abs().total_cmp(&(v[b] / s[b]).abs()))
            .unwrap();
        if v[imax] < 0.0 {
            v.iter_mut().for_each(|x| *x = -*x);
        }
        let size = p.perturbation_size(&v);
        v.iter_mut().for_each(|x| *x *= size);
        let mut alpha = p.max_step(&v);
        let constrained = self.qp.is_some();
        for _ in 0..30 {
            if constrained {
                let scaled: Vec<f64> = v.iter().map(|x| alpha * x).collect();
                if !p.feasible(&scaled) {
                    alpha *= 0.5;
                    continue;
                }
            }
            let e = p.trial_energy(&v, alpha);
            if e.is_finite() && e < e0 - 1e-12 * e0.abs() {
                p.accept(&v, alpha);
                return Saddle::Escaped;
            }
            alpha *= 0.5;
        }
        Saddle::NoDecrease
    }
}
