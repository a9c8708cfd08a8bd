//! Rotational `Spring` supports (`rotational: (k₁, k₂, k₃)` N·m/rad, `axes`, `rotate_by`) against
//! mechanics: a cantilever on an elastic base (δ = PL³/3EI + PL²/k, converging at second order),
//! a rod turned by a torque through a large angle (θ = T/k exactly: the spring measures the
//! rotation's logarithm), an anchor turned by `rotate_by`, a stiff base against a clamp, and
//! springs along oblique axes.

use rodnet::pipeline::{settings_of, solve_scene, Solution};
use rodnet::scene::parse;

const E: f64 = 1e9;
const R: f64 = 0.01;

fn ei() -> f64 {
    E * std::f64::consts::PI * R.powi(4) / 4.0
}

fn material() -> String {
    format!(
        "materials: {{\"m\": Material(young_modulus: {E:e}, poisson_ratio: 0.3, density: 0.0, \
         section: Circle(radius: {R}))}},"
    )
}

fn solve(text: &str) -> Solution {
    let scene = parse("rotational.ron", text).unwrap_or_else(|e| panic!("{e}"));
    let s = solve_scene(&scene, &settings_of(&scene)).unwrap();
    assert!(s.results.converged, "{:?}", s.results.solver.message);
    s
}

fn tip(s: &Solution) -> [f64; 3] {
    *s.results.rods[0].points.last().unwrap()
}

