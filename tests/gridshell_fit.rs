//! `rodnet gridshell fit`: gridshells fitted to target meshes, checked against the analytic
//! hemisphere job, on the validation surfaces, and through the command line.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::Arc;

use rodnet::gridshell::fit::footprint::{FitSpec, DEFAULT_MIN_ANGLE_DEG};
use rodnet::gridshell::fit::job;
use rodnet::gridshell::fit::net::Layout;
use rodnet::gridshell::footprint::{HemisphereSpec, JointChoice};
use rodnet::scene::types::Section;
use rodnet::surface::{shapes, Surface};

fn spec(spacing: f64, layout: Layout) -> FitSpec {
    FitSpec {
        spacing,
        origin: None,
        directions: None,
        layout,
        min_angle_deg: DEFAULT_MIN_ANGLE_DEG,
        subdivide: 4,
        joint: JointChoice::Ball,
        section: Section::Circle { radius: 0.005 },
        young_modulus: 1e9,
        poisson_ratio: 0.3,
        tolerance: None,
        max_iterations: 1000,
    }
}

fn surface(name: &str, mesh: &shapes::Mesh) -> Arc<Surface> {
    Arc::new(Surface::from_obj(name, &shapes::to_obj(mesh)).unwrap())
}

fn fit(s: &Arc<Surface>, spec: &FitSpec) -> job::FitRun {
    match job::run(s, "target.obj", spec, None, &rodnet::pipeline::Limits::NONE) {
        Ok(r) => r,
        Err(job::FitError::Net(e)) => panic!("{e}"),
        Err(job::FitError::Scene(e)) => panic!("{}: {}", e.path(), e.message),
    }
}

/// The fitted dome of a hemisphere mesh is the analytic hemisphere job's dome: joint by joint
/// (same names), to a distance that falls with the mesh's resolution.
#[test]
fn a_fitted_hemisphere_mesh_is_the_hemisphere_jobs_dome() {
    let exact = rodnet::gridshell::job::run(
        &HemisphereSpec::new(1.0, 12, 4),
        5.0,
        None,
        &rodnet::pipeline::Limits::NONE,
    )
    .unwrap();
    let position = |r: &rodnet::io::results::Results, name: &str| {
        r.joints
            .iter()
            .find(|j| j.name == name)
            .map(|j| j.position)
            .unwrap_or_else(|| panic!("joint {name}"))
    };
    let mut last = f64::INFINITY;
    for rings in [24, 48] {
        let s = surface("hemisphere", &shapes::hemisphere(1.0, rings));
        let run = fit(&s, &spec(std::f64::consts::PI / 13.0, Layout::Between));
        assert!(run.results.converged && run.report.stable);
        assert_eq!(run.results.joints.len(), 112);
        let d = exact
            .results
            .joints
            .iter()
            .map(|j| {
                let p = position(&run.results, &j.name);
                (0..3)
                    .map(|k| (p[k] - j.position[k]).powi(2))
                    .sum::<f64>()
                    .sqrt()
            })
            .fold(0.0, f64::max);
        println!("rings {rings}: max joint distance to the analytic job {d:.3e} m");
        assert!(d < 0.6 * last, "rings {rings}: {d} after {last}");
        last = d;
        // The target block measures against the mesh what the job measures against the sphere.
        let t = run.results.target.as_ref().unwrap();
        let rms = exact.metrics.rms_radial_deviation;
        assert!((t.rms_distance.unwrap() - rms).abs() < 0.02 * rms);
        assert!(t.mean_signed_distance.unwrap().abs() < 1e-3);
    }
    assert!(last < 3e-3, "{last}");
}

/// The validation surfaces: each form-finds from its net to a stable shell near the target.
#[test]
fn validation_surfaces_form_find_to_stable_shells_near_their_targets() {
    let cases: Vec<(&str, shapes::Mesh, Option<[f64; 3]>, f64)> = vec![
        ("paraboloid", shapes::paraboloid(1.0, 0.6, 32), None, 0.01),
        ("spheroid", shapes::spheroid(1.0, 0.6, 32), None, 0.08),
        (
            "vault",
            shapes::vault(1.0, 2.0, 16),
            Some([0.5, 0.0, 1.0]),
            0.06,
        ),
        ("saddle", shapes::saddle(1.0, 1.5, 32), Some([0.0; 3]), 0.01),
    ];
    for (name, mesh, origin, bound) in cases {
        let s = surface(name, &mesh);
        let mut sp = spec(0.2, Layout::On);
        sp.origin = origin;
        let run = fit(&s, &sp);
        let t = run.results.target.as_ref().unwrap();
        let net = &run.net_block;
        println!(
            "{name}: {} rods {} joints, angles {:.1}-{:.1}, max |d| {:.3e} rms {:.3e}, {} its, escapes {}",
            net.rods,
            net.joints,
            net.min_angle_deg,
            net.max_angle_deg,
            t.max_abs_distance.unwrap(),
            t.rms_distance.unwrap(),
            run.results.iterations,
            run.report.saddle_escapes
        );
        assert!(run.results.converged, "{name}");
        assert!(run.report.stable, "{name}");
        assert!(net.joints > 50, "{name}");
        assert!(t.max_abs_distance.unwrap() < bound, "{name}");
        assert!(net.min_angle_deg >= DEFAULT_MIN_ANGLE_DEG, "{name}");
    }
}

