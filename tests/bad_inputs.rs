//! Bad input through the binary: every case must exit with code 2 and one located message, never
//! panic, and write nothing. The scene corpus is `tests/bad_scenes/*.ron`, listed with the
//! expected line and message fragment in `tests/bad_scenes/expected.txt`.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn rodnet() -> Command {
    Command::new(env!("CARGO_BIN_EXE_rodnet"))
}

fn tmpdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rodnet-bad-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Exit code 2, exactly one `error:` line on stderr, no panic; returns the message.
fn assert_bad(what: &str, o: &Output) -> String {
    let err = stderr(o);
    assert_eq!(o.status.code(), Some(2), "{what}: {err}");
    assert!(!err.contains("panicked"), "{what}: {err}");
    let lines: Vec<&str> = err.lines().filter(|l| !l.trim().is_empty()).collect();
    assert_eq!(lines.len(), 1, "{what}: expected one message, got {err}");
    assert!(lines[0].starts_with("error: "), "{what}: {err}");
    lines[0].to_string()
}

struct Case {
    name: String,
    line: usize,
    fragment: String,
}

fn corpus() -> Vec<Case> {
    let text = std::fs::read_to_string("tests/bad_scenes/expected.txt").unwrap();
    text.lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(|l| {
            let mut parts = l.splitn(3, " | ");
            let name = parts.next().unwrap().trim().to_string();
            let line = parts.next().unwrap().trim().parse().unwrap();
            let fragment = parts.next().unwrap().to_string();
            Case {
                name,
                line,
                fragment,
            }
        })
        .collect()
}

#[test]
fn bad_scene_corpus_gives_located_messages() {
    let cases = corpus();
    assert!(cases.len() >= 25, "the corpus has {} cases", cases.len());
    // Every file is listed and every listed case has its file.
    let mut files: Vec<String> = std::fs::read_dir("tests/bad_scenes")
        .unwrap()
        .filter_map(|e| {
            let p = e.unwrap().path();
            (p.extension()? == "ron").then(|| p.file_stem().unwrap().to_string_lossy().into())
        })
        .collect();
    files.sort();
    let mut listed: Vec<String> = cases.iter().map(|c| c.name.clone()).collect();
    listed.sort();
    assert_eq!(files, listed, "tests/bad_scenes and expected.txt disagree");

    let d = tmpdir("corpus");
    for c in &cases {
        let path = format!("tests/bad_scenes/{}.ron", c.name);
        let json = d.join(format!("{}.json", c.name));
        let out = rodnet()
            .args(["solve", &path, "--quiet", "--json"])
            .arg(&json)
            .output()
            .unwrap();
        let msg = assert_bad(&c.name, &out);
        let at = format!("error: {path}:{}:", c.line);
        assert!(
            msg.starts_with(&at),
            "{}: expected {at}…, got {msg}",
            c.name
        );
        assert!(
            msg.contains(&c.fragment),
            "{}: message lacks {:?}: {msg}",
            c.name,
            c.fragment
        );
        assert!(!json.exists(), "{}: results written for bad input", c.name);
    }
}

#[test]
fn unreadable_paths_are_named() {
    let d = tmpdir("paths");
    let missing = d.join("missing.ron");
    let out = rodnet().arg("solve").arg(&missing).output().unwrap();
    let msg = assert_bad("missing", &out);
    assert!(
        msg.contains("missing.ron") && msg.contains("cannot read"),
        "{msg}"
    );

    let out = rodnet().arg("solve").arg(&d).output().unwrap();
    let msg = assert_bad("directory", &out);
    assert!(msg.contains("is a directory"), "{msg}");

    // Refused from its size alone, before reading: the file is sparse.
    let huge = d.join("huge.ron");
    let f = std::fs::File::create(&huge).unwrap();
    f.set_len(rodnet::scene::validate::MAX_SCENE_BYTES + 1)
        .unwrap();
    let out = rodnet().arg("solve").arg(&huge).output().unwrap();
    let msg = assert_bad("huge", &out);
    assert!(msg.contains("above the limit"), "{msg}");
}

const GOOD: &str = "networks/cantilever.ron";

