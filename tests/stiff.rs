//! The stiff and extreme suite (issue 7): slenderness down to r/L = 1e-5, Nitinol rods on soft
//! elastic joints, scale invariance, near-folds, a rod closed into a ring, ten turns of twist,
//! Michell's instability. Every case loads a scene from `networks/extreme/` and checks physics
//! against an analytic answer; docs/stiff.md has the measured numbers.

mod support;

use std::path::Path;
use std::time::Instant;

use rodnet::pipeline::{settings_of, solve_scene, Solution};
use rodnet::scene::types::*;

fn load(name: &str) -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("networks/extreme")
        .join(format!("{name}.ron"));
    rodnet::scene::load(&path)
        .unwrap_or_else(|e| panic!("{name}: {e:?}"))
        .0
}

/// Solves and checks that the state is finite; returns the solution and the wall time.
fn solve(s: &Scene) -> (Solution, f64) {
    let t = Instant::now();
    let sol = solve_scene(s, &settings_of(s)).unwrap();
    let secs = t.elapsed().as_secs_f64();
    let r = &sol.results;
    for rod in &r.rods {
        for p in &rod.points {
            assert!(p.iter().all(|v| v.is_finite()), "non-finite node {p:?}");
        }
    }
    assert!(sol.report.energy.is_finite() && sol.report.residual.is_finite());
    (sol, secs)
}

fn solve_converged(s: &Scene) -> (Solution, f64) {
    let (sol, secs) = solve(s);
    assert!(sol.report.converged, "{:?}", sol.report.message);
    (sol, secs)
}

fn material(s: &mut Scene) -> &mut Material {
    s.materials.values_mut().next().unwrap()
}

fn ei_of(m: &Material) -> f64 {
    let Section::Circle { radius } = m.section else {
        panic!("circular sections only")
    };
    m.young_modulus * std::f64::consts::PI * radius.powi(4) / 4.0
}

// ---------------------------------------------------------------------------------------------
// 1. Slenderness
// ---------------------------------------------------------------------------------------------

/// Tip (x/L, y/L) of the planar *extensible* cantilever elastica under a dead tip force
/// −P ŷ, `load` = PL²/EI, `eta` = EI/(EA L²) (= (r/L)²/4 for a circle). The DER model is
/// unshearable with axial force N = EA ε and moment M = EI dθ/dS (S the rest arclength), so
/// θ'' = load · (1 + ε) cos θ, ε = −load·eta·sin θ, θ(0) = 0, θ'(1) = 0, and
/// (x, y)' = (1 + ε)(cos θ, sin θ). Shooting on the tip angle, RK4 with 4000 steps (error
/// ~1e-14); with eta = 0 it reproduces the elliptic-integral elastica (checked below).
fn extensible_cantilever_tip(load: f64, eta: f64) -> [f64; 2] {
    let n = 4000;
    let h = 1.0 / n as f64;
    // State (θ, θ', x, y) integrated backwards from the tip (x, y measured from the tip).
    let rhs = |s: [f64; 4]| {
        let eps = -load * eta * s[0].sin();
        [
            s[1],
            load * (1.0 + eps) * s[0].cos(),
            (1.0 + eps) * s[0].cos(),
            (1.0 + eps) * s[0].sin(),
        ]
    };
    let shoot = |alpha: f64| {
        let mut s = [alpha, 0.0, 0.0, 0.0];
        for _ in 0..n {
            let k1 = rhs(s);
            let a = |k: [f64; 4], f: f64| std::array::from_fn::<f64, 4, _>(|i| s[i] - f * h * k[i]);
            let k2 = rhs(a(k1, 0.5));
            let k3 = rhs(a(k2, 0.5));
            let k4 = rhs(a(k3, 1.0));
            for i in 0..4 {
                s[i] -= h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
            }
        }
        s
    };
    // Secant iteration on θ(0) = 0 from the inextensible elliptic solution's tip angle region.
    let (mut a0, mut a1) = (-0.5, -0.6);
    let (mut f0, mut f1) = (shoot(a0)[0], shoot(a1)[0]);
    for _ in 0..60 {
        if f1 == f0 || f1.abs() < 1e-15 {
            break;
        }
        let a2 = a1 - f1 * (a1 - a0) / (f1 - f0);
        (a0, f0) = (a1, f1);
        a1 = a2;
        f1 = shoot(a1)[0];
    }
    let s = shoot(a1);
    // (x, y) at the clamp relative to the tip is −(tip − clamp).
    [-s[2], -s[3]]
}

