//! `rodnet study convergence` through the binary: the observed order of the large-deflection
//! cantilever against its analytic reference and against Richardson extrapolation, the CSV and
//! the plot, levels that do not converge, the gridshell variant, and refused input.

mod support;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use rodnet::study::report::CSV_COLUMNS;

fn rodnet() -> Command {
    Command::new(env!("CARGO_BIN_EXE_rodnet"))
}

fn tmpdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rodnet-study-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

const CANTILEVER: &str = "networks/cantilever_elastica.ron";

fn study(args: &[&str], csv: &Path) -> Output {
    rodnet()
        .args(["study", "convergence"])
        .args(args)
        .arg("--csv")
        .arg(csv)
        .arg("--quiet")
        .output()
        .unwrap()
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

/// The CSV as one map from column name to cell per row, after checking the header.
fn rows(csv: &Path) -> Vec<std::collections::HashMap<String, String>> {
    let t = std::fs::read_to_string(csv).unwrap();
    let mut lines = t.lines();
    let head: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(head, CSV_COLUMNS);
    lines
        .map(|l| {
            let cells: Vec<&str> = l.split(',').collect();
            assert_eq!(cells.len(), head.len(), "{l}");
            head.iter()
                .zip(cells)
                .map(|(h, c)| (h.to_string(), c.to_string()))
                .collect()
        })
        .collect()
}

fn num(row: &std::collections::HashMap<String, String>, key: &str) -> f64 {
    row[key]
        .parse()
        .unwrap_or_else(|_| panic!("{key} = {:?}", row[key]))
}

/// The number after "observed order: " on stdout.
fn observed_order(stdout: &str) -> f64 {
    let line = stdout
        .lines()
        .find(|l| l.starts_with("observed order: "))
        .unwrap_or_else(|| panic!("no observed order in\n{stdout}"));
    line["observed order: ".len()..]
        .split_whitespace()
        .next()
        .unwrap()
        .parse()
        .unwrap_or_else(|_| panic!("{line}"))
}

#[test]
fn cantilever_reference_is_the_elastica() {
    let (scene, _) = rodnet::scene::load(Path::new(CANTILEVER)).unwrap();
    let r = scene.reference.expect("the scene declares its reference");
    let tip = support::cantilever_tip_load(2.0);
    let exact = [1.0 - tip.shortening, -tip.deflection, 0.0];
    for (got, want) in r.position.iter().zip(exact) {
        assert!((got - want).abs() < 1e-15, "{:?}", r.position);
    }
}

#[test]
fn cantilever_converges_at_second_order_against_its_reference() {
    let d = tmpdir("cantilever");
    let (csv, png) = (d.join("c.csv"), d.join("c.png"));
    let out = rodnet()
        .args([
            "study",
            "convergence",
            CANTILEVER,
            "--levels",
            "4",
            "--quiet",
        ])
        .arg("--csv")
        .arg(&csv)
        .arg("--plot")
        .arg(&png)
        .output()
        .unwrap();
    let stdout = text(&out.stdout);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert!(out.stderr.is_empty(), "{}", text(&out.stderr));
    assert!(stdout.contains("against the scene's reference"), "{stdout}");
    let p = observed_order(&stdout);
    assert!((1.8..=2.2).contains(&p), "observed order {p}\n{stdout}");

    let rows = rows(&csv);
    assert_eq!(rows.len(), 4);
    for (k, r) in rows.iter().enumerate() {
        assert_eq!(num(r, "level"), (k + 1) as f64);
        assert_eq!(num(r, "subdivide"), (10 << k) as f64);
        assert_eq!(num(r, "nodes"), ((10 << k) + 1) as f64);
        assert_eq!(r["converged"], "true");
        assert!(num(r, "seconds") > 0.0 && num(r, "iterations") >= 1.0);
        assert!(r["sphere_deviation"].is_empty());
    }
    // Level 1 (10 edges): the tip is off by 0.3 % of L (docs/validation.md); the error falls
    // by about 4 per level.
    let e: Vec<f64> = rows.iter().map(|r| num(r, "reference_error")).collect();
    assert!((1e-3..1e-2).contains(&e[0]), "{e:?}");
    for k in 1..4 {
        let order = num(&rows[k], "order");
        assert!((1.8..=2.2).contains(&order), "level {}: {order}", k + 1);
        assert!(((e[k - 1] / e[k]).log2() - order).abs() < 1e-3);
    }
    let png = std::fs::read(&png).unwrap();
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    assert!(png.len() > 2000, "an empty picture");
}

#[test]
fn richardson_errors_match_the_reference_errors() {
    // The same cantilever without its reference: the error then comes from Richardson
    // extrapolation over levels 1-3, and must agree with the analytic one. The scale is the
    // same (the tip is the only free input vertex), so the errors compare directly.
    let d = tmpdir("richardson");
    let src = std::fs::read_to_string(CANTILEVER).unwrap();
    let bare: String = src
        .lines()
        .filter(|l| !l.trim_start().starts_with("reference:"))
        .map(|l| format!("{l}\n"))
        .collect();
    assert_ne!(bare, src);
    let scene = d.join("bare.ron");
    std::fs::write(&scene, bare).unwrap();
    let (with, without) = (d.join("with.csv"), d.join("without.csv"));
    let out = study(&[CANTILEVER, "--levels", "3"], &with);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let out = study(&[scene.to_str().unwrap(), "--levels", "3"], &without);
    let stdout = text(&out.stdout);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert!(
        stdout.contains("against the Richardson extrapolate"),
        "{stdout}"
    );
    let p = observed_order(&stdout);
    assert!((1.8..=2.2).contains(&p), "Richardson order {p}\n{stdout}");
    let (with, without) = (rows(&with), rows(&without));
    for k in 0..2 {
        assert!(without[k]["reference_error"].is_empty());
        let (exact, estimate) = (
            num(&with[k], "reference_error"),
            num(&without[k], "richardson_error"),
        );
        assert!(
            (estimate / exact - 1.0).abs() < 0.02,
            "level {}: Richardson {estimate:e} vs reference {exact:e}",
            k + 1
        );
    }
}

#[test]
fn levels_that_do_not_converge_are_reported_and_left_out() {
    // One Newton iteration cannot bend the cantilever to PL²/EI = 2.
    let d = tmpdir("nonconv");
    let src = std::fs::read_to_string(CANTILEVER)
        .unwrap()
        .replace("max_iterations: 200", "max_iterations: 1");
    let scene = d.join("one_iteration.ron");
    std::fs::write(&scene, src).unwrap();
    let csv = d.join("n.csv");
    let out = study(&[scene.to_str().unwrap(), "--levels", "3"], &csv);
    let stdout = text(&out.stdout);
    assert_eq!(out.status.code(), Some(1), "{stdout}");
    assert!(text(&out.stderr).contains("did not converge"));
    assert_eq!(stdout.matches("NOT converged").count(), 3, "{stdout}");
    assert!(stdout.contains("observed order: not available"), "{stdout}");
    assert!(
        stdout.contains("Richardson extrapolation not applied"),
        "{stdout}"
    );
    for r in rows(&csv) {
        assert_eq!(r["converged"], "false");
        assert!(r["order"].is_empty() && r["richardson_error"].is_empty());
    }
}

#[test]
fn gridshell_study_reports_the_sphere_deviation_and_its_limit() {
    let d = tmpdir("gridshell");
    let csv = d.join("g.csv");
    let args = [
        "--gridshell",
        "hemisphere",
        "--rods",
        "2",
        "--subdivide",
        "1",
        "--levels",
        "3",
    ];
    let out = study(&args, &csv);
    let stdout = text(&out.stdout);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    assert!(stdout.contains("the sphere radius R"), "{stdout}");
    assert!(stdout.contains("extrapolated to infinitely fine subdivision"));
    let rows = rows(&csv);
    let subdivide: Vec<f64> = rows.iter().map(|r| num(r, "subdivide")).collect();
    assert_eq!(subdivide, [1.0, 2.0, 4.0]);
    for r in &rows {
        assert!(num(r, "sphere_deviation") > 0.0 && num(r, "richardson_error") > 0.0);
    }
    // Halving the edges shrinks the error against the extrapolate.
    assert!(num(&rows[2], "richardson_error") < 0.5 * num(&rows[1], "richardson_error"));
}

#[test]
fn bad_input_is_refused_before_solving_and_writes_nothing() {
    let d = tmpdir("bad");
    let csv = d.join("keep.csv");
    std::fs::write(&csv, "old").unwrap();
    // A too fine level is found before anything is solved (level 1 alone is 300001 nodes).
    let huge = d.join("huge.ron");
    let src = std::fs::read_to_string(CANTILEVER)
        .unwrap()
        .replace("subdivide: 10", "subdivide: 300000");
    std::fs::write(&huge, src).unwrap();
    let huge = huge.to_str().unwrap().to_string();
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (
            vec!["tests/bad_scenes/reference_at_rest.ron"],
            "reference_at_rest.ron:18:52: reference.position: is the rest position",
        ),
        (
            vec!["tests/bad_scenes/unknown_material.ron"],
            "unknown_material.ron:7:",
        ),
        // Found by the builder, not the validator.
        (
            vec!["tests/bad_scenes/joint_points_apart.ron"],
            "joint_points_apart.ron:10:26: joints[0].at: entry 1",
        ),
        (
            vec![&huge, "--levels", "4"],
            "rods[0].subdivide: the scene would have more than 2000000 nodes",
        ),
        (
            vec![CANTILEVER, "--levels", "1"],
            "--levels must be in 2..=",
        ),
        (
            vec!["networks/grid.ron", "--levels", "2"],
            "Richardson extrapolation, which needs three levels",
        ),
        (
            vec!["--gridshell", "hemisphere", "--rods", "0"],
            "--rods must be in 1..=",
        ),
    ];
    for (args, expected) in cases {
        let out = study(&args, &csv);
        let err = text(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(
            err.starts_with("error: ") && err.contains(expected),
            "{args:?}: {err}"
        );
        assert!(!err.contains("panicked"), "{err}");
        // Refused before any level was solved: no table row was printed (speed is not
        // asserted in tests).
        assert!(
            text(&out.stdout).is_empty(),
            "{args:?} solved before refusing"
        );
        assert_eq!(std::fs::read_to_string(&csv).unwrap(), "old", "{args:?}");
    }
    // The level over the node limit is named.
    let out = study(&[&huge, "--levels", "4"], &csv);
    assert!(text(&out.stderr).contains("at level 4 (every subdivide × 8)"));
    // Gridshell options need --gridshell.
    let out = study(&[CANTILEVER, "--rods", "3"], &csv);
    assert_eq!(out.status.code(), Some(2));
    // An output over the input is refused.
    let out = rodnet()
        .args(["study", "convergence", CANTILEVER, "--csv", CANTILEVER])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains("is an input file"));
}

