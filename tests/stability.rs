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

// ---------------------------------------------------------------------------------------------
// Michell's twisted ring
// ---------------------------------------------------------------------------------------------

mod support;

use rodnet::network::initial::RodState;

/// `networks/extreme/michell.ron` (GJ/EI = 5) with radius `r`, `n` edges and total twist Θ:
/// the far clamp turned by π about (0, sin Θ/2, cos Θ/2), the near clamp's final frame twisted
/// by Θ about their common tangent.
fn michell_ring(r: f64, n: usize, theta: f64) -> rodnet::scene::Scene {
    use rodnet::scene::types::Section;
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/networks/extreme/michell.ron");
    let mut s = rodnet::scene::load(std::path::Path::new(path)).unwrap().0;
    s.rods[0].subdivide = n;
    for m in s.materials.values_mut() {
        m.section = Section::Circle { radius: r };
    }
    s.supports[1].rotate_by = Some([0.0, PI * (theta / 2.0).sin(), PI * (theta / 2.0).cos()]);
    s
}

/// A planar equilibrium of the twisted ring: its lowest eigenvalue (N/m) other than the
/// neutral one, the neutral one, its largest distance from the plane (m), and its rods to start
/// the next Θ from.
struct Planar {
    buckling: f64,
    neutral: f64,
    off_plane: f64,
    rods: Vec<RodState>,
}

/// Solves the ring twisted by Θ (from `from` when given: a few Newton iterations instead of
/// the closing path) and analyses it; None when the solve left the planar path.
fn michell_state(r: f64, n: usize, theta: f64, from: Option<&[RodState]>) -> Option<Planar> {
    use rodnet::jobs::analyse_modes;
    use rodnet::pipeline::{settings_of, solve_scene, solve_scene_from};
    let scene = michell_ring(r, n, theta);
    let settings = settings_of(&scene);
    let mut sol = match from {
        Some(rods) => solve_scene_from(&scene, &settings, rods).ok().unwrap(),
        None => solve_scene(&scene, &settings).unwrap(),
    };
    assert!(
        sol.report.converged,
        "Θ = {theta}: {:?}",
        sol.report.message
    );
    // A saddle escape, or a restart that failed and solved from rest, may end off the path.
    if sol.report.saddle_escapes > 0 || sol.report.message.is_some() {
        return None;
    }
    let st = analyse_modes(&mut sol, 3).unwrap();
    // One zero mode at every Θ: the isotropic ring's plane turning about the clamps' common
    // tangent. The buckling mode is the lowest of the others.
    let ev = &st.eigenvalues;
    let neutral = (0..ev.len())
        .min_by(|&a, &b| ev[a].abs().total_cmp(&ev[b].abs()))
        .unwrap();
    let buckling = (0..ev.len())
        .filter(|&i| i != neutral)
        .map(|i| ev[i])
        .fold(f64::INFINITY, f64::min);
    let rods = rodnet::io::initial::of_results(&sol.results);
    Some(Planar {
        buckling,
        neutral: ev[neutral],
        off_plane: off_plane(&sol.results.rods[0].points),
        rods,
    })
}

/// The largest distance of the ring's nodes from the plane through the clamps' tangent (x)
/// and the ring's centroid, m.
fn off_plane(points: &[[f64; 3]]) -> f64 {
    let p = &points[..points.len() - 1];
    let c: Vec<f64> = (0..3)
        .map(|k| p.iter().map(|q| q[k]).sum::<f64>() / p.len() as f64)
        .collect();
    // The plane's normal x̂ × c.
    let (ny, nz) = (-c[2], c[1]);
    points
        .iter()
        .map(|q| (q[1] * ny + q[2] * nz).abs() / ny.hypot(nz))
        .fold(0.0, f64::max)
}

/// Fraction of its value at 0.8 Θc below which the buckling eigenvalue is no longer sampled:
/// the discrete ring is planar only up to O(1/N²) (the clamps), so its bifurcation is an
/// imperfect one and the eigenvalue levels off just above zero instead of crossing (0.21 N/m,
/// 0.4 % of its 0.8 Θc value, for `michell.ron` itself, r = 1 cm, N = 40).
const MICHELL_STOP: f64 = 0.02;