/// Large-deflection cantilever (PL²/EI = 2, N = 40) from r/L = 1e-1 down to 1e-5
/// (EA L²/EI = 4e2 … 4e10). The tip must be the same to 1e-6 relative over the inextensible
/// range r/L ≤ 1e-3; at larger r/L the difference is the rod's extensibility, O((r/L)²),
/// and must match the extensible elastica's. Newton iterations are printed and bounded.
#[test]
fn slenderness_sweep_cantilever() {
    let load_factor = 2.0;
    let inext = support::cantilever_tip_load(load_factor);
    let check = extensible_cantilever_tip(load_factor, 0.0);
    assert!(
        (check[0] - (1.0 - inext.shortening)).abs() < 1e-12,
        "{check:?}"
    );
    assert!((-check[1] - inext.deflection).abs() < 1e-12, "{check:?}");
    let base = load("slender_cantilever");
    let radii = [1e-1, 1e-2, 1e-3, 1e-4, 1e-5];
    let mut rows = vec![];
    for &r in &radii {
        let mut s = base.clone();
        material(&mut s).section = Section::Circle { radius: r };
        let ei = ei_of(material(&mut s));
        s.loads[0] = Load::Force {
            rod: "beam".into(),
            vertex: 1,
            force: [0.0, -load_factor * ei, 0.0],
        };
        let (sol, secs) = solve_converged(&s);
        let tip = *sol.results.rods[0].points.last().unwrap();
        println!(
            "r/L = {r:.0e}: tip ({:.10}, {:.10}), {} iterations, {} factorizations, residual \
             {:.1e} (floor {:.1e}), {:.3} s",
            tip[0],
            tip[1],
            sol.report.iterations,
            sol.report.factorizations,
            sol.report.residual,
            sol.report.residual_floor,
            secs
        );
        rows.push((r, tip, sol.report.iterations));
    }
    // The baseline of the extensibility differences is r/L = 1e-4, not the slimmest rod: at
    // r/L = 1e-5 (EA L²/EI = 4e10) the residual's round-off floor is 2e-4 and the tip is
    // resolved only to about 3e-9 (a one-ulp change of the load moves it that much), while at
    // 1e-4 it is the same to 13 digits under any such change. The slimmest rod still has to
    // give the same answer over the inextensible range.
    let (_, slim, _) = rows[rows.len() - 1];
    let (base_r, base, _) = rows[rows.len() - 2];
    let ext0 = extensible_cantilever_tip(load_factor, base_r * base_r / 4.0);
    for &(r, tip, its) in &rows {
        let eta = r * r / 4.0;
        let ext = extensible_cantilever_tip(load_factor, eta);
        let d_der = [tip[0] - base[0], tip[1] - base[1]];
        let d_ref = [ext[0] - ext0[0], ext[1] - ext0[1]];
        println!(
            "r/L = {r:.0e}: tip − tip(1e-4) = ({:+.3e}, {:+.3e}), extensible elastica \
             ({:+.3e}, {:+.3e}), (L/r)² × Δy = {:+.4}",
            d_der[0],
            d_der[1],
            d_ref[0],
            d_ref[1],
            d_der[1] / (r * r)
        );
        // Extensibility: DER's change of the tip from the baseline is the extensible
        // elastica's, up to the relative discretization error O(1/N²) of that change itself.
        for k in (r > base_r).then_some(0..2).into_iter().flatten() {
            assert!(
                (d_der[k] - d_ref[k]).abs() <= 1e-3 * d_ref[k].abs() + 1e-11,
                "r/L = {r}: {d_der:?} vs {d_ref:?}"
            );
        }
        // Inextensible range: the same answer to 1e-6 relative.
        if r <= 1e-3 {
            let d = [tip[0] - slim[0], tip[1] - slim[1]];
            let rel = d[0].hypot(d[1]) / slim[0].hypot(slim[1]);
            assert!(rel < 1e-6, "r/L = {r}: differs by {rel:.2e}");
        }
        // The N = 40 discretization error of the elastica (docs/validation.md: 1.8e-4).
        assert!((-tip[1] - inext.deflection).abs() < 2e-4 + 0.3 * r * r);
        assert!(its <= 80, "r/L = {r}: {its} iterations");
    }
    // Newton iterations grow with slenderness, but boundedly: at most 2× per decade (or 24,
    // the count of the stubbiest rod before the stretch-force correction of the step made it
    // converge in 6: a fast first case does not make an unchanged second one a regression).
    for w in rows.windows(2) {
        assert!(
            w[1].2 <= (2 * w[0].2).max(24),
            "{} → {} iterations",
            w[0].2,
            w[1].2
        );
    }
}

// ---------------------------------------------------------------------------------------------
// 3. Scale invariance
// ---------------------------------------------------------------------------------------------

/// The scene with every length multiplied by `ls` and every modulus by `ms`; loads scaled so
/// that the dimensionless problem (F L²/EI, T L/EI, joint k L/EI, weight L²/EI) is unchanged.
fn scaled(s: &Scene, ls: f64, ms: f64) -> Scene {
    let mut s = s.clone();
    let v = |p: &mut [f64; 3]| p.iter_mut().for_each(|x| *x *= ls);
    for m in s.materials.values_mut() {
        m.young_modulus *= ms;
        if let Some(g) = m.shear_modulus.as_mut() {
            *g *= ms;
        }
        // Weight per length ρ A g scales as ρ ls²: ρ × ms/ls keeps weight·L²/EI.
        m.density *= ms / ls;
        m.section = match m.section {
            Section::Circle { radius } => Section::Circle {
                radius: radius * ls,
            },
            Section::Ellipse { a, b } => Section::Ellipse {
                a: a * ls,
                b: b * ls,
            },
            Section::Rectangle { width, height } => Section::Rectangle {
                width: width * ls,
                height: height * ls,
            },
        };
    }
    for r in &mut s.rods {
        r.points.iter_mut().for_each(v);
    }
    for j in &mut s.joints {
        if let JointKind::Elastic {
            bending,
            twist,
            scissor,
            cylinder,
            translation,
        } = &mut j.kind
        {
            for k in [bending, twist, scissor].into_iter().flatten() {
                *k *= ms * ls.powi(3);
            }
            if let Some(t) = translation {
                *t *= ms * ls;
            }
            if let Some(c) = cylinder {
                c.young_modulus *= ms;
                c.diameter *= ls;
                c.height *= ls;
            }
        }
    }
    for sp in &mut s.supports {
        if let Some(p) = sp.move_to.as_mut() {
            v(p);
        }
    }
    for l in &mut s.loads {
        match l {
            Load::Force { force, .. } => force.iter_mut().for_each(|f| *f *= ms * ls * ls),
            Load::Torque { torque, .. } => torque.iter_mut().for_each(|t| *t *= ms * ls.powi(3)),
            Load::Gravity { .. } => {}
        }
    }
    assert!(s.obstacles.is_empty() && s.bounds.is_empty() && s.target.is_none());
    s
}

