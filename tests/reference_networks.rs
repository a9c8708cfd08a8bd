//! The reference scenes in `networks/` solve through the scene loader and give their stated
//! answers. Bounds are the measured discretization errors at the files' subdivisions, with the
//! end-corrected bending weights (the convergence itself is tested in network_validation.rs and
//! end_correction.rs), with 20 % margin; the cantilever's includes its extensibility.

use rodnet::pipeline::{settings_of, solve_scene, Solution};

fn run(name: &str) -> Solution {
    let (s, _) =
        rodnet::scene::load(std::path::Path::new(&format!("networks/{name}.ron"))).unwrap();
    let sol = solve_scene(&s, &settings_of(&s)).unwrap();
    assert!(sol.report.converged, "{name}: {:?}", sol.report.message);
    sol
}

fn check(name: &str, value: f64, expected: f64, measured_error: f64) {
    let err = (value - expected).abs() / expected.abs();
    println!("{name}: {value:.9e} vs {expected:.9e}, relative error {err:.2e}");
    assert!(err < 1.2 * measured_error, "{name}: error {err:.2e}");
}

#[test]
fn cantilever() {
    let sol = run("cantilever");
    let tip = sol.results.rods[0].points.last().unwrap();
    // Elastica PL²/EI = 2 (P = 1.5708 N, EI = 0.785398): v/L = 0.49345748; N = 40, r/L = 0.01.
    check("cantilever", -tip[1], 0.49345748, 1.12e-4);
}

#[test]
fn l_frame() {
    let sol = run("l_frame");
    check(
        "l_frame",
        sol.results.rods[1].points.last().unwrap()[2],
        1.0846667e-5,
        2.25e-5,
    );
}

#[test]
fn square_frame() {
    let sol = run("square_frame");
    let (a, c) = (
        sol.results.joints[0].position,
        sol.results.joints[2].position,
    );
    let delta = ((c[0] - a[0]) + (c[1] - a[1])) / 2f64.sqrt() - 2f64.sqrt();
    check("square_frame", delta, 4.1679167e-6, 2.45e-4);
}

#[test]
fn star() {
    let sol = run("star");
    check(
        "star",
        -sol.results.joints[0].position[2],
        1.6666667e-6,
        2.5e-4,
    );
}

#[test]
fn grid() {
    let sol = run("grid");
    for j in &sol.results.joints {
        check("grid", -j.position[2], 4.1666667e-7, 7.8e-4);
    }
}
