//! The outside contract (docs/contract.md) through the binary: exit codes, results JSON
//! keys, OBJ and CSV outputs, and located errors for bad scenes.

use std::path::PathBuf;
use std::process::Command;

fn rodnet() -> Command {
    Command::new(env!("CARGO_BIN_EXE_rodnet"))
}

fn tmpdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rodnet-cli-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn solve_writes_contract_outputs() {
    let d = tmpdir("solve");
    let (json, obj, csv) = (d.join("r.json"), d.join("r.obj"), d.join("r.csv"));
    let out = rodnet()
        .args(["solve", "networks/cantilever.ron", "--quiet", "--json"])
        .arg(&json)
        .arg("--obj")
        .arg(&obj)
        .arg("--csv")
        .arg(&csv)
        .output()
        .unwrap();
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        out.stderr.is_empty(),
        "quiet run printed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let r: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
    for k in [
        "converged",
        "iterations",
        "load_steps",
        "residual",
        "seconds",
        "energy",
        "rods",
        "joints",
        "reactions",
    ] {
        assert!(r.get(k).is_some(), "missing key {k}");
    }
    for k in ["total", "stretch", "bend", "twist", "joints", "external"] {
        assert!(r["energy"][k].is_number(), "missing energy.{k}");
    }
    assert_eq!(r["converged"], true);
    let rod = &r["rods"][0];
    assert_eq!(rod["name"], "beam");
    assert_eq!(rod["points"].as_array().unwrap().len(), 41);
    assert_eq!(rod["twist"].as_array().unwrap().len(), 40);
    let reaction = &r["reactions"][0];
    assert_eq!(reaction["rod"], "beam");
    assert_eq!(reaction["vertex"], 0);
    // Global equilibrium: the clamp reaction balances the tip load.
    assert!((reaction["force"][1].as_f64().unwrap() - std::f64::consts::FRAC_PI_2).abs() < 1e-8);
    assert!(r.get("target").is_none());
    // OBJ: one object named after the rod, 41 vertices, one polyline through all of them.
    let text = std::fs::read_to_string(&obj).unwrap();
    assert!(text.lines().any(|l| l == "o beam"));
    assert_eq!(text.lines().filter(|l| l.starts_with("v ")).count(), 41);
    let line: Vec<&str> = text.lines().filter(|l| l.starts_with("l ")).collect();
    assert_eq!(line.len(), 1);
    assert_eq!(line[0].split_whitespace().count(), 42);
    let csv = std::fs::read_to_string(&csv).unwrap();
    assert!(csv.starts_with("rod,index,x,y,z,twist,"));
    assert_eq!(csv.lines().count(), 42);
}

fn bad(name: &str, text: &str) -> (i32, String) {
    let d = tmpdir(name);
    let p = d.join(format!("{name}.ron"));
    std::fs::write(&p, text).unwrap();
    let json = d.join("out.json");
    let out = rodnet()
        .arg("solve")
        .arg(&p)
        .arg("--json")
        .arg(&json)
        .output()
        .unwrap();
    assert!(!json.exists(), "{name}: results written for bad input");
    (
        out.status.code().unwrap(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

const GOOD: &str = r#"Scene(
    materials: { "steel": Material(young_modulus: 1e8, poisson_ratio: 0.3, section: Circle(radius: 0.01)) },
    rods: [ Rod(name: "beam", material: "steel", points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0)], subdivide: 4) ],
    supports: [ Support(rod: "beam", vertex: 0, kind: Clamp) ],
    loads: [ Force(rod: "beam", vertex: 1, force: (0.0, -1.0, 0.0)) ],
)"#;

