//! Issue 39, the third reliability round: resumed sweeps recompute points whose inputs changed,
//! Slurm scripts cannot be made to run a command by a path, named FIFOs are refused as outputs
//! before the solve, `max_iterations` is bounded and a time limit is one budget for the whole job.

mod common;

use common::cli::{rodnet, text, tmpdir};

use std::path::Path;
use std::process::Command;

fn energy(p: &Path) -> f64 {
    let v: serde_json::Value = serde_json::from_slice(&std::fs::read(p).unwrap()).unwrap();
    v["energy"]["total"].as_f64().unwrap()
}

const SWEEP: &str = r#"Sweep(scene: "beam.ron", grid: {"solver.max_iterations": [100, 200]},
                 quantities: ["energy.total"], output: "out")"#;

/// A resumed sweep whose base scene changed solves its points again (their energy is the new
/// scene's, solved on its own); with nothing changed, both points are kept.
#[test]
fn a_resumed_sweep_recomputes_points_whose_inputs_changed() {
    let d = tmpdir("rel-out", "sweep");
    let beam = d.join("beam.ron");
    std::fs::copy("networks/cantilever.ron", &beam).unwrap();
    let sweep = d.join("s.ron");
    std::fs::write(&sweep, SWEEP).unwrap();
    let run = || rodnet().arg("sweep").arg(&sweep).output().unwrap();
    let o = run();
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    let o = run();
    assert!(text(&o).contains("(2 kept"), "{}", text(&o));

    // The load doubled: the elastica of P L²/EI = 4, not the stored points' P L²/EI = 2.
    let doubled = std::fs::read_to_string(&beam)
        .unwrap()
        .replace("-1.5707963267948966", "-3.141592653589793");
    std::fs::write(&beam, doubled).unwrap();
    let fresh = d.join("fresh.json");
    let o = rodnet()
        .arg("solve")
        .arg(&beam)
        .args(["--quiet", "--json"])
        .arg(&fresh)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", text(&o));
    let o = run();
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    assert!(text(&o).contains("(0 kept"), "{}", text(&o));
    for name in ["solver.max_iterations=100", "solver.max_iterations=200"] {
        let point = d.join("out").join(format!("{name}.json"));
        let (e, want) = (energy(&point), energy(&fresh));
        assert!(
            (e - want).abs() <= 1e-9 * want.abs(),
            "{name}: {e} J, the new scene {want} J"
        );
    }
}

/// A newline in the sweep file's name or the script folder is refused (exit 2) before anything
/// is written: it would start a line of the script of its own.
#[test]
fn slurm_scripts_refuse_paths_with_control_characters() {
    let d = tmpdir("rel-out", "slurm");
    std::fs::copy("networks/cantilever.ron", d.join("beam.ron")).unwrap();
    let evil = d.join("s\ntouch ran\n.ron");
    std::fs::write(&evil, SWEEP).unwrap();
    let plain = d.join("s.ron");
    std::fs::write(&plain, SWEEP).unwrap();
    let cases = [
        (evil.clone(), d.join("array")),
        (plain.clone(), d.join("a\ntouch ran\n")),
    ];
    for (sweep, dir) in cases {
        let o = rodnet()
            .arg("sweep")
            .arg(&sweep)
            .arg("--emit")
            .arg("slurm")
            .arg(&dir)
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(2), "{sweep:?} {dir:?}: {}", text(&o));
        assert!(text(&o).contains("control character"), "{}", text(&o));
        assert!(
            !dir.join("sweep.sbatch").exists(),
            "{dir:?}: script written"
        );
    }
}

/// A named FIFO as output is refused with exit 2 before the solve (nobody reading it, the
/// write would wait forever), and the other outputs are not written.
#[cfg(unix)]
#[test]
fn a_named_fifo_output_is_refused_before_the_solve() {
    let d = tmpdir("rel-out", "fifo");
    let fifo = d.join("out.json");
    let made = Command::new("mkfifo").arg(&fifo).status();
    if !made.is_ok_and(|s| s.success()) {
        eprintln!("no mkfifo here: skipped");
        return;
    }
    let csv = d.join("out.csv");
    let o = rodnet()
        .args(["solve", "networks/cantilever.ron", "--json"])
        .arg(&fifo)
        .arg("--csv")
        .arg(&csv)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("FIFO"), "{}", text(&o));
    assert!(
        !text(&o).contains("converged"),
        "solved first: {}",
        text(&o)
    );
    assert!(!csv.exists());
}

/// A time limit set with the settings is one budget, counted from when it was set: a solve
/// started after it ran out stops at once (stopped: "time limit") instead of starting its own.
#[test]
fn a_time_limit_is_one_budget_for_every_solve_of_a_job() {
    let (scene, _) = rodnet::scene::load(Path::new("networks/cantilever.ron")).unwrap();
    let settings = rodnet::pipeline::settings_of(&scene).time_limit(Some(0.05));
    // Past the deadline (no assertion on durations: only that it has passed).
    std::thread::sleep(std::time::Duration::from_millis(100));
    let sol = rodnet::pipeline::solve_scene(&scene, &settings).unwrap();
    assert!(!sol.report.converged);
    assert!(sol.report.stopped.is_some(), "{:?}", sol.report.message);
}
