//! `Spring(stiffness: (kx, ky, kz))` supports against linear mechanics: a cantilever propped by a
//! spring, a bar on an axial spring, a frame floating on springs, and a stiff spring that moves
//! a rod end like a pinned `move_to`.

use std::path::PathBuf;
use std::process::Command;

use rodnet::pipeline::{settings_of, solve_scene};
use rodnet::scene::parse;

const E: f64 = 1e9;
const R: f64 = 0.01;

fn ei() -> f64 {
    E * std::f64::consts::PI * R.powi(4) / 4.0
}

fn ea() -> f64 {
    E * std::f64::consts::PI * R * R
}

fn material() -> String {
    format!(
        "materials: {{\"m\": Material(young_modulus: {E:e}, poisson_ratio: 0.3, density: 0.0, \
         section: Circle(radius: {R}))}},"
    )
}

fn solve(text: &str) -> rodnet::pipeline::Solution {
    let scene = parse("spring.ron", text).unwrap_or_else(|e| panic!("{e}"));
    let s = solve_scene(&scene, &settings_of(&scene)).unwrap();
    assert!(s.results.converged, "{:?}", s.results.solver.message);
    s
}

fn tip(s: &rodnet::pipeline::Solution) -> [f64; 3] {
    *s.results.rods[0].points.last().unwrap()
}

