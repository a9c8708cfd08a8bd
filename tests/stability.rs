//! Eigen-analysis and linear buckling (issue 14): Euler's four columns, Greenhill's twisted
//! shaft, eigenvalue signs at stable and unstable states, against analytic values.

use std::f64::consts::PI;

use rodnet::network::stability::{analyse, buckling};

const E: f64 = 1e9;
const R: f64 = 0.001;
const L: f64 = 1.0;

fn ei() -> f64 {
    E * PI * R.powi(4) / 4.0
}

/// A straight column along z from 0 to L with `n` edges: bottom and top supports, and either a
/// compressive unit tip force (`force`) or the top support moved down by `shorten` (m).
fn column(n: usize, bottom: &str, top: &str, tip: &str) -> String {
    format!(
        r#"Scene(
    materials: {{ "m": Material(young_modulus: {E}, poisson_ratio: 0.3, section: Circle(radius: {R})) }},
    rods: [ Rod(name: "c", material: "m", points: [(0.0, 0.0, 0.0), (0.0, 0.0, {L})], subdivide: {n}) ],
    supports: [ Support(rod: "c", vertex: 0, kind: {bottom}) {top} ],
    loads: [ {tip} ],
)"#
    )
}

fn factors(text: &str, k: usize) -> Vec<f64> {
    let scene = rodnet::scene::parse("column.ron", text).unwrap();
    let mut net = rodnet::network::build(&scene).unwrap();
    buckling(&mut net, k).unwrap().factors
}

/// The compressive axial force of a pinned or clamped top moved down by `d` (uniform strain).
fn axial(d: f64) -> f64 {
    E * PI * R * R * d / L
}

fn euler(n: usize, case: &str) -> f64 {
    let d = 1e-6;
    let moved = format!(
        ", Support(rod: \"c\", vertex: 1, kind: {{}}, move_to: Some((0.0, 0.0, {})))",
        L - d
    );
    match case {
        "cantilever" => {
            let t = column(
                n,
                "Clamp",
                "",
                r#"Force(rod: "c", vertex: 1, force: (0.0, 0.0, -1.0))"#,
            );
            factors(&t, 1)[0]
        }
        "pinned-pinned" | "clamped-clamped" | "clamped-pinned" => {
            let (b, t) = match case {
                "pinned-pinned" => ("Pin", "Pin"),
                "clamped-clamped" => ("Clamp", "Clamp"),
                _ => ("Clamp", "Pin"),
            };
            let text = column(n, b, &moved.replace("{}", t), "");
            factors(&text, 1)[0] * axial(d)
        }
        _ => unreachable!(),
    }
}

#[test]
fn euler_columns_converge_to_their_critical_loads() {
    let cases = [
        ("cantilever", PI * PI / 4.0),
        ("pinned-pinned", PI * PI),
        ("clamped-clamped", 4.0 * PI * PI),
        ("clamped-pinned", 20.190729),
    ];
    for (case, coef) in cases {
        let exact = coef * ei() / (L * L);
        let errs: Vec<f64> = [16, 32, 64]
            .iter()
            .map(|&n| (euler(n, case) - exact) / exact)
            .collect();
        eprintln!("{case}: relative errors {errs:?}");
        assert!(errs[2].abs() < 2e-3, "{case}: {errs:?}");
        // Second order in the edge length: halving it quarters the error.
        for w in errs.windows(2) {
            let ratio = w[0] / w[1];
            assert!((3.5..4.5).contains(&ratio), "{case}: {errs:?}");
        }
    }
}

/// Greenhill's shaft: clamped at both ends, the top clamp turned about the axis; the critical
/// torque T_c = GJ φ_c / L satisfies T_c L / EI = 8.98682 (2.86π).
#[test]
fn greenhill_shaft_buckles_at_its_critical_torque() {
    let phi = 1e-3;
    let gj = E / (2.0 * 1.3) * PI * R.powi(4) / 2.0;
    let exact = 8.98682;
    let errs: Vec<f64> = [16, 32, 64]
        .iter()
        .map(|&n| {
            let top = format!(
                ", Support(rod: \"c\", vertex: 1, kind: Clamp, rotate_by: Some((0.0, 0.0, {phi})))"
            );
            let lam = factors(&column(n, "Clamp", &top, ""), 1)[0];
            (lam * gj * phi / L * L / ei() - exact) / exact
        })
        .collect();
    eprintln!("Greenhill: relative errors {errs:?}");
    assert!(errs[2].abs() < 2e-3, "{errs:?}");
    for w in errs.windows(2) {
        assert!((3.5..4.5).contains(&(w[0] / w[1])), "{errs:?}");
    }
}