#[test]
fn solve_reports_the_reference_in_the_results() {
    let d = tmpdir("solve");
    let json = d.join("l.json");
    let out = rodnet()
        .args(["solve", "networks/l_frame.ron", "--quiet", "--json"])
        .arg(&json)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0), "{}", text(&out.stderr));
    let r: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
    let reference = &r["reference"];
    assert_eq!(reference["rod"], "b");
    assert_eq!(reference["computed"], r["rods"][1]["points"][20]);
    // The L-frame's tip at N = 20 is 2.3e-5 off in z (docs/validation.md; 5.2e-4 with the plain
    // Voronoi weights); the error is the distance to the reference over its displacement.
    let d: f64 = (0..3)
        .map(|k| {
            reference["computed"][k].as_f64().unwrap() - reference["position"][k].as_f64().unwrap()
        })
        .map(|x| x * x)
        .sum::<f64>()
        .sqrt();
    let error = reference["error"].as_f64().unwrap();
    assert!(
        (error / (d / 1.0846666666666666e-5) - 1.0).abs() < 1e-3,
        "{error}"
    );
    assert!((2.2e-5..2.4e-5).contains(&error), "{error}");
    // Scenes without a reference have no block.
    let out = rodnet()
        .args([
            "solve",
            CANTILEVER.replace("_elastica", "").as_str(),
            "--quiet",
            "--json",
        ])
        .arg(&json)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0));
    let r: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
    assert!(r.get("reference").is_none());
}