fn rodnet() -> Command {
    Command::new(env!("CARGO_BIN_EXE_rodnet"))
}

fn temp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rodnet-fit-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn write(d: &Path, name: &str, text: &str) -> PathBuf {
    let p = d.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

#[test]
fn the_command_writes_results_cut_list_drawing_and_a_scene_that_solves_to_the_same_shell() {
    let d = temp("cli");
    let mesh = write(
        &d,
        "dome.obj",
        &shapes::to_obj(&shapes::paraboloid(1.0, 0.5, 24)),
    );
    let out = rodnet()
        .args(["gridshell", "fit"])
        .arg(&mesh)
        .args(["--spacing", "0.25", "--quiet", "--out-dir"])
        .arg(&d)
        .args(["--footprint-csv"])
        .arg(d.join("cut.csv"))
        .args(["--footprint-svg"])
        .arg(d.join("fp.svg"))
        .args(["--scene-out"])
        .arg(d.join("fp.ron"))
        .args(["--json"])
        .arg(d.join("fit.json"))
        .args(["--modes", "3"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let r: serde_json::Value =
        serde_json::from_slice(&std::fs::read(d.join("fit.json")).unwrap()).unwrap();
    let t = &r["target"];
    assert_eq!(t["shape"], "mesh");
    for k in ["max_abs_distance", "rms_distance", "mean_signed_distance"] {
        assert!(t[k].as_f64().unwrap().is_finite(), "{k}");
    }
    for k in [
        "spacing",
        "rods",
        "joints",
        "min_angle_deg",
        "max_angle_deg",
        "max_net_distance",
        "rms_net_distance",
    ] {
        assert!(t["net"][k].is_number(), "{k}");
        assert_eq!(t["net"][k], r["net"][k]);
    }
    // --modes: the shell's lowest eigenvalues, positive for the stable shell.
    let st = &r["stability"];
    assert_eq!(st["stable"], true, "{st}");
    assert_eq!(st["eigenvalues"].as_array().unwrap().len(), 3);
    assert!(st["eigenvalues"][0].as_f64().unwrap() > 0.0);
    let rods = t["net"]["rods"].as_u64().unwrap() as usize;
    let csv = std::fs::read_to_string(d.join("cut.csv")).unwrap();
    assert_eq!(csv.lines().count(), rods + 1);
    // Every crossing position lies on its rod, and neighbours are one spacing apart.
    for line in csv.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let length: f64 = f[3].parse().unwrap();
        let at: Vec<f64> = f[5].split(';').map(|x| x.parse().unwrap()).collect();
        assert!(at.iter().all(|&x| x > 0.0 && x < length), "{line}");
        for w in at.windows(2) {
            assert!((w[1] - w[0] - 0.25).abs() < 1e-5, "{line}");
        }
    }
    assert!(std::fs::read_to_string(d.join("fp.svg"))
        .unwrap()
        .contains("<svg"));
    // The footprint scene, solved from flat along its buckling path, rises to the same shell.
    let out = rodnet()
        .arg("solve")
        .arg(d.join("fp.ron"))
        .args(["--quiet", "--json"])
        .arg(d.join("solved.json"))
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let s: serde_json::Value =
        serde_json::from_slice(&std::fs::read(d.join("solved.json")).unwrap()).unwrap();
    let e = |v: &serde_json::Value| v["energy"]["total"].as_f64().unwrap();
    assert!((e(&s) - e(&r)).abs() < 1e-6 * e(&r), "{} {}", e(&s), e(&r));
    assert_eq!(s["target"]["shape"], "mesh");
}

#[test]
fn bad_meshes_and_options_are_refused_with_their_place() {
    let d = temp("bad");
    let cases = [
        (
            "nan.obj",
            "v 0 0 0\nv 1 0 nan\nv 0 1 0\nf 1 2 3\n",
            "nan.obj:2:",
        ),
        (
            "closed.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n",
            "closed",
        ),
        (
            "flat.obj",
            "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n",
            "flat.obj:4: face 1: degenerate",
        ),
        (
            "two.obj",
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 0\nv 6 5 0\nv 5 6 0\nf 1 2 3\nf 4 5 6\n",
            "several components",
        ),
    ];
    for (name, text, want) in cases {
        let p = write(&d, name, text);
        let out = rodnet()
            .args(["gridshell", "fit"])
            .arg(&p)
            .args(["--spacing", "0.1", "--out-dir"])
            .arg(&d)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{name}: {err}");
        assert!(err.contains(want), "{name}: {err}");
        assert!(!err.contains("panicked"), "{err}");
    }
    let mesh = write(&d, "dome.obj", &shapes::to_obj(&shapes::hemisphere(1.0, 8)));
    for (args, want) in [
        (vec!["--spacing", "-1"], "--spacing"),
        (vec!["--spacing", "5", "--layout", "between"], "no usable"),
        (vec!["--spacing", "0.2", "--min-angle", "95"], "--min-angle"),
        (
            vec!["--spacing", "0.2", "--directions", "1,0,0:1,0.01,0"],
            "--directions",
        ),
    ] {
        let out = rodnet()
            .args(["gridshell", "fit"])
            .arg(&mesh)
            .args(&args)
            .args(["--out-dir"])
            .arg(&d)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(want), "{args:?}: {err}");
    }
    // Nothing was written by any refused run.
    assert!(!d.join("dome-gridshell.json").exists());
    // A scene whose Mesh target is bad names the mesh file and line.
    let scene = write(
        &d,
        "s.ron",
        "(materials: {\"m\": (young_modulus: 1e9, poisson_ratio: 0.3, density: 0.0, section: Circle(radius: 0.01))},\
         rods: [(name: \"a\", material: \"m\", points: [(0,0,0), (1,0,0)])],\
         supports: [(rod: \"a\", vertex: 0, kind: Clamp)],\
         target: Some(Mesh(path: \"flat.obj\")))",
    );
    let out = rodnet().arg("solve").arg(&scene).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("flat.obj:4:1: target mesh: face 1: degenerate"),
        "{err}"
    );
}

