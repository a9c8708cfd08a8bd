//! A flat spoked wheel prestressed by its hub (issue 36): a polygonal rim (one closed rod
//! through N points), N radial spokes ball-jointed to the rim at those points, their inner ends
//! pinned on the hub and pulled inward by δ. Unstressed, the rim may translate and tilt out of
//! plane, and turn in plane, at no elastic cost (the spokes turn about their pins); stretched,
//! the spokes' tension makes those motions stiff. The mechanism test looked at the unstressed
//! start only and refused the wheel at iteration 0.
//!
//! Reference (exact, not linearized): by symmetry the rim stays a regular polygon of radius
//! R − u with straight sides and the spokes stay straight and radial, so nothing bends. Spokes
//! of length L = R − a become L + δ − u: tension T = EA_s (δ − u)/L. Rim sides shrink with the
//! radius: compression C = EA_r u/R. At a rim vertex T = 2 C sin(π/N) (for many spokes
//! C → T N/(2π), the hoop force of a ring under the smeared pull N T/(2πR)). Hence
//! u = δ / (1 + 2 sin(π/N) EA_r L/(EA_s R)). Out of plane, a rim translation w under a total
//! force F is held by the tilted spokes only: F = N T' w/√(L'² + w²), T' the spokes' tension
//! at their tilted length (the rim's radius changes at O(w²)).

use rodnet::io::results::Results;
use rodnet::pipeline::{settings_of, solve_scene};
use rodnet::scene::parse;
use std::f64::consts::PI;

const R: f64 = 1.0;
const A: f64 = 0.1;
const E_RIM: f64 = 7e10;
const RIM_SIDE: f64 = 0.02;
const E_SPOKE: f64 = 2e11;
const SPOKE_RADIUS: f64 = 0.001;

fn ea_rim() -> f64 {
    E_RIM * RIM_SIDE * RIM_SIDE
}

fn ea_spoke() -> f64 {
    E_SPOKE * PI * SPOKE_RADIUS * SPOKE_RADIUS
}

/// The wheel with `n` spokes, its hub pulled in by `delta`; `extra` is appended (stages).
fn wheel(n: usize, delta: f64, extra: &str) -> String {
    let at = |r: f64, k: usize| {
        let t = 2.0 * PI * k as f64 / n as f64;
        format!("({:e}, {:e}, 0.0)", r * t.cos(), r * t.sin())
    };
    let rim: Vec<String> = (0..n).map(|k| at(R, k)).collect();
    let mut rods = vec![format!(
        "Rod(name: \"rim\", material: \"rim\", points: [{}], subdivide: 4, closed: true)",
        rim.join(", ")
    )];
    let (mut joints, mut supports) = (vec![], vec![]);
    for k in 0..n {
        rods.push(format!(
            "Rod(name: \"s{k}\", material: \"spoke\", points: [{}, {}], subdivide: 4)",
            at(A, k),
            at(R, k)
        ));
        joints.push(format!(
            "Joint(name: \"j{k}\", at: [(\"rim\", {k}), (\"s{k}\", 1)], kind: Ball)"
        ));
        supports.push(format!(
            "Support(rod: \"s{k}\", vertex: 0, kind: Pin, move_to: Some({}))",
            at(A - delta, k)
        ));
    }
    format!(
        "Scene(materials: {{
            \"rim\": Material(young_modulus: {E_RIM:e}, poisson_ratio: 0.3,
                section: Rectangle(width: {RIM_SIDE}, height: {RIM_SIDE})),
            \"spoke\": Material(young_modulus: {E_SPOKE:e}, poisson_ratio: 0.3,
                section: Circle(radius: {SPOKE_RADIUS}))}},
         rods: [{}], joints: [{}], supports: [{}]{extra})",
        rods.join(", "),
        joints.join(", "),
        supports.join(", ")
    )
}

fn solve(text: &str) -> Results {
    let sc = parse("wheel.ron", text).unwrap_or_else(|e| panic!("{e}"));
    let s = solve_scene(&sc, &settings_of(&sc)).unwrap();
    assert!(s.results.converged, "{:?}", s.results.solver.message);
    s.results
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt()
}