/// A rod along x of length `l`, `n` edges, pinned at vertex 0 with a second support there
/// (`base`: its `kind` and any further fields).
fn on_elastic_base(l: f64, n: usize, base: &str, loads: &str) -> String {
    format!(
        "Scene({} rods: [Rod(name: \"b\", material: \"m\", points: [(0,0,0), ({l},0,0)], subdivide: {n})],
         supports: [Support(rod: \"b\", vertex: 0, kind: Pin),
                    Support(rod: \"b\", vertex: 0, kind: {base})],
         loads: [{loads}])",
        material()
    )
}

/// Tip load P across a cantilever on a rotational spring k: the base turns by PL/k, so
/// δ = PL³/3EI + PL²/k; the reactions are the pin's P and the spring's moment PL.
#[test]
fn a_cantilever_on_an_elastic_base() {
    let l = 1.0f64;
    let k = ei() / l;
    let p = 1e-4 * ei() / (l * l);
    let want = p * l.powi(3) / (3.0 * ei()) + p * l * l / k;
    let mut errors = Vec::new();
    for n in [8, 16, 32] {
        let text = on_elastic_base(
            l,
            n,
            &format!("Spring(rotational: ({k:e}, {k:e}, {k:e}))"),
            &format!("Force(rod: \"b\", vertex: 1, force: (0.0, {}, 0.0))", -p),
        );
        let s = solve(&text);
        let got = -tip(&s)[1];
        errors.push((got - want) / want);
        let moment = s.results.reactions[1].moment;
        let pin = s.results.reactions[0].force;
        // Statics of the whole rod about the pin, at the deformed tip.
        let m_load = tip(&s)[0] * -p;
        assert!((moment[2] + m_load).abs() < 1e-9 * p * l, "{moment:?}");
        assert!((pin[1] - p).abs() < 1e-9 * p, "{pin:?}");
        // The spring's energy is ½ k θ² with θ = M/k.
        let theta = moment[2] / k;
        let e = s.results.energy.supports;
        assert!((e - 0.5 * k * theta * theta).abs() < 1e-6 * e, "{e}");
    }
    println!("relative tip errors at n = 8, 16, 32: {errors:?}");
    for w in errors.windows(2) {
        let order = (w[0] / w[1]).abs().log2();
        assert!(order > 1.9, "order {order:.3} ({errors:?})");
    }
    assert!(errors[2].abs() < 2e-4, "{errors:?}");
}

/// A torque T about z on a rod held by a pin and a rotational spring k turns it rigidly by
/// θ = T/k; at T/k = 1.2 rad the bounded sin θ measure would give no equilibrium near there
/// (sin θ < 1.2 everywhere).
#[test]
fn a_torque_turns_the_rod_by_t_over_k() {
    let (k, theta) = (50.0, 1.2);
    let text = on_elastic_base(
        1.0,
        8,
        &format!("Spring(rotational: ({k}, {k}, {k}))"),
        &format!(
            "Torque(rod: \"b\", vertex: 0, torque: (0.0, 0.0, {}))",
            k * theta
        ),
    );
    let s = solve(&text);
    let t = tip(&s);
    let got = t[1].atan2(t[0]);
    assert!((got - theta).abs() < 1e-9, "turned {got}, want {theta}");
    let m = s.results.reactions[1].moment;
    assert!((m[2] + k * theta).abs() < 1e-9 * k, "{m:?}");
    let e = s.results.energy.supports;
    assert!((e - 0.5 * k * theta * theta).abs() < 1e-9 * e, "{e}");
}

/// `rotate_by` turns the spring's anchor; with no load the rod follows it rigidly and the spring
/// ends unstressed.
#[test]
fn rotate_by_turns_the_anchor() {
    let w: [f64; 3] = [0.3, -0.2, 0.9];
    let text = on_elastic_base(
        2.0,
        8,
        &format!(
            "Spring(rotational: (10.0, 20.0, 30.0)), rotate_by: Some(({}, {}, {}))",
            w[0], w[1], w[2]
        ),
        "",
    );
    let s = solve(&text);
    let angle = (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
    let axis = w.map(|x| x / angle);
    // The rod's direction turned about `axis` by `angle` (Rodrigues on x̂).
    let (c, sn) = (angle.cos(), angle.sin());
    let x = [1.0, 0.0, 0.0];
    let ax = axis[0];
    let cross = [0.0, axis[2], -axis[1]];
    let want: Vec<f64> = (0..3)
        .map(|i| 2.0 * (x[i] * c + cross[i] * sn + axis[i] * ax * (1.0 - c)))
        .collect();
    let t = tip(&s);
    for i in 0..3 {
        assert!((t[i] - want[i]).abs() < 1e-9, "{t:?} {want:?}");
    }
    assert!(s.results.energy.supports.abs() < 1e-15);
}

/// A base a million times stiffer than the rod (k = 1e6 EI/L) is a clamp to 1e-6.
#[test]
fn a_stiff_base_is_a_clamp() {
    let (l, n) = (1.0f64, 16);
    let p = 1e-4 * ei();
    let load = format!("Force(rod: \"b\", vertex: 1, force: (0.0, 0.0, {}))", -p);
    let k = 1e6 * ei() / l;
    let spring = solve(&on_elastic_base(
        l,
        n,
        &format!("Spring(rotational: ({k:e}, {k:e}, {k:e}))"),
        &load,
    ));
    let clamp = solve(&on_elastic_base(l, n, "Clamp", &load));
    let (a, b) = (tip(&spring)[2], tip(&clamp)[2]);
    // The base's own turn adds PL²/k = 1e-6 of the clamped deflection's PL³/3EI × 3.
    assert!(((a - b) / b).abs() < 4e-6, "{a} {b}");
    assert!(
        ((a - b) / b).abs() > 1e-7,
        "{a} {b}: the spring did not turn"
    );
}

/// Springs along oblique axes: a rotational spring soft about one horizontal axis u and stiff
/// about the others, a transverse tip load: the base turns only about u, by the moment's
/// component along u over k.
#[test]
fn springs_along_oblique_axes() {
    let l = 1.0f64;
    let s2 = std::f64::consts::FRAC_1_SQRT_2;
    let (soft, stiff) = (ei() / l, 1e6 * ei() / l);
    let p = 1e-5 * ei() / (l * l);
    let base = format!(
        "Spring(rotational: ({soft:e}, {stiff:e}, {stiff:e}), axes: Some((({s2}, {s2}, 0.0), (-{s2}, {s2}, 0.0), (0.0, 0.0, 1.0))))"
    );
    let text = on_elastic_base(
        l,
        32,
        &base,
        &format!("Force(rod: \"b\", vertex: 1, force: (0.0, 0.0, {}))", -p),
    );
    let s = solve(&text);
    // The load's moment about the base is PL about +y; its part along u = (1, 1, 0)/√2 is
    // PL/√2, which turns the base by PL/(√2 k) about u, lowering the tip by L·PL/(2k) (the
    // component of the turn about y); the stiff axis takes the rest.
    let want = p * l.powi(3) / (3.0 * ei()) + p * l * l / (2.0 * soft);
    let got = -tip(&s)[2];
    assert!(((got - want) / want).abs() < 1e-3, "{got} {want}");
    // A turn about u (or the stiff v) moves x̂ along u × x̂ ∥ −ẑ: the tip stays at y = 0 up to
    // terms of second order in the turn.
    assert!(tip(&s)[1].abs() < 1e-4 * got, "{:?}", tip(&s));
}