#[test]
fn bad_output_paths_are_refused_before_solving() {
    let d = tmpdir("outputs");
    let cases: Vec<(Vec<String>, &str)> = vec![
        (
            vec![
                "--json".into(),
                d.join("nodir/r.json").display().to_string(),
            ],
            "does not exist",
        ),
        (
            vec!["--json".into(), d.display().to_string()],
            "is a directory",
        ),
        (vec!["--json".into(), GOOD.into()], "is an input file"),
        (
            vec![
                "--json".into(),
                d.join("same").display().to_string(),
                "--obj".into(),
                d.join("same").display().to_string(),
            ],
            "same file as --json",
        ),
    ];
    for (args, needle) in cases {
        let out = rodnet()
            .args(["solve", GOOD, "--quiet"])
            .args(&args)
            .output()
            .unwrap();
        let msg = assert_bad(needle, &out);
        assert!(msg.contains(needle), "{msg}");
        assert!(out.stdout.is_empty(), "solved anyway: {args:?}");
    }
    assert!(!d.join("same").exists());
    let before = std::fs::read(GOOD).unwrap();
    assert_eq!(before, std::fs::read(GOOD).unwrap());
}

#[test]
fn usage_errors_exit_2() {
    for args in [
        vec!["solve"],
        vec!["solve", GOOD, "--network", "networks/vault.obj"],
        vec!["solve", GOOD, "--radius", "0.1"],
        vec!["frobnicate"],
    ] {
        let out = rodnet().args(&args).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}: {}", stderr(&out));
        assert!(!stderr(&out).contains("panicked"));
    }
}

#[test]
fn self_equilibrated_loads_on_a_free_rod_are_accepted() {
    // The check for unsupported loads looks at the net force and moment, not at supports alone.
    let src = r#"Scene(
    materials: { "m": Material(young_modulus: 1e7, poisson_ratio: 0.3, section: Circle(radius: 0.01)) },
    rods: [ Rod(name: "a", material: "m", points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0)], subdivide: 4) ],
    loads: [ Force(rod: "a", vertex: 0, force: (-1.0, 0.0, 0.0)), Force(rod: "a", vertex: 1, force: (1.0, 0.0, 0.0)) ],
)"#;
    assert!(rodnet::scene::parse("free.ron", src).is_ok());
    let pulled_sideways = src.replace("(1.0, 0.0, 0.0)) ]", "(1.0, 0.5, 0.0)) ]");
    let e = rodnet::scene::parse("free.ron", &pulled_sideways).unwrap_err();
    assert!(e.message.contains("has a support"), "{e}");
    assert_eq!(e.line, Some(4));
}

#[test]
fn a_diverging_solve_names_the_load_step_and_residual() {
    let d = tmpdir("diverge");
    let p = d.join("hard.ron");
    // One Newton iteration cannot carry a cantilever to a tip load of 100 EI/L².
    let text = std::fs::read_to_string(GOOD)
        .unwrap()
        .replace("-1.5707963267948966", "-78.5")
        .replace(
            "max_iterations: 200, load_steps: 1",
            "max_iterations: 1, load_steps: 3",
        );
    assert!(text.contains("-78.5") && text.contains("load_steps: 3"));
    std::fs::write(&p, text).unwrap();
    let json = d.join("r.json");
    let out = rodnet()
        .arg("solve")
        .arg(&p)
        .arg("--json")
        .arg(&json)
        .output()
        .unwrap();
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    assert!(
        err.contains("stopped at load step 1/3")
            && err.contains("largest relative residual in load step 1/3"),
        "{err}"
    );
    let r: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
    assert_eq!(r["converged"], false);
}