/// (u, T, C) of the exact symmetric solution.
fn reference(n: usize, delta: f64) -> (f64, f64, f64) {
    let (l, s) = (R - A, (PI / n as f64).sin());
    let u = delta / (1.0 + 2.0 * s * ea_rim() * l / (ea_spoke() * R));
    (u, ea_spoke() * (delta - u) / l, ea_rim() * u / R)
}

#[test]
fn a_wheel_tensioned_by_its_hub_is_no_mechanism() {
    let delta = 2e-4;
    for n in [8, 16, 32] {
        let r = solve(&wheel(n, delta, ""));
        let (u, t, c) = reference(n, delta);
        let rim = &r.rods[0];
        let radius_err = rim
            .points
            .iter()
            .step_by(4)
            .map(|p| ((R - p[0].hypot(p[1])) / u - 1.0).abs())
            .fold(0.0, f64::max);
        let spoke = &r.rods[1].points;
        let tension = ea_spoke() * (dist(spoke[0], spoke[4]) / (R - A) - 1.0);
        let compression = -rim
            .forces
            .iter()
            .map(|f| f.axial)
            .fold(f64::INFINITY, f64::min);
        println!(
            "{n} spokes: {} iterations; u {:.6e} m (exact {u:.6e}, error {radius_err:.1e}), T {tension:.6} N \
             (exact {t:.6}), rim C {compression:.6} N (exact {c:.6}, smeared T N/2π {:.3})",
            r.iterations,
            R - rim.points[0][0],
            t * n as f64 / (2.0 * PI)
        );
        assert!(radius_err < 1e-6, "{radius_err:e}");
        assert!((tension / t - 1.0).abs() < 1e-6, "{tension} vs {t}");
        assert!((compression / c - 1.0).abs() < 1e-6, "{compression} vs {c}");
        assert!(r.solver.stable);
    }
}

/// After the prestress, a vertical force F shared by the rim's N spoke vertices moves the rim
/// as a whole by w: the prestress is the only out-of-plane stiffness (N T/L).
#[test]
fn the_prestress_holds_the_rim_out_of_plane() {
    let (n, delta, f) = (8, 2e-4, 0.1);
    let loads: Vec<String> = (0..n)
        .map(|k| {
            format!(
                "Force(rod: \"rim\", vertex: {k}, force: (0.0, 0.0, {:e}))",
                f / n as f64
            )
        })
        .collect();
    let stage = format!(
        ", stages: [Stage(name: \"push\", loads: [{}])]",
        loads.join(", ")
    );
    // The last stage's results.
    let r = &solve(&wheel(n, delta, &stage));
    let w = r.rods[0].points[0][2];
    // F = N T'(w) w / √(L'² + w²) with the rim's radius at its prestressed value.
    let (u, _, _) = reference(n, delta);
    let lp = R - u - (A - delta);
    let force = |w: f64| {
        let len = (lp * lp + w * w).sqrt();
        n as f64 * ea_spoke() * (len / (R - A) - 1.0) * w / len
    };
    let (mut lo, mut hi) = (0.0, 1e-2);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if force(mid) < f {
            lo = mid
        } else {
            hi = mid
        }
    }
    let want = 0.5 * (lo + hi);
    let spread = r.rods[0]
        .points
        .iter()
        .map(|p| (p[2] - w).abs())
        .fold(0.0, f64::max);
    println!("rim lifted by {w:.6e} m (prestress alone {want:.6e}), spread {spread:.1e} m");
    assert!((w / want - 1.0).abs() < 1e-5, "{w} vs {want}");
    assert!(spread < 1e-6 * w);
}

/// True mechanisms are still refused: the same wheel without prestress under an out-of-plane
/// force (the loads work on the rim's translation), and the wheel pushed apart by its hub (the
/// spokes' compression softens the out-of-plane modes).
#[test]
fn slack_or_compressed_wheels_are_mechanisms() {
    let push = ", loads: [Force(rod: \"rim\", vertex: 0, force: (0.0, 0.0, 1.0))]";
    for text in [wheel(8, 0.0, push), wheel(8, -2e-4, "")] {
        let sc = parse("wheel.ron", &text).unwrap_or_else(|e| panic!("{e}"));
        let s = solve_scene(&sc, &settings_of(&sc)).unwrap();
        let m = s.results.mechanism.as_ref().map(|m| m.description.clone());
        assert!(!s.results.converged && m.is_some(), "{m:?}");
    }
}
