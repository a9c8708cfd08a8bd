//! The reported energy does not depend on where a scene sits: `energy.external`, the loads'
//! potential, is measured from the rest configuration (minus the work the loads did from the
//! rest positions), not from the coordinate origin.

use rodnet::pipeline::{settings_of, solve_scene};
use rodnet::scene::types::{Load, Obstacle, Scene};

/// An L-shaped frame, clamped at its foot, under a tip force, a torque and its own weight.
const FRAME: &str = r#"Scene(
    materials: { "m": Material(young_modulus: 2e9, poisson_ratio: 0.3, density: 1200.0, section: Circle(radius: 0.01)) },
    rods: [
        Rod(name: "post", material: "m", points: [(0.0, 0.0, 0.0), (0.0, 0.0, 1.0)], subdivide: 10),
        Rod(name: "arm", material: "m", points: [(0.0, 0.0, 1.0), (0.8, 0.0, 1.0)], subdivide: 8),
    ],
    joints: [Joint(name: "corner", at: [("post", 1), ("arm", 0)], kind: Rigid)],
    supports: [Support(rod: "post", vertex: 0, kind: Clamp)],
    loads: [
        Force(rod: "arm", vertex: 1, force: (0.0, 2.0, -5.0)),
        Gravity(g: (0.0, 0.0, -9.81)),
    ],
)"#;

fn shifted(scene: &Scene, by: [f64; 3]) -> Scene {
    let mut s = scene.clone();
    let add = |p: &mut [f64; 3]| (0..3).for_each(|k| p[k] += by[k]);
    for r in &mut s.rods {
        r.points.iter_mut().for_each(add);
    }
    for o in &mut s.obstacles {
        if let Obstacle::Plane { point, .. } = o {
            add(point);
        }
    }
    s
}

#[test]
fn lifting_a_structure_does_not_change_its_energy() {
    let base = rodnet::scene::parse("frame.ron", FRAME).unwrap();
    let solve = |s: &Scene| {
        let sol = solve_scene(s, &settings_of(s)).unwrap();
        assert!(sol.results.converged, "{:?}", sol.report.message);
        sol.results.energy
    };
    let e0 = solve(&base);
    let elastic = e0.stretch + e0.bend + e0.twist + e0.joints;
    assert!(elastic > 0.0 && e0.external < 0.0, "{e0:?}");
    for by in [[0.0, 0.0, 100.0], [37.0, -12.0, 100.0], [-1e3, 0.0, 0.0]] {
        let e = solve(&shifted(&base, by));
        println!(
            "shifted by {by:?}: total {:.12e} J, external {:.12e} J (at the origin: {:.12e}, {:.12e})",
            e.total, e.external, e0.total, e0.external
        );
        assert!(
            (e.total - e0.total).abs() <= 1e-7 * e0.total.abs(),
            "total {} vs {}",
            e.total,
            e0.total
        );
        assert!((e.external - e0.external).abs() <= 1e-7 * e0.external.abs());
    }
}

#[test]
fn external_energy_is_minus_the_work_from_rest() {
    // A cantilever under a small tip force, in the linear range: the loads' potential is
    // −F·u with u the tip's displacement from rest, and twice the elastic energy (Clapeyron).
    let text = std::fs::read_to_string("networks/cantilever.ron")
        .unwrap()
        .replace("-1.5707963267948966", "-1e-4");
    let mut scene = rodnet::scene::parse("small.ron", &text).unwrap();
    // Far from the origin, where −F·x alone would be 1e-4 N × 500 m.
    scene = shifted(&scene, [0.0, 500.0, 0.0]);
    let sol = solve_scene(&scene, &settings_of(&scene)).unwrap();
    assert!(sol.results.converged);
    let r = &sol.results;
    let Load::Force { force, .. } = scene.loads[0] else {
        panic!("a force")
    };
    let tip = *r.rods[0].points.last().unwrap();
    let u = [tip[0] - 1.0, tip[1] - 500.0, tip[2]];
    let work: f64 = (0..3).map(|k| force[k] * u[k]).sum();
    let e = &r.energy;
    println!("external {:.9e} J, −F·u {:.9e} J", e.external, -work);
    assert!((e.external + work).abs() <= 1e-9 * work.abs());
    let elastic = e.stretch + e.bend + e.twist;
    assert!((e.external + 2.0 * elastic).abs() <= 1e-5 * elastic);
    assert!((e.total + elastic).abs() <= 1e-5 * elastic);
}
