//! Independent analytic and semi-analytic reference solutions from rod mechanics.
//!
//! Everything here is deliberately separate from the discrete-elastic-rod machinery of the
//! crate: the validation tests and `rodnet study convergence` compare the simulator against
//! these numbers, so they must not share code paths with it. Only `std` is used.
//!
//! Two kinds of tools are provided:
//!
//! * closed forms in terms of Legendre elliptic integrals, evaluated through Carlson's
//!   symmetric integrals `R_F` and `R_D` (duplication algorithm, B. C. Carlson, "Numerical
//!   computation of real or complex elliptic integrals", Numer. Algorithms 10, 1995);
//! * shooting solutions of the planar inextensible elastica, integrated with a fixed-step
//!   Gragg–Bulirsch–Stoer (modified midpoint + polynomial extrapolation) scheme whose error
//!   is far below 1e-12 for the smooth problems below.
//!
//! Where both exist (cantilever with a tip force, post-buckled Euler strut, heavy elastica
//! shot upwards and downwards) the tests check that they agree to 1e-9; the measured
//! agreement is 1e-12 or better.
//!
//! All results are dimensionless; each function documents its scaling.

use std::f64::consts::{FRAC_1_SQRT_2, FRAC_PI_2, FRAC_PI_4, PI, SQRT_2};

// ---------------------------------------------------------------------------------------------
// Elliptic integrals
// ---------------------------------------------------------------------------------------------

/// Carlson's symmetric elliptic integral of the first kind,
/// `R_F(x, y, z) = ½ ∫₀^∞ dt / √((t+x)(t+y)(t+z))`.
///
/// # Panics
/// If an argument is negative or more than one is zero.
#[must_use]
pub fn carlson_rf(x: f64, y: f64, z: f64) -> f64 {
    assert!(
        x >= 0.0 && y >= 0.0 && z >= 0.0,
        "carlson_rf: negative argument"
    );
    assert!(
        (x == 0.0) as u8 + (y == 0.0) as u8 + (z == 0.0) as u8 <= 1,
        "carlson_rf: more than one zero argument"
    );
    let (mut x, mut y, mut z) = (x, y, z);
    loop {
        let a = (x + y + z) / 3.0;
        let (dx, dy) = (1.0 - x / a, 1.0 - y / a);
        let dz = -(dx + dy);
        // The neglected terms of the Taylor series are O(r^6); r < 1e-3 keeps them < 1e-18.
        if dx.abs().max(dy.abs()).max(dz.abs()) < 1e-3 {
            let e2 = dx * dy - dz * dz;
            let e3 = dx * dy * dz;
            return (1.0 - e2 / 10.0 + e3 / 14.0 + e2 * e2 / 24.0 - 3.0 * e2 * e3 / 44.0)
                / a.sqrt();
        }
        let (sx, sy, sz) = (x.sqrt(), y.sqrt(), z.sqrt());
        let lambda = sx * sy + sy * sz + sz * sx;
        x = 0.25 * (x + lambda);
        y = 0.25 * (y + lambda);
        z = 0.25 * (z + lambda);
    }
}

/// Carlson's symmetric elliptic integral of the second kind,
/// `R_D(x, y, z) = 3/2 ∫₀^∞ dt / ((t+z) √((t+x)(t+y)(t+z)))`.
///
/// # Panics
/// If an argument is negative, `z` is zero, or both `x` and `y` are zero.
#[must_use]
pub fn carlson_rd(x: f64, y: f64, z: f64) -> f64 {
    assert!(
        x >= 0.0 && y >= 0.0 && z > 0.0,
        "carlson_rd: invalid argument"
    );
    assert!(x + y > 0.0, "carlson_rd: x and y both zero");
    let (mut x, mut y, mut z) = (x, y, z);
    let mut sum = 0.0;
    let mut scale = 1.0;
    loop {
        let a = (x + y + 3.0 * z) / 5.0;
        let (dx, dy) = (1.0 - x / a, 1.0 - y / a);
        let dz = -(dx + dy) / 3.0;
        if dx.abs().max(dy.abs()).max(dz.abs()) < 1e-3 {
            let xy = dx * dy;
            let z2 = dz * dz;
            let e2 = xy - 6.0 * z2;
            let e3 = (3.0 * xy - 8.0 * z2) * dz;
            let e4 = 3.0 * (xy - z2) * z2;
            let e5 = xy * z2 * dz;
            let series = 1.0 - 3.0 * e2 / 14.0 + e3 / 6.0 + 9.0 * e2 * e2 / 88.0
                - 3.0 * e4 / 22.0
                - 9.0 * e2 * e3 / 52.0
                + 3.0 * e5 / 26.0;
            return 3.0 * sum + scale * series / (a * a.sqrt());
        }
        let (sx, sy, sz) = (x.sqrt(), y.sqrt(), z.sqrt());
        let lambda = sx * sy + sy * sz + sz * sx;
        sum += scale / (sz * (z + lambda));
        scale *= 0.25;
        x = 0.25 * (x + lambda);
        y = 0.25 * (y + lambda);
        z = 0.25 * (z + lambda);
    }
}

/// Complete elliptic integral of the first kind `K(m)`, parameter `m = k²`.
///
/// # Panics
/// If `m ≥ 1` (`K` diverges at `m = 1`).
#[must_use]
pub fn elliptic_k(m: f64) -> f64 {
    assert!(m < 1.0, "elliptic_k: parameter must be < 1");
    carlson_rf(0.0, 1.0 - m, 1.0)
}

/// Complete elliptic integral of the second kind `E(m)`, parameter `m = k²`.
///
/// # Panics
/// If `m > 1`.
#[must_use]
pub fn elliptic_e(m: f64) -> f64 {
    assert!(m <= 1.0, "elliptic_e: parameter must be <= 1");
    if m == 1.0 {
        return 1.0;
    }
    let y = 1.0 - m;
    carlson_rf(0.0, y, 1.0) - m / 3.0 * carlson_rd(0.0, y, 1.0)
}

/// Splits `phi` into `phi_r + j π` with `|phi_r| ≤ π/2`, because the Carlson forms below are
/// valid on one half-period only and the Legendre integrals grow by `2K` per period.
fn reduce_amplitude(phi: f64) -> (f64, f64) {
    let j = (phi / PI).round();
    (phi - j * PI, j)
}

/// Incomplete elliptic integral of the first kind `F(φ | m) = ∫₀^φ dθ / √(1 − m sin²θ)`.
#[must_use]
pub fn elliptic_f(phi: f64, m: f64) -> f64 {
    let (p, j) = reduce_amplitude(phi);
    let (s, c) = p.sin_cos();
    let part = s * carlson_rf(c * c, 1.0 - m * s * s, 1.0);
    if j == 0.0 {
        part
    } else {
        part + 2.0 * j * elliptic_k(m)
    }
}

/// Incomplete elliptic integral of the second kind `E(φ | m) = ∫₀^φ √(1 − m sin²θ) dθ`.
#[must_use]
pub fn elliptic_e_incomplete(phi: f64, m: f64) -> f64 {
    let (p, j) = reduce_amplitude(phi);
    let (s, c) = p.sin_cos();
    let (x, y) = (c * c, 1.0 - m * s * s);
    let part = s * carlson_rf(x, y, 1.0) - m / 3.0 * s * s * s * carlson_rd(x, y, 1.0);
    if j == 0.0 {
        part
    } else {
        part + 2.0 * j * elliptic_e(m)
    }
}

// ---------------------------------------------------------------------------------------------
// ODE integration (Gragg–Bulirsch–Stoer with fixed macro steps)
// ---------------------------------------------------------------------------------------------

/// Substep counts of the extrapolation tableau. Eight levels of the even sequence give an
/// order-16 method per macro step, so a few dozen macro steps reach round-off for the
/// smooth, non-stiff elastica equations.
const GBS_SUBSTEPS: [usize; 8] = [2, 4, 6, 8, 10, 12, 14, 16];

