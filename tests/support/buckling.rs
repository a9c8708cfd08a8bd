//! Stability of straight and circular rods: Euler's critical load, the post-buckled pinned–pinned
//! strut (first-mode elastica) and Michell's twist instability of a ring.

use std::f64::consts::PI;

use super::elliptic::{carlson_rd, carlson_rf, elliptic_k};
use super::roots::bisect_increasing;

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
