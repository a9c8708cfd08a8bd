//! Successive solves of one `NetworkProblem` keep the factorization object while the model's
//! Hessian pattern is unchanged (`Model::pattern_fingerprint`), and make a new one when it
//! changes.

mod common;

use rodnet::energy::point_load::PointLoad;
use rodnet::network::build::build;
use rodnet::network::problem::NetworkProblem;
use rodnet::solver::NewtonSettings;

#[test]
fn the_fingerprint_follows_the_free_map_and_the_terms() {
    let mut m = build(&common::cantilever(8, 1.0)).unwrap().model;
    let f0 = m.pattern_fingerprint();
    assert_eq!(m.pattern_fingerprint(), f0, "a hash of the same data");
    m.state.q.iter_mut().for_each(|q| *q += 0.25);
    assert_eq!(m.pattern_fingerprint(), f0, "positions are not the pattern");
    let mut held = m.clone();
    let v = held.free.iter().position(|&f| f != u32::MAX).unwrap();
    held.hold(v);
    assert_ne!(held.pattern_fingerprint(), f0, "a variable held");
    let mut loaded = m.clone();
    let last = loaded.terms.loads[0].vars;
    loaded.terms.loads.push(PointLoad {
        vars: [last[0] - 3, last[1] - 3, last[2] - 3],
        force: [0.0; 3],
    });
    assert_ne!(loaded.pattern_fingerprint(), f0, "a term added");
    let mut moved = m.clone();
    moved.terms.loads[0].vars = [last[0] - 3, last[1] - 3, last[2] - 3];
    assert_ne!(moved.pattern_fingerprint(), f0, "a term on other variables");
}

#[test]
fn a_changed_pattern_between_solves_is_analysed_again() {
    let scene = common::cantilever(8, 1.0);
    let settings = NewtonSettings::default().automatic_tolerance(true);
    let mut m = build(&scene).unwrap().model;
    let mut p = NetworkProblem::new(&mut m);
    let first = p.solve(&settings);
    assert!(first.converged, "{:?}", first.message);
    // Hold the tip's y: fewer unknowns, another pattern; the kept factorization would not fit.
    let tip_y = p.model.terms.loads[0].vars[1];
    p.model.hold(tip_y);
    let again = p.solve(&settings);
    assert!(again.converged);
    let q = p.model.state.q.clone();
    let mut fresh = build(&scene).unwrap().model;
    fresh.state.q.clone_from(&q);
    fresh.hold(tip_y);
    let r = rodnet::network::solve(&mut fresh, &settings);
    assert!(r.converged);
    let diff = q
        .iter()
        .zip(&fresh.state.q)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(diff < 1e-12, "{diff}");
}
