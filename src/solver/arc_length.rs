//! Pseudo-arclength continuation: the load factor λ becomes an unknown, and each step moves a
//! distance Δs along the equilibrium path (x(s), λ(s)) instead of a fixed increment of λ, so
//! that paths through limit points (snap-through: λ first rises, then falls) are followed.
//!
//! Predictor: the tangent t = (t_x, t_λ) with H t_x = −t_λ ∂g/∂λ, normalized in the metric
//! κ‖t_x‖²_W + t_λ² (κ makes the first tangent's two parts weigh alike) and oriented along the
//! previous one. Corrector: Newton on g(x, λ) = 0 and the hyperplane κ t_xᵀW(x − x_p) + t_λ(λ −
//! λ_p) = 0 through the predicted point, by block elimination with an LDLᵀ factorization of H
//! (indefinite past a limit point, where the Cholesky of the load-controlled path fails). Δs
//! halves when a corrector does not converge and grows ×1.5 after easy steps. A sign change of
//! t_λ between two steps is a limit point (reported with its λ). When λ passes 1, the state is
//! interpolated to λ = 1 and converged there by the ordinary Newton iteration.

use std::time::Instant;

use super::modes::wdot;
use super::newton::{Limits, Newton, Outcome};
use super::path_events::{EventKind, PathEvent};
use super::problem::{ContinuationPath, Core, NewtonProblem};
use super::settings::{LimitPoint, NewtonSettings};

/// Corrector iterations before Δs is halved.
const CORRECTOR_CAP: usize = 10;
/// Relative residual of the corrector (intermediate points only start the next step).
const CORRECTOR_TOLERANCE: f64 = 1e-7;
/// First step length in the normalized metric (about a tenth of the way to λ = 1 on a linear
/// path).
const FIRST_STEP: f64 = 0.1;
const MIN_STEP: f64 = 1e-7;
const MAX_STEPS: usize = 20_000;

struct Tangent {
    x: Vec<f64>,
    lam: f64,
    /// ∂g/∂λ at the point the tangent was taken.
    g_lam: Vec<f64>,
}

pub(super) fn follow<P: NewtonProblem>(
    st: &mut Newton,
    p: &mut P,
    s: &NewtonSettings,
    deadline: Option<Instant>,
) -> Outcome {
    let n = st.g.len();
    let mut lam = 0.0;
    p.set_continuation(lam);
    let mut ds = FIRST_STEP / s.load_steps.max(1) as f64;
    let mut kappa = 0.0;
    let mut prev_t: Option<Tangent> = None;
    // The last step: where it started (λ, state) and its length.
    let mut last_step: Option<(f64, P::Snapshot, f64)> = None;
    let budget = s.max_iterations.saturating_mul(s.load_steps.max(1));
    let mut was_stable = true;
    for step in 0..MAX_STEPS {
        if st.report.iterations >= budget {
            return Outcome::Budget(format!(
                "{} Newton iterations on the arc-length path at λ = {lam:.6}",
                st.report.iterations
            ));
        }
        if deadline.is_some_and(|t| Instant::now() >= t) {
            return Outcome::Budget(format!(
                "time limit reached on the arc-length path at λ = {lam:.6}"
            ));
        }
        let Some(mut t) = tangent(st, p, lam, n) else {
            return Outcome::Failed(format!(
                "singular Hessian on the arc-length path at λ = {lam:.6}"
            ));
        };
        if kappa == 0.0 {
            let tx = wdot(&t.x, &t.x, &st.weights);
            kappa = if tx > 0.0 { 1.0 / tx } else { 1.0 };
        }
        normalize(&mut t, kappa, &st.weights, prev_t.as_ref());
        // H is assembled here: whether it is positive definite tells a stable point of the
        // path (one Cholesky attempt per step).
        st.report.factorizations += 1;
        let stable_here = st.chol.factor(0.0).is_ok();
        let limit = matches!(&prev_t, Some(pt) if pt.lam * t.lam < 0.0);
        if let (Some(pt), Some((l0, s0, len)), true, false) =
            (&prev_t, &last_step, was_stable && !stable_here, limit)
        {
            // Stability lost without the load factor turning back: a bifurcation, which the
            // path passes on its unstable branch. Located like a limit point, then back here.
            let after = p.snapshot();
            let at = locate(st, p, (s, kappa), (*l0, s0, pt), *len, |st, _, _| {
                st.report.factorizations += 1;
                st.chol.factor(0.0).is_err()
            });
            st.report.path_events.push(PathEvent {
                kind: EventKind::Bifurcation,
                load_factor: at,
                detail: format!(
                    "between load factors {l0:.6} and {lam:.6} the arc-length path's state turned \
                     unstable without a limit point (last stable point located at {at:.6}): a \
                     bifurcation, passed on the path's unstable branch"
                ),
            });
            p.restore(&after);
            p.set_continuation(lam);
            t = tangent(st, p, lam, n).map_or(t, |mut nt| {
                normalize(&mut nt, kappa, &st.weights, prev_t.as_ref());
                nt
            });
        }
        was_stable = stable_here;
        if let (Some(pt), Some((l0, s0, len))) = (&prev_t, &last_step) {
            if pt.lam * t.lam < 0.0 {
                // A limit point between the last two points: locate it, then come back here.
                let after = p.snapshot();
                let load_factor = locate_limit(st, p, s, kappa, (*l0, s0, pt), *len);
                st.report
                    .limit_points
                    .push(LimitPoint { load_factor, step });
                p.restore(&after);
                p.set_continuation(lam);
                // The tangent was computed here before the detour; the factor was not kept.
                t = tangent(st, p, lam, n).map_or(t, |mut nt| {
                    normalize(&mut nt, kappa, &st.weights, prev_t.as_ref());
                    nt
                });
            }
        }
        let here = (lam, p.snapshot());
        let (new_lam, ok) = loop {
            match correct(st, p, s, &t, kappa, lam, ds) {
                Some(l) => break (l, true),
                None => {
                    p.restore(&here.1);
                    p.set_continuation(lam);
                    st.report.retries += 1;
                    ds *= 0.5;
                    if ds < MIN_STEP {
                        break (lam, false);
                    }
                }
            }
        };
        if !ok {
            return Outcome::Failed(format!(
                "the arc-length corrector did not converge at λ = {lam:.6} even with a step of {MIN_STEP:e}"
            ));
        }
        st.report.substeps += 1;
        st.report.arc_length_steps += 1;
        let (lp, snap) = here;
        lam = new_lam;
        prev_t = Some(t);
        last_step = Some((lp, snap.clone(), ds));
        if lam >= 1.0 {
            let f = (1.0 - lp) / (lam - lp);
            p.extrapolate(&[(&snap, 1.0 - f)]);
            p.set_continuation(1.0);
            let lim = Limits {
                tolerance: s.tolerance,
                cap: budget.saturating_sub(st.report.iterations).max(1),
                extended_cap: budget.saturating_sub(st.report.iterations).max(1),
                deadline,
                retry_on_damping: false,
                step_tolerance: None,
                judge_stability: true,
            };
            return st.iterate(p, s, &lim, s.load_steps.max(1));
        }
        ds = (ds * 1.5).min(1.0);
    }
    Outcome::Failed(format!(
        "{MAX_STEPS} arc-length steps without reaching λ = 1 (at λ = {lam:.6})"
    ))
}

