//! A heavy inextensible rod lifted off a frictionless floor by a pinned end: linear beam
//! theory, and the large-deflection solution by shooting (upwards from the lift-off point for
//! low lifts, downwards from the pin for tall ones, where upward shooting is unstable).

use std::f64::consts::FRAC_PI_2;

use super::ode::integrate;
use super::roots::{continuation, newton_2d};

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
/// ~31.6 per decade of `h`.
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

/// Carries a solution of `newton` from height `from` (solution `start`) to `to`, stepping in
/// `ln h` because the solutions vary like powers of `h`; `slope` is the first `d/d ln h`.
fn continue_in_height(
    newton: fn(f64, [f64; 2]) -> Option<[f64; 2]>,
    from: f64,
    start: [f64; 2],
    to: f64,
    slope: [f64; 2],
) -> Option<[f64; 2]> {
    let solve = |log_h: f64, guess| newton(log_h.exp(), guess);
    continuation(solve, from.ln(), start, to.ln(), slope, 0.5, 1e-6)
}

/// Upward shooting: integrates from the lift-off point (`t = 0`) to `t = t_end` of the
/// suspended length `l`, for the floor reaction `r`. State `[x, z, φ, m, energy]`.
pub fn shoot_up(r: f64, l: f64, t_end: f64) -> [f64; 5] {
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
fn newton_up(height: f64, start: [f64; 2]) -> Option<[f64; 2]> {
    let lin = heavy_elastica_small_deflection(height);
    let m_scale = (lin.suspended_length.powi(2) / 8.0).min(1.0);
    let residual = |p: [f64; 2]| {
        if p[0] <= 0.0 || p[1] <= 0.0 {
            return None;
        }
        let y = shoot_up(p[0], p[1], 1.0);
        Some([(y[1] - height) / height, y[3] / m_scale])
    };
    let fd = 1e-6 * lin.suspended_length;
    newton_2d(&residual, start, [fd, fd], 1e-13)
}

/// Upward-shooting solution `[r, l]`, from linear theory or, failing that, by continuation
/// from `h = 0.1`.
pub fn solve_up(height: f64) -> Option<[f64; 2]> {
    let linear_start = |h: f64| {
        let lin = heavy_elastica_small_deflection(h);
        [lin.touchdown_force, lin.suspended_length]
    };
    newton_up(height, linear_start(height)).or_else(|| {
        let from = 0.1f64.min(0.5 * height);
        let start = newton_up(from, linear_start(from))?;
        // Linear theory: r and l both grow like h^{1/4}.
        let slope = [0.25 * start[0], 0.25 * start[1]];
        continue_in_height(newton_up, from, start, height, slope)
    })
}

/// Downward shooting: integrates from the pin (`t = 0`) to `t = t_end` of the suspended
/// length; unknowns `p = [u, l]` with `u = ln ε`, `ε = π/2 − φ(l)`. State
/// `[x, z, ψ, m, energy]` with `ψ = π/2 − φ` and `x` measured from the pin. The pin force
/// follows from the first integral: `F = h / sin φ(l) = h / cos ε`.
pub fn shoot_down(height: f64, p: [f64; 2], t_end: f64) -> [f64; 5] {
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
fn newton_down(height: f64, start: [f64; 2]) -> Option<[f64; 2]> {
    let residual = |p: [f64; 2]| {
        if p[0] >= FRAC_PI_2.ln() || p[1] <= 0.0 {
            return None;
        }
        let y = shoot_down(height, p, 1.0);
        Some([y[2] - FRAC_PI_2, y[3]])
    };
    newton_2d(&residual, start, [1e-6, 1e-6 * (1.0 + start[1])], 1e-13)
}

/// Heights up to this are solved by upward shooting from linear theory, larger ones by
/// downward shooting and continuation. Both work for `1 ≤ h ≤ 3`, where the tests compare
/// them.
const SWITCH_HEIGHT: f64 = 1.0;

/// Above this height the top of the suspended part is vertical and straight far below
/// round-off (`ε ≈ e^{-(2/3) h^{3/2}} ≈ 1e-26`), so taller configurations are this one plus
/// a vertical segment: shooting further would only cost time and eventually underflow `ε`.
pub const EXTEND_FROM: f64 = 20.0;

/// Downward-shooting solution `[u, l]` for `height ≥ SWITCH_HEIGHT`, by continuation in
/// `ln h` from the upward-shooting solution at `SWITCH_HEIGHT`.
pub fn solve_down(height: f64) -> [f64; 2] {
    let [r, l] = solve_up(SWITCH_HEIGHT).expect("heavy_elastica_lifted_end: no start");
    let pin_angle = shoot_up(r, l, 1.0)[2];
    let start = [(FRAC_PI_2 - pin_angle).ln(), l];
    continue_in_height(newton_down, SWITCH_HEIGHT, start, height, [0.0, 0.0])
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
    if height <= SWITCH_HEIGHT {
        let [r, l] = solve_up(height).expect("heavy_elastica_lifted_end: Newton failed");
        let pin = shoot_up(r, l, 1.0);
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
    let solved_height = height.min(EXTEND_FROM);
    let p = solve_down(solved_height);
    let bottom = shoot_down(solved_height, p, 1.0);
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
