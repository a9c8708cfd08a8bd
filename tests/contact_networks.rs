//! The contact scenes in `networks/` solve through the scene loader and give their stated
//! answers (bounds are the measured errors with 20 % margin), and bad contact input is rejected
//! with a located message (exit 2).

mod support;

use std::process::Command;

use rodnet::pipeline::{settings_of, solve_scene, Solution};
use support::{cantilever_tip_load, heavy_elastica_lifted_end};

fn run(name: &str) -> Solution {
    let (s, _) =
        rodnet::scene::load(std::path::Path::new(&format!("networks/{name}.ron"))).unwrap();
    let sol = solve_scene(&s, &settings_of(&s)).unwrap();
    assert!(sol.report.converged, "{name}: {:?}", sol.report.message);
    let k = sol.results.kkt.as_ref().expect("kkt");
    println!(
        "{name}: {} iterations, {:.3} s, kkt {k:?}",
        sol.results.iterations, sol.results.seconds
    );
    assert!(
        k.primal_feasibility_relative <= 1e-9 && k.min_multiplier >= 0.0,
        "{k:?}"
    );
    assert!(
        k.stationarity <= 1e-9f64.max(sol.report.residual_floor),
        "{k:?}"
    );
    sol
}

/// Steel wire lifted 5 cm off the floor (h = 0.0577 ℓ_c): the pin force against the heavy
/// elastica, F = lift_force · w ℓ_c. Measured relative error 1.00e-4 at N = 150 (dx = 2 cm).
#[test]
fn lifted_wire() {
    let sol = run("lifted_wire");
    let (e, r, rho, g): (f64, f64, f64, f64) = (2e11, 1e-3, 7850.0, 9.81);
    let ei = e * std::f64::consts::PI * r.powi(4) / 4.0;
    let w = rho * std::f64::consts::PI * r * r * g;
    let lc = (ei / w).cbrt();
    let reference = heavy_elastica_lifted_end(0.05 / lc).lift_force * w * lc;
    let f = sol.results.reactions[0].force[2];
    let err = (f - reference) / reference;
    println!("lifted_wire: F = {f:.9} N, elastica {reference:.9} N, relative error {err:.2e}");
    assert!(err.abs() < MEASURED_WIRE * 1.2, "{err:.2e}");
}
const MEASURED_WIRE: f64 = 1.0e-4;

/// Rod pulled over a ball: reactions, contact forces and weight balance.
#[test]
fn rod_over_sphere() {
    let sol = run("rod_over_sphere");
    let r = &sol.results;
    let c = r.contacts.as_ref().unwrap();
    let mut f = [0.0; 3];
    let mut scale = 0.0;
    for v in c
        .iter()
        .map(|c| c.force)
        .chain(r.reactions.iter().map(|x| x.force))
    {
        for k in 0..3 {
            f[k] += v[k];
        }
        scale += v.iter().map(|a| a * a).sum::<f64>().sqrt();
    }
    f[2] -= 2.0; // weight: 1 N/m over 2 m
    let imbalance = f.iter().map(|v| v.abs()).fold(0.0, f64::max) / scale;
    println!(
        "rod_over_sphere: {} contacts, force imbalance {imbalance:.2e} of {scale:.3} N",
        c.len()
    );
    assert!(imbalance <= 1e-9, "{imbalance:.2e}");
}

/// Cantilever against a stop: only the tip touches, and the elastica under the net tip load
/// P − R (R the stop's force) must deflect exactly to the stop, v/L = 0.3. Measured: −3.53e-4,
/// the N = 40 discretization error of the large-deflection cantilever (4.2e-4 in
/// `reference_networks.rs`).
#[test]
fn cantilever_stop() {
    let sol = run("cantilever_stop");
    let r = &sol.results;
    let c = r.contacts.as_ref().unwrap();
    assert_eq!(c.len(), 1, "{c:?}");
    assert_eq!(c[0].node, 40);
    let ei = 1e8 * std::f64::consts::PI * 1e-8 / 4.0;
    let p = std::f64::consts::FRAC_PI_2; // the scene's tip force, N
    let net = p - c[0].force[1];
    let v = cantilever_tip_load(net / ei).deflection;
    let err = (v - 0.3) / 0.3;
    println!("cantilever_stop: stop force {:.9} N, elastica deflection under the net load {v:.9}, relative error {err:.2e}", c[0].force[1]);
    assert!(err.abs() < MEASURED_STOP * 1.2, "{err:.2e}");
}
const MEASURED_STOP: f64 = 3.53e-4;