#[test]
fn bad_scenes_exit_2_with_located_messages() {
    let cases: Vec<(&str, String, &str)> = vec![
        ("syntax", GOOD.replace("kind: Clamp)", "kind: Clamp"), ":4:"),
        (
            "unknown_field",
            GOOD.replace("subdivide: 4", "subdivid: 4"),
            ":3:",
        ),
        (
            "unknown_material",
            GOOD.replace("material: \"steel\"", "material: \"stel\""),
            "unknown material \"stel\"",
        ),
        (
            "bad_vertex",
            GOOD.replace("vertex: 1,", "vertex: 5,"),
            "vertex 5 is out of range",
        ),
        (
            "zero_length",
            GOOD.replace("(1.0, 0.0, 0.0)]", "(0.0, 0.0, 0.0)]"),
            "zero-length",
        ),
        (
            "negative_modulus",
            GOOD.replace("young_modulus: 1e8", "young_modulus: -1e8"),
            "young_modulus",
        ),
        (
            "poisson",
            GOOD.replace("poisson_ratio: 0.3", "poisson_ratio: 0.7"),
            "(-1, 0.5]",
        ),
        (
            "unknown_rod",
            GOOD.replace("Support(rod: \"beam\"", "Support(rod: \"bean\""),
            "unknown rod \"bean\"",
        ),
    ];
    for (name, text, needle) in cases {
        let (code, err) = bad(name, &text);
        assert_eq!(code, 2, "{name}: {err}");
        assert!(
            err.contains(needle),
            "{name}: message lacks {needle:?}: {err}"
        );
        assert!(
            err.contains(&format!("{name}.ron")),
            "{name}: message lacks the file: {err}"
        );
        assert!(!err.contains("panicked"), "{name}: {err}");
    }
    let (code, err) = {
        let out = rodnet()
            .args(["solve", "does/not/exist.ron"])
            .output()
            .unwrap();
        (
            out.status.code().unwrap(),
            String::from_utf8_lossy(&out.stderr).into_owned(),
        )
    };
    assert_eq!(code, 2);
    assert!(
        err.contains("does/not/exist.ron") && err.contains("cannot read"),
        "{err}"
    );
}

#[test]
fn nonconvergence_exits_1_and_still_writes_results() {
    let d = tmpdir("noconv");
    let p = d.join("hard.ron");
    let text = GOOD.replace(
        "-1.0, 0.0)) ],",
        "-100.0, 0.0)) ],\n    solver: Solver(max_iterations: 1),",
    );
    assert!(text.contains("max_iterations"));
    std::fs::write(&p, text).unwrap();
    let json = d.join("r.json");
    let out = rodnet()
        .arg("solve")
        .arg(&p)
        .arg("--json")
        .arg(&json)
        .output()
        .unwrap();
    assert_eq!(
        out.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let r: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
    assert_eq!(r["converged"], false);
}

/// Every syntax form the contract shows must parse: bare and explicit optionals, `Some((x, y, z))`
/// for `move_to`, `Some(Sphere(..))` for `target`, and elastic joints with named fields.
#[test]
fn contract_syntax_forms_parse() {
    let src = r#"Scene(
    materials: {
        "steel": Material(young_modulus: 1e8, poisson_ratio: 0.5, density: 0.0, section: Circle(radius: 0.01)),
        "soft": Material(young_modulus: 1e6, shear_modulus: Some(4e5), section: Rectangle(width: 0.02, height: 0.01)),
    },
    rods: [
        Rod(name: "a", material: "steel", points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0)], subdivide: 4, closed: false, normal: None),
        Rod(name: "b", material: "soft", points: [(1.0, 0.0, 0.0), (1.0, 1.0, 0.0)], normal: Some((0.0, 0.0, 1.0))),
    ],
    joints: [Joint(name: "j0", at: [("a", 1), ("b", 0)], kind: Elastic(bending: 1.0, twist: 2.0, scissor: 3.0))],
    supports: [
        Support(rod: "a", vertex: 0, kind: Clamp),
        Support(rod: "b", vertex: 1, kind: Pin, move_to: Some((1.0, 0.9, 0.1))),
    ],
    loads: [Gravity(g: (0.0, 0.0, -9.81)), Torque(rod: "a", vertex: 1, torque: (0.0, 0.0, 0.0))],
    obstacles: [],
    target: Some(Sphere(center: (0, 0, 0), radius: 1.0)),
    solver: Solver(tolerance: 1e-9, max_iterations: 200, load_steps: 1),
)"#;
    let s = rodnet::scene::parse("contract.ron", src).unwrap();
    assert_eq!(s.supports[1].move_to, Some([1.0, 0.9, 0.1]));
    assert!(s.target.is_some());
    let e = s.joints[0].kind.elastic().unwrap();
    assert_eq!(
        (e.bending, e.twist, e.scissor),
        (Some(1.0), Some(2.0), Some(3.0))
    );
    let cyl = src.replace(
        "Elastic(bending: 1.0, twist: 2.0, scissor: 3.0)",
        "Elastic(cylinder: Some(JointCylinder(young_modulus: 1.3e6, diameter: 0.003, height: 0.005)))",
    );
    assert!(rodnet::scene::parse("cyl.ron", &cyl).unwrap().joints[0]
        .kind
        .elastic()
        .unwrap()
        .cylinder
        .is_some());
}