/// The `n`-edge ring's critical twist: the zero of its buckling eigenvalue as a function of Θ,
/// extrapolated from below (Θ as the quadratic in the eigenvalue through the last three
/// samples). Samples from 0.8 and 0.9 of `guess`, each next one half way to the extrapolated
/// zero, until the eigenvalue is below `MICHELL_STOP` of its first value. Returns Θc and the
/// samples (Θ, eigenvalue, off-plane distance).
fn michell_critical(r: f64, n: usize, guess: f64) -> (f64, Vec<(f64, f64, f64)>) {
    let first = michell_state(r, n, 0.8 * guess, None).expect("a planar start");
    let mut samples = vec![(0.8 * guess, first.buckling, first.off_plane)];
    let mut rods = first.rods;
    let mut next = 0.9 * guess;
    for _ in 0..30 {
        let (t, f, _) = *samples.last().unwrap();
        // Past Θc the solve buckles out of plane (some 30 times the planar ring's O(1/N²)
        // distance): back to half the step.
        let Some(s) = michell_state(r, n, next, Some(&rods))
            .filter(|s| s.buckling < f && s.off_plane < 10.0 * samples[0].2)
        else {
            next = t + 0.5 * (next - t);
            continue;
        };
        samples.push((next, s.buckling, s.off_plane));
        // The neutral mode is the zero one (round-off against the stretch stiffness), far below
        // any buckling eigenvalue sampled.
        assert!(
            s.neutral.abs() < 1e-5 * samples[0].1,
            "{samples:?}: {}",
            s.neutral
        );
        rods = s.rods;
        let est = zero_of(&samples[samples.len().saturating_sub(3)..]);
        if s.buckling < MICHELL_STOP * samples[0].1 {
            return (est, samples);
        }
        next += 0.5 * (est - next);
    }
    panic!("no crossing within 30 solves: {samples:?}");
}

/// Θ at f = 0 of the polynomial Θ(f) through the samples (Θ, f, _) (inverse interpolation).
fn zero_of(s: &[(f64, f64, f64)]) -> f64 {
    (0..s.len())
        .map(|i| {
            let w: f64 = (0..s.len())
                .filter(|&j| j != i)
                .map(|j| s[j].1 / (s[j].1 - s[i].1))
                .product();
            s[i].0 * w
        })
        .sum()
}

/// Michell (1889): the planar twisted ring loses stability at Θc = 2π√3·EI/GJ. The ring of
/// `michell.ron` made slender (r = 1 mm: its finite thickness moves the threshold by
/// −4.9e-4 at r = 1 cm, about as r²), N = 40 to 320 edges: the discrete Θc approaches Michell's from
/// below as 1/N² once N ≥ 80 (measured −4.49e-3, −1.26e-3, −3.24e-4, −8.5e-5).
#[test]
fn michell_ring_loses_stability_at_its_critical_twist() {
    let r: f64 = 0.001;
    let (ei, gj) = (E * PI * r.powi(4) / 4.0, 2.5e9 * PI * r.powi(4) / 2.0);
    let exact = support::michell_critical_twist(ei, gj);
    let errs: Vec<f64> = [40, 80, 160, 320]
        .iter()
        .map(|&n| {
            let (theta_c, samples) = michell_critical(r, n, exact);
            let err = theta_c / exact - 1.0;
            eprintln!(
                "Michell, N = {n}: Θc = {theta_c:.9} rad ({err:+.3e}), {} equilibria, last \
                 eigenvalue {:.3e} of {:.3e} N/m, off-plane {:.2e} .. {:.2e} m",
                samples.len(),
                samples.last().unwrap().1,
                samples[0].1,
                samples[0].2,
                samples.last().unwrap().2,
            );
            err
        })
        .collect();
    eprintln!("Michell: relative errors {errs:?}");
    assert!(errs.iter().all(|&e| e < 0.0), "{errs:?}");
    assert!(errs[3].abs() < 2e-4, "{errs:?}");
    // Second order in the edge length from N = 80 on (N = 40 is still pre-asymptotic: 3.6).
    for w in errs[1..].windows(2) {
        assert!((3.5..4.5).contains(&(w[0] / w[1])), "{errs:?}");
    }
}
