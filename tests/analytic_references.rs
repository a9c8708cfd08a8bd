//! Checks of the analytic references in `tests/support` against published values, limits,
//! independent algorithms (AGM, quadrature, literal Legendre forms, shooting) and each other.

mod support;

use std::f64::consts::{FRAC_PI_2, PI};

use support::elliptic::{
    carlson_rd, carlson_rf, elliptic_e, elliptic_e_incomplete, elliptic_f, elliptic_k,
};
use support::heavy::{self, EXTEND_FROM};
use support::ode::integrate;
use support::*;

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
        let [r, l] = heavy::solve_up(h).expect("upward shooting");
        let pin = heavy::shoot_up(r, l, 1.0);
        let p = heavy::solve_down(h);
        let bottom = heavy::shoot_down(h, p, 1.0);
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
        let z_bottom = heavy::shoot_down(h, heavy::solve_down(h), 1.0)[1];
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
        let y = heavy::shoot_up(r, l, i as f64 / 50.0);
        assert!(
            y[1] > 0.0 && y[3] > 0.0 && y[2] > 0.0,
            "t = {}",
            i as f64 / 50.0
        );
    }
    let h = 5.0;
    let p = heavy::solve_down(h);
    for i in 1..50 {
        let y = heavy::shoot_down(h, p, i as f64 / 50.0);
        assert!(
            y[1] > 0.0 && y[3] > 0.0 && y[2] < FRAC_PI_2,
            "t = {}",
            i as f64 / 50.0
        );
    }
}

#[test]
fn heavy_elastica_tall_lift_is_continuous() {
    // Across EXTEND_FROM the solution switches from shooting to "shooting plus a
    // vertical segment"; everything below the segment must not notice.
    let below = heavy_elastica_lifted_end(EXTEND_FROM - 0.5);
    let above = heavy_elastica_lifted_end(EXTEND_FROM + 7.0);
    let excess = |s: &HeavyElastica, h: f64| s.suspended_length - h;
    assert!((excess(&below, EXTEND_FROM - 0.5) - excess(&above, EXTEND_FROM + 7.0)).abs() < 1e-11);
    assert!((below.span - above.span).abs() < 1e-11);
    assert!((below.touchdown_force - above.touchdown_force).abs() < 1e-11);
    assert!((above.lift_force - (EXTEND_FROM + 7.0)).abs() < 1e-11);
    // The bottom bend converges to a universal shape for tall lifts.
    eprintln!(
        "tall lift: l - h = {:.12}, span = {:.12}, R = {:.12}",
        excess(&above, EXTEND_FROM + 7.0),
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