/// Dimensionless results: node positions / ls, reaction forces / (ms ls²), moments / (ms ls³),
/// energy / (ms ls³), and the solver's counts.
struct Dimensionless {
    points: Vec<f64>,
    reactions: Vec<f64>,
    energy: f64,
    counts: [usize; 5],
    stable: bool,
    /// Zero-stiffness modes at the end (a neutral family of equal-energy states).
    neutral: bool,
}

fn dimensionless(sol: &Solution, ls: f64, ms: f64) -> Dimensionless {
    let r = &sol.results;
    let points = r
        .rods
        .iter()
        .flat_map(|rod| rod.points.iter().flatten().map(|x| x / ls))
        .collect();
    let reactions = r
        .reactions
        .iter()
        .flat_map(|re| {
            re.force
                .iter()
                .map(move |f| f / (ms * ls * ls))
                .chain(re.moment.iter().map(move |m| m / (ms * ls.powi(3))))
        })
        .collect();
    let rep = &sol.report;
    Dimensionless {
        points,
        reactions,
        energy: rep.energy / (ms * ls.powi(3)),
        counts: [
            rep.iterations,
            rep.factorizations,
            rep.regularized_iterations,
            rep.saddle_escapes,
            rep.retries,
        ],
        neutral: rep.neutral(),
        stable: rep.stable,
    }
}

fn max_rel_diff(a: &[f64], b: &[f64]) -> f64 {
    let scale = a.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs() / scale)
        .fold(0.0, f64::max)
}

/// Solves `base` and its copies with lengths × 1e-6 and × 1e3 and moduli × 1e-3 and × 1e6.
/// Dimensionless positions, reactions and energy must agree to 1e-8 (relative to their
/// largest value); with `counts`, the regularized iterations, saddle escapes and retries must
/// be identical too, Newton iterations and factorizations within one (whether H + τW factors
/// at the edge of positive definiteness, and which of the line search's two correction curves
/// wins a near-tie, can depend on the last bit: the ring's path differs by one iteration in its
/// tenth load step at length × 1e-6).
fn check_scale_invariance(name: &str, base: &Scene, counts: bool) {
    let (sol, secs) = solve_converged(base);
    let reference = dimensionless(&sol, 1.0, 1.0);
    println!(
        "{name}: iterations, factorizations, regularized, escapes, retries {:?}, {secs:.3} s",
        reference.counts
    );
    for (ls, ms) in [(1e-6, 1.0), (1e3, 1.0), (1.0, 1e-3), (1.0, 1e6)] {
        let (sol, _) = solve_converged(&scaled(base, ls, ms));
        let d = dimensionless(&sol, ls, ms);
        let dp = max_rel_diff(&reference.points, &d.points);
        let dr = max_rel_diff(&reference.reactions, &d.reactions);
        let de = (d.energy - reference.energy).abs() / reference.energy.abs();
        println!(
            "{name}: length × {ls:.0e}, modulus × {ms:.0e}: positions {dp:.1e}, reactions \
             {dr:.1e}, energy {de:.1e}, counts {:?}",
            d.counts
        );
        // A neutral state is one point of a family of equal-energy states (the Michell ring at
        // 0.95 Θc may turn about its clamps' axis while counter-rotating its frames): where on
        // the family the path ends is not a property of the scene, and the step's stretch
        // correction, solved with a shifted Hessian, moves along such modes by round-off
        // amplified 1/τ (1.7e-5 apart in scaled copies). There only the energy is compared, and
        // the solver's counts only to 1 % (the path itself wanders along the family).
        let family = reference.neutral && d.neutral;
        assert!(
            de < 1e-8 && (family || (dp < 1e-8 && dr < 1e-8)),
            "{name}: not scale invariant"
        );
        assert_eq!(d.stable, reference.stable);
        if counts && family {
            let (a, b) = (reference.counts, d.counts);
            let near = |x: usize, y: usize| x.abs_diff(y) <= 1 + x / 100;
            assert!(
                (0..5).all(|k| near(a[k], b[k])),
                "{name}: solver path changed with scale: {a:?} vs {b:?}"
            );
        } else if counts {
            let (a, b) = (reference.counts, d.counts);
            assert!(
                a[0].abs_diff(b[0]) <= 1 && a[2..] == b[2..] && a[1].abs_diff(b[1]) <= 1,
                "{name}: solver path changed with scale: {a:?} vs {b:?}"
            );
        }
    }
}