fn modified_midpoint<const N: usize, F>(
    f: &F,
    t: f64,
    y: &[f64; N],
    h_big: f64,
    n: usize,
) -> [f64; N]
where
    F: Fn(f64, &[f64; N]) -> [f64; N],
{
    let h = h_big / n as f64;
    let mut prev = *y;
    let d = f(t, y);
    let mut cur = [0.0; N];
    for i in 0..N {
        cur[i] = prev[i] + h * d[i];
    }
    for step in 1..n {
        let d = f(t + step as f64 * h, &cur);
        for i in 0..N {
            let next = prev[i] + 2.0 * h * d[i];
            prev[i] = cur[i];
            cur[i] = next;
        }
    }
    let d = f(t + h_big, &cur);
    let mut out = [0.0; N];
    for i in 0..N {
        out[i] = 0.5 * (cur[i] + prev[i] + h * d[i]);
    }
    out
}

/// Integrates `y' = f(t, y)` from `t0` to `t1` with `macro_steps` equal Bulirsch–Stoer steps.
/// A fixed step (rather than adaptive control) keeps every result a smooth function of the
/// shooting parameters, which the Newton iterations and finite differences rely on.
fn integrate<const N: usize, F>(
    f: &F,
    y0: [f64; N],
    t0: f64,
    t1: f64,
    macro_steps: usize,
) -> [f64; N]
where
    F: Fn(f64, &[f64; N]) -> [f64; N],
{
    let h_big = (t1 - t0) / macro_steps as f64;
    let mut y = y0;
    let mut row: Vec<[f64; N]> = Vec::with_capacity(GBS_SUBSTEPS.len());
    let mut new_row: Vec<[f64; N]> = Vec::with_capacity(GBS_SUBSTEPS.len());
    for step in 0..macro_steps {
        let t = t0 + step as f64 * h_big;
        row.clear();
        for (j, &n) in GBS_SUBSTEPS.iter().enumerate() {
            new_row.clear();
            new_row.push(modified_midpoint(f, t, &y, h_big, n));
            // Aitken–Neville in the variable (H/n)², the midpoint rule's error expansion.
            for k in 1..=j {
                let ratio = n as f64 / GBS_SUBSTEPS[j - k] as f64;
                let denom = ratio * ratio - 1.0;
                let mut v = [0.0; N];
                for i in 0..N {
                    v[i] = new_row[k - 1][i] + (new_row[k - 1][i] - row[k - 1][i]) / denom;
                }
                new_row.push(v);
            }
            std::mem::swap(&mut row, &mut new_row);
        }
        y = row[row.len() - 1];
    }
    y
}

// ---------------------------------------------------------------------------------------------
// Scalar root finding
// ---------------------------------------------------------------------------------------------

/// Bisection for an increasing function on `[lo, hi]`, run until the bracket is two adjacent
/// floating-point numbers. Used where monotonicity is known analytically, so robustness is
/// worth more than the handful of extra evaluations.
fn bisect_increasing(g: impl Fn(f64) -> f64, mut lo: f64, mut hi: f64) -> f64 {
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

// ---------------------------------------------------------------------------------------------
// Cantilever elastica
// ---------------------------------------------------------------------------------------------

/// Tip response of a planar inextensible cantilever, all lengths divided by the rod length `L`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElasticaTip {
    /// Tip displacement perpendicular to the undeformed axis, `v/L` (positive in the
    /// direction of the applied force or moment).
    pub deflection: f64,
    /// Tip displacement back along the undeformed axis, `u/L = 1 − x_tip/L`.
    pub shortening: f64,
    /// Tip rotation in radians (same sign as `deflection`).
    pub tip_angle: f64,
}

/// Cantilever clamped horizontally at `s = 0`, loaded by a dead tip force `P` perpendicular
/// to the undeformed axis; `load = P L² / EI`. Exact elliptic-integral solution.
///
/// With `θ(s)` the slope, moment balance about the section at `s` gives
/// `EI θ'' = −P cos θ`, `θ(0) = 0`, `θ'(L) = 0`. Its first integral is
/// `θ'² = 2λ (sin α − sin θ)`, `λ = P/EI`, `α = θ(L)`. The substitution
/// `1 + sin θ = 2k² sin²ψ`, `k² = (1 + sin α)/2`, turns `ds = dθ/θ'` into
/// `ds = dψ / (√λ √(1 − k² sin²ψ))`, so (with `ψ₀` the image of the root, `sin ψ₀ = 1/(k√2)`)
///
/// * `√λ L = K(k) − F(ψ₀, k)`,
/// * `√λ v = [K − F(ψ₀)] − 2 [E(k) − E(ψ₀, k)]`,
/// * `x_tip = √(2 sin α / λ)` (integrate `cos θ dθ / θ'` directly).
///
/// Evaluated literally these lose all accuracy for small loads (`ψ₀ → π/2`), so they are
/// rewritten with the addition theorems for `F` and `E` and the homogeneity of `R_F`, `R_D`.
/// With `s = sin α`, `c = (1 − s)/2 = sin²(π/4 − α/2)` and `k² = 1 − c`:
///
/// * `load = s · R_F(c, 2ck², k²)²`,
/// * `x_tip/L = √2 / R_F(c, 2ck², k²)`,
/// * `v/L = 2 (k² s R_D(c, 2ck², k²)/3 + 1/√2) / R_F(c, 2ck², k²) − 1`.
///
/// The load is increasing in `α ∈ (0, π/2)`; `α` is found by bisection to the last bit
/// (on `β = π/2 − α` when `α > π/4`, so that `c = sin²(β/2)` stays accurate for large loads,
/// where `α → π/2`).
/// Reference: K. E. Bisshopp and D. C. Drucker, "Large deflection of cantilever beams",
/// Q. Appl. Math. 3 (1945) 272–275 (`load = 2`: `v/L = 0.49345748`, `u/L = 0.16064172`).
///
/// A negative `load` mirrors the solution.
///
/// Accuracy: about 1e-16 absolute for every output and any load (the elliptic forms are
/// exact; the bisection is run to the last bit). For tiny loads `deflection` and especially
/// `shortening` (∝ load²) are small, so their *relative* accuracy degrades like
/// 1e-16/value: 1e-10 for the deflection at `load = 1e-6`.
///
/// # Panics
/// If `load` is not finite.
#[must_use]
pub fn cantilever_tip_load(load: f64) -> ElasticaTip {
    assert!(load.is_finite(), "cantilever_tip_load: load must be finite");
    if load == 0.0 {
        return ElasticaTip {
            deflection: 0.0,
            shortening: 0.0,
            tip_angle: 0.0,
        };
    }
    let root_load = load.abs().sqrt();
    // Whichever of s = sin α and c = (1 − s)/2 is small must come from an exactly stored
    // variable: α itself for moderate loads, β = π/2 − α once α passes π/4 (large loads).
    let params = |alpha: f64, beta: f64| {
        let s = if alpha <= FRAC_PI_4 {
            alpha.sin()
        } else {
            beta.cos()
        };
        let c = (0.5 * beta).sin().powi(2);
        (s, c, 0.5 * (1.0 + s))
    };
    let excess = |alpha: f64, beta: f64| {
        let (s, c, k2) = params(alpha, beta);
        s.sqrt() * carlson_rf(c, 2.0 * c * k2, k2) - root_load
    };
    let (alpha, beta) = if excess(FRAC_PI_4, FRAC_PI_4) >= 0.0 {
        let alpha = bisect_increasing(|a| excess(a, FRAC_PI_2 - a), 0.0, FRAC_PI_4);
        (alpha, FRAC_PI_2 - alpha)
    } else {
        let beta = bisect_increasing(|b| -excess(FRAC_PI_2 - b, b), 0.0, FRAC_PI_4);
        (FRAC_PI_2 - beta, beta)
    };
    let (s, c, k2) = params(alpha, beta);
    let rf = carlson_rf(c, 2.0 * c * k2, k2);
    let rd = carlson_rd(c, 2.0 * c * k2, k2);
    let deflection = 2.0 * (k2 * s * rd / 3.0 + FRAC_1_SQRT_2) / rf - 1.0;
    let shortening = 1.0 - SQRT_2 / rf;
    ElasticaTip {
        deflection: deflection.copysign(load),
        shortening,
        tip_angle: alpha.copysign(load),
    }
}

