//! The path from λ = 0 to 1: load steps, each reached through adaptive sub-steps, with Newton
//! iterations (`newton.rs`) at each. How the report says what ended it: `verdict.rs`.

use std::time::{Duration, Instant};

use super::linalg::{AnalysisCache, SparseCholesky};
use super::newton::{Limits, Newton, Outcome};
use super::path_events::{bifurcation, Judged, PathEvent};
use super::problem::NewtonProblem;
use super::qp::StepQp;
use super::settings::{ConstraintReport, NewtonReport, NewtonSettings};
use super::verdict::finish;

/// Newton iterations a continuation sub-step may take before it is retried with a smaller
/// increment (unless the increment is already minimal).
const ATTEMPT_CAP: usize = 8;
/// Smallest continuation increment, as a fraction of the whole load path.
const MIN_INCREMENT: f64 = 1e-5;
/// A sub-step judged a snap is retried with a quarter of its increment until the increment is
/// at most this share of the load step: a real snap stays a jump, a smooth branch does not.
const SNAP_BRACKET: f64 = 1.0 / 64.0;
/// Converged states the predictor extrapolates from, besides the current one.
const HISTORY: usize = 2;
/// Residual to which intermediate continuation sub-steps are converged (or the solve's tolerance
/// if looser): their states only start the next sub-step, and a few digits are enough for that;
/// iterating them to round-off would spend iterations on states that are discarded. (1e-4 let
/// a twisted ring leave its plane below its critical twist: docs/design.md.)
pub const INTERMEDIATE_TOLERANCE: f64 = 1e-6;
/// An intermediate sub-step also ends once a full, unregularized Newton step is at most this
/// large (in edge lengths and radians) and has been taken, if it was not the attempt's first
/// (a step from a prediction shows nothing of Newton's contraction): Newton then converges
/// quadratically, and the state is as close as the next prediction needs. Measured on the step,
/// not on the residual, which says little of the position along a soft mode (a residual of 1e-4
/// let a twisted ring leave its plane below its critical twist: docs/design.md).
const INTERMEDIATE_STEP: f64 = 1e-2;

pub fn solve<P: NewtonProblem + Send>(p: &mut P, s: &NewtonSettings) -> NewtonReport {
    solve_with(p, s, None, &AnalysisCache::default()).0
}

/// [`solve`], starting from the factorization object of an earlier solve of the same problem
/// (`kept`) when its Hessian pattern has not changed since, so that its pattern, slots and
/// factor storage are not made again (form finding's cap steps: one per step, docs/performance.md).
/// The caller vouches that the pattern and the ordering asked for are unchanged; `p`'s Hessian
/// slots are then still those set for it. Otherwise the pattern's analysis is taken from, or
/// kept in, `analyses`. Returns the factorization object for the next solve.
pub fn solve_with<P: NewtonProblem + Send>(
    p: &mut P,
    s: &NewtonSettings,
    kept: Option<SparseCholesky>,
    analyses: &AnalysisCache,
) -> (NewtonReport, SparseCholesky) {
    super::pool::in_pool(|| solve_here(p, s, kept, analyses))
}

/// [`solve_with`] on the calling thread.
fn solve_here<P: NewtonProblem>(
    p: &mut P,
    s: &NewtonSettings,
    kept: Option<SparseCholesky>,
    analyses: &AnalysisCache,
) -> (NewtonReport, SparseCholesky) {
    let t0 = Instant::now();
    let deadline = s.deadline.or_else(|| {
        s.time_limit
            .map(|t| t0 + Duration::from_secs_f64(t.clamp(0.0, 1e9)))
    });
    let n = p.num_free();
    let chol = match kept {
        Some(chol) => chol,
        None => {
            let pairs = p.hessian_pattern();
            let (chol, slots) =
                analyses.factorization(n, &pairs, s.ordering, || p.unknown_positions());
            p.set_hessian_slots(&slots);
            chol
        }
    };
    // Only a problem with constraints builds a QP; without, every step is the Cholesky solve.
    let m = p.num_constraints();
    let qp = (m > 0).then(|| StepQp::new(n, m, p.constraint_pattern()));
    let mut st = Newton::new(chol, qp, n);
    let steps = s.load_steps.max(1);
    st.report.load_steps = steps;
    st.report.tolerance = s.tolerance;
    p.unknown_scales(&mut st.scales);
    for (w, s) in st.weights.iter_mut().zip(&st.scales) {
        *w = 1.0 / (s * s);
    }
    let mut path = Path {
        deadline,
        root_path: !p.bias().is_empty(),
        steps,
        lam: 0.0,
        inc: 1.0 / steps as f64,
        start_iterations: 0,
        modes_checked_at: None,
    };
    path.follow(&mut st, p, s);
    let r = &mut st.report;
    r.seconds = t0.elapsed().as_secs_f64();
    if let Some(qp) = &st.qp {
        r.constraints = Some(ConstraintReport {
            multipliers: qp.z.clone(),
            qp_solves: qp.solves,
            steps_without_qp: qp.skipped,
            polished_qps: qp.polished,
            inexact_qps: qp.inexact,
            qp_iterations: qp.iterations,
            qp_seconds: qp.seconds,
        });
    }
    (std::mem::take(&mut st.report), st.chol)
}