/// The same scenes in µm and km, and with moduli × 1e-3 and × 1e6: identical dimensionless
/// results and, except for the near-fold, identical solver paths. The ring
/// exercises the Hessian regularization and saddle escapes (13, at an out-of-plane
/// bifurcation), the Nitinol cross the line search at round-off.
#[test]
fn scale_invariance() {
    check_scale_invariance("nitinol_cross", &load("nitinol_cross"), true);
    check_scale_invariance("ring", &load("ring"), true);
    check_scale_invariance("twist_10_turns", &load("twist_10_turns"), true);
    check_scale_invariance("michell (0.95 Θc)", &load("michell"), true);
    let mut s = load("slender_cantilever");
    material(&mut s).section = Section::Circle { radius: 1e-3 };
    let ei = ei_of(material(&mut s));
    s.loads[0] = Load::Force {
        rod: "beam".into(),
        vertex: 1,
        force: [0.0, -2.0 * ei, 0.0],
    };
    check_scale_invariance("cantilever r/L = 1e-3", &s, true);
    // The near-fold's iteration count varies by two over the scalings (64–66; not traced; before
    // the gauge fix for frameless straight rods its Hessian was singular and it varied by ten),
    // so only its results are compared.
    check_scale_invariance("near_fold", &load("near_fold"), false);
}

// ---------------------------------------------------------------------------------------------
// 2. Nitinol rods on soft elastic joints
// ---------------------------------------------------------------------------------------------

fn tip_z(sol: &Solution) -> f64 {
    sol.results.rods[1].points.last().unwrap()[2]
}

/// Baek et al.'s gridshell materials: Nitinol rods (E = 83 GPa, d = 254 µm) on VPS joints
/// (E = 1.3 MPa, 6.4e4 times softer). The L-frame's tip deflection adds the joint's series
/// compliance 2Pb²/k to the rigid-frame answer; third order in N, Richardson within 1e-5.
#[test]
fn nitinol_l_frame_on_soft_joint() {
    let base = load("nitinol_l_frame");
    let m = &base.materials["nitinol"];
    let ei = ei_of(m);
    let gj = ei / (1.0 + m.poisson_ratio.unwrap());
    let JointKind::Elastic {
        cylinder: Some(c), ..
    } = &base.joints[0].kind
    else {
        panic!("the scene's joint is a cylinder")
    };
    let k = c.young_modulus * std::f64::consts::PI * c.diameter.powi(4) / (64.0 * c.height);
    let (a, b, p) = (0.06, 0.04, 1e-6);
    let rigid = support::l_frame_tip_deflection(a, b, ei, gj, p);
    let exact = rigid + 2.0 * p * b * b / k;
    println!(
        "EI = {ei:.4e} N·m², k = {k:.4e} N·m/rad, E_rod/E_joint = {:.2e}; rigid frame \
         {rigid:.6e} m, with the joint {exact:.6e} m",
        m.young_modulus / c.young_modulus
    );
    let mut f = [0.0; 2];
    for (i, n) in [20, 40].into_iter().enumerate() {
        let mut s = base.clone();
        s.rods.iter_mut().for_each(|r| r.subdivide = n);
        let (sol, secs) = solve_converged(&s);
        f[i] = tip_z(&sol);
        // Global equilibrium: the clamp's reaction balances the load (force, and moment about
        // x of the load at the deformed tip), to the converged residual.
        let re = &sol.results.reactions[0];
        let y_tip = sol.results.rods[1].points.last().unwrap()[1];
        let fz = re.force[2] + p;
        let mx = re.moment[0] + p * y_tip;
        let model = &sol.network.model;
        let bound = sol.report.residual * model.force_scale * sol.network.n_nodes() as f64;
        println!(
            "N = {n}: tip {:.9e} m ({:.2e} rel.), {} iterations, residual {:.1e} (floor {:.1e}), \
             reaction imbalance {fz:.1e} N, {mx:.1e} N·m, {secs:.3} s",
            f[i],
            (f[i] - exact) / exact,
            sol.report.iterations,
            sol.report.residual,
            sol.report.residual_floor
        );
        assert!(fz.abs() <= bound && mx.abs() <= bound * model.length_scale);
    }
    // Third order: the rods end at the clamp and the joint, whose end-corrected bending weights
    // leave O(h³) of the quadrature's end terms on this linear problem.
    let (e1, e2) = ((f[0] - exact).abs(), (f[1] - exact).abs());
    let rich = (8.0 * f[1] - f[0]) / 7.0;
    let er = (rich - exact).abs() / exact;
    println!(
        "errors ratio {:.2}, Richardson {rich:.9e} ({er:.1e})",
        e1 / e2
    );
    assert!(e1 / e2 > 7.0 && e1 / e2 < 9.2, "not third order");
    assert!(er < 1e-5, "Richardson error {er:.2e}");
    // The joint is not negligible: without its compliance the answer would be 19 % off.
    assert!((rich - rigid).abs() > 0.1 * exact);
}