fn solve_text(name: &str, text: &str) -> (i32, String) {
    let d = std::env::temp_dir().join(format!("rodnet-contact-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    let p = d.join(format!("{name}.ron"));
    std::fs::write(&p, text).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_rodnet"))
        .arg("solve")
        .arg(&p)
        .arg("--quiet")
        .output()
        .unwrap();
    (
        out.status.code().unwrap(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

const BASE: &str = r#"Scene(
    materials: { "m": Material(young_modulus: 1e8, poisson_ratio: 0.3, section: Circle(radius: 0.01)) },
    rods: [ Rod(name: "a", material: "m", points: [(0.0, 0.0, 0.01), (1.0, 0.0, 0.01)], subdivide: 4) ],
    supports: [ Support(rod: "a", vertex: 0, kind: Clamp) ],
    loads: [ Force(rod: "a", vertex: 1, force: (0.0, 0.0, -1.0)) ],
    obstacles: [
        Plane(point: (0.0, 0.0, 0.0), normal: (0.0, 0.0, 1.0)),
    ],
    bounds: [
        Bound(rod: "a", min: (None, -1.0, None)),
    ],
)"#;

/// Bad contact input: exit 2, the file, line and field named, never a panic.
#[test]
fn bad_contact_input_is_located() {
    let (code, err) = solve_text("good", BASE);
    assert_eq!(code, 0, "{err}");
    let cases = [
        (
            "zero_normal",
            BASE.replace("normal: (0.0, 0.0, 1.0)", "normal: (0.0, 0.0, 0.0)"),
            ":7:",
            "obstacles[0].normal",
        ),
        (
            "radius",
            BASE.replace(
                "Plane(point: (0.0, 0.0, 0.0), normal: (0.0, 0.0, 1.0))",
                "Sphere(center: (0.0, 0.0, -1.0), radius: -1.0)",
            ),
            ":7:",
            "obstacles[0].radius",
        ),
        (
            "axis",
            BASE.replace(
                "Plane(point: (0.0, 0.0, 0.0), normal: (0.0, 0.0, 1.0))",
                "Cylinder(point: (0.0, 0.0, -1.0), axis: (0.0, 0.0, 0.0), radius: 0.5)",
            ),
            ":7:",
            "obstacles[0].axis",
        ),
        (
            "penetrating",
            BASE.replace("point: (0.0, 0.0, 0.0)", "point: (0.0, 0.0, 0.005)"),
            ":7:",
            "penetrates this obstacle",
        ),
        (
            "min_above_max",
            BASE.replace(
                "min: (None, -1.0, None)",
                "min: (None, -1.0, None), max: (None, -2.0, None)",
            ),
            ":10:",
            "bounds[0].max",
        ),
        (
            "equal_bounds",
            BASE.replace(
                "min: (None, -1.0, None)",
                "min: (None, -1.0, None), max: (None, -1.0, None)",
            ),
            ":10:",
            "must be above min",
        ),
        (
            "unknown_rod",
            BASE.replace("Bound(rod: \"a\"", "Bound(rod: \"b\""),
            ":10:",
            "unknown rod \"b\"",
        ),
        (
            "vertex",
            BASE.replace("Bound(rod: \"a\",", "Bound(rod: \"a\", vertices: [7],"),
            ":10:",
            "vertex 7 is out of range",
        ),
        (
            "violated",
            BASE.replace("min: (None, -1.0, None)", "min: (None, 0.5, None)"),
            ":10:",
            "bounds[0].min",
        ),
        (
            "empty",
            BASE.replace("min: (None, -1.0, None)", "min: (None, None, None)"),
            ":10:",
            "at least one",
        ),
        (
            "unknown_field",
            BASE.replace(
                "normal: (0.0, 0.0, 1.0)",
                "normal: (0.0, 0.0, 1.0), friction: 0.3",
            ),
            ":7:",
            "friction",
        ),
    ];
    for (name, text, line, needle) in cases {
        let (code, err) = solve_text(name, &text);
        assert_eq!(code, 2, "{name}: {err}");
        assert!(
            err.contains(&format!("{name}.ron{line}")),
            "{name}: no location {line}: {err}"
        );
        assert!(err.contains(needle), "{name}: lacks {needle:?}: {err}");
        assert!(!err.contains("panicked"), "{name}: {err}");
    }
}

/// Obstacles but no free node to constrain (every node supported): no QP, and the results
/// still carry an empty `contacts` list and a `kkt` block with no constraints.
#[test]
fn obstacles_without_free_nodes() {
    let text = BASE.replace("subdivide: 4", "subdivide: 1").replace(
        "Support(rod: \"a\", vertex: 0, kind: Clamp)",
        "Support(rod: \"a\", vertex: 0, kind: Clamp), Support(rod: \"a\", vertex: 1, kind: Pin)",
    );
    let s = rodnet::scene::parse("t.ron", &text).unwrap();
    let sol = solve_scene(&s, &settings_of(&s)).unwrap();
    assert!(sol.report.converged);
    assert!(sol.report.constraints.is_none());
    assert_eq!(sol.results.contacts.as_ref().map(|c| c.len()), Some(0));
    assert_eq!(sol.results.kkt.as_ref().map(|k| k.constraints), Some(0));
}
