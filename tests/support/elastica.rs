//! The planar inextensible cantilever elastica: exact elliptic-integral solution under a tip
//! force, the circular arc under an end moment, and an independent shooting solution for
//! both loads together (which cross-checks the other two).

use std::f64::consts::{FRAC_1_SQRT_2, FRAC_PI_2, FRAC_PI_4, SQRT_2};

use super::elliptic::{carlson_rd, carlson_rf};
use super::ode::integrate;
use super::roots::{bisect_increasing, continuation};

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

impl ElasticaTip {
    /// The unloaded, straight cantilever.
    const STRAIGHT: Self = Self {
        deflection: 0.0,
        shortening: 0.0,
        tip_angle: 0.0,
    };
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
        return ElasticaTip::STRAIGHT;
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
        return ElasticaTip::STRAIGHT;
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
/// Beyond `load ≈ 150` the tip angle is within 1e-8 of π/2, which shooting cannot resolve;
/// use the elliptic solution there.
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
    // Continuation in t (loads t·load, t·moment) from the straight rod; the first slope is
    // linear theory, θ(1) = load/2 + moment.
    let [alpha] = continuation(
        |t, [guess]| newton(t * load, t * moment, guess).map(|a| [a]),
        0.0,
        [0.0],
        1.0,
        [0.5 * load + moment],
        1.0 / (1.0 + 0.5 * load.abs().max(moment.abs())),
        1e-9,
    )
    .expect("cantilever_shooting: continuation failed");
    // Integrated from the tip, so the clamp sits at (x, y) and the tip at the origin.
    let root = shoot(load, moment, alpha);
    ElasticaTip {
        deflection: -root[1],
        shortening: 1.0 + root[0],
        tip_angle: alpha,
    }
}