/// The symmetric Nitinol cross under a large central load (membrane regime): the crossing
/// moves straight down, the four clamp reactions are equal and balance the load.
#[test]
fn nitinol_cross_large_deflection_symmetric() {
    let s = load("nitinol_cross");
    let (sol, secs) = solve_converged(&s);
    let p = 0.02;
    let j = sol.results.joints[0].position;
    let re = &sol.results.reactions;
    let sum_z: f64 = re.iter().map(|r| r.force[2]).sum();
    let tension = re[0].force[0].abs();
    println!(
        "crossing {j:?} m, reactions z {:?} N, tension {tension:.4} N, {} iterations, {secs:.3} s",
        re.iter().map(|r| r.force[2]).collect::<Vec<_>>(),
        sol.report.iterations
    );
    assert!(j[2] < -1e-4, "the load must deflect the crossing");
    assert!(j[0].abs() < 1e-12 * j[2].abs() && j[1].abs() < 1e-12 * j[2].abs());
    assert!(
        (sum_z - p).abs() < 1e-9 * p,
        "Σ reactions {sum_z} vs load {p}"
    );
    for r in re {
        assert!((r.force[2] - p / 4.0).abs() < 1e-9 * p, "{r:?}");
        let axial = r.force[0].abs().max(r.force[1].abs());
        assert!((axial - tension).abs() < 1e-9 * tension, "{r:?}");
    }
    // Membrane regime: the rods carry the load mainly by tension.
    assert!(tension > 5.0 * p);
    assert!(sol.report.stable || sol.report.neutral());
}

// ---------------------------------------------------------------------------------------------
// 4. Near-fold
// ---------------------------------------------------------------------------------------------

/// A single bending stencil folded to 175° by a dead force (exact discrete answer, stretch
/// included) and a hairpin whose rest shape folds back by 175° (Castigliano).
#[test]
fn near_fold_175_degrees() {
    let s = load("near_fold");
    let (sol, secs) = solve_converged(&s);
    let m = &s.materials["steel"];
    let Section::Circle { radius } = m.section else {
        unreachable!()
    };
    let ei = ei_of(m);
    let ea = m.young_modulus * std::f64::consts::PI * radius * radius;
    let Load::Force { force, .. } = s.loads[0] else {
        unreachable!()
    };
    let f = (force[0] * force[0] + force[1] * force[1]).sqrt();
    let gamma = force[1].atan2(force[0]);
    // Exact discrete equilibrium: unknowns φ and ε.
    let (mut phi, mut eps) = (175f64.to_radians(), 0.0);
    for _ in 0..50 {
        eps = f * (gamma - phi).cos() / ea;
        let r = ei * phi.sin() - f * (1.0 + eps) * (gamma - phi).sin();
        let dr = ei * phi.cos() + f * (1.0 + eps) * (gamma - phi).cos();
        phi -= r / dr;
    }
    let p = &sol.results.rods[0].points;
    let e1 = [p[2][0] - p[1][0], p[2][1] - p[1][1], p[2][2] - p[1][2]];
    let got_phi = e1[1].atan2(e1[0]);
    let got_eps = (e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]).sqrt() - 1.0;
    let energy = sol.results.energy.bend;
    println!(
        "fold: φ = {:.12}° (exact {:.12}°), ε = {got_eps:.6e} (exact {eps:.6e}), bend energy \
         {energy:.12e} (exact {:.12e}), {} iterations, {secs:.3} s",
        got_phi.to_degrees(),
        phi.to_degrees(),
        ei * (1.0 - phi.cos()),
        sol.report.iterations
    );
    assert!((got_phi - phi).abs() < 1e-9, "fold angle");
    assert!(
        (got_eps - eps).abs() < 1e-9 * eps.abs().max(1e-12) + 1e-13,
        "stretch"
    );
    assert!((energy - ei * (1.0 - phi.cos())).abs() < 1e-9 * energy);
    assert!(sol.report.stable || sol.report.neutral());

    // Hairpin: the rest shape is folded; Castigliano with the arms 5° apart.
    let base = load("hairpin");
    let m = &base.materials["steel"];
    let ei = ei_of(m);
    let gj = ei / (1.0 + m.poisson_ratio.unwrap());
    let (c, sn) = (175f64.to_radians().cos(), 175f64.to_radians().sin());
    let (a, b, p): (f64, f64, f64) = (1.0, 1.0, 1e-6);
    let exact = p * b.powi(3) / (3.0 * ei)
        + p * ((a + b * c).powi(3) - (b * c).powi(3)) / (3.0 * ei)
        + p * a * b * b * sn * sn / gj;
    let mut f = [0.0; 2];
    for (i, n) in [20, 40].into_iter().enumerate() {
        let mut s = base.clone();
        s.rods[0].subdivide = n;
        let (sol, _) = solve_converged(&s);
        f[i] = sol.results.rods[0].points.last().unwrap()[2];
        assert!(sol.results.energy.total.is_finite());
        println!(
            "hairpin N = {n}: tip {:.9e} m vs {exact:.9e} ({:.2e}), {} iterations",
            f[i],
            (f[i] - exact) / exact,
            sol.report.iterations
        );
    }
    let rich = (4.0 * f[1] - f[0]) / 3.0;
    let (e1, e2) = ((f[0] - exact).abs(), (f[1] - exact).abs());
    println!(
        "hairpin: error ratio {:.2}, Richardson {:.2e}",
        e1 / e2,
        (rich - exact).abs() / exact
    );
    assert!(
        (rich - exact).abs() < 1e-5 * exact,
        "hairpin {rich} vs {exact}"
    );
}

// ---------------------------------------------------------------------------------------------
// 5. A rod closed into a ring
// ---------------------------------------------------------------------------------------------