/// Cantilever clamped horizontally at `s = 0` under a pure end moment, `moment = M L / EI`.
///
/// The curvature is uniform, `θ = moment · s/L`, so the rod is a circular arc:
/// `v/L = (1 − cos m)/m`, `u/L = 1 − sin m / m`, tip angle `m`. The forms below avoid the
/// cancellation of those expressions for small `m`.
///
/// # Panics
/// If `moment` is not finite.
#[must_use]
pub fn cantilever_tip_moment(moment: f64) -> ElasticaTip {
    assert!(
        moment.is_finite(),
        "cantilever_tip_moment: moment must be finite"
    );
    let m = moment;
    if m == 0.0 {
        return ElasticaTip {
            deflection: 0.0,
            shortening: 0.0,
            tip_angle: 0.0,
        };
    }
    let half_sin = (0.5 * m).sin();
    let deflection = 2.0 * half_sin * half_sin / m;
    let shortening = if m.abs() < 0.1 {
        // Taylor series of 1 − sin m/m; the first omitted term is < 2e-22 here.
        let m2 = m * m;
        m2 * (1.0 / 6.0
            - m2 * (1.0 / 120.0 - m2 * (1.0 / 5040.0 - m2 * (1.0 / 362_880.0 - m2 / 39_916_800.0))))
    } else {
        1.0 - m.sin() / m
    };
    ElasticaTip {
        deflection,
        shortening,
        tip_angle: m,
    }
}

/// Cantilever clamped horizontally at `s = 0` under a dead tip force (`load = P L²/EI`,
/// perpendicular to the undeformed axis) combined with an end moment (`moment = M L/EI`,
/// turning the tip towards the force). Shooting solution, independent of the elliptic one.
///
/// In `s ∈ [0, 1]`: `x' = cos θ`, `y' = sin θ`, `θ' = κ`, `κ' = −load · cos θ`. The tip
/// conditions `θ(1) = α`, `κ(1) = moment` fix an initial-value problem that is integrated
/// backwards to the clamp; Newton's method on the unknown tip angle `α` enforces
/// `θ(0) = 0`, with `∂θ(0)/∂α` from the variational equations integrated alongside.
/// Shooting from the tip is much better conditioned than shooting from the clamp: the
/// clamp-side map grows like `exp(√load)` and its roots (looped branches) crowd together.
/// The loads are ramped up from zero by adaptive continuation so that Newton always starts
/// close to the natural branch (the one connected to the straight rod).
///
/// Accuracy: agrees with [`cantilever_tip_load`] to ~1e-14 at `load = 2` and 5e-13 at
/// `load = 60`. Beyond `load ≈ 150` the tip angle is within 1e-8 of π/2 and shooting
/// cannot resolve it (2e-9 error at 200); use the elliptic solution there.
///
/// # Panics
/// If an input is not finite or the continuation fails.
#[must_use]
pub fn cantilever_shooting(load: f64, moment: f64) -> ElasticaTip {
    assert!(
        load.is_finite() && moment.is_finite(),
        "cantilever_shooting: inputs must be finite"
    );
    let macro_steps = 32 + (8.0 * load.abs().sqrt() + 4.0 * moment.abs()).ceil() as usize;
    let shoot = |p: f64, m: f64, alpha: f64| {
        let rhs = |_s: f64, y: &[f64; 6]| {
            let (sin_t, cos_t) = y[2].sin_cos();
            [cos_t, sin_t, y[3], -p * cos_t, y[5], p * sin_t * y[4]]
        };
        integrate(&rhs, [0.0, 0.0, alpha, m, 1.0, 0.0], 1.0, 0.0, macro_steps)
    };
    // Newton that gives up unless it contracts at every step, so that a poor predictor
    // leads to a smaller continuation step instead of a jump to another branch.
    let newton = |p: f64, m: f64, mut alpha: f64| -> Option<f64> {
        let mut last = f64::INFINITY;
        for _ in 0..40 {
            let root = shoot(p, m, alpha);
            let delta = root[2] / root[4];
            if !delta.is_finite() || delta.abs() > 0.5 * last {
                return None;
            }
            alpha -= delta;
            // Quadratic convergence: after a step this small the remaining error is ~delta²,
            // far below the round-off floor of the residual itself.
            if delta.abs() <= 1e-9 * (1.0 + alpha.abs()) {
                return Some(alpha);
            }
            last = delta.abs();
        }
        None
    };
    // Continuation in t (loads t·load, t·moment) with a secant predictor; the first slope
    // is linear theory, θ(1) = load/2 + moment.
    let (mut t, mut alpha) = (0.0, 0.0);
    let mut slope = 0.5 * load + moment;
    let mut dt: f64 = 1.0 / (1.0 + 0.5 * load.abs().max(moment.abs()));
    while t < 1.0 {
        let t_new = (t + dt).min(1.0);
        let guess = alpha + slope * (t_new - t);
        match newton(t_new * load, t_new * moment, guess) {
            Some(a) => {
                slope = (a - alpha) / (t_new - t);
                alpha = a;
                t = t_new;
                dt *= 1.5;
            }
            None => {
                dt *= 0.5;
                assert!(dt > 1e-9, "cantilever_shooting: continuation failed");
            }
        }
    }
    // Integrated from the tip, so the clamp sits at (x, y) and the tip at the origin.
    let root = shoot(load, moment, alpha);
    ElasticaTip {
        deflection: -root[1],
        shortening: 1.0 + root[0],
        tip_angle: alpha,
    }
}

// ---------------------------------------------------------------------------------------------
// Post-buckled Euler strut
// ---------------------------------------------------------------------------------------------

/// First-mode post-buckled pinned–pinned inextensible elastica.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PostBuckled {
    /// Axial compressive load `P L² / EI`.
    pub load: f64,
    /// Largest lateral deflection (at midspan) over the length, `w/L`.
    pub midspan_deflection: f64,
    /// Slope at either pinned end, radians.
    pub end_angle: f64,
}

/// Shape data of the first-mode elastica from its modulus `k = sin(α/2)`.
///
/// With `θ` the slope and `α = θ(0)`, `EI θ'' + P sin θ = 0`, `θ'(0) = 0` (pin: no moment)
/// and `θ(L/2) = 0` (symmetry). Substituting `sin(θ/2) = k sin ψ` gives
/// `ds = dψ / (√λ √(1 − k² sin²ψ))`, `λ = P/EI`; a quarter wave spans `ψ ∈ [0, π/2]`, so
///
/// * `L/2 = K(k)/√λ`, i.e. `P L²/EI = 4 K²`;
/// * `x(L) = ∫ cos θ ds = (2E − K) · 2/√λ`, i.e. `d/L = 2 − 2E/K = 2 (K − E)/K`;
/// * `w = ∫₀^{L/2} sin θ ds = 2k/√λ`, i.e. `w/L = k/K`.
///
/// `K − E = (k²/3) R_D(0, 1 − k², 1)` is used directly to avoid cancellation when `k → 0`.
fn postbuckled_from_modulus(k: f64) -> (PostBuckled, f64) {
    let m = k * k;
    let kk = carlson_rf(0.0, 1.0 - m, 1.0);
    let k_minus_e = m / 3.0 * carlson_rd(0.0, 1.0 - m, 1.0);
    let shortening = 2.0 * k_minus_e / kk;
    (
        PostBuckled {
            load: 4.0 * kk * kk,
            midspan_deflection: k / kk,
            end_angle: 2.0 * k.asin(),
        },
        shortening,
    )
}

/// Post-buckled pinned–pinned inextensible strut (Euler elastica, first mode) for a given
/// end shortening `d/L`, `0 ≤ d/L < 2` (beyond `d/L = 1` the ends have passed each other,
/// which the planar elastica allows).
///
/// Solves `d/L = 2 (K(k) − E(k)) / K(k)` for the modulus `k` by bisection (it is increasing
/// in `k`), then returns `P L²/EI = 4K²`, `w/L = k/K`, end angle `2 asin k`; see
/// `postbuckled_from_modulus` for the derivation. Small shortening: `d ≈ k²`, so
/// `P L²/EI ≈ π² (1 + d/2)` and `w/L ≈ 2√d / π`. Reference value (d/L = 0.1):
/// `P L²/EI = 10.392564`, `w/L = 0.194924`.
///
/// # Panics
/// If `end_shortening` is outside `[0, 2)`.
#[must_use]
pub fn euler_buckling_postbuckled(end_shortening: f64) -> PostBuckled {
    assert!(
        (0.0..2.0).contains(&end_shortening),
        "euler_buckling_postbuckled: end shortening must be in [0, 2)"
    );
    if end_shortening == 0.0 {
        return PostBuckled {
            load: PI * PI,
            midspan_deflection: 0.0,
            end_angle: 0.0,
        };
    }
    let k = bisect_increasing(|k| postbuckled_from_modulus(k).1 - end_shortening, 0.0, 1.0);
    postbuckled_from_modulus(k).0
}

