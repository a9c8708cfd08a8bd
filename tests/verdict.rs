//! The convergence verdict (issue 36): a floor known before the solve refuses scenes whose
//! round-off makes a meaningful answer impossible, at the field that causes it; a state whose
//! residual or floor is too large is never called converged; fine rods up to that limit
//! converge to the right answer.

use std::path::PathBuf;
use std::process::Command;

use rodnet::pipeline::{settings_of, solve_scene};
use rodnet::solver::verdict::{meaningful, MEANINGFUL_FLOOR};
use rodnet::solver::NewtonReport;

const CANTILEVER: &str = "networks/cantilever.ron";
/// Bisshopp & Drucker (1945), PL²/EI = 2: tip deflection and shortening over L.
const TIP_V: f64 = 0.49345748;
const TIP_U: f64 = 0.16064172;

fn tmpdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rodnet-verdict-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// `rodnet solve` on `text`: exit code, stderr, and whether the JSON was written.
fn solve_cli(name: &str, text: &str) -> (Option<i32>, String, bool) {
    let d = tmpdir(name);
    let (scene, json) = (d.join("scene.ron"), d.join("r.json"));
    std::fs::write(&scene, text).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_rodnet"))
        .args(["solve", scene.to_str().unwrap(), "--json"])
        .arg(&json)
        .output()
        .unwrap();
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
        json.exists(),
    )
}

/// `rodnet solve` refuses `text` (exit 2, nothing written) at `field`, with a suggested value
/// after `suggests`; returns that value.
fn refused(name: &str, text: &str, field: &str, suggests: &str) -> f64 {
    let (code, stderr, written) = solve_cli(name, text);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(!written);
    assert!(
        stderr.contains(field) && stderr.contains("round-off floor"),
        "{stderr}"
    );
    stderr
        .split(suggests)
        .nth(1)
        .and_then(|s| s.split(' ').next())
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("no suggested value in {stderr}"))
}

/// The value a refusal suggests works: the scene then solves, exit 0.
fn solves(name: &str, text: &str) {
    let (code, stderr, _) = solve_cli(name, text);
    assert_eq!(code, Some(0), "{stderr}");
}

#[test]
fn a_column_too_stiff_for_its_load_is_refused_at_its_modulus() {
    let text = std::fs::read_to_string("networks/euler_column.ron")
        .unwrap()
        .replace("young_modulus: 1e9", "young_modulus: 1e19");
    let field = "materials[\"steel\"].young_modulus";
    let e = refused("stiff", &text, field, "young_modulus ≤ ");
    solves(
        "suggested-modulus",
        &text.replace("young_modulus: 1e19", &format!("young_modulus: {e:e}")),
    );
}

#[test]
fn a_rod_subdivided_past_its_floor_is_refused_at_its_subdivision() {
    let text = std::fs::read_to_string(CANTILEVER).unwrap();
    let fine = text.replace("subdivide: 40", "subdivide: 100000");
    let n = refused("fine", &fine, "rods[0].subdivide", "subdivide ≤ ");
    solves(
        "suggested-subdivision",
        &text.replace("subdivide: 40", &format!("subdivide: {n}")),
    );
}

/// A translational and a rotational spring of 1e60 at an elastic joint (rotations are rounded
/// to ε rad whatever their angle, so the second is seen too).
#[test]
fn a_joint_spring_beyond_doubles_is_refused_at_the_joint() {
    let scene = |kind: &str| {
        format!(
            r#"Scene(
    materials: {{ "m": Material(young_modulus: 1e9, poisson_ratio: 0.3, section: Circle(radius: 0.01)) }},
    rods: [
        Rod(name: "a", material: "m", points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0)], subdivide: 8),
        Rod(name: "b", material: "m", points: [(1.0, 0.0, 0.0), (1.0, 1.0, 0.0)], subdivide: 8),
    ],
    joints: [ Joint(name: "knee", at: [("a", 1), ("b", 0)], kind: {kind}) ],
    supports: [ Support(rod: "a", vertex: 0, kind: Clamp) ],
    loads: [ Force(rod: "b", vertex: 1, force: (0.0, 0.0, -10.0)) ],
)"#
        )
    };
    let translation = "Elastic(bending: 1e3, twist: 1e3, scissor: 1e3, translation: 1e60)";
    let k = refused(
        "spring",
        &scene(translation),
        "joints[0].kind",
        "stiffness ≤ ",
    );
    solves(
        "suggested-spring",
        &scene(&translation.replace("1e60", &format!("{k:e}"))),
    );
    let rotation = "Elastic(bending: 1e60, twist: 1e60, scissor: 1e60)";
    let c = refused("turn", &scene(rotation), "joints[0].kind", "stiffness ≤ ");
    solves(
        "suggested-turn",
        &scene(&rotation.replace("1e60", &format!("{c:e}"))),
    );
}