/// Radius (mean distance of the nodes from their centroid, the closing node counted once),
/// and the largest distance of a node from the ring's plane, the plane through the clamps'
/// point (the origin) containing their common tangent (the x axis) and the centroid.
fn ring_shape(points: &[[f64; 3]]) -> (f64, f64) {
    let p = &points[..points.len() - 1];
    let n = p.len() as f64;
    let c: [f64; 3] = std::array::from_fn(|k| p.iter().map(|q| q[k]).sum::<f64>() / n);
    let radius = p
        .iter()
        .map(|q| ((q[0] - c[0]).powi(2) + (q[1] - c[1]).powi(2) + (q[2] - c[2]).powi(2)).sqrt())
        .sum::<f64>()
        / n;
    // Normal x̂ × c, normalized.
    let (ny, nz) = (-c[2], c[1]);
    let nn = ny.hypot(nz);
    let off = points
        .iter()
        .map(|q| (q[1] * ny + q[2] * nz).abs() / nn)
        .fold(0.0, f64::max);
    (radius, off)
}

/// Closing a straight rod into a ring by turning one clamp through 2π while moving it onto
/// the other: radius L/2π, uniform moment EI·2π/L, energy EI(2π)²/(2L), no force; second
/// order in N. (The ring may end in any plane containing the clamps' tangent: rotating it
/// about that axis while counter-rotating the material frame costs nothing.)
#[test]
fn rod_closed_into_ring() {
    use std::f64::consts::PI;
    let base = load("ring");
    let ei = ei_of(&base.materials["polymer"]);
    let (l, e_ring, m_ring, r_ring) = (1.0, 2.0 * PI * PI * ei, 2.0 * PI * ei, 1.0 / (2.0 * PI));
    let mut vals = vec![];
    for n in [40, 80] {
        let mut s = base.clone();
        s.rods[0].subdivide = n;
        let (sol, secs) = solve_converged(&s);
        let (radius, off) = ring_shape(&sol.results.rods[0].points);
        let energy = sol.results.energy.bend;
        let re = &sol.results.reactions;
        let moment = re[1].moment.iter().map(|m| m * m).sum::<f64>().sqrt();
        let force = re
            .iter()
            .map(|r| r.force.iter().map(|f| f * f).sum::<f64>().sqrt())
            .fold(0.0, f64::max);
        println!(
            "N = {n}: radius {radius:.9} ({:.2e}), moment {moment:.9} ({:.2e}), energy \
             {energy:.9} ({:.2e}), largest reaction force {:.1e} EI/L², off-plane {off:.1e} L, \
             stretch energy {:.1e}, {} iterations ({:?} per step), {} escapes, {secs:.2} s",
            radius / r_ring - 1.0,
            moment / m_ring - 1.0,
            energy / e_ring - 1.0,
            force * l * l / ei,
            sol.results.energy.stretch,
            sol.report.iterations,
            sol.report.step_iterations,
            sol.report.saddle_escapes
        );
        assert!(sol.report.stable || sol.report.neutral());
        assert!(off < 1e-9 * l, "the ring is not planar: {off}");
        // No force in a ring under pure bending: what is left is O(1/N²) of EI/L².
        assert!(force * l * l / ei < 20.0 / (n * n) as f64, "{force}");
        vals.push([radius, moment, energy]);
    }
    for (k, (name, exact)) in [("radius", r_ring), ("moment", m_ring), ("energy", e_ring)]
        .into_iter()
        .enumerate()
    {
        let (e1, e2) = ((vals[0][k] - exact).abs(), (vals[1][k] - exact).abs());
        let rich = (4.0 * vals[1][k] - vals[0][k]) / 3.0;
        println!(
            "{name}: errors {:.2e}, {:.2e} (ratio {:.2}), Richardson {:.1e}",
            e1 / exact,
            e2 / exact,
            e1 / e2,
            (rich - exact).abs() / exact
        );
        assert!(e1 / e2 > 3.5 && e1 / e2 < 4.6, "{name}: not second order");
        assert!((rich - exact).abs() < 1e-4 * exact, "{name}: Richardson");
    }
    // The symmetric path (each clamp turns by π, no bifurcation on the way) reaches the same
    // ring.
    let mut s = base.clone();
    s.supports[0].rotate_by = Some([0.0, 0.0, -PI]);
    s.supports[1].rotate_by = Some([0.0, 0.0, PI]);
    let (sym, _) = solve_converged(&s);
    let (one, _) = solve_converged(&base);
    println!(
        "symmetric path: {} iterations, {} escapes, energy {:.12} vs {:.12}",
        sym.report.iterations,
        sym.report.saddle_escapes,
        sym.results.energy.total,
        one.results.energy.total
    );
    assert!((sym.results.energy.total - one.results.energy.total).abs() < 1e-10 * e_ring);
}

// ---------------------------------------------------------------------------------------------
// 6. Ten full turns of twist
// ---------------------------------------------------------------------------------------------

/// Clamped–clamped twist buckling torque (Greenhill, no axial force): M_c = 2x₁·EI/L with x₁
/// the first positive root of tan x = x (x₁ = 4.4934, M_c L/EI = 2.8606 π).
fn greenhill_clamped(ei: f64, l: f64) -> f64 {
    let mut x: f64 = 4.49;
    for _ in 0..50 {
        x -= (x.tan() - x) / (1.0 / x.cos().powi(2) - 1.0);
    }
    2.0 * x * ei / l
}