/// A clamped cantilever of length L propped at its tip by a spring k across it, tip load P:
/// δ = P / (k + 3EI/L³); the spring carries kδ, the clamp the rest.
#[test]
fn a_cantilever_propped_by_a_spring() {
    let (l, n) = (1.0f64, 64);
    let k = 3.0 * ei() / l.powi(3);
    let p = 1e-4 * ei() / (l * l);
    let text = format!(
        "Scene({} rods: [Rod(name: \"b\", material: \"m\", points: [(0,0,0), ({l},0,0)], subdivide: {n})],
         supports: [Support(rod: \"b\", vertex: 0, kind: Clamp),
                    Support(rod: \"b\", vertex: 1, kind: Spring(stiffness: (0.0, {k:e}, 0.0)))],
         loads: [Force(rod: \"b\", vertex: 1, force: (0.0, {}, 0.0))])",
        material(),
        -p
    );
    let s = solve(&text);
    let want = -p / (k + 3.0 * ei() / l.powi(3));
    let got = tip(&s)[1];
    println!("tip {got:.9e}, linear theory {want:.9e}");
    assert!((got - want).abs() < 1e-3 * want.abs(), "{got} {want}");
    let spring = s.results.reactions[1].force;
    assert!((spring[1] + k * got).abs() < 1e-9 * p, "{spring:?}");
    let clamp = s.results.reactions[0].force;
    assert!(
        (clamp[1] + spring[1] - p).abs() < 1e-6 * p,
        "{clamp:?} {spring:?}"
    );
    assert!((s.results.energy.supports - 0.5 * k * got * got).abs() < 1e-9 * p * l);
}

/// A bar pinned at one end and held at the other by an axial spring k, pulled by F:
/// u = F / (k + EA/L), exactly (the bar stays straight).
#[test]
fn a_bar_on_an_axial_spring() {
    let (l, k) = (2.0f64, 0.5 * ea() / 2.0);
    let f = 1e-4 * ea();
    let text = format!(
        "Scene({} rods: [Rod(name: \"b\", material: \"m\", points: [(0,0,0), ({l},0,0)], subdivide: 8)],
         supports: [Support(rod: \"b\", vertex: 0, kind: Pin),
                    Support(rod: \"b\", vertex: 1, kind: Spring(stiffness: ({k:e}, 1e9, 1e9)))],
         loads: [Force(rod: \"b\", vertex: 1, force: ({f:e}, 0.0, 0.0))])",
        material()
    );
    let s = solve(&text);
    let u = tip(&s)[0] - l;
    let want = f / (k + ea() / l);
    assert!((u - want).abs() < 1e-6 * want, "{u} {want}");
}

/// A square frame floating on springs at its corners, under its weight: the springs carry the
/// weight, and each sinks by its share over its stiffness (z = −W/(4k), exactly).
#[test]
fn a_frame_floats_on_springs() {
    let k = 1e4;
    let corners = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];
    let rods: Vec<String> = (0..4)
        .map(|i| {
            let (a, b) = (corners[i], corners[(i + 1) % 4]);
            format!(
                "Rod(name: \"r{i}\", material: \"m\", points: [({}, {}, 0), ({}, {}, 0)], subdivide: 10)",
                a.0, a.1, b.0, b.1
            )
        })
        .collect();
    let joints: Vec<String> = (0..4)
        .map(|i| {
            format!(
                "Joint(name: \"c{i}\", at: [(\"r{i}\", 0), (\"r{}\", 1)], kind: Rigid)",
                (i + 3) % 4
            )
        })
        .collect();
    let springs: Vec<String> = (0..4)
        .map(|i| {
            format!("Support(rod: \"r{i}\", vertex: 0, kind: Spring(stiffness: ({k}, {k}, {k})))")
        })
        .collect();
    let text = format!(
        "Scene(materials: {{\"m\": Material(young_modulus: {E:e}, poisson_ratio: 0.3, density: 7850.0, \
         section: Circle(radius: {R}))}}, rods: [{}], joints: [{}], supports: [{}], \
         loads: [Gravity(g: (0.0, 0.0, -9.81))])",
        rods.join(", "),
        joints.join(", "),
        springs.join(", ")
    );
    let s = solve(&text);
    let weight = 7850.0 * std::f64::consts::PI * R * R * 4.0 * 9.81;
    let lift: f64 = s.results.reactions.iter().map(|r| r.force[2]).sum();
    assert!((lift - weight).abs() < 1e-6 * weight, "{lift} {weight}");
    // By symmetry each corner carries a quarter; the corners also move inward as the sides
    // sag, and the horizontal spring forces that follow cancel in pairs.
    for r in &s.results.reactions {
        assert!(
            (r.force[2] - weight / 4.0).abs() < 1e-6 * weight,
            "{:?}",
            r.force
        );
    }
    for k in 0..2 {
        let sum: f64 = s.results.reactions.iter().map(|r| r.force[k]).sum();
        assert!(sum.abs() < 1e-9 * weight, "{sum}");
    }
    let z = s.results.rods[0].points[0][2];
    assert!((z + weight / 4.0 / k).abs() < 1e-6 * weight / k, "{z}");
}

/// A spring far stiffer than the rod, anchored at a `move_to`, moves the rod end as a pinned
/// `move_to` does.
#[test]
fn a_stiff_spring_with_move_to_acts_as_a_moved_pin() {
    let scene = |kind: &str| {
        format!(
            "Scene({} rods: [Rod(name: \"b\", material: \"m\", points: [(0,0,0), (1,0,0)], subdivide: 32)],
             supports: [Support(rod: \"b\", vertex: 0, kind: Clamp),
                        Support(rod: \"b\", vertex: 1, kind: {kind}, move_to: Some((0.8, 0.3, 0.0)))])",
            material()
        )
    };
    let pin = solve(&scene("Pin"));
    let stiff = solve(&scene(&format!(
        "Spring(stiffness: ({k:e}, {k:e}, {k:e}))",
        k = 1e6 * ea()
    )));
    let (a, b) = (tip(&pin), tip(&stiff));
    let gap = (0..3).map(|k| (a[k] - b[k]).abs()).fold(0.0, f64::max);
    assert!(gap < 1e-6, "{a:?} {b:?}");
    let (fa, fb) = (
        pin.results.reactions[1].force,
        stiff.results.reactions[1].force,
    );
    let scale = fa.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    for k in 0..3 {
        assert!((fa[k] - fb[k]).abs() < 1e-4 * scale, "{fa:?} {fb:?}");
    }
}

#[test]
fn bad_springs_are_refused_at_their_field() {
    let d = std::env::temp_dir().join(format!("rodnet-spring-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    for (kind, want) in [
        ("Spring(stiffness: (-1.0, 0.0, 0.0))", "non-negative"),
        ("Spring(stiffness: (0.0, 0.0, 0.0))", "needs a non-zero"),
        ("Spring(rotational: Some((1.0, -2.0, 0.0)))", "non-negative"),
        (
            "Spring(rotational: Some((1.0, 1.0, 1.0)), axes: Some(((1,0,0), (1,1,0), (0,0,1))))",
            "perpendicular",
        ),
        (
            "Spring(stiffness: (1.0, 1.0, 1.0), axes: Some(((1,0,0), (0,0,0), (0,0,1))))",
            "axes[1]",
        ),
        (
            "Spring(stiffness: (1.0, 1.0, 1.0)), rotate_by: Some((0.0, 0.0, 1.0))",
            "rotate_by",
        ),
    ] {
        let text = format!(
            "Scene({}\n rods: [Rod(name: \"b\", material: \"m\", points: [(0,0,0), (1,0,0)])],\n supports: [Support(rod: \"b\", vertex: 0, kind: Clamp),\n  Support(rod: \"b\", vertex: 1, kind: {kind})])",
            material()
        );
        let p: PathBuf = d.join("s.ron");
        std::fs::write(&p, text).unwrap();
        let out = Command::new(env!("CARGO_BIN_EXE_rodnet"))
            .arg("solve")
            .arg(&p)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(
            err.contains(want) && err.contains("supports[1].") && err.contains(":4:"),
            "{err}"
        );
    }
}