struct Path {
    deadline: Option<Instant>,
    /// The path parameter is t = √λ (λ = t²): past a bifurcation from a symmetric state, the
    /// state moves away from it as √(λ − λc) (inextensible post-buckling under prescribed end
    /// motion), and in t it is smooth, so secant predictions hold over long increments. Used on
    /// `buckle_toward` paths, which are such problems by declaration (docs/design.md).
    root_path: bool,
    steps: usize,
    lam: f64,
    /// Current sub-step increment of λ.
    inc: f64,
    /// Iterations spent equilibrating the start (reported with the first load step).
    start_iterations: usize,
    /// The path parameter whose state the tangent predictor has already searched for
    /// zero-stiffness modes and found no mechanism: a first sub-step that is retried restarts
    /// from that same state (restored from its snapshot), and the search, a block inverse
    /// iteration of up to 120 solves, would find the same.
    modes_checked_at: Option<f64>,
}

impl Path {
    fn follow<P: NewtonProblem>(&mut self, st: &mut Newton, p: &mut P, s: &NewtonSettings) {
        // An unsupported structure whose full dead loads make one of its rigid turns unstable
        // has no stable path from λ = 0 (every state on it is a saddle, and sub-steps only
        // crawl): it is solved at the full load directly, where the saddle escape turns it.
        let trivial = s.equilibrate_only
            || p.continuation_is_trivial()
            || (st.qp.is_none() && st.turns_unstable_under_full_load(p));
        p.set_continuation(if trivial { 1.0 } else { 0.0 });
        if trivial {
            // Nothing moves along the path (a form-finding step with fixed supports and no
            // loads): the solve is the start's equilibration, to the full tolerance unless its
            // state only starts another solve.
            let mut lim = self.limits(s.tolerance, (s.max_iterations, s.max_iterations), false);
            if s.intermediate {
                lim.tolerance = s.tolerance.max(INTERMEDIATE_TOLERANCE);
                lim.step_tolerance = Some(INTERMEDIATE_STEP);
            }
            let outcome = st.iterate(p, s, &lim, self.steps);
            st.report.substeps = 1;
            st.report.step_iterations = vec![st.report.iterations];
            finish(
                st,
                outcome,
                (self.steps, self.steps),
                st.report.iterations,
                s,
            );
            return;
        }
        self.equilibrate_start(st, p, s);
        if s.continuation == super::Continuation::ArcLength && st.qp.is_none() {
            let outcome = super::arc_length::follow(st, p, s, self.deadline);
            let its = st.report.iterations;
            st.report.step_iterations = vec![its];
            finish(st, outcome, (self.steps, self.steps), its, s);
            return;
        }
        let mut prev: Vec<(f64, P::Snapshot)> = Vec::new();
        for k in 1..=self.steps {
            let its_before = st.report.iterations;
            let reported_before = its_before - if k == 1 { self.start_iterations } else { 0 };
            let outcome = self.load_step(st, p, s, k, its_before, &mut prev);
            st.report
                .step_iterations
                .push(st.report.iterations - reported_before);
            let last = k == self.steps;
            let its = st.report.iterations - reported_before;
            match outcome {
                Outcome::Converged | Outcome::AtFloor if !last => {}
                o => {
                    finish(st, o, (k, self.steps), its, s);
                    return;
                }
            }
        }
    }