#[test]
fn gridshell_hemisphere_without_output_options_writes_into_the_current_directory() {
    let d = tmpdir("gridshell-cwd");
    let out = rodnet()
        .current_dir(&d)
        .args(["gridshell", "hemisphere", "--rods", "4", "--subdivide", "2"])
        .output()
        .unwrap();
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(stdout.contains("against the sphere"), "{stdout}");
    assert_eq!(
        std::fs::read_to_string(d.join("hemisphere.txt")).unwrap(),
        stdout
    );
    let r: serde_json::Value =
        serde_json::from_slice(&std::fs::read(d.join("hemisphere.json")).unwrap()).unwrap();
    assert_eq!(r["converged"], true);
    assert_eq!(r["rods"].as_array().unwrap().len(), 8);
    let t = &r["target"];
    assert_eq!(t["shape"], "sphere");
    for k in [
        "max_abs_radial_deviation",
        "rms_radial_deviation",
        "apex_height",
        "max_net_distance",
        "rms_net_distance",
    ] {
        assert!(t[k].is_number(), "missing target.{k}");
    }
    assert!(t["apex_height"].as_f64().unwrap() > 0.9);
    assert_eq!(r["gridshell"]["rods_per_family"], 4);
    let obj = std::fs::read_to_string(d.join("hemisphere.obj")).unwrap();
    assert_eq!(obj.lines().filter(|l| l.starts_with("o ")).count(), 8);
    assert_eq!(obj.lines().filter(|l| l.starts_with("l ")).count(), 8);
}

#[test]
fn gridshell_scene_out_alone_writes_only_a_valid_scene() {
    let d = tmpdir("gridshell-scene");
    let out = rodnet()
        .current_dir(&d)
        .args([
            "gridshell",
            "hemisphere",
            "--rods",
            "3",
            "--joint",
            "hinge",
            "--radius",
            "2",
            "--scene-out",
            "s.ron",
        ])
        .output()
        .unwrap();
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let files: Vec<_> = std::fs::read_dir(&d)
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!(files, vec![std::ffi::OsString::from("s.ron")]);
    let (scene, _) = rodnet::scene::load(&d.join("s.ron")).unwrap();
    assert_eq!(scene.rods.len(), 6);
    assert_eq!(scene.supports.len(), 12);
    assert!(scene.supports.iter().all(|s| s.move_to.is_some()));
    assert!(!scene.joints.is_empty());
    assert!(scene
        .joints
        .iter()
        .all(|j| j.kind == rodnet::scene::types::JointKind::Hinge));
    assert_eq!(
        scene.target,
        Some(rodnet::scene::types::Target::Sphere {
            center: [0.0; 3],
            radius: 2.0
        })
    );
}

#[test]
fn gridshell_bad_options_exit_2() {
    for args in [
        vec!["--rods", "0"],
        vec!["--radius", "-1"],
        vec!["--subdivide", "0"],
        vec!["--section", "circle:-0.1"],
        vec!["--section", "square:0.1"],
        vec!["--joint", "elastic"],
        vec!["--start-cap", "0.5"],
    ] {
        let out = rodnet()
            .args([
                "gridshell",
                "hemisphere",
                "--json",
                "/nonexistent/never.json",
            ])
            .args(&args)
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert!(!String::from_utf8_lossy(&out.stderr).is_empty(), "{args:?}");
    }
}