/// 10 to 10⁴ edges: converged, exit 0 by the verdict, the tip within DER's O(1/N²) error of
/// the elastica (plus the rod's extension P/EA, which the inextensible elastica leaves out).
#[test]
fn a_cantilever_converges_from_ten_to_ten_thousand_edges() {
    let base = std::fs::read_to_string(CANTILEVER).unwrap();
    for n in [10, 100, 1000, 10000] {
        let text = base.replace("subdivide: 40", &format!("subdivide: {n}"));
        let s = rodnet::scene::parse(CANTILEVER, &text).unwrap();
        let sol = solve_scene(&s, &settings_of(&s)).unwrap();
        assert!(sol.results.converged, "N = {n}: {:?}", sol.report.message);
        assert!(sol.report.residual_floor <= MEANINGFUL_FLOOR);
        let tip = *sol.results.rods[0].points.last().unwrap();
        let err = ((1.0 - tip[0]) - TIP_U).abs().max((-tip[1] - TIP_V).abs());
        assert!(
            err < 0.33 / (n * n) as f64 + 3e-5,
            "N = {n}: tip error {err:.2e}"
        );
    }
}

#[test]
fn no_state_beyond_the_meaningful_residual_is_converged() {
    let report = |residual: f64, floor: f64| NewtonReport {
        converged: true,
        residual,
        residual_floor: floor,
        tolerance: 1e-9,
        ..Default::default()
    };
    let mut r = report(1e-12, 1e-10);
    meaningful(&mut r);
    assert!(r.converged && r.message.is_none());
    // Stalled at a floor that forces still resolve to a few percent: converged to the floor.
    let mut r = report(2e-3, 5e-3);
    meaningful(&mut r);
    assert!(r.converged && r.message.is_none());
    // A floor above the bound: forces are noise at that level.
    let mut r = report(0.2, 0.5);
    meaningful(&mut r);
    assert!(!r.converged && r.message.unwrap().contains("round-off floor"));
    // A loose tolerance asked for is not an answer above the bound either.
    let mut r = report(5e-3, 1e-8);
    meaningful(&mut r);
    assert!(!r.converged && r.message.unwrap().contains("5.000e-3"));
}

/// The L-frame under its check load (P = 1e-5 EI/L²) with a tolerance far below its floor
/// (5.7e-5): converged to the floor, and every command that starts from a solve takes it.
#[test]
fn commands_start_from_a_state_converged_to_the_floor() {
    let text = std::fs::read_to_string("networks/l_frame.ron").unwrap();
    let text = format!(
        "{},\n    solver: Solver(tolerance: 1e-12),\n)\n",
        text.trim_end()
            .trim_end_matches(')')
            .trim_end()
            .trim_end_matches(',')
    );
    let d = tmpdir("lframe");
    let scene = d.join("scene.ron");
    std::fs::write(&scene, &text).unwrap();
    let run = |args: &[&str]| {
        let out = Command::new(env!("CARGO_BIN_EXE_rodnet"))
            .args(args)
            .arg("--quiet")
            .output()
            .unwrap();
        (
            out.status.code(),
            String::from_utf8_lossy(&out.stderr).into_owned(),
        )
    };
    let s = scene.to_str().unwrap();
    let json = d.join("r.json");
    let (code, stderr) = run(&["solve", s, "--json", json.to_str().unwrap()]);
    assert_eq!(code, Some(0), "{stderr}");
    assert!(stderr.contains("tolerance 1.0e-12"), "{stderr}");
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_eq!(v["converged"], true);
    assert_eq!(v["stopped_at_floor"], true);
    // The deflection is the reference's (the scene's `reference`, from the analytic L-frame).
    let err = v["reference"]["error"].as_f64().unwrap();
    assert!(err < 1e-3, "reference error {err:e}");
    let states = d.join("states");
    for args in [
        vec!["states", s, "--out-dir", states.to_str().unwrap()],
        vec!["buckle", s],
        vec!["solve", s, "--initial", json.to_str().unwrap()],
        vec!["indent", s, "--at", "b:1", "--depth", "1e-4"],
    ] {
        let (code, stderr) = run(&args);
        assert_eq!(code, Some(0), "{args:?}: {stderr}");
    }
}