    /// A start that is not in equilibrium at λ = 0 (a form-finding guess; a rest state always
    /// is) is equilibrated before the path starts: every sub-step then begins from an
    /// equilibrium, and the start's own imbalance is not mistaken for a too-large increment.
    fn equilibrate_start<P: NewtonProblem>(
        &mut self,
        st: &mut Newton,
        p: &mut P,
        s: &NewtonSettings,
    ) {
        if !(p.assemble(&mut st.g, None).is_finite() && p.relative_residual(&st.g) > s.tolerance) {
            return;
        }
        let mut lim = self.limits(
            s.tolerance.max(INTERMEDIATE_TOLERANCE),
            (s.max_iterations, s.max_iterations),
            false,
        );
        // The path's states replace the start's verdict (see `load_step` for `s.intermediate`).
        lim.judge_stability = s.intermediate;
        let saved = p.snapshot();
        match st.iterate(p, s, &lim, 0) {
            Outcome::Converged | Outcome::AtFloor => st.report.substeps += 1,
            // Not fatal: the path then starts from the guess itself, as it would without this.
            _ => {
                st.report.retries += 1;
                p.restore(&saved);
            }
        }
        self.start_iterations = st.report.iterations;
    }

    /// The load factor λ at path parameter `t`.
    fn load(&self, t: f64) -> f64 {
        if self.root_path {
            t * t
        } else {
            t
        }
    }

    /// An attempt that may be retried (`retry_on_damping`) may also go on past `cap` while it
    /// converges, up to `extended_cap`; a last chance has its whole budget as `cap`.
    fn limits(&self, tolerance: f64, caps: (usize, usize), retry_on_damping: bool) -> Limits {
        Limits {
            tolerance,
            cap: caps.0,
            extended_cap: caps.1,
            deadline: self.deadline,
            retry_on_damping,
            step_tolerance: None,
            judge_stability: true,
        }
    }

    /// Predicts the state at `next` from the current one (`current`) and the earlier converged
    /// states: by the secant through the last of them and, on a buckling path with two, also by
    /// the parabola through both, keeping the prediction of lower energy. In t = √λ prescribed
    /// motions are quadratic, and so is a post-buckled shape once it is far from its
    /// bifurcation: the secant alone extrapolates a quadratic motion linearly and falls short
    /// of it, the more the longer the increment (docs/design.md).
    fn predict<P: NewtonProblem>(
        &self,
        p: &mut P,
        prev: &[(f64, P::Snapshot)],
        next: f64,
        current: &P::Snapshot,
    ) {
        let by = |p: &mut P, hist: &[(f64, P::Snapshot)]| {
            let w = secant_weights(hist, self.lam, next);
            let from: Vec<_> = hist.iter().zip(&w).map(|((_, s), &w)| (s, w)).collect();
            p.predict(&from, self.load(next));
            p.energy()
        };
        let linear = by(p, &prev[prev.len() - 1..]);
        if prev.len() < 2 || !self.root_path {
            return;
        }
        let first = p.snapshot();
        p.restore(current);
        let quadratic = by(p, prev);
        // A margin: where the two agree to round-off (states along a line), the choice must not
        // depend on the last bits (scaled copies of a scene follow the same path).
        if quadratic.is_nan() || quadratic >= linear - 1e-9 * linear.abs() {
            p.restore(&first);
        }
    }

    /// The first sub-step's prediction from the current state toward `next`
    /// (`Newton::tangent_predict`), which looks for mechanisms only at a state not yet looked at.
    fn tangent_predict<P: NewtonProblem>(
        &mut self,
        st: &mut Newton,
        p: &mut P,
        next: f64,
    ) -> Result<bool, String> {
        let r = st.tangent_predict(
            p,
            (self.load(self.lam), self.load(next)),
            self.root_path && self.inc > MIN_INCREMENT * 1.0001,
            self.modes_checked_at != Some(self.lam),
        );
        if r.is_ok() {
            self.modes_checked_at = Some(self.lam);
        }
        r
    }

