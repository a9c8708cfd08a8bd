//! Scenes at survey coordinates (issue 36, item 3): a scene and its copy translated by
//! (512345, 5412345, 250) m converge in the same iterations to the same displacements. The
//! copies are made here field by field (not by the library's own translation, whose omissions
//! would cancel out), and compared with the scene solved where it was drawn.

use rodnet::pipeline::{settings_of, solve_scene, Solution};
use rodnet::scene::types::Obstacle;
use rodnet::scene::Scene;

const SITE: [f64; 3] = [512345.0, 5412345.0, 250.0];

fn moved(mut s: Scene, d: [f64; 3]) -> Scene {
    let mv = |p: &mut [f64; 3]| (0..3).for_each(|k| p[k] += d[k]);
    for r in &mut s.rods {
        r.points.iter_mut().for_each(mv);
    }
    for x in &mut s.supports {
        if let Some(p) = x.move_to.as_mut() {
            mv(p);
        }
    }
    for o in &mut s.obstacles {
        match o {
            Obstacle::Plane { point, .. } => mv(point),
            Obstacle::Cylinder { point, .. } => mv(point),
            Obstacle::Sphere { center, .. } => mv(center),
        }
    }
    for b in &mut s.bounds {
        for (k, dk) in d.iter().enumerate() {
            b.min[k] = b.min[k].map(|x| x + dk);
            b.max[k] = b.max[k].map(|x| x + dk);
        }
    }
    s
}

fn load(path: &str) -> Scene {
    let text = std::fs::read_to_string(path).unwrap();
    rodnet::scene::parse(path, &text).unwrap()
}

fn solve(s: &Scene) -> Solution {
    solve_scene(s, &settings_of(s)).expect("valid scene")
}

/// Largest displacement difference between the two solutions (positions of the far one taken
/// back by `SITE`), and the largest displacement.
fn displacements(near: &Solution, far: &Solution, rest: &Scene) -> (f64, f64) {
    let (mut diff, mut largest) = (0.0_f64, 0.0_f64);
    for ((a, b), r) in near
        .results
        .rods
        .iter()
        .zip(&far.results.rods)
        .zip(&rest.rods)
    {
        // Input vertex k is node k·subdivide; compare every node, displacements from the
        // rest polyline's nodes (equal edges along each input segment).
        let s = r.subdivide;
        for (i, (p, q)) in a.points.iter().zip(&b.points).enumerate() {
            let (k, t) = (i / s, (i % s) as f64 / s as f64);
            let x0 = match r.points.get(k + 1) {
                Some(next) => [0, 1, 2].map(|c| r.points[k][c] + t * (next[c] - r.points[k][c])),
                None => r.points[k],
            };
            for c in 0..3 {
                largest = largest.max((p[c] - x0[c]).abs());
                diff = diff.max((p[c] - (q[c] - SITE[c])).abs());
            }
        }
    }
    (diff, largest)
}

/// Both solves must agree to 1e-9 of the largest displacement, beyond what neither can resolve:
/// the far results' own coordinates are doubles near `SITE` (half an ulp each), and a state
/// converged to its round-off floor f is known along its soft modes to about f of its
/// displacements (scenes near the origin are solved where they are drawn, the far copy about its
/// centre: their rounding differs).
fn check(path: &str, edit: impl Fn(Scene) -> Scene) {
    let near = edit(load(path));
    let far = moved(near.clone(), SITE);
    let (a, b) = (solve(&near), solve(&far));
    assert!(
        a.results.converged && b.results.converged,
        "{path}: {:?} / {:?}",
        a.report.message,
        b.report.message
    );
    assert_eq!(a.results.iterations, b.results.iterations, "{path}");
    let (diff, largest) = displacements(&a, &b, &near);
    let floor = a.report.residual_floor.max(b.report.residual_floor);
    let resolution = SITE.iter().fold(0.0_f64, |m, x| m.max(x.abs())) * f64::EPSILON;
    let allowed = (1e-9 + 4.0 * floor) * largest + resolution;
    println!(
        "{path}: {} iterations, displacements differ by {:.2e} of the largest ({largest:.2e} m), \
         floors {:.2e} / {:.2e}",
        a.results.iterations,
        diff / largest,
        a.report.residual_floor,
        b.report.residual_floor
    );
    assert!(
        diff <= allowed,
        "{path}: displacements differ by {diff:.2e} m of {largest:.2e} m (allowed {allowed:.2e})"
    );
    // The floor does not depend on where the structure stands.
    let (fa, fb) = (a.report.residual_floor, b.report.residual_floor);
    assert!(
        fb < 4.0 * fa.max(1e-15),
        "{path}: floor {fa:.2e} → {fb:.2e}"
    );
}

#[test]
fn a_cantilever_converges_alike_at_survey_coordinates() {
    for n in [40, 1000] {
        check("networks/cantilever.ron", |mut s| {
            s.rods[0].subdivide = n;
            s
        });
    }
}

#[test]
fn frames_grids_and_obstacles_converge_alike_at_survey_coordinates() {
    for path in [
        "networks/l_frame.ron",
        "networks/grid.ron",
        "networks/rod_over_sphere.ron",
        "networks/lifted_wire.ron",
        "networks/cantilever_stop.ron",
        "networks/buckled_strip.ron",
    ] {
        check(path, |s| s);
    }
}

/// A restart from the far results starts at their equilibrium: the positions it reads are in
/// the scene's coordinates.
#[test]
fn a_restart_at_survey_coordinates_starts_at_its_equilibrium() {
    let far = moved(load("networks/cantilever.ron"), SITE);
    let first = solve(&far);
    let initial: Vec<_> = first
        .results
        .rods
        .iter()
        .map(|r| rodnet::network::initial::RodState {
            name: r.name.clone(),
            points: r.points.clone(),
            twist: r.twist.clone(),
        })
        .collect();
    let again = rodnet::pipeline::solve_scene_from(&far, &settings_of(&far), &initial).unwrap();
    assert!(again.results.converged);
    assert!(
        again.results.iterations <= 1,
        "{}",
        again.results.iterations
    );
}
