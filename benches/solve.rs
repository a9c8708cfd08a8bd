//! Solve times of reference scenes (`cargo bench --bench solve`).
//!
//! - `unconstrained`: scenes without obstacles or bounds; they never build a QP, so their cost
//!   must be what it was before contact existed (run this bench on both commits to compare).
//! - `inactive_bound`: the cantilever with a bound it never reaches, against the same cantilever
//!   without it: the only extra work is checking the unconstrained step against the bound.
//! - `with_constraints` / `constraints_removed`: each contact scene, and the same scene with its
//!   obstacles and bounds deleted (a different equilibrium: the rod stays straight, the
//!   cantilever swings freely).

use rodnet::pipeline::{settings_of, solve_scene};
use rodnet::scene::types::{Bound, Scene};

fn main() {
    divan::main();
}

fn load(name: &str) -> Scene {
    let path = format!("{}/networks/{name}.ron", env!("CARGO_MANIFEST_DIR"));
    rodnet::scene::load(std::path::Path::new(&path))
        .expect("reference scene")
        .0
}

fn run(s: &Scene) {
    let sol = solve_scene(s, &settings_of(s)).expect("valid scene");
    assert!(sol.report.converged, "{:?}", sol.report.message);
    divan::black_box(sol);
}

#[divan::bench(args = ["cantilever", "l_frame", "square_frame", "star", "grid"], sample_count = 20)]
fn unconstrained(bencher: divan::Bencher, name: &str) {
    let s = load(name);
    bencher.bench(|| run(&s));
}

#[divan::bench(args = [false, true], sample_count = 20)]
fn inactive_bound(bencher: divan::Bencher, bounded: bool) {
    let mut s = load("cantilever");
    if bounded {
        s.bounds = vec![Bound {
            rod: None,
            vertices: None,
            min: [None, Some(-10.0), None],
            max: [None; 3],
        }];
    }
    bencher.bench(|| run(&s));
}

#[divan::bench(args = ["lifted_wire", "rod_over_sphere", "cantilever_stop"], sample_count = 10)]
fn with_constraints(bencher: divan::Bencher, name: &str) {
    let s = load(name);
    bencher.bench(|| run(&s));
}

// Not the lifted wire: without its floor it swings down to hang from the pin, and the
// unconstrained solver stalls at 1e-7 relative residual on that 3 m, r = 1 mm wire.
#[divan::bench(args = ["rod_over_sphere", "cantilever_stop"], sample_count = 10)]
fn constraints_removed(bencher: divan::Bencher, name: &str) {
    let mut s = load(name);
    s.obstacles.clear();
    s.bounds.clear();
    bencher.bench(|| run(&s));
}

/// The cantilever of `networks/cantilever.ron` with its tip load raised to PL²/EI = 5, refined
/// from 10 to 10⁴ edges, default solver settings (issue 12: iterations flat in N).
#[divan::bench(args = [10, 100, 1000, 10000], sample_count = 3, sample_size = 1)]
fn refined_cantilever(bencher: divan::Bencher, n: usize) {
    let mut s = load("cantilever");
    s.rods[0].subdivide = n;
    s.solver = Default::default();
    if let rodnet::scene::types::Load::Force { force, .. } = &mut s.loads[0] {
        force[1] *= 2.5;
    }
    bencher.bench(|| run(&s));
}

/// The issue-12 target: the PL²/EI = 5 cantilever to a tip error of 1e-4·L against the
/// extensible elastica (tests/extrapolate.rs): 50 edges solved directly (error 9.6e-5), 12
/// and 24 edges with `--extrapolate` (5.3e-5), or 4, 8 and 16 with `--levels 3` (5.5e-5).
#[divan::bench(args = ["direct_50", "extrapolated_12", "three_levels_4"], sample_count = 20)]
fn cantilever_to_1e4(bencher: divan::Bencher, how: &str) {
    let mut s = load("cantilever");
    s.solver = Default::default();
    if let rodnet::scene::types::Load::Force { force, .. } = &mut s.loads[0] {
        force[1] *= 2.5;
    }
    let (subdivide, levels) = match how {
        "extrapolated_12" => (12, 2),
        "three_levels_4" => (4, 3),
        _ => (50, 1),
    };
    s.rods[0].subdivide = subdivide;
    bencher.bench(|| {
        let sol = if levels > 1 {
            rodnet::study::extrapolate::solve_levels(&s, &settings_of(&s), levels)
                .expect("valid scene")
        } else {
            solve_scene(&s, &settings_of(&s)).expect("valid scene")
        };
        assert!(sol.report.converged, "{:?}", sol.report.message);
        divan::black_box(sol);
    });
}