fn lateral(points: &[[f64; 3]]) -> f64 {
    points.iter().map(|p| p[1].hypot(p[2])).fold(0.0, f64::max)
}

/// Ten full turns between clamps, torque 0.70 of Greenhill's: uniform twist GJ·20π/L,
/// twist angle linear along the rod, straight to round-off, stable. Bracketing the threshold
/// (GJ set so that the same ten turns give 0.97 and 1.03 M_c): straight below, buckled above.
#[test]
fn ten_turns_of_twist() {
    use std::f64::consts::PI;
    let base = load("twist_10_turns");
    let m = &base.materials["cable"];
    let ei = ei_of(m);
    let Section::Circle { radius } = m.section else {
        unreachable!()
    };
    let j = PI * radius.powi(4) / 2.0;
    let gj = m.shear_modulus.unwrap() * j;
    let (l, phi) = (1.0, 20.0 * PI);
    let mc = greenhill_clamped(ei, l);
    let torque = support::uniform_twist_torque(gj, phi, l);
    println!(
        "GJ/EI = {:.3}, M_c L/EI = {:.6} = {:.4} π, torque / M_c = {:.3}",
        gj / ei,
        mc * l / ei,
        mc * l / ei / PI,
        torque / mc
    );
    let (sol, secs) = solve_converged(&base);
    let re = &sol.results.reactions;
    let side = lateral(&sol.results.rods[0].points);
    println!(
        "torque {:.12} (exact {torque:.12}), lateral {side:.1e} m, {} iterations, stable {}, \
         {secs:.3} s",
        re[1].moment[0], sol.report.iterations, sol.report.stable
    );
    assert!((re[1].moment[0] - torque).abs() < 1e-9 * torque);
    assert!((re[0].moment[0] + torque).abs() < 1e-9 * torque);
    assert!(side < 1e-12, "the rod left the axis: {side}");
    assert!(sol.report.stable && sol.report.saddle_escapes == 0);
    let tw = &sol.results.rods[0].twist;
    let n = tw.len();
    for (e, t) in tw.iter().enumerate() {
        let exact = phi * (e as f64 + 0.5) / n as f64;
        assert!((t - exact).abs() < 1e-9, "edge {e}: {t} vs {exact}");
    }
    let e_twist = gj * phi * phi / (2.0 * l);
    assert!((sol.results.energy.twist - e_twist).abs() < 1e-9 * e_twist);

    for (factor, buckles) in [(0.97, false), (1.03, true)] {
        let mut s = base.clone();
        let g = factor * mc * l / phi / j;
        material(&mut s).shear_modulus = Some(g);
        let (sol, secs) = solve_converged(&s);
        let side = lateral(&sol.results.rods[0].points);
        println!(
            "torque {factor} M_c: lateral {side:.3e} m, {} iterations, {} escapes, stable {}, \
             {secs:.3} s",
            sol.report.iterations, sol.report.saddle_escapes, sol.report.stable
        );
        assert!(sol.report.stable || sol.report.neutral());
        if buckles {
            assert!(side > 1e-3 * l, "did not buckle");
        } else {
            assert!(
                side < 1e-12 && sol.report.saddle_escapes == 0,
                "buckled below M_c"
            );
        }
    }
}

// ---------------------------------------------------------------------------------------------
// 7. Michell's instability
// ---------------------------------------------------------------------------------------------

/// The twisted ring of `michell.ron` with total twist Θ: near clamp turned by −π about z, far
/// clamp by π about (0, sin Θ/2, cos Θ/2), i.e. the near clamp's final frame twisted by Θ
/// about the common tangent.
fn michell_ring(theta: f64) -> Scene {
    use std::f64::consts::PI;
    let mut s = load("michell");
    s.supports[1].rotate_by = Some([0.0, PI * (theta / 2.0).sin(), PI * (theta / 2.0).cos()]);
    s
}