/// Bisects the arc from (λ₀, state, tangent t₀) over `len` for the point where the tangent's λ
/// component changes sign, and returns λ there (to about 1e-8 of the step in arc length).
fn locate_limit<P: NewtonProblem>(
    st: &mut Newton,
    p: &mut P,
    s: &NewtonSettings,
    kappa: f64,
    start: (f64, &P::Snapshot, &Tangent),
    len: f64,
) -> f64 {
    locate(st, p, (s, kappa), start, len, |_, t_m, t_a| {
        t_m.lam * t_a.lam <= 0.0
    })
}

/// Bisects the arc from (λ₀, state, tangent t₀) over `len` for the first point where
/// `crossed(st, tangent there, tangent before)` holds (the Hessian there is assembled), and
/// returns λ at the last point before it.
fn locate<P: NewtonProblem>(
    st: &mut Newton,
    p: &mut P,
    (s, kappa): (&NewtonSettings, f64),
    (lam0, state0, t0): (f64, &P::Snapshot, &Tangent),
    len: f64,
    crossed: impl Fn(&mut Newton, &Tangent, &Tangent) -> bool,
) -> f64 {
    let n = st.g.len();
    let (mut lam_a, mut state_a) = (lam0, state0.clone());
    let mut t_a = Tangent {
        x: t0.x.clone(),
        lam: t0.lam,
        g_lam: t0.g_lam.clone(),
    };
    let mut len = len;
    for _ in 0..40 {
        if len < 1e-9 {
            break;
        }
        let h = 0.5 * len;
        p.restore(&state_a);
        p.set_continuation(lam_a);
        let Some(lam_m) = correct(st, p, s, &t_a, kappa, lam_a, h) else {
            break;
        };
        let Some(mut t_m) = tangent(st, p, lam_m, n) else {
            break;
        };
        normalize(&mut t_m, kappa, &st.weights, Some(&t_a));
        if !crossed(st, &t_m, &t_a) {
            // Still before the limit: move the start there.
            lam_a = lam_m;
            state_a = p.snapshot();
            t_a = t_m;
            len -= h;
        } else {
            len = h;
        }
    }
    // The last point before the sign change: λ there differs from the extreme by the square of
    // the remaining arc, which the bisection has made negligible.
    lam_a
}