fn write(d: &Path, name: &str, text: &str) -> PathBuf {
    let p = d.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

#[test]
fn bad_networks_give_located_messages() {
    let d = tmpdir("networks");
    let material = [
        "--young-modulus",
        "1e9",
        "--poisson-ratio",
        "0.3",
        "--radius",
        "0.01",
    ];
    let good = "o a\nv 0 0 0\nv 1 0 0\nv 2 0 1\nl 1 2 3\n";
    let cases: Vec<(&str, String, Vec<&str>, &str)> = vec![
        (
            "short_vertex",
            good.replace("v 1 0 0", "v 1 0"),
            vec![],
            ":3: `v` needs x, y and z",
        ),
        (
            "index_out_of_range",
            good.replace("l 1 2 3", "l 1 2 4"),
            vec![],
            ":5: vertex index 4 is out of range",
        ),
        (
            "zero_length",
            good.replace("v 2 0 1", "v 1 0 0"),
            vec![],
            ":5: points 2 and 3 of this polyline",
        ),
        (
            "no_polylines",
            good.replace("l 1 2 3", "f 1 2 3"),
            vec![],
            "no `l` polylines",
        ),
        (
            "fold_back",
            good.replace("v 2 0 1", "v 0.5 0 0"),
            vec![],
            ":5: polyline (rod \"a\"): points: the rod folds back",
        ),
        (
            "nothing_below",
            good.to_string(),
            vec!["--pin-below", "-1"],
            "no polyline vertex lies at or below z = -1",
        ),
        (
            "unknown_group",
            good.to_string(),
            vec!["--pin-group", "feet"],
            "no `o` or `g` of that name",
        ),
        (
            "bad_modulus",
            good.to_string(),
            vec!["--shear-modulus", "-3"],
            "--shear-modulus: give exactly one",
        ),
        (
            "unsupported_weight",
            good.to_string(),
            vec!["--density", "1000", "--gravity", "9.81"],
            "is loaded but neither it nor any rod joined to it has a support",
        ),
        (
            "gravity_without_density",
            good.to_string(),
            vec!["--gravity", "9.81", "--pin-below", "0"],
            "--gravity needs --density",
        ),
        (
            "hinge_in_line",
            "o a\nv 0 0 0\nv 1 0 0\nl 1 2\no b\nv 1 0 0\nv 2 0 0\nl 3 4\n".into(),
            vec!["--joint", "hinge", "--pin-below", "0"],
            ":3: joint \"v2\" at this vertex: normal: hinge axis undefined",
        ),
    ];
    for (name, text, extra, needle) in cases {
        let p = write(&d, &format!("{name}.obj"), &text);
        let json = d.join(format!("{name}.json"));
        let out = rodnet()
            .args(["solve", "--quiet", "--network"])
            .arg(&p)
            .args(material)
            .args(&extra)
            .arg("--json")
            .arg(&json)
            .output()
            .unwrap();
        let msg = assert_bad(name, &out);
        assert!(
            msg.contains(needle),
            "{name}: message lacks {needle:?}: {msg}"
        );
        if needle.starts_with(':') {
            assert!(
                msg.contains(&format!("{name}.obj{}", &needle[..3])),
                "{name}: not located: {msg}"
            );
        }
        assert!(!json.exists(), "{name}: results written for bad input");
    }
}

#[test]
fn gravity_on_no_mass_is_a_located_warning() {
    // Every material at density 0 (the default): the weight is nothing. Not an error (the
    // contract's example has `density: 0.0`), but a warning naming the load and the materials,
    // on stderr (even with --quiet) and in the results JSON.
    let d = tmpdir("weightless");
    let scene = r#"Scene(
    materials: {
        "steel": Material(young_modulus: 2e11, poisson_ratio: 0.3, section: Circle(radius: 0.01)),
        "wire": Material(young_modulus: 2e11, poisson_ratio: 0.3, density: 0.0, section: Circle(radius: 0.001)),
    },
    rods: [
        Rod(name: "a", material: "steel", points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0)], subdivide: 4),
        Rod(name: "b", material: "wire", points: [(1.0, 0.0, 0.0), (1.0, 1.0, 0.0)], subdivide: 4),
    ],
    joints: [Joint(name: "j", at: [("a", 1), ("b", 0)], kind: Rigid)],
    supports: [Support(rod: "a", vertex: 0, kind: Clamp)],
    loads: [
        Force(rod: "b", vertex: 1, force: (0.0, 0.0, -1.0)),
        Gravity(g: (0.0, 0.0, -9.81)),
    ],
)"#;
    let p = write(&d, "weightless.ron", scene);
    let json = d.join("r.json");
    let out = rodnet()
        .args(["solve", "--quiet"])
        .arg(&p)
        .arg("--json")
        .arg(&json)
        .output()
        .unwrap();
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(0), "{err}");
    let at = format!("warning: {}:14:", p.display());
    assert!(err.starts_with(&at), "{err}");
    assert!(
        err.contains("loads[1].g: Gravity acts on no mass")
            && err.contains("materials \"steel\", \"wire\""),
        "{err}"
    );
    assert_eq!(err.lines().count(), 1, "{err}");
    let r: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
    let w = r["warnings"][0].as_str().unwrap();
    assert!(w.starts_with("loads[1].g: Gravity acts on no mass"), "{w}");
    // One material with mass is enough: rods of density 0 beside it are weightless on purpose.
    let heavy = scene.replace(
        "poisson_ratio: 0.3, section: Circle(radius: 0.01)",
        "poisson_ratio: 0.3, density: 7850.0, section: Circle(radius: 0.01)",
    );
    let p = write(&d, "heavy.ron", &heavy);
    let out = rodnet()
        .args(["solve", "--quiet"])
        .arg(&p)
        .arg("--json")
        .arg(&json)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(out.stderr.is_empty(), "{}", stderr(&out));
    let r: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
    assert!(r.get("warnings").is_none());
}
