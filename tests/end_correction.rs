//! Gregory's end correction of the bending weights (`network/build/end_weights.rs`) against
//! the quadrature error it removes. In the linear limit the clamped cantilever's discrete tip
//! deflection is a quadrature of ∫ M m / EI dx (m = L − x, the unit tip load's moment) with
//! the bending weights: with the plain Voronoi weights the trapezoidal rule, whose whole h² term
//! sits at the clamp (Euler–Maclaurin; M m has zero slope at the free end), so the relative error
//! is C/N² with C = 1/2 for a tip load and 1 for self weight. With the clamp's half-stencil at
//! 5h/12 and h/12 moved to the next vertex, what is left is the one-sided difference's own
//! error, h²/12 (f'(0) − (f₁ − f₀)/h) = −h³f''(0)/24 − h⁴f'''/72: relative 1/(4N³) for the tip
//! load (f = P(L − x)²) and (1 − 1/(3N))/N³ for self weight (f = q(L − x)³/2, lumped loads
//! give the exact nodal moments).

use rodnet::pipeline::{settings_of, solve_scene};
use rodnet::scene::Scene;

const EI: f64 = 1e8 * std::f64::consts::PI * 1e-8 / 4.0;

/// The clamped unit cantilever of `networks/cantilever.ron` (EI = 0.785 N·m², EA L²/EI = 4e4)
/// with `n` edges and the given loads.
fn cantilever(n: usize, correct: bool, density: f64, loads: &str) -> Scene {
    let text = format!(
        r#"Scene(
    materials: {{ "steel": Material(young_modulus: 1e8, poisson_ratio: 0.5, density: {density:?},
                                   section: Circle(radius: 0.01)) }},
    rods: [ Rod(name: "beam", material: "steel", points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0)],
                subdivide: {n}, end_correction: {correct}) ],
    supports: [ Support(rod: "beam", vertex: 0, kind: Clamp) ],
    loads: [ {loads} ],
)"#
    );
    rodnet::scene::parse("cantilever", &text).unwrap()
}

/// Relative error of the tip deflection (−y) against `exact`.
fn tip_error(s: &Scene, exact: f64) -> f64 {
    let sol = solve_scene(s, &settings_of(s)).unwrap();
    assert!(sol.report.converged, "{:?}", sol.report.message);
    let tip = sol.results.rods[0].points.last().unwrap();
    (-tip[1] - exact) / exact
}

/// The plain weights' N²·error and the corrected weights' N³·error of the tip at N = 10, 20, 40.
fn constants(density: f64, load: &str, exact: f64) -> [(usize, f64, f64); 3] {
    [10, 20, 40].map(|n| {
        let nf = n as f64;
        let plain = tip_error(&cantilever(n, false, density, load), exact) * nf * nf;
        let corrected = tip_error(&cantilever(n, true, density, load), exact) * nf.powi(3);
        println!("N = {n}: plain N²·e = {plain:.7}, corrected N³·e = {corrected:.7}");
        (n, plain, corrected)
    })
}

/// Tip load PL²/EI = 1e-4 (Euler–Bernoulli v = PL³/3EI). Measured: plain C = 0.5000 to 2e-6,
/// corrected N³·error = 0.25000, 0.24999, 0.24993 at N = 10, 20, 40 (the rest is the load's
/// geometric nonlinearity, 1e-8 relative, times N³).
#[test]
fn tip_load_error_is_gregorys_remainder() {
    let p = 1e-4 * EI;
    let load = format!(
        "Force(rod: \"beam\", vertex: 1, force: (0.0, {:?}, 0.0))",
        -p
    );
    for (n, plain, corrected) in constants(0.0, &load, p / (3.0 * EI)) {
        assert!((plain - 0.5).abs() < 1e-5, "{n}: {plain:.7}");
        assert!((corrected - 0.25).abs() < 5e-4, "{n}: {corrected:.7}");
    }
}

/// Self weight qL³/EI = 1e-4 (v = qL⁴/8EI). Measured: plain C = 1.0000 to 2e-7, corrected
/// N³·error against 1 − 1/(3N): 1e-7, 1e-6, 8e-6 apart at N = 10, 20, 40.
#[test]
fn self_weight_error_is_gregorys_remainder() {
    // ρ g A = q = 1e-4 EI/L³ with A = π·1e-4 m² and g = 1 m/s².
    let density = 1e-4 * EI / (std::f64::consts::PI * 1e-4);
    let q = 1e-4 * EI;
    let load = "Gravity(g: (0.0, -1.0, 0.0))";
    for (n, plain, corrected) in constants(density, load, q / (8.0 * EI)) {
        let predicted = 1.0 - 1.0 / (3.0 * n as f64);
        assert!((plain - 1.0).abs() < 1e-5, "{n}: {plain:.7}");
        assert!(
            (corrected - predicted).abs() < 5e-5,
            "{n}: {corrected:.7} against {predicted:.7}"
        );
    }
}

/// A straight rod whose clamps are brought together into a ring (`networks/extreme/michell.ron`
/// without twist) is a closed smooth curve: the plain weights are the periodic rule there, and
/// corrected weights at that junction made the twisted ring's planar state imperfect (its
/// off-plane distance near Michell's critical twist 10× larger). The correction stays off at
/// two clamped ends that meet with a continuous tangent: the ring is the same with and without
/// `end_correction`, while the same rod with its far clamp 1 mm short of closing is not (its
/// weights differ, by O(h²) of its shape).
#[test]
fn a_ring_closed_by_its_clamps_keeps_the_plain_weights() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/networks/extreme/michell.ron");
    let mut ring = rodnet::scene::load(std::path::Path::new(path)).unwrap().0;
    ring.supports[1].rotate_by = Some([0.0, 0.0, std::f64::consts::PI]);
    // Default solver settings, not the Michell scene's load steps.
    ring.solver = Default::default();
    let mut open = ring.clone();
    open.supports[1].move_to = Some([0.0, 0.0, 1e-3]);
    for (what, s, same) in [("ring", ring, true), ("open ring", open, false)] {
        let points = |correct: bool| {
            let mut s = s.clone();
            s.rods[0].end_correction = correct;
            let sol = solve_scene(&s, &settings_of(&s)).unwrap();
            assert!(sol.report.converged, "{what}: {:?}", sol.report.message);
            sol.results.rods[0].points.clone()
        };
        let (a, b) = (points(true), points(false));
        let d = a
            .iter()
            .zip(&b)
            .map(|(p, q)| (0..3).map(|k| (p[k] - q[k]).abs()).fold(0.0, f64::max))
            .fold(0.0, f64::max);
        println!("{what}: corrected and plain weights {d:.2e} m apart");
        assert_eq!(d == 0.0, same, "{what}: {d:.2e}");
        assert!(d < 1e-2, "{what}: {d:.2e}");
    }
}
