//! A simply supported beam (a pin and a roller) over a floor `Plane`: rollers and obstacles on
//! one node (issue 36). A roller whose normal is along z eliminates the node's z coordinate; its
//! floor row used to ask for that coordinate's unknown and panicked ("free node"). A slanted
//! roller swinging its end down onto the floor used to run out of iterations (the contact's
//! Jacobian pushed the node off its plane). Checked against Euler–Bernoulli beam theory and
//! against the same end held on the line where the roller's plane meets the floor.

use rodnet::io::results::Results;
use rodnet::pipeline::{settings_of, solve_scene};
use rodnet::scene::parse;

/// EI = 1 N·m² (E = 4/(π r⁴) with r = 0.01 m), L = 1 m.
const E: &str = "127323954.47351627";

/// The beam at height `z` (centreline; its surface is r = 0.01 m lower), pinned at x = 0, its
/// other end on `rollers`, the force P down at midspan; `edges` per half.
fn beam(z: f64, rollers: &[([f64; 3], Option<[f64; 3]>)], p: f64, edges: usize) -> String {
    let rollers: Vec<String> = rollers
        .iter()
        .map(|(n, to)| {
            let to = to.map_or("None".into(), |t| {
                format!("Some(({}, {}, {}))", t[0], t[1], t[2])
            });
            format!(
                "Support(rod: \"b\", vertex: 2, kind: Roller(normal: ({}, {}, {})), move_to: {to})",
                n[0], n[1], n[2]
            )
        })
        .collect();
    format!(
        "Scene(materials: {{\"m\": Material(young_modulus: {E}, poisson_ratio: 0.3, \
         section: Circle(radius: 0.01))}},
         rods: [Rod(name: \"b\", material: \"m\", points: [(0.0, 0.0, {z}), (0.5, 0.0, {z}), \
         (1.0, 0.0, {z})], subdivide: {edges})],
         supports: [Support(rod: \"b\", vertex: 0, kind: Pin), {}],
         loads: [Force(rod: \"b\", vertex: 1, force: (0.0, 0.0, {}))],
         obstacles: [Plane(point: (0.0, 0.0, 0.0), normal: (0.0, 0.0, 1.0))])",
        rollers.join(", "),
        -p
    )
}

fn solve(text: &str) -> Results {
    let sc = parse("beam.ron", text).unwrap_or_else(|e| panic!("{e}"));
    let s = solve_scene(&sc, &settings_of(&sc)).unwrap();
    assert!(s.results.converged, "{:?}", s.results.solver.message);
    s.results
}

/// |Σ reactions + Σ loads + Σ contact forces|, N.
fn imbalance(r: &Results, p: f64) -> f64 {
    let mut sum = [0.0, 0.0, -p];
    for f in r.reactions.iter().map(|s| s.force) {
        (0..3).for_each(|k| sum[k] += f[k]);
    }
    for c in r.contacts.iter().flatten() {
        (0..3).for_each(|k| sum[k] += c.force[k]);
    }
    sum.iter().map(|x| x * x).sum::<f64>().sqrt()
}

const UP: [f64; 3] = [0.0, 0.0, 1.0];

/// Clear of the floor, the midspan deflection is P L³/(48 EI), with the discretization's O(h²)
/// error: 1.2e-3 relative at 40 edges, 2.9e-4 at 80. Pressed onto it (the floor g = 0.01 m
/// below the surface, P L³/(48 EI) = 0.21 m), the midspan rests on the floor and the beam takes
/// 48 EI g / L³ of the load: the floor's force is P − 0.48 N.
#[test]
fn simply_supported_beam_over_a_floor() {
    let z = 0.02;
    let mut last = f64::INFINITY;
    for edges in [20, 40] {
        let p = 0.1;
        let r = solve(&beam(z, &[(UP, None)], p, edges));
        let w = z - r.rods[0].points[edges][2];
        let err = (w / (p / 48.0) - 1.0).abs();
        println!(
            "{} edges, clear: deflection {w:.6e} m, error {err:.2e}, {} iterations",
            2 * edges,
            r.iterations
        );
        assert!(r.contacts.iter().flatten().next().is_none());
        assert!(err < 1.5e-3 && err < 0.3 * last, "{err:e}");
        assert!(imbalance(&r, p) < 1e-9 * p);
        last = err;

        let p = 10.0;
        let r = solve(&beam(z, &[(UP, None)], p, edges));
        let contacts: Vec<_> = r.contacts.iter().flatten().collect();
        assert_eq!(contacts.len(), 1, "{contacts:?}");
        let want = p - 48.0 * 0.01;
        let err = (contacts[0].force[2] / want - 1.0).abs();
        println!(
            "{} edges, pressed: floor force {:.6} N (beam theory {want} N), error {err:.1e}",
            2 * edges,
            contacts[0].force[2]
        );
        assert_eq!(contacts[0].node, edges);
        assert!(err < 5e-5, "{err:e}");
        assert!(imbalance(&r, p) < 1e-9 * p);
    }
}

/// A roller on the plane of normal (0, 0.6, 0.8) lets the beam swing about the axis along that
/// normal through the pin until its end lands on the floor; there the end is held by the roller
/// and the floor together, on the line where the roller's plane meets the plane z = r. The same
/// beam with its end moved onto that line by two rollers (no contact there) is the reference.
/// The beam at rest on the floor with a roller along z is in equilibrium as it stands.
#[test]
fn rollers_on_nodes_that_touch_the_floor() {
    let (z, p, n) = (0.05, 0.1, [0.0, 0.6, 0.8]);
    let swung = solve(&beam(z, &[(n, None)], p, 10));
    // On the roller's plane 0.6 y + 0.8 (z − 0.05) = 0 at z = 0.01.
    let on_line = [1.0, 0.8 * (z - 0.01) / 0.6, 0.01];
    let line = solve(&beam(z, &[(n, Some(on_line)), (UP, Some(on_line))], p, 10));
    let worst = swung.rods[0]
        .points
        .iter()
        .zip(&line.rods[0].points)
        .fold(0.0f64, |m, (a, b)| {
            (0..3).fold(m, |m, k| m.max((a[k] - b[k]).abs()))
        });
    println!("slanted roller onto the floor: {} iterations, largest difference from the line support {worst:.1e} m", swung.iterations);
    assert!(worst < 1e-12, "{worst:e}");
    assert!(imbalance(&swung, p) < 1e-9 * p);
    let end = swung
        .contacts
        .iter()
        .flatten()
        .find(|c| c.node == 20)
        .expect("end on the floor");
    let held = line.reactions.iter().map(|s| s.force[2]).sum::<f64>() - line.reactions[0].force[2];
    assert!(
        (end.force[2] - held).abs() < 1e-9 * p,
        "{} vs {held}",
        end.force[2]
    );

    for normal in [UP, n] {
        let r = solve(&beam(0.01, &[(normal, None)], 10.0, 10));
        let moved = r.rods[0]
            .points
            .iter()
            .map(|x| (x[2] - 0.01).abs())
            .fold(0.0, f64::max);
        assert!(
            moved < 1e-12 && imbalance(&r, 10.0) < 1e-9 * 10.0,
            "{moved:e}"
        );
    }
}
