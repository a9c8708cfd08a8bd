//! Nonlinear solvers of the references: bisection where monotonicity is known analytically,
//! damped Newton for the two-parameter shooting problems, and the continuation that carries
//! either kind of shooting solution from an easy problem to the requested one.

use super::vector::axpy;

/// Bisection for an increasing function on `[lo, hi]`, run until the bracket is two adjacent
/// floating-point numbers. Used where monotonicity is known analytically, so robustness is
/// worth more than the handful of extra evaluations.
pub fn bisect_increasing(g: impl Fn(f64) -> f64, mut lo: f64, mut hi: f64) -> f64 {
    for _ in 0..2000 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if g(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Damped Newton iteration for two equations in two unknowns, with a central-difference
/// Jacobian (it only steers the iteration; the converged accuracy is set by the residual).
/// `residual` returns `None` outside the admissible region. Gives up (`None`) unless every
/// step contracts, so that callers shorten a continuation step rather than drift to a
/// non-physical branch.
pub fn newton_2d(
    residual: &dyn Fn([f64; 2]) -> Option<[f64; 2]>,
    start: [f64; 2],
    fd_step: [f64; 2],
    tol: f64,
) -> Option<[f64; 2]> {
    let norm = |v: [f64; 2]| v[0].hypot(v[1]);
    let mut p = start;
    let mut res = residual(p)?;
    let mut last_step = f64::INFINITY;
    for _ in 0..60 {
        if !norm(res).is_finite() {
            return None;
        }
        if norm(res) <= tol {
            return Some(p);
        }
        let column = |i: usize| -> Option<[f64; 2]> {
            let (mut plus, mut minus) = (p, p);
            plus[i] += fd_step[i];
            minus[i] -= fd_step[i];
            let (a, b) = (residual(plus)?, residual(minus)?);
            Some([
                (a[0] - b[0]) / (2.0 * fd_step[i]),
                (a[1] - b[1]) / (2.0 * fd_step[i]),
            ])
        };
        let (c0, c1) = (column(0)?, column(1)?);
        let det = c0[0] * c1[1] - c1[0] * c0[1];
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        let step = [
            (c1[1] * res[0] - c1[0] * res[1]) / det,
            (c0[0] * res[1] - c0[1] * res[0]) / det,
        ];
        let size = (step[0] / fd_step[0])
            .abs()
            .max((step[1] / fd_step[1]).abs());
        if size > 0.5 * last_step && size > 1e-2 {
            return None;
        }
        last_step = size;
        let mut damping = 1.0;
        loop {
            let trial = axpy(&p, -damping, &step);
            if let Some(trial_res) = residual(trial) {
                if norm(trial_res) < norm(res) {
                    p = trial;
                    res = trial_res;
                    break;
                }
            }
            damping *= 0.5;
            if damping < 1e-3 {
                // No descent left: accept only if already at the round-off floor.
                return (norm(res) <= 1e3 * tol).then_some(p);
            }
        }
    }
    (norm(res) <= 1e3 * tol).then_some(p)
}

/// Follows the solution `p(t)` of `solve(t, guess)` from `t = from` (solution `start`) to
/// `t = to`, with a secant predictor whose first slope is `slope`. The step grows by half
/// after each success and is halved whenever `solve` refuses (a poor prediction then costs a
/// shorter step rather than a jump to another branch); `None` once it falls below `min_step`.
pub fn continuation<const N: usize>(
    solve: impl Fn(f64, [f64; N]) -> Option<[f64; N]>,
    from: f64,
    start: [f64; N],
    to: f64,
    mut slope: [f64; N],
    first_step: f64,
    min_step: f64,
) -> Option<[f64; N]> {
    let (mut t, mut p, mut dt) = (from, start, first_step);
    while t < to {
        let next = (t + dt).min(to);
        let step = next - t;
        match solve(next, axpy(&p, step, &slope)) {
            Some(q) => {
                slope = std::array::from_fn(|i| (q[i] - p[i]) / step);
                p = q;
                t = next;
                dt *= 1.5;
            }
            None => {
                dt *= 0.5;
                if dt < min_step {
                    return None;
                }
            }
        }
    }
    Some(p)
}