/// Post-buckled first-mode state of the same strut for a given axial load `P L²/EI ≥ π²`,
/// together with its end shortening `d/L`: solves `2 K(k) = √load` for `k`.
///
/// # Panics
/// If `load < π²` (no buckled first-mode equilibrium) or not finite.
#[must_use]
pub fn euler_buckling_postbuckled_at_load(load: f64) -> (PostBuckled, f64) {
    assert!(
        load.is_finite() && load >= PI * PI,
        "euler_buckling_postbuckled_at_load: load must be finite and >= pi^2"
    );
    let half_root = 0.5 * load.sqrt();
    let k = bisect_increasing(|k| elliptic_k(k * k) - half_root, 0.0, 1.0);
    postbuckled_from_modulus(k)
}

/// Euler critical load of a pinned–pinned column, `π² EI / L²`.
#[must_use]
pub fn euler_critical_load(ei: f64, l: f64) -> f64 {
    PI * PI * ei / (l * l)
}

// ---------------------------------------------------------------------------------------------
// Heavy elastica lifted from a floor
// ---------------------------------------------------------------------------------------------

/// Solution of the lifted heavy rod, in the units of [`heavy_elastica_lifted_end`]:
/// lengths over `ℓ_c = (EI/w)^{1/3}`, forces over `w ℓ_c`, energies over `w ℓ_c² = EI/ℓ_c`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeavyElastica {
    /// Arc length of the suspended part, from the lift-off point to the pin.
    pub suspended_length: f64,
    /// Horizontal distance between the lift-off point and the pin.
    pub span: f64,
    /// Vertical force the pin applies to the rod.
    pub lift_force: f64,
    /// Horizontal force the pin applies to the rod (zero: frictionless floor, free far end).
    pub horizontal_force: f64,
    /// Concentrated upward reaction of the floor at the lift-off point.
    pub touchdown_force: f64,
    /// Slope of the rod at the pin, radians (0 = horizontal).
    pub pin_angle: f64,
    /// Potential energy of the suspended part: bending `∫ EI κ²/2` plus gravity `∫ w z`.
    /// The lying part contributes nothing, so `d(energy)/d(height) = lift_force`.
    pub energy: f64,
}

/// Small-deflection (linear beam) theory of the lifted heavy rod; `height = h/ℓ_c`.
///
/// Take `ξ` from the lift-off point towards the pin. On the floor the rod is straight and
/// carries no moment; moment continuity (no point couple) and slope continuity give
/// `z(0) = z'(0) = z''(0) = 0` at lift-off. The free-boundary condition is exactly this
/// third condition: without it the contact length would be undetermined. The shear may
/// jump there: the floor transmits a concentrated reaction `R`. With `EI z'''' = −w`,
///
/// `z(ξ) = R ξ³/(6 EI) − w ξ⁴/(24 EI)`.
///
/// At the pin (`ξ = l`) the moment vanishes: `R l − w l²/2 = 0`, so `R = w l/2`, and then
/// `h = z(l) = w l⁴/12 − w l⁴/24 = w l⁴/(24 EI)`. Vertical equilibrium of the suspended part
/// gives the lift force `F = w l − R = w l/2` (equivalently, moments about the lift-off
/// point: `F l = w l²/2`). The slope at the pin is `z'(l) = w l³/(12 EI) = 2h/l`.
/// In `ℓ_c` units: `l = (24 h)^{1/4}`, `F = R = l/2`, span `= l` (to first order),
/// energy `= ∫ (z''²/2 + z) dξ = (4/5) h F` (since `dΠ/dh = F ∝ h^{1/4}`).
///
/// The neglected geometric nonlinearity is of relative size `φ_pin² ∝ (h/l)² ∝ h^{3/2}`,
/// so the relative error of these formulas against [`heavy_elastica_lifted_end`] falls by
/// ~31.6 per decade of `h` (measured: 1.4e-4, 4.5e-6, 1.4e-7 at h = 1e-2, 1e-3, 1e-4).
///
/// # Panics
/// If `height` is negative or not finite.
#[must_use]
pub fn heavy_elastica_small_deflection(height: f64) -> HeavyElastica {
    assert!(
        height.is_finite() && height >= 0.0,
        "heavy_elastica_small_deflection: height must be finite and >= 0"
    );
    let l = (24.0 * height).powf(0.25);
    let force = 0.5 * l;
    HeavyElastica {
        suspended_length: l,
        span: l,
        lift_force: force,
        horizontal_force: 0.0,
        touchdown_force: force,
        pin_angle: if l > 0.0 { 2.0 * height / l } else { 0.0 },
        energy: 0.8 * height * force,
    }
}

