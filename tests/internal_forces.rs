//! Internal forces at equilibrium against statics: in a cantilever loaded only at its tip, the
//! internal force at every section is the tip force, so the axial force of each edge is
//! N = F·t (tension positive, t the edge's unit tangent towards the tip). Bending and twisting
//! energies see an edge only through scale-free curvatures (κb = 2 e₁×e₂ / (|e₁||e₂| + e₁·e₂)
//! and frames of unit tangents), so they exert no force along an edge, and the edge's stretch
//! force carries the whole axial component. The only error is the solve's:
//! each node is in equilibrium to tolerance × |F|, and the edge force sums the nodes beyond it,
//! so |N − F·t| ≤ n · tolerance · |F| for n edges.

mod common;

use common::*;
use rodnet::math::vec::{dot, norm, normalize, sub};
use rodnet::pipeline::{settings_of, solve_scene};

/// Largest |N_e − F·t_e| / |F| over the edges of the cantilever with `n` edges, and the
/// tolerance of its solve.
fn axial_error(n: usize) -> (f64, f64) {
    let s = cantilever(n, 2.0);
    let sol = solve_scene(&s, &settings_of(&s)).unwrap();
    assert!(sol.report.converged);
    let force = match s.loads[0] {
        rodnet::scene::types::Load::Force { force, .. } => force,
        _ => unreachable!("a tip force"),
    };
    let rod = &sol.equilibrium.rods[0];
    assert_eq!(rod.axial_force.len(), rod.points.len() - 1);
    let err = rod
        .axial_force
        .iter()
        .enumerate()
        .map(|(e, &n_e)| {
            let t = normalize(sub(rod.points[e + 1], rod.points[e]));
            (n_e - dot(force, t)).abs() / norm(force)
        })
        .fold(0.0, f64::max);
    (err, sol.report.tolerance)
}

#[test]
fn cantilever_axial_force_is_the_tip_force_along_the_tangent() {
    for n in [20, 40, 80] {
        let (err, tol) = axial_error(n);
        println!(
            "{n} edges: max |N − F·t| / |F| = {err:.3e} (bound n·tol = {:.1e})",
            n as f64 * tol
        );
        assert!(err <= n as f64 * tol, "{n} edges: {err:.3e}");
    }
}