    /// Reaches λ = k/steps through sub-steps whose increment is quartered on failure and
    /// doubles after easy convergence; a prediction from the last converged states (`predict`)
    /// starts each sub-step. `max_iterations` bounds the Newton iterations of the whole load
    /// step, sub-steps and retries included.
    fn load_step<P: NewtonProblem>(
        &mut self,
        st: &mut Newton,
        p: &mut P,
        s: &NewtonSettings,
        k: usize,
        its_before: usize,
        prev: &mut Vec<(f64, P::Snapshot)>,
    ) -> Outcome {
        let target = k as f64 / self.steps as f64;
        let mut last = Outcome::Converged;
        while self.lam < target {
            let mut next = (self.lam + self.inc).min(target);
            if target - next < 0.25 * self.inc {
                next = target;
            }
            let saved = p.snapshot();
            let start = p.unknown_positions();
            let mut linear = None;
            match prev.last() {
                Some((lp, _)) if self.lam > *lp => self.predict(p, prev, next, &saved),
                Some(_) => p.set_continuation(self.load(next)),
                None => match self.tangent_predict(st, p, next) {
                    Err(m) => return Outcome::Mechanism(m),
                    // Past a bifurcation the linear response is the symmetric saddle's; where it
                    // does not even hold over the increment, Newton from the lifted prediction
                    // fails, and the attempt's iterations are wasted: the increment is cut
                    // before iterating.
                    Ok(false) if self.root_path && self.inc > MIN_INCREMENT * 1.0001 => {
                        p.restore(&saved);
                        st.report.retries += 1;
                        self.inc = (0.25 * self.inc).max(MIN_INCREMENT);
                        continue;
                    }
                    Ok(held) => {
                        if !held {
                            linear = linear_response(st, p, &saved);
                        }
                        p.keep_lengths(&saved)
                    }
                },
            }
            let minimal = self.inc <= MIN_INCREMENT * 1.0001;
            let remaining = s
                .max_iterations
                .saturating_sub(st.report.iterations - its_before);
            let last_chance = minimal || remaining <= ATTEMPT_CAP;
            let caps = if last_chance {
                (remaining, remaining)
            } else {
                (ATTEMPT_CAP, (2 * ATTEMPT_CAP).min(remaining))
            };
            let intermediate = next < 1.0 || s.intermediate;
            let tolerance = if intermediate {
                s.tolerance.max(INTERMEDIATE_TOLERANCE)
            } else {
                s.tolerance
            };
            let mut lim = self.limits(tolerance, caps, !last_chance);
            if intermediate {
                lim.step_tolerance = Some(INTERMEDIATE_STEP);
            }
            // Only the state at the path's end is reported. (A solve whose end state is itself
            // intermediate, `s.intermediate`, judges every sub-step: its last may end on a small
            // step, which does not judge, and keep the verdict of the one before.)
            lim.judge_stability = next >= 1.0 || s.intermediate;
            let before = st.report.iterations;
            // Where the linear response was cut short or refused as the start, the whole of it
            // is still what a smooth branch's end is measured against.
            let predicted = linear.or_else(|| p.unknown_positions());
            let turns = (st.report.regularized_iterations, st.report.saddle_escapes);
            st.escaped = None;
            match st.iterate(p, s, &lim, k) {
                o @ (Outcome::Converged | Outcome::AtFloor) => {
                    let ends = (self.load(self.lam), self.load(next));
                    if let (Some(start), Some(predicted)) = (&start, &predicted) {
                        // A jump is called a snap only once it survives increments this small:
                        // over a long increment a smooth branch's end also lies far from a
                        // poor prediction (none at all when the linear response was refused),
                        // and iterates far from equilibrium are indefinite on any branch.
                        let refinable = !last_chance
                            && next - self.lam > SNAP_BRACKET / self.steps as f64
                            && st.report.iterations - its_before + ATTEMPT_CAP < s.max_iterations;
                        let snap = snap_of(st, p, ends, (start, predicted), turns);
                        if refinable && snap.is_some() {
                            st.report.retries += 1;
                            p.restore(&saved);
                            self.inc = (0.25 * (next - self.lam)).max(MIN_INCREMENT);
                            continue;
                        }
                        judge_substep(st, p, (&saved, ends), snap, turns.1);
                    }
                    st.report.substeps += 1;
                    if prev.len() == HISTORY {
                        prev.remove(0);
                    }
                    prev.push((self.lam, saved));
                    self.lam = next;
                    if st.report.iterations - before <= 5 {
                        self.inc = (2.0 * self.inc).min(1.0 / self.steps as f64);
                    }
                    last = o;
                }
                Outcome::Budget(msg) if self.deadline.is_some_and(|t| Instant::now() >= t) => {
                    return Outcome::Budget(msg)
                }
                o if last_chance => return o,
                _ => {
                    st.report.retries += 1;
                    p.restore(&saved);
                    self.inc = (0.25 * self.inc).max(MIN_INCREMENT);
                }
            }
        }
        last
    }
}