/// Damped Newton iteration for two equations in two unknowns, with a central-difference
/// Jacobian (it only steers the iteration; the converged accuracy is set by the residual).
/// `residual` returns `None` outside the admissible region. Gives up (`None`) unless every
/// step contracts, so that callers shorten a continuation step rather than drift to a
/// non-physical branch.
fn newton_2d(
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
            let trial = [p[0] - damping * step[0], p[1] - damping * step[1]];
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

/// Continuation of a two-unknown solution from height `from` (solution `start`) to `to`,
/// stepping in `ln h` with a secant predictor (first slope `slope`) and halving the step
/// whenever Newton refuses to converge.
fn heavy_continuation(
    newton: &dyn Fn(f64, [f64; 2]) -> Option<[f64; 2]>,
    from: f64,
    start: [f64; 2],
    to: f64,
    mut slope: [f64; 2],
) -> Option<[f64; 2]> {
    let (mut log_h, target) = (from.ln(), to.ln());
    let mut p = start;
    let mut dt: f64 = 0.5;
    while log_h < target {
        let next = (log_h + dt).min(target);
        let step = next - log_h;
        let guess = [p[0] + slope[0] * step, p[1] + slope[1] * step];
        match newton(next.exp(), guess) {
            Some(q) => {
                slope = [(q[0] - p[0]) / step, (q[1] - p[1]) / step];
                p = q;
                log_h = next;
                dt *= 1.5;
            }
            None => {
                dt *= 0.5;
                if dt < 1e-6 {
                    return None;
                }
            }
        }
    }
    Some(p)
}

/// Upward shooting: integrates from the lift-off point (`t = 0`) to `t = t_end` of the
/// suspended length `l`, for the floor reaction `r`. State `[x, z, φ, m, energy]`.
fn heavy_shoot_up(r: f64, l: f64, t_end: f64) -> [f64; 5] {
    let rhs = |t: f64, y: &[f64; 5]| {
        let (sin_p, cos_p) = y[2].sin_cos();
        // n_x = 0 and n_z = l t − r, so m' = n_x sin φ − n_z cos φ = (r − l t) cos φ.
        [
            l * cos_p,
            l * sin_p,
            l * y[3],
            l * (r - l * t) * cos_p,
            l * (0.5 * y[3] * y[3] + y[1]),
        ]
    };
    integrate(&rhs, [0.0; 5], 0.0, t_end, 16 + (4.0 * l) as usize)
}

/// Solves the pin conditions `z(l) = h`, `m(l) = 0` for `(r, l)` by upward shooting.
/// Residuals are scaled by the linear-theory magnitudes of `z` and `m` (`h` and `l²/8`), so
/// that the tolerance is relative however small `h` is.
fn heavy_newton_up(height: f64, start: [f64; 2]) -> Option<[f64; 2]> {
    let lin = heavy_elastica_small_deflection(height);
    let m_scale = (lin.suspended_length.powi(2) / 8.0).min(1.0);
    let residual = |p: [f64; 2]| {
        if p[0] <= 0.0 || p[1] <= 0.0 {
            return None;
        }
        let y = heavy_shoot_up(p[0], p[1], 1.0);
        Some([(y[1] - height) / height, y[3] / m_scale])
    };
    let fd = 1e-6 * lin.suspended_length;
    newton_2d(&residual, start, [fd, fd], 1e-13)
}

/// Upward-shooting solution `[r, l]`, from linear theory or, failing that, by continuation
/// from `h = 0.1`.
fn heavy_solve_up(height: f64) -> Option<[f64; 2]> {
    let linear_start = |h: f64| {
        let lin = heavy_elastica_small_deflection(h);
        [lin.touchdown_force, lin.suspended_length]
    };
    heavy_newton_up(height, linear_start(height)).or_else(|| {
        let from = 0.1f64.min(0.5 * height);
        let start = heavy_newton_up(from, linear_start(from))?;
        // Linear theory: r and l both grow like h^{1/4}.
        let slope = [0.25 * start[0], 0.25 * start[1]];
        heavy_continuation(&heavy_newton_up, from, start, height, slope)
    })
}

/// Downward shooting: integrates from the pin (`t = 0`) to `t = t_end` of the suspended
/// length; unknowns `p = [u, l]` with `u = ln ε`, `ε = π/2 − φ(l)`. State
/// `[x, z, ψ, m, energy]` with `ψ = π/2 − φ` and `x` measured from the pin. The pin force
/// follows from the first integral: `F = h / sin φ(l) = h / cos ε`.
fn heavy_shoot_down(height: f64, p: [f64; 2], t_end: f64) -> [f64; 5] {
    let (eps, l) = (p[0].exp(), p[1]);
    let force = height / eps.cos();
    let rhs = |t: f64, y: &[f64; 5]| {
        let (sin_psi, cos_psi) = y[2].sin_cos();
        // σ = l t is the distance from the pin; n_z = F − σ is the tension there.
        [
            -l * sin_psi,
            -l * cos_psi,
            l * y[3],
            l * (force - l * t) * sin_psi,
            l * (0.5 * y[3] * y[3] + y[1]),
        ]
    };
    integrate(
        &rhs,
        [0.0, height, eps, 0.0, 0.0],
        0.0,
        t_end,
        16 + (4.0 * l) as usize,
    )
}

/// Solves the lift-off conditions `φ = 0`, `m = 0` for `[u, l]` by downward shooting.
fn heavy_newton_down(height: f64, start: [f64; 2]) -> Option<[f64; 2]> {
    let residual = |p: [f64; 2]| {
        if p[0] >= FRAC_PI_2.ln() || p[1] <= 0.0 {
            return None;
        }
        let y = heavy_shoot_down(height, p, 1.0);
        Some([y[2] - FRAC_PI_2, y[3]])
    };
    newton_2d(&residual, start, [1e-6, 1e-6 * (1.0 + start[1])], 1e-13)
}

/// Heights up to this are solved by upward shooting from linear theory, larger ones by
/// downward shooting and continuation. Both work for `1 ≤ h ≤ 3`, where the tests compare
/// them.
const HEAVY_SWITCH: f64 = 1.0;

/// Above this height the top of the suspended part is vertical and straight far below
/// round-off (`ε ≈ e^{-(2/3) h^{3/2}} ≈ 1e-26`), so taller configurations are this one plus
/// a vertical segment: shooting further would only cost time and eventually underflow `ε`.
const HEAVY_EXTEND_FROM: f64 = 20.0;

/// Downward-shooting solution `[u, l]` for `height ≥ HEAVY_SWITCH`, by continuation in
/// `ln h` from the upward-shooting solution at `HEAVY_SWITCH`.
fn heavy_solve_down(height: f64) -> [f64; 2] {
    let [r, l] = heavy_solve_up(HEAVY_SWITCH).expect("heavy_elastica_lifted_end: no start");
    let pin_angle = heavy_shoot_up(r, l, 1.0)[2];
    let start = [(FRAC_PI_2 - pin_angle).ln(), l];
    heavy_continuation(&heavy_newton_down, HEAVY_SWITCH, start, height, [0.0, 0.0])
        .expect("heavy_elastica_lifted_end: continuation failed")
}

/// Large-deflection solution of a heavy inextensible rod (weight `w` per length, bending
/// stiffness `EI`) lying on a rigid frictionless floor, with one end lifted by a pin (free
/// rotation, zero moment) to height `h`; the other end lies far away on the floor.
/// `height = h / ℓ_c` with `ℓ_c = (EI/w)^{1/3}`; results are in the units of
/// [`HeavyElastica`] (e.g. the dimensional lift force is `lift_force · w ℓ_c`).
///
/// # Formulation
/// Arc length `s` runs from the lift-off point (`s = 0`) to the pin (`s = l`), all scaled by
/// `ℓ_c`, so that `EI = w = 1`. `n = (n_x, n_z)` is the force that the material beyond `s`
/// exerts on the material before it, `m` the bending moment, `φ` the slope. Then
///
/// * `x' = cos φ`, `z' = sin φ`, `φ' = m` (constitutive law),
/// * `n' = (0, 1)` (the weight per length is `(0, −1)`),
/// * `m' = n_x sin φ − n_z cos φ` (moment balance),
///
/// and the pin applies the force `n(l)` to the rod.
///
/// # Boundary conditions
/// * Lift-off point, `s = 0`: `z = 0`, `φ = 0` (tangent to the floor) and `m = 0` (the flat
///   part carries no moment and no point couple acts there). The floor may push with a
///   concentrated reaction `R` there: `n_z(0) = −R`.
/// * Frictionless floor and a free far end: the lying part carries no axial force, so
///   `n_x ≡ 0` throughout and the pin's horizontal force vanishes.
/// * Pin, `s = l`: `z = h` and `m = 0`.
///
/// Hence `n_z(s) = s − R`, and the pin force is `F = n_z(l) = l − R`. Two unknowns, two
/// conditions beyond the initial values.
///
/// # Solution method
/// For `h ≤ 1`: shooting upwards from the lift-off point with unknowns `(R, l)`, Newton's
/// method (damped, finite-difference Jacobian) on `z(l) = h`, `m(l) = 0`, started from
/// linear theory ([`heavy_elastica_small_deflection`]).
///
/// For larger `h` upward shooting becomes ill-conditioned: in the tensioned, nearly
/// vertical upper part the linearised equation for `ψ = π/2 − φ` is `ψ'' = n_z ψ`, whose
/// physical solution decays towards the pin, so errors grow like `exp((2/3) h^{3/2})` on
/// the way up (it fails beyond `h ≈ 5`). There the equations are shot *downwards* from the
/// pin, the stable direction. `H = m²/2 + n_x cos φ + n_z sin φ − z` is a first integral
/// (in `H'` the moment terms cancel and `n_z' sin φ = z'`) and vanishes at the lift-off
/// point, so `F sin φ(l) = h`; the
/// unknowns become `u = ln ψ(l)` (well scaled while `ψ(l)` becomes exponentially small)
/// and `l`, with `F = h / cos ψ(l)`, and Newton enforces `φ = 0`, `m = 0` at the bottom
/// (`z = 0` there then follows from `H`; the tests check it). The solution is reached by
/// continuation in `ln h` from `h = 1`. Beyond `h = 20` a vertical straight segment is
/// added on top of the `h = 20` solution, which is exact to round-off.
///
/// # Panics
/// If `height` is negative or not finite, or the solver fails.
#[must_use]
pub fn heavy_elastica_lifted_end(height: f64) -> HeavyElastica {
    assert!(
        height.is_finite() && height >= 0.0,
        "heavy_elastica_lifted_end: height must be finite and >= 0"
    );
    if height == 0.0 {
        return heavy_elastica_small_deflection(0.0);
    }
    if height <= HEAVY_SWITCH {
        let [r, l] = heavy_solve_up(height).expect("heavy_elastica_lifted_end: Newton failed");
        let pin = heavy_shoot_up(r, l, 1.0);
        return HeavyElastica {
            suspended_length: l,
            span: pin[0],
            lift_force: l - r,
            horizontal_force: 0.0,
            touchdown_force: r,
            pin_angle: pin[2],
            energy: pin[4],
        };
    }
    let solved_height = height.min(HEAVY_EXTEND_FROM);
    let p = heavy_solve_down(solved_height);
    let bottom = heavy_shoot_down(solved_height, p, 1.0);
    let eps = p[0].exp();
    let force = solved_height / eps.cos();
    // A vertical segment of length `extra` above the solved configuration adds its weight
    // to the pin force and its gravitational energy ∫ z dz, and changes nothing below.
    let extra = height - solved_height;
    HeavyElastica {
        suspended_length: p[1] + extra,
        span: -bottom[0],
        lift_force: force + extra,
        horizontal_force: 0.0,
        touchdown_force: p[1] - force,
        pin_angle: FRAC_PI_2 - eps,
        energy: bottom[4] + 0.5 * (height * height - solved_height * solved_height),
    }
}

// ---------------------------------------------------------------------------------------------
// Linear frame, torsion and ring results
// ---------------------------------------------------------------------------------------------

/// Tip deflection of an L-shaped frame under a small out-of-plane tip force.
///
/// Arm 1 runs from the clamp at the origin along `x` (length `a`); a rigid corner joins it
/// to arm 2 along `y` (length `b`); the force `P` acts along `z` at the free end of arm 2.
/// Both arms have bending stiffness `EI` for out-of-plane bending and torsional stiffness
/// `GJ`.
///
/// Internal forces: arm 2 bends under `M = P η` (`η` the distance from the tip) and is not
/// twisted; arm 1 bends under `M = P ξ` (`ξ` from the corner) and carries the constant
/// torque `T = P b`. The complementary energy is
/// `U = P² b³/(6EI) + P² a³/(6EI) + P² b² a/(2GJ)`, and Castigliano's theorem gives
///
/// `δ = ∂U/∂P = P (a³ + b³)/(3 EI) + P a b² / GJ`.
///
/// Geometrically: arm 2 as a cantilever (`P b³/3EI`), the corner deflection of arm 1
/// (`P a³/3EI`), and the twist `P b a/GJ` of arm 1 rotating arm 2 rigidly (`× b`). The slope
/// of arm 1 at the corner is a rotation about `y`, along arm 2, so it moves the tip not at all.
#[must_use]
pub fn l_frame_tip_deflection(a: f64, b: f64, ei: f64, gj: f64, p: f64) -> f64 {
    p * (a.powi(3) + b.powi(3)) / (3.0 * ei) + p * a * b * b / gj
}

/// Torque needed to twist a straight rod uniformly by a total angle `phi` over length `l`:
/// `GJ φ / L` (Saint-Venant torsion, uniform twist rate `φ/L`).
#[must_use]
pub fn uniform_twist_torque(gj: f64, phi: f64, l: f64) -> f64 {
    gj * phi / l
}

/// Michell's critical total twist (radians) of a closed, naturally straight, isotropic ring:
/// the planar circular configuration with total twist `Tw` is stable only for
/// `Tw < 2π √3 · EI/GJ`, independent of the ring's length. Above it the ring writhes out
/// of plane (subcritically).
///
/// J. H. Michell, "On the stability of a bent and twisted wire", Messenger of Mathematics
/// 19 (1889) 181–184; A. Goriely, "Twisted elastic rings and the rediscoveries of Michell's
/// instability", J. Elasticity 84 (2006) 281–299.
#[must_use]
pub fn michell_critical_twist(ei: f64, gj: f64) -> f64 {
    2.0 * PI * 3f64.sqrt() * ei / gj
}

// ---------------------------------------------------------------------------------------------
// Tests
// ---------------------------------------------------------------------------------------------

#[cfg(test)]
mod tests {
    use super::*;

    fn rel(a: f64, b: f64) -> f64 {
        (a - b).abs() / b.abs()
    }

    /// Complete integrals by the arithmetic–geometric mean: an algorithm independent of
    /// Carlson's duplication, used to cross-check it.
    fn agm_k_e(m: f64) -> (f64, f64) {
        let (mut a, mut b) = (1.0, (1.0 - m).sqrt());
        let mut sum = 0.5 * m; // 2^{n-1} c_n² for n = 0, c_0² = m
        let mut pow = 0.5;
        for _ in 0..40 {
            let c = 0.5 * (a - b);
            pow *= 2.0;
            sum += pow * c * c;
            let next_b = (a * b).sqrt();
            a = 0.5 * (a + b);
            b = next_b;
            if c.abs() < 1e-17 {
                break;
            }
        }
        let k = PI / (2.0 * a);
        (k, k * (1.0 - sum))
    }

    /// Composite Gauss–Legendre (5 points) quadrature, for the incomplete integrals.
    fn quad(f: impl Fn(f64) -> f64, lo: f64, hi: f64, panels: usize) -> f64 {
        let nodes = [
            (0.0, 128.0 / 225.0),
            (-0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
            (0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
            (-0.906_179_845_938_664, 0.236_926_885_056_189_1),
            (0.906_179_845_938_664, 0.236_926_885_056_189_1),
        ];
        let h = (hi - lo) / panels as f64;
        let mut total = 0.0;
        for p in 0..panels {
            let mid = lo + (p as f64 + 0.5) * h;
            for (x, w) in nodes {
                total += w * f(mid + 0.5 * h * x);
            }
        }
        0.5 * h * total
    }

    #[test]
    fn carlson_published_values() {
        // Test values from Carlson (1995), Numer. Algorithms 10, Sec. 3.
        assert!((carlson_rf(1.0, 2.0, 0.0) - 1.311_028_777_146_1).abs() < 1e-13);
        assert!((carlson_rf(2.0, 3.0, 4.0) - 0.584_082_841_677_15).abs() < 1e-13);
        assert!((carlson_rd(0.0, 2.0, 1.0) - 1.797_210_352_103_4).abs() < 1e-13);
        assert!((carlson_rd(2.0, 3.0, 4.0) - 0.165_105_272_942_61).abs() < 1e-13);
    }

    #[test]
    fn complete_integrals_match_agm() {
        for &m in &[0.0, 1e-6, 0.1, 0.5, 0.9, 0.999, 1.0 - 1e-10] {
            let (k, e) = agm_k_e(m);
            assert!(rel(elliptic_k(m), k) < 2e-15, "K({m})");
            // E = R_F − (m/3) R_D cancels by a factor ~K as m → 1, and so does the AGM sum.
            assert!(rel(elliptic_e(m), e) < 2e-15 * k, "E({m})");
        }
        assert!((elliptic_k(0.5) - 1.854_074_677_301_372).abs() < 1e-15);
        assert!((elliptic_e(0.5) - 1.350_643_881_047_675_5).abs() < 1e-15);
    }

    #[test]
    fn incomplete_integrals_match_quadrature() {
        for &m in &[0.2, 0.7, 0.95] {
            for &phi in &[0.3, 1.0, 1.5, 2.8, -2.0] {
                let f = quad(|t| 1.0 / (1.0 - m * t.sin().powi(2)).sqrt(), 0.0, phi, 200);
                let e = quad(|t| (1.0 - m * t.sin().powi(2)).sqrt(), 0.0, phi, 200);
                assert!((elliptic_f(phi, m) - f).abs() < 1e-13, "F({phi}|{m})");
                assert!(
                    (elliptic_e_incomplete(phi, m) - e).abs() < 1e-13,
                    "E({phi}|{m})"
                );
            }
        }
    }

    /// The cantilever formulas rely on `K − F(ψ₀) = F(ψ₁)` and
    /// `E − E(ψ₀) = E(ψ₁) − k² sin ψ₀ sin ψ₁` for `tan ψ₀ tan ψ₁ = 1/k'`: check them.
    #[test]
    fn addition_theorems() {
        for &m in &[0.55_f64, 0.8, 0.99] {
            let kp = (1.0 - m).sqrt();
            for &psi0 in &[0.2_f64, 0.9, 1.4] {
                let psi1 = (1.0 / (kp * psi0.tan())).atan();
                let lhs_f = elliptic_k(m) - elliptic_f(psi0, m);
                assert!((lhs_f - elliptic_f(psi1, m)).abs() < 1e-14);
                let lhs_e = elliptic_e(m) - elliptic_e_incomplete(psi0, m);
                let rhs_e = elliptic_e_incomplete(psi1, m) - m * psi0.sin() * psi1.sin();
                assert!((lhs_e - rhs_e).abs() < 1e-14);
            }
        }
    }

    #[test]
    fn integrator_reaches_roundoff_on_harmonic_oscillator() {
        let rhs = |_t: f64, y: &[f64; 2]| [y[1], -25.0 * y[0]];
        let y = integrate(&rhs, [1.0, 0.0], 0.0, 3.0, 40);
        assert!((y[0] - 15.0f64.cos()).abs() < 1e-13);
        assert!((y[1] + 5.0 * 15.0f64.sin()).abs() < 1e-12);
    }

    #[test]
    fn bisshopp_drucker_reference() {
        let tip = cantilever_tip_load(2.0);
        assert!((tip.deflection - 0.493_457_48).abs() < 5e-9, "{tip:?}");
        assert!((tip.shortening - 0.160_641_72).abs() < 5e-9, "{tip:?}");
    }

    /// Literal Legendre-form evaluation, as in Bisshopp & Drucker: independent of the
    /// rewritten Carlson forms (valid away from tiny loads, where it cancels badly).
    #[test]
    fn cantilever_matches_literal_legendre_form() {
        for &load in &[0.5, 2.0, 10.0] {
            let tip = cantilever_tip_load(load);
            let m = 0.5 * (1.0 + tip.tip_angle.sin());
            let psi0 = (1.0 / (2.0 * m).sqrt()).asin();
            let kf = elliptic_k(m) - elliptic_f(psi0, m);
            let ee = elliptic_e(m) - elliptic_e_incomplete(psi0, m);
            assert!((kf * kf - load).abs() < 1e-12 * load);
            assert!((tip.deflection - (1.0 - 2.0 * ee / kf)).abs() < 1e-12);
            let x_tip = (2.0 * tip.tip_angle.sin() / load).sqrt();
            assert!((tip.shortening - (1.0 - x_tip)).abs() < 1e-12);
        }
    }

    #[test]
    fn cantilever_elliptic_and_shooting_agree() {
        let mut worst: f64 = 0.0;
        for &load in &[-3.0, 1e-3, 0.3, 1.0, 2.0, 5.0, 20.0, 60.0] {
            let a = cantilever_tip_load(load);
            let b = cantilever_shooting(load, 0.0);
            for (x, y) in [
                (a.deflection, b.deflection),
                (a.shortening, b.shortening),
                (a.tip_angle, b.tip_angle),
            ] {
                worst = worst.max((x - y).abs());
            }
        }
        eprintln!("cantilever elliptic vs shooting: max |diff| = {worst:.2e}");
        assert!(worst < 1e-9);
    }

    #[test]
    fn cantilever_small_load_limit() {
        // v/L = load/3 (1 + O(load²)): the relative error must shrink ~100x per decade.
        let err = |load: f64| rel(cantilever_tip_load(load).deflection, load / 3.0);
        let (e1, e2, e3) = (err(1e-1), err(1e-2), err(1e-3));
        eprintln!("cantilever small-load rel. error: {e1:.3e} {e2:.3e} {e3:.3e}");
        assert!(e1 < 1e-2 && e2 < 1e-4 && e3 < 1e-6);
        assert!(e1 / e2 > 80.0 && e2 / e3 > 80.0);
        // Linear theory for the other two outputs: θ_tip = load/2, u/L = O(load²).
        let tip = cantilever_tip_load(1e-4);
        assert!(rel(tip.tip_angle, 0.5e-4) < 1e-8);
        assert!(tip.shortening.abs() < 1e-8);
    }

    #[test]
    fn cantilever_moment_is_a_circular_arc() {
        for &m in &[-2.0, 1e-6, 0.05, 0.5, 1.0, PI, 5.0] {
            let tip = cantilever_tip_moment(m);
            let radius = 1.0 / m;
            let x = 1.0 - tip.shortening;
            // Centre of curvature at (0, R): the tip must lie on that circle ...
            let on_circle = (x * x + (tip.deflection - radius).powi(2)).sqrt() - radius.abs();
            assert!(on_circle.abs() < 1e-12 * (1.0 + radius.abs()), "m = {m}");
            // ... and agree with the (independent) shooting solution.
            let shot = cantilever_shooting(0.0, m);
            assert!((tip.deflection - shot.deflection).abs() < 1e-12, "m = {m}");
            assert!((tip.shortening - shot.shortening).abs() < 1e-12, "m = {m}");
            assert!((tip.tip_angle - m).abs() == 0.0);
        }
        // Just below the switch the series must agree with the closed form to round-off.
        let m: f64 = 0.1 - 1e-12;
        let closed = 1.0 - m.sin() / m;
        assert!((cantilever_tip_moment(m).shortening - closed).abs() < 5e-16);
        let tiny = cantilever_tip_moment(1e-5);
        assert!(rel(tiny.shortening, 1e-10 / 6.0) < 1e-9);
    }

    #[test]
    fn combined_force_and_moment_superpose_in_the_linear_limit() {
        // Linear theory: v/L = load/3 + moment/2.
        let (p, m) = (1e-5, 2e-5);
        let tip = cantilever_shooting(p, m);
        assert!(rel(tip.deflection, p / 3.0 + m / 2.0) < 1e-8);
    }

    #[test]
    fn postbuckled_reference() {
        let pb = euler_buckling_postbuckled(0.1);
        assert!((pb.load - 10.392_564).abs() < 5e-7, "{pb:?}");
        assert!((pb.midspan_deflection - 0.194_924).abs() < 5e-7, "{pb:?}");
    }

    #[test]
    fn postbuckled_small_shortening_limit() {
        // load = π² (1 + d/2 + O(d²)), w/L = 2√d/π (1 + O(d)).
        let err = |d: f64| {
            rel(
                euler_buckling_postbuckled(d).load,
                PI * PI * (1.0 + 0.5 * d),
            )
        };
        let (e1, e2) = (err(1e-3), err(1e-4));
        assert!(e1 < 1e-5 && e2 < 1e-7 && e1 / e2 > 80.0, "{e1:e} {e2:e}");
        let w = euler_buckling_postbuckled(1e-8).midspan_deflection;
        assert!(rel(w, 2e-4 / PI) < 1e-7);
        assert!(rel(euler_buckling_postbuckled(1e-12).load, PI * PI) < 1e-11);
    }

    #[test]
    fn postbuckled_load_inverse() {
        for &d in &[1e-4, 0.1, 0.5, 1.2] {
            let pb = euler_buckling_postbuckled(d);
            let (back, d_back) = euler_buckling_postbuckled_at_load(pb.load);
            assert!((d_back - d).abs() < 1e-13 && rel(back.load, pb.load) < 1e-14);
        }
    }

    /// Independent shooting for the strut: from a pinned end with slope `α` and zero
    /// curvature, Newton on `λ` until the slope vanishes at midspan; then integrate the
    /// whole length for the shortening and read the midspan deflection.
    fn strut_shooting(alpha: f64) -> (f64, f64, f64) {
        let shoot = |lambda: f64, s_end: f64| {
            let rhs = |_s: f64, y: &[f64; 6]| {
                let (sin_t, cos_t) = y[2].sin_cos();
                [
                    cos_t,
                    sin_t,
                    y[3],
                    -lambda * sin_t,
                    y[5],
                    -sin_t - lambda * cos_t * y[4],
                ]
            };
            integrate(&rhs, [0.0, 0.0, alpha, 0.0, 0.0, 0.0], 0.0, s_end, 64)
        };
        let mut lambda = PI * PI;
        for _ in 0..50 {
            let y = shoot(lambda, 0.5);
            let delta = y[2] / y[4];
            lambda -= delta;
            if delta.abs() < 1e-14 * lambda {
                break;
            }
        }
        let mid = shoot(lambda, 0.5);
        let end = shoot(lambda, 1.0);
        (lambda, 1.0 - end[0], mid[1])
    }

    #[test]
    fn postbuckled_elliptic_and_shooting_agree() {
        let mut worst: f64 = 0.0;
        for &alpha in &[0.05, 0.5, 1.0, 2.0] {
            let (lambda, d, w) = strut_shooting(alpha);
            let pb = euler_buckling_postbuckled(d);
            worst = worst
                .max(rel(pb.load, lambda))
                .max((pb.midspan_deflection - w).abs())
                .max((pb.end_angle - alpha).abs());
        }
        eprintln!("strut elliptic vs shooting: max diff = {worst:.2e}");
        assert!(worst < 1e-9);
    }

    #[test]
    fn heavy_elastica_small_height_limit() {
        let hs = [1e-2, 1e-3, 1e-4];
        let mut errs = [0.0; 3];
        for (i, &h) in hs.iter().enumerate() {
            let exact = heavy_elastica_lifted_end(h);
            let lin = heavy_elastica_small_deflection(h);
            errs[i] = rel(exact.suspended_length, lin.suspended_length)
                .max(rel(exact.lift_force, lin.lift_force))
                .max(rel(exact.touchdown_force, lin.touchdown_force))
                .max(rel(exact.span, lin.span))
                .max(rel(exact.pin_angle, lin.pin_angle))
                .max(rel(exact.energy, lin.energy));
        }
        eprintln!(
            "heavy elastica rel. error vs linear theory at h = {hs:?}: {:.3e} {:.3e} {:.3e}",
            errs[0], errs[1], errs[2]
        );
        // Nonlinearity enters through φ² ~ (2h/l)² ∝ h^{3/2}: ~31.6x per decade of h.
        for w in errs.windows(2) {
            let order = (w[0] / w[1]).log10();
            assert!((1.3..1.7).contains(&order), "observed order {order}");
        }
        assert!(errs[2] < 1e-5);
    }

    #[test]
    fn heavy_elastica_upward_and_downward_shooting_agree() {
        let mut worst: f64 = 0.0;
        for &h in &[1.5, 2.0, 3.0] {
            let [r, l] = heavy_solve_up(h).expect("upward shooting");
            let pin = heavy_shoot_up(r, l, 1.0);
            let p = heavy_solve_down(h);
            let bottom = heavy_shoot_down(h, p, 1.0);
            let force = h / p[0].exp().cos();
            worst = worst
                .max((l - p[1]).abs())
                .max((l - r - force).abs())
                .max((pin[0] + bottom[0]).abs())
                .max((pin[2] - (FRAC_PI_2 - p[0].exp())).abs())
                .max((pin[4] - bottom[4]).abs());
        }
        eprintln!("heavy elastica upward vs downward shooting: max |diff| = {worst:.2e}");
        assert!(worst < 1e-9);
    }

    #[test]
    fn heavy_elastica_first_integral() {
        // H = m²/2 + n_z sin φ − z is conserved and zero. Upward shooting does not use it,
        // so F sin φ_pin = h is a check there; downward shooting imposes it at the pin, so
        // the check is that the rod arrives at the floor, z = 0, at the lift-off point.
        for &h in &[0.05, 0.5, 1.0] {
            let sol = heavy_elastica_lifted_end(h);
            let first_integral = sol.lift_force * sol.pin_angle.sin() - h;
            assert!(
                first_integral.abs() < 1e-12 * h,
                "h = {h}: {first_integral:e}"
            );
        }
        for &h in &[2.0, 5.0, 10.0] {
            let z_bottom = heavy_shoot_down(h, heavy_solve_down(h), 1.0)[1];
            assert!(z_bottom.abs() < 1e-11 * h, "h = {h}: {z_bottom:e}");
        }
    }

    #[test]
    fn heavy_elastica_energy_derivative_is_lift_force() {
        // Virtual work: the pin force is the derivative of the potential energy with
        // respect to the lift height (the floor does no work; the lift-off point is free).
        for &h in &[0.05, 0.5, 2.0, 5.0] {
            let sol = heavy_elastica_lifted_end(h);
            let dh = 1e-4 * h;
            let up = heavy_elastica_lifted_end(h + dh).energy;
            let down = heavy_elastica_lifted_end(h - dh).energy;
            let de = (up - down) / (2.0 * dh);
            assert!(
                rel(de, sol.lift_force) < 1e-7,
                "h = {h}: {de} vs {}",
                sol.lift_force
            );
            // Global balance: the weight of the suspended part is carried by pin and floor.
            assert!((sol.lift_force + sol.touchdown_force - sol.suspended_length).abs() < 1e-12);
        }
    }

    #[test]
    fn heavy_elastica_shape_is_admissible() {
        // The rod must stay above the floor and bend one way only (m > 0): a Newton
        // iteration that had drifted to another branch would violate this.
        let h = 0.8;
        let sol = heavy_elastica_lifted_end(h);
        let (r, l) = (sol.touchdown_force, sol.suspended_length);
        for i in 1..50 {
            let y = heavy_shoot_up(r, l, i as f64 / 50.0);
            assert!(
                y[1] > 0.0 && y[3] > 0.0 && y[2] > 0.0,
                "t = {}",
                i as f64 / 50.0
            );
        }
        let h = 5.0;
        let p = heavy_solve_down(h);
        for i in 1..50 {
            let y = heavy_shoot_down(h, p, i as f64 / 50.0);
            assert!(
                y[1] > 0.0 && y[3] > 0.0 && y[2] < FRAC_PI_2,
                "t = {}",
                i as f64 / 50.0
            );
        }
    }

    #[test]
    fn heavy_elastica_tall_lift_is_continuous() {
        // Across HEAVY_EXTEND_FROM the solution switches from shooting to "shooting plus a
        // vertical segment"; everything below the segment must not notice.
        let below = heavy_elastica_lifted_end(HEAVY_EXTEND_FROM - 0.5);
        let above = heavy_elastica_lifted_end(HEAVY_EXTEND_FROM + 7.0);
        let excess = |s: &HeavyElastica, h: f64| s.suspended_length - h;
        assert!(
            (excess(&below, HEAVY_EXTEND_FROM - 0.5) - excess(&above, HEAVY_EXTEND_FROM + 7.0))
                .abs()
                < 1e-11
        );
        assert!((below.span - above.span).abs() < 1e-11);
        assert!((below.touchdown_force - above.touchdown_force).abs() < 1e-11);
        assert!((above.lift_force - (HEAVY_EXTEND_FROM + 7.0)).abs() < 1e-11);
        // The bottom bend converges to a universal shape for tall lifts.
        eprintln!(
            "tall lift: l - h = {:.12}, span = {:.12}, R = {:.12}",
            excess(&above, HEAVY_EXTEND_FROM + 7.0),
            above.span,
            above.touchdown_force
        );
    }

    #[test]
    fn l_frame_castigliano_by_quadrature() {
        let (a, b, ei, gj, p) = (1.3, 0.7, 2.0, 1.1, 0.3);
        // Unit-load method: δ = ∫ M m / EI + ∫ T t / GJ with the unit-force fields m, t.
        let arm2 = quad(|eta| (p * eta) * eta / ei, 0.0, b, 20);
        let arm1 = quad(|xi| (p * xi) * xi / ei + (p * b) * b / gj, 0.0, a, 20);
        assert!(rel(l_frame_tip_deflection(a, b, ei, gj, p), arm1 + arm2) < 1e-14);
        // Limits: straight cantilevers.
        assert!(
            rel(
                l_frame_tip_deflection(2.0, 0.0, ei, gj, p),
                p * 8.0 / (3.0 * ei)
            ) < 1e-15
        );
        assert!(
            rel(
                l_frame_tip_deflection(0.0, 2.0, ei, gj, p),
                p * 8.0 / (3.0 * ei)
            ) < 1e-15
        );
    }

    #[test]
    fn simple_formulas() {
        assert!(rel(uniform_twist_torque(2.0, 0.5, 4.0), 0.25) < 1e-15);
        assert!(rel(euler_critical_load(3.0, 2.0), 0.75 * PI * PI) < 1e-15);
        // Equal stiffnesses: √3 full turns.
        assert!(rel(michell_critical_twist(1.0, 1.0) / (2.0 * PI), 3f64.sqrt()) < 1e-15);
        // Consistency with the post-buckled strut at vanishing shortening.
        assert!(
            rel(
                euler_critical_load(1.0, 1.0),
                euler_buckling_postbuckled(0.0).load
            ) < 1e-15
        );
    }
}