/// A pinned–pinned column held straight under a compressive force P: its lowest bending
/// eigenvalue falls as 1 − P/P_E (EIk⁴ − Pk², k = π/L, the same sine mode), doubly (both
/// lateral directions); past P_E the straight state has two negative eigenvalues and is
/// called unstable.
#[test]
fn a_compressed_column_softens_and_turns_unstable_at_euler() {
    let n = 32;
    let p_e = PI * PI * ei() / (L * L);
    // The DER column's own critical shortening (from linear buckling), so that P/P_E is exact.
    let probe = 1e-6;
    let moved = |d: f64| {
        format!(
            ", Support(rod: \"c\", vertex: 1, kind: Pin, move_to: Some((0.0, 0.0, {})))",
            L - d
        )
    };
    let d_crit = factors(&column(n, "Pin", &moved(probe), ""), 1)[0] * probe;
    let lowest = |ratio: f64| {
        let d = ratio * d_crit;
        let scene = rodnet::scene::parse("c.ron", &column(n, "Pin", &moved(d), "")).unwrap();
        let mut net = rodnet::network::build(&scene).unwrap();
        net.model.set_load(1.0);
        // The straight, uniformly compressed state: an exact equilibrium.
        for k in 0..=n {
            let z = k as f64 / n as f64 * (L - d);
            net.model
                .layout
                .set_position(&mut net.model.state.q, k, [0.0, 0.0, z]);
        }
        net.model.commit();
        analyse(&mut net, 4).unwrap()
    };
    let s0 = lowest(0.0);
    assert!(s0.stable && s0.negative == 0, "{s0:?}");
    // The two lateral sine modes are the lowest pair.
    let (a, b) = (s0.eigenvalues[0], s0.eigenvalues[1]);
    assert!((a - b).abs() < 1e-8 * a, "{:?}", s0.eigenvalues);
    for ratio in [0.5, 0.9] {
        let s = lowest(ratio);
        let got = s.eigenvalues[0] / a;
        assert!(s.stable, "{ratio}: {s:?}");
        // Beyond the linear theory only terms of the order of the axial strain d/L.
        let strain = ratio * d_crit / L;
        assert!((got - (1.0 - ratio)).abs() < 4.0 * strain, "{ratio}: {got}");
    }
    let s = lowest(1.5);
    assert!(!s.stable && s.negative == 2, "{:?}", s.eigenvalues);
    assert!(
        (s.eigenvalues[0] / a + 0.5).abs() < 4.0 * 1.5 * d_crit / L,
        "{:?}",
        s.eigenvalues
    );
    // The DER column's critical force, from its critical shortening, against Euler's.
    let p_crit = E * PI * R * R * d_crit / L;
    assert!((p_crit / p_e - 1.0).abs() < 1e-3, "{p_crit} vs {p_e}");
}

fn rodnet() -> std::process::Command {
    std::process::Command::new(env!("CARGO_BIN_EXE_rodnet"))
}