/// Positions of the whole linear response to the increment from the state `from` (Newton's
/// step `d` after `tangent_predict`), without moving the state.
fn linear_response<P: NewtonProblem>(
    st: &Newton,
    p: &mut P,
    from: &P::Snapshot,
) -> Option<Vec<[f64; 3]>> {
    let here = p.snapshot();
    p.restore(from);
    // Even where a step that long is refused: only its positions are read.
    p.accept(&st.d, 1.0);
    let x = p.unknown_positions();
    p.restore(&here);
    x
}

/// The snap of a converged sub-step, if any: judged only where no saddle escape ran in it or in
/// the sub-step before (`judge_substep`: what a state does while it leaves a bifurcation
/// belongs to that bifurcation). `turns`: the regularized iterations and saddle escapes counted
/// before the sub-step.
fn snap_of<P: NewtonProblem>(
    st: &Newton,
    p: &P,
    ends: (f64, f64),
    (start, predicted): (&[[f64; 3]], &[[f64; 3]]),
    turns: (usize, usize),
) -> Option<PathEvent> {
    let escapes = st.report.saddle_escapes - turns.1;
    if escapes > 0 || st.leaving_path {
        return None;
    }
    let end = p.unknown_positions()?;
    Judged {
        from: ends.0,
        to: ends.1,
        start,
        predicted,
        end: &end,
        regularized: st.report.regularized_iterations - turns.0,
        escapes,
    }
    .snap()
}

/// Records the path event of a converged sub-step between the load factors `ends`: its `snap`
/// ([`snap_of`]), else a bifurcation where the saddle escape ran (located from the curvature of
/// its direction at the sub-step's start, `saved`). `escapes_before`: the saddle escapes
/// counted before the sub-step.
fn judge_substep<P: NewtonProblem>(
    st: &mut Newton,
    p: &mut P,
    (saved, ends): (&P::Snapshot, (f64, f64)),
    snap: Option<PathEvent>,
    escapes_before: usize,
) {
    // Sub-steps that escape one after another leave the same bifurcation (the new branch is
    // shallow near it, and the next prediction may fall back onto the old one): one event, and
    // what the state does while it leaves (a column's √ growth, an arch's snap to its inverted
    // state) is that bifurcation's consequence, not another event.
    let leaving = st.report.saddle_escapes > escapes_before;
    let was_leaving = std::mem::replace(&mut st.leaving_path, leaving);
    if !leaving && !was_leaving {
        st.report.path_events.extend(snap);
        return;
    }
    let Some((v, at_end)) = st.escaped.take().filter(|_| leaving && !was_leaving) else {
        return;
    };
    // The direction's curvature at the sub-step's start: the Hessian there, then back. (The
    // values are the next iteration's to assemble again.)
    let now = p.snapshot();
    p.restore(saved);
    p.assemble(&mut st.g, Some(&mut st.chol.values));
    st.chol.multiply(&v, &mut st.c);
    let at_start: f64 = v.iter().zip(&st.c).map(|(a, b)| a * b).sum();
    p.restore(&now);
    st.report
        .path_events
        .push(bifurcation(ends.0, ends.1, at_start, at_end));
}

/// Weights wᵢ of the earlier converged states (parameters sᵢ, oldest first) in the prediction
/// x + Σ wᵢ (xᵢ − x) at `next` from the current state x at `now`: Lagrange interpolation through
/// them all, evaluated no further than twice the last interval ahead.
fn secant_weights<S>(prev: &[(f64, S)], now: f64, next: f64) -> Vec<f64> {
    let last = prev.last().map_or(now, |p| p.0);
    let at = next.min(now + 2.0 * (now - last));
    let nodes: Vec<f64> = prev.iter().map(|p| p.0).chain([now]).collect();
    (0..prev.len())
        .map(|i| {
            nodes
                .iter()
                .enumerate()
                .filter(|&(j, _)| j != i)
                .map(|(_, &sj)| (at - sj) / (nodes[i] - sj))
                .product()
        })
        .collect()
}