/// Michell (1889): the planar twisted ring is stable below Θc = 2π√3·EI/GJ. Both runs take the
/// same non-planar path (the far clamp's axis is tilted), N = 40 and 80. At 0.95 Θc the ring
/// ends planar up to the clamps' O(1/N²) discretization (measured 8.8e-4 L and 2.1e-4 L, ratio
/// 4.2), with the uniform twist torque GJ·Θ/L; at 1.05 Θc it ends out of plane by O(1)
/// (2.9e-2 L at both N), stable, with part of the twist turned into writhe.
#[test]
fn michell_twisted_ring() {
    let base = load("michell");
    let m = &base.materials["rod"];
    let ei = ei_of(m);
    let gj = 2.0 * m.shear_modulus.unwrap() / m.young_modulus * ei;
    let theta_c = support::michell_critical_twist(ei, gj);
    let l = 1.0;
    // The scene file is the 0.95 Θc case.
    let (a, b) = (
        base.supports[1].rotate_by.unwrap(),
        michell_ring(0.95 * theta_c).supports[1].rotate_by.unwrap(),
    );
    assert!(
        (0..3).all(|k| (a[k] - b[k]).abs() < 1e-12),
        "{a:?} vs {b:?}"
    );
    for (factor, planar) in [(0.95, true), (1.05, false)] {
        let theta = factor * theta_c;
        let mut offs = vec![];
        for n in [40, 80] {
            let mut s = michell_ring(theta);
            s.rods[0].subdivide = n;
            let (sol, secs) = solve_converged(&s);
            let (radius, off) = ring_shape(&sol.results.rods[0].points);
            // Twist torque: the far clamp's reaction moment along the common tangent (−x).
            let torque = -sol.results.reactions[1].moment[0];
            let en = &sol.results.energy;
            println!(
                "Θ = {factor} Θc = {theta:.6} rad, N = {n}: off-plane {off:.2e} L, radius \
                 {radius:.6} L, tangent torque {torque:.6} (GJΘ/L = {:.6}), bend {:.4} J (ring \
                 {:.4}), twist {:.4} J (GJΘ²/2L = {:.4}), {} iterations, {} escapes, stable {}, \
                 {secs:.2} s",
                gj * theta / l,
                en.bend,
                2.0 * std::f64::consts::PI.powi(2) * ei / l,
                en.twist,
                gj * theta * theta / (2.0 * l),
                sol.report.iterations,
                sol.report.saddle_escapes,
                sol.report.stable
            );
            assert!(sol.report.stable || sol.report.neutral());
            if planar {
                assert!((torque - gj * theta / l).abs() < 1e-3 * gj * theta / l);
            }
            offs.push(off);
        }
        if planar {
            assert!(
                offs[0] < 2e-3 * l && offs[0] / offs[1] > 3.5,
                "not planar: {offs:?}"
            );
        } else {
            assert!(
                offs.iter().all(|&o| o > 1e-2 * l),
                "stayed planar: {offs:?}"
            );
        }
    }
}

// ---------------------------------------------------------------------------------------------
// 8. A 10⁵-node gridshell (ignored: minutes, not seconds)
// ---------------------------------------------------------------------------------------------

/// Peak resident memory of this process (VmHWM), MiB.
fn peak_rss_mib() -> f64 {
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    status
        .lines()
        .find_map(|l| l.strip_prefix("VmHWM:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<f64>().ok())
        .map_or(f64::NAN, |kb| kb / 1024.0)
}

static START: std::sync::OnceLock<Instant> = std::sync::OnceLock::new();

/// Prints every 10th Newton iteration with the elapsed time and the peak memory so far.
fn progress(step: usize, it: usize, res: f64, _energy: f64) {
    if it.is_multiple_of(10) {
        let t = START.get().map_or(0.0, |s| s.elapsed().as_secs_f64());
        eprintln!(
            "  load step {step}, iteration {it}, relative residual {res:.2e}, {t:.0} s, \
             peak RSS {:.0} MiB",
            peak_rss_mib()
        );
    }
}

/// The hemispherical gridshell at about 10⁵ nodes (n = 100 rods per family, subdivide 8 by
/// default; `RODNET_BIG_RODS`, `RODNET_BIG_SUBDIVIDE` override): time and peak memory, as
/// measured in docs/stiff.md. Run with
/// `cargo test --release --test stiff -- --ignored --nocapture big_gridshell`.
#[test]
#[ignore]
fn big_gridshell() {
    use rodnet::gridshell::footprint::{footprint, HemisphereSpec};
    let var = |k: &str, d: usize| {
        std::env::var(k)
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(d)
    };
    let (n, k) = (var("RODNET_BIG_RODS", 100), var("RODNET_BIG_SUBDIVIDE", 8));
    let spec = HemisphereSpec::new(1.0, n, k);
    let net = rodnet::network::build::build(&footprint(&spec).scene).unwrap();
    println!(
        "n = {n}, subdivide {k}: {} nodes, {} free unknowns, peak RSS {:.0} MiB after building",
        net.n_nodes(),
        net.model.n_free,
        peak_rss_mib()
    );
    if std::env::var("RODNET_BIG_PLAN").is_ok() {
        return;
    }
    drop(net);
    let t = Instant::now();
    let _ = START.set(t);
    let r = rodnet::gridshell::job::run(
        &spec,
        rodnet::gridshell::formfind::DEFAULT_START_CAP,
        Some(std::sync::Arc::new(progress)),
        &rodnet::pipeline::Limits::NONE,
    )
    .unwrap();
    let secs = t.elapsed().as_secs_f64();
    let rep = &r.results.solver;
    println!(
        "converged {}, {} Newton iterations, {} factorizations, factorization {:.1} s of {secs:.1} s, \
         peak RSS {:.0} MiB, max radial deviation {:.3e}, apex {:.5}, message {:?}",
        r.results.converged,
        r.results.iterations,
        rep.factorizations,
        rep.factor_seconds,
        peak_rss_mib(),
        r.metrics.max_abs_radial_deviation,
        r.metrics.apex_height,
        rep.message
    );
    // Baek et al.'s analysis: the form-found dome is the hemisphere to a few percent of R,
    // at every rod count (n = 12 gives 2.6e-2, n = 50 to 150 about 3.1e-2); a dome that
    // stalls flat or buckles through misses that bound, and a stalled solve misses `converged`.
    assert!(r.results.converged, "not converged: {:?}", rep.message);
    assert!(
        r.metrics.max_abs_radial_deviation < 0.05,
        "max radial deviation {:.3e} R",
        r.metrics.max_abs_radial_deviation
    );
    assert!(
        (0.94..1.0).contains(&r.metrics.apex_height),
        "apex {:.4} R",
        r.metrics.apex_height
    );
}