/// Where the net shears past the locking angle, the rods stop there, pinned, and the report
/// says which and where; the shell still forms.
#[test]
fn rods_stop_where_the_net_locks() {
    let s = surface("hemisphere", &shapes::hemisphere(1.0, 32));
    let mut sp = spec(std::f64::consts::PI / 13.0, Layout::Between);
    sp.min_angle_deg = 50.0;
    let run = fit(&s, &sp);
    let stops = run.stops();
    assert!(!stops.is_empty());
    for line in &stops {
        assert!(
            line.contains("net locks") || line.contains("stopped first"),
            "{line}"
        );
    }
    // Without the lock, every rod reaches the equator with angles down to 41°.
    let free = fit(&s, &spec(std::f64::consts::PI / 13.0, Layout::Between));
    assert!(free.stops().is_empty());
    assert!(free.net_block.min_angle_deg < 42.0);
    let b = &run.net_block;
    assert!(b.min_angle_deg > 49.0 && b.max_angle_deg < 131.0, "{b:?}");
    assert!(b.joints < free.net_block.joints);
    assert!(run.results.converged && run.report.stable);
    let report = run.summary();
    assert!(report.contains("stop inside the surface"), "{report}");
    // Every stopped end is pinned where the rod stops, off the equator.
    for (rod, &ri) in run.footprint.scene.rods.iter().zip(&run.footprint.rods) {
        let r = &run.footprint.net.rods[ri];
        for (k, e) in r.ends.iter().enumerate() {
            let vertex = if k == 0 { 0 } else { rod.points.len() - 1 };
            let pin = run
                .footprint
                .scene
                .supports
                .iter()
                .find(|p| p.rod == rod.name && p.vertex == vertex)
                .unwrap();
            assert_eq!(pin.move_to, Some(e.point));
        }
    }
}

/// A scene with a Mesh target keeps comparing with its mesh when it is copied without the
/// loaded mesh (serialized and read back, as sweeps and Python do) and when its RON is read
/// from another folder.
#[test]
fn a_mesh_target_survives_copies_of_its_scene() {
    let d = temp("copies");
    write(
        &d,
        "cap.obj",
        &shapes::to_obj(&shapes::paraboloid(1.0, 0.5, 8)),
    );
    let text =
        "Scene(materials: {\"m\": Material(young_modulus: 1e9, poisson_ratio: 0.3, density: 0.0, \
                section: Circle(radius: 0.01))}, rods: [Rod(name: \"a\", material: \"m\", \
                points: [(0,0,0.5), (0.5,0,0.375)], subdivide: 4)], \
                supports: [Support(rod: \"a\", vertex: 0, kind: Clamp)], \
                target: Some(Mesh(path: \"cap.obj\")))";
    let file = d.join("s.ron").display().to_string();
    let scene = rodnet::scene::parse(&file, text).unwrap();
    let solve = |sc: &rodnet::scene::Scene| {
        let s = rodnet::pipeline::solve_scene(sc, &rodnet::pipeline::settings_of(sc)).unwrap();
        s.results.target.unwrap()
    };
    let want = solve(&scene);
    assert_eq!(want.shape, "mesh");
    // Through JSON, the loaded mesh is gone; the path reads it again.
    let copy: rodnet::scene::Scene =
        serde_json::from_value(serde_json::to_value(&scene).unwrap()).unwrap();
    let got = solve(&copy);
    assert_eq!(got.max_abs_distance, want.max_abs_distance);
    // The RON written back reads from anywhere.
    let elsewhere = temp("copies-elsewhere").join("t.ron").display().to_string();
    let again =
        rodnet::scene::parse(&elsewhere, &rodnet::gridshell::footprint::to_ron(&scene)).unwrap();
    assert_eq!(solve(&again).rms_distance, want.rms_distance);
}