fn tmpdir(name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("rodnet-stability-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Runs `cmd`, which must exit 0, then reads the results JSON it wrote to `json`.
fn run_json(cmd: &mut std::process::Command, json: &std::path::Path) -> serde_json::Value {
    let out = cmd.output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{err}");
    serde_json::from_str(&std::fs::read_to_string(json).unwrap()).unwrap()
}

/// A JSON array of numbers.
fn floats(v: &serde_json::Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

fn load_obj(path: &std::path::Path) -> Vec<tobj::Model> {
    let opts = tobj::LoadOptions {
        single_index: false,
        triangulate: false,
        ignore_points: false,
        ignore_lines: false,
    };
    let text = std::fs::read_to_string(path).unwrap();
    tobj::load_obj_buf(&mut text.as_bytes(), &opts, |_| {
        Err(tobj::LoadError::OpenFileFailed)
    })
    .expect("tobj loads the modes")
    .0
}

/// `rodnet solve --modes K --modes-obj F` and `rodnet buckle` on a cantilever column loaded at
/// half its Euler load: stable, K positive eigenvalues in pairs, K OBJ objects; the buckle
/// command's first factor is Euler's within the discretization error.
#[test]
fn modes_and_buckle_commands_report_and_draw_the_modes() {
    let d = tmpdir("cli");
    let n = 32;
    let p_cr = PI * PI * ei() / (4.0 * L * L);
    let tip = format!(
        r#"Force(rod: "c", vertex: 1, force: (0.0, 0.0, {}))"#,
        -0.5 * p_cr
    );
    let scene = d.join("col.ron");
    std::fs::write(&scene, column(n, "Clamp", "", &tip)).unwrap();
    let (json, obj) = (d.join("s.json"), d.join("m.obj"));
    let v = run_json(
        rodnet()
            .args(["solve", scene.to_str().unwrap(), "--modes", "4", "--quiet"])
            .args(["--json", json.to_str().unwrap()])
            .args(["--modes-obj", obj.to_str().unwrap()]),
        &json,
    );
    let st = &v["stability"];
    assert_eq!(st["stable"], true, "{st}");
    assert_eq!(st["negative"], 0);
    assert_eq!(st["unit"], "N/m");
    assert_eq!(st["converged"], true);
    let ev = floats(&st["eigenvalues"]);
    assert_eq!(ev.len(), 4);
    assert!(ev[0] > 0.0 && ev.windows(2).all(|w| w[0] <= w[1]), "{ev:?}");
    assert!((ev[0] - ev[1]).abs() < 1e-6 * ev[0], "lateral pair: {ev:?}");
    let models = load_obj(&obj);
    assert_eq!(models.len(), 4);
    assert_eq!(models[0].name, "mode_1");
    assert_eq!(models[0].mesh.positions.len(), 3 * (n + 1));

    let bj = d.join("b.json");
    let b = run_json(
        rodnet()
            .args(["buckle", scene.to_str().unwrap(), "--modes", "2"])
            .args(["--json", bj.to_str().unwrap()]),
        &bj,
    );
    let f = floats(&b["critical_load_factors"]);
    // The load is half Euler's: the factor is 2, within the n = 32 error (2e-4).
    assert!((f[0] - 2.0).abs() < 1e-3, "{f:?}");
    assert_eq!(b["modes"].as_array().unwrap().len(), 2);
    assert_eq!(b["converged"], true);
    // Checked along the nonlinear path: the straight column's tangent stiffness loses its
    // lowest eigenvalue at the same factor.
    let on_path = b["path"]["critical_load_factor"]
        .as_f64()
        .expect("a crossing");
    assert!(
        (on_path - f[0]).abs() < 1e-4 * f[0],
        "{on_path} vs {}",
        f[0]
    );
    let disp = &b["modes"][0]["rods"][0]["displacement"];
    assert_eq!(disp.as_array().unwrap().len(), n + 1);
}

/// Linear buckling needs loads, and a stable start.
#[test]
fn buckle_refuses_a_scene_without_loads() {
    let d = tmpdir("noload");
    let scene = d.join("c.ron");
    std::fs::write(&scene, column(8, "Clamp", "", "")).unwrap();
    let out = rodnet()
        .args(["buckle", scene.to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("no loads"), "{err}");
    let out = rodnet()
        .args(["solve", scene.to_str().unwrap(), "--modes-obj", "x.obj"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2), "--modes-obj needs --modes");
}

/// A cantilever under a transverse tip load does not buckle: the linear analysis about the rest
/// state finds spurious factors (the rotation of its stiff stretch terms along the bending
/// response), and the check along the nonlinear path says there is no crossing up to the load.
#[test]
fn buckle_path_check_rejects_the_spurious_factor_of_a_bent_cantilever() {
    let out = rodnet()
        .args(["buckle", "networks/cantilever.ron", "--modes", "1"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0));
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("no buckling there"), "{text}");
}

/// `rodnet gridshell hemisphere --modes K`: the form-found dome's lowest eigenvalues, stable.
#[test]
fn the_gridshell_job_reports_its_modes() {
    let d = tmpdir("gridshell");
    let json = d.join("h.json");
    let v = run_json(
        rodnet()
            .args([
                "gridshell",
                "hemisphere",
                "--rods",
                "6",
                "--modes",
                "3",
                "--quiet",
            ])
            .arg("--json")
            .arg(&json),
        &json,
    );
    let st = &v["stability"];
    assert_eq!(st["stable"], true, "{st}");
    assert_eq!(st["eigenvalues"].as_array().unwrap().len(), 3);
    assert!(st["eigenvalues"][0].as_f64().unwrap() > 0.0);
}