/// ∂g/∂λ at the current state by a central difference (exact for dead loads, whose gradient is
/// linear in λ; prescribed motions move with λ as well).
fn g_lambda<P: Core + ContinuationPath>(p: &mut P, lam: f64, n: usize) -> Vec<f64> {
    let h = 1e-4;
    let (mut a, mut b) = (vec![0.0; n], vec![0.0; n]);
    p.set_continuation(lam + h);
    p.assemble(&mut a, None);
    p.set_continuation(lam - h);
    p.assemble(&mut b, None);
    p.set_continuation(lam);
    a.iter_mut()
        .zip(&b)
        .for_each(|(a, b)| *a = (*a - b) / (2.0 * h));
    a
}

/// The unnormalized tangent (t_x, 1) with H t_x = −∂g/∂λ.
fn tangent<P: NewtonProblem>(st: &mut Newton, p: &mut P, lam: f64, n: usize) -> Option<Tangent> {
    let g_lam = g_lambda(p, lam, n);
    p.assemble(&mut st.g, Some(&mut st.chol.values));
    st.report.factorizations += 1;
    st.chol.factor_ldlt().ok()?;
    let mut x: Vec<f64> = g_lam.iter().map(|v| -v).collect();
    st.chol.solve_ldlt(&mut x);
    x.iter()
        .all(|v| v.is_finite())
        .then_some(Tangent { x, lam: 1.0, g_lam })
}

/// Unit length in the path metric, oriented along the previous tangent (the first one toward
/// increasing λ).
fn normalize(t: &mut Tangent, kappa: f64, w: &[f64], prev: Option<&Tangent>) {
    let len = (kappa * wdot(&t.x, &t.x, w) + t.lam * t.lam).sqrt();
    let mut sign = 1.0 / len;
    if let Some(pt) = prev {
        if kappa * wdot(&t.x, &pt.x, w) * sign + t.lam * pt.lam * sign < 0.0 {
            sign = -sign;
        }
    }
    t.x.iter_mut().for_each(|v| *v *= sign);
    t.lam *= sign;
}

/// Predictor and corrector of one step of length `ds`; returns the new λ, or None when the
/// corrector fails (the caller restores the state).
fn correct<P: NewtonProblem>(
    st: &mut Newton,
    p: &mut P,
    s: &NewtonSettings,
    t: &Tangent,
    kappa: f64,
    lam0: f64,
    ds: f64,
) -> Option<f64> {
    let n = st.g.len();
    let step: Vec<f64> = t.x.iter().map(|v| ds * v).collect();
    let alpha = p.max_step(&step).min(1.0);
    if alpha < 1.0 {
        return None;
    }
    p.accept(&step, 1.0);
    let lam_p = lam0 + ds * t.lam;
    let mut lam = lam_p;
    p.set_continuation(lam);
    // Motion since the predicted point, for the hyperplane constraint.
    let mut moved = vec![0.0; n];
    let tolerance = s.tolerance.max(CORRECTOR_TOLERANCE);
    let (mut a, mut b) = (vec![0.0; n], vec![0.0; n]);
    for it in 0..=CORRECTOR_CAP {
        let e = p.assemble(&mut st.g, Some(&mut st.chol.values));
        let res = p.relative_residual(&st.g);
        st.report.residual = res;
        st.report.energy = e;
        if !(e.is_finite() && res.is_finite()) {
            return None;
        }
        if let Some(cb) = &s.progress {
            cb(0, st.report.iterations, res, e);
        }
        let c = kappa * wdot(&t.x, &moved, &st.weights) + t.lam * (lam - lam_p);
        if res < tolerance && c.abs() < 1e-9 * ds.max(1e-12) {
            return Some(lam);
        }
        if it == CORRECTOR_CAP {
            return None;
        }
        st.report.factorizations += 1;
        st.chol.factor_ldlt().ok()?;
        a.copy_from_slice(&st.g);
        st.chol.solve_ldlt(&mut a);
        b.copy_from_slice(&t.g_lam);
        st.chol.solve_ldlt(&mut b);
        let den = t.lam - kappa * wdot(&t.x, &b, &st.weights);
        if den == 0.0 || !den.is_finite() {
            return None;
        }
        let dlam = (kappa * wdot(&t.x, &a, &st.weights) - c) / den;
        // dx = −a − b·dλ, formed in `a`.
        a.iter_mut().zip(&b).for_each(|(a, b)| *a = -*a - b * dlam);
        let alpha = p.max_step(&a).min(1.0);
        p.accept(&a, alpha);
        moved.iter_mut().zip(&a).for_each(|(m, d)| *m += alpha * d);
        lam += alpha * dlam;
        p.set_continuation(lam);
        st.report.iterations += 1;
    }
    None
}
