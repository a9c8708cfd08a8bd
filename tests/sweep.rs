//! `rodnet sweep` through the binary (docs/sweep.md): the local run and its table, resuming,
//! refusals before any solve, failed points, and the Slurm array's tasks run here with
//! SLURM_ARRAY_TASK_ID set, merged into the same table as the local run.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn rodnet() -> Command {
    Command::new(env!("CARGO_BIN_EXE_rodnet"))
}

fn tmpdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rodnet-sweep-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn run(args: &[&str], sweep: &Path) -> Output {
    rodnet()
        .arg("sweep")
        .arg(sweep)
        .args(args)
        .output()
        .unwrap()
}

fn text(o: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}

const HEMISPHERE: &str = r#"Sweep(
    hemisphere: {"subdivide": 2},
    grid: {"rods": [4, 6], "section_ratio": [0.005, 0.01]},
    output: "out",
)
"#;

fn table(path: &Path) -> Vec<Vec<String>> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .map(|l| l.split(',').map(String::from).collect())
        .collect()
}

fn point_files(dir: &Path) -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|r| r.map(|e| e.unwrap().path()).collect())
        .unwrap_or_default();
    v.retain(|p| {
        p.file_name()
            .unwrap()
            .to_string_lossy()
            .starts_with("rods=")
    });
    v.sort();
    v
}

#[test]
fn hemisphere_sweep_writes_points_and_table_and_resumes() {
    let d = tmpdir("local");
    let sweep = d.join("dome.ron");
    std::fs::write(&sweep, HEMISPHERE).unwrap();
    let o = run(&["--jobs", "2"], &sweep);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    let files = point_files(&d.join("out"));
    let names: Vec<String> = files
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    assert_eq!(
        names,
        [
            "rods=4,section_ratio=0.005.json",
            "rods=4,section_ratio=0.01.json",
            "rods=6,section_ratio=0.005.json",
            "rods=6,section_ratio=0.01.json"
        ]
    );
    let t = table(&d.join("out/sweep.csv"));
    assert_eq!(t.len(), 5);
    let col = |name: &str| {
        t[0].iter()
            .position(|h| h == name)
            .unwrap_or_else(|| panic!("{name} in {:?}", t[0]))
    };
    let (conv, dev, energy) = (
        col("converged"),
        col("target.max_abs_radial_deviation [1]"),
        col("energy.total [J]"),
    );
    assert!(t[0].contains(&"rods [1]".to_string()) && t[0].contains(&"seconds [s]".to_string()));
    assert!(t[1..].iter().all(|r| r[conv] == "true"));
    let num = |r: usize, c: usize| t[r][c].parse::<f64>().unwrap();
    // More rods: closer to the sphere; a thicker section (same shape): more bending energy.
    assert!(num(3, dev) < num(1, dev) && num(4, dev) < num(2, dev));
    assert!(num(2, energy) > num(1, energy) && num(4, energy) > num(3, energy));

    // Resumed: every point is kept; a removed point alone is solved again.
    let stamps: Vec<_> = files
        .iter()
        .map(|p| p.metadata().unwrap().modified().unwrap())
        .collect();
    std::fs::remove_file(&files[1]).unwrap();
    let o = run(&["--jobs", "2"], &sweep);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    assert_eq!(
        text(&o).matches("kept (results exist)").count(),
        3,
        "{}",
        text(&o)
    );
    for (k, p) in files.iter().enumerate().filter(|(k, _)| *k != 1) {
        assert_eq!(p.metadata().unwrap().modified().unwrap(), stamps[k]);
    }
    // Only the re-solved point's time may differ.
    let blank = |mut t: Vec<Vec<String>>| {
        let s = col("seconds [s]");
        t.iter_mut().skip(1).for_each(|r| r[s].clear());
        t
    };
    assert_eq!(blank(table(&d.join("out/sweep.csv"))), blank(t.clone()));
}

#[test]
fn bad_parameters_are_refused_before_any_solve_naming_the_path() {
    let d = tmpdir("bad");
    std::fs::copy("networks/cantilever.ron", d.join("beam.ron")).unwrap();
    for (grid, named, exit) in [
        (
            r#"{"materials.steel.young_modulas": [1e8]}"#,
            "materials.steel.young_modulas",
            2,
        ),
        (
            r#"{"rods.beam.subdivide": [4, "many"]}"#,
            "rods.beam.subdivide",
            2,
        ),
        (
            r#"{"rods.beam.subdivide": [4, 0]}"#,
            "rods.beam.subdivide",
            2,
        ),
        (r#"{"loads[3].force": [1.0]}"#, "loads[3].force", 2),
    ] {
        let sweep = d.join("s.ron");
        std::fs::write(
            &sweep,
            format!(
                "Sweep(\n    scene: \"beam.ron\",\n    grid: {grid},\n    output: \"out\",\n)\n"
            ),
        )
        .unwrap();
        let o = run(&[], &sweep);
        let msg = text(&o);
        assert_eq!(o.status.code(), Some(exit), "{msg}");
        assert!(msg.contains(&format!("parameter `{named}`")), "{msg}");
        assert!(msg.contains("s.ron:3:"), "not located: {msg}");
        assert!(!d.join("out").exists(), "{grid}: something was written");
    }
    let sweep = d.join("h.ron");
    std::fs::write(
        &sweep,
        "Sweep(hemisphere: {}, grid: {\"rods\": [4, 6.5]}, output: \"o\")",
    )
    .unwrap();
    let o = run(&[], &sweep);
    assert_eq!(o.status.code(), Some(2));
    assert!(text(&o).contains("parameter `rods`"), "{}", text(&o));
}

#[test]
fn a_failed_point_is_recorded_and_the_others_finish() {
    let d = tmpdir("fail");
    std::fs::copy("networks/cantilever.ron", d.join("beam.ron")).unwrap();
    let sweep = d.join("s.ron");
    std::fs::write(
        &sweep,
        r#"Sweep(scene: "beam.ron", grid: {"solver.max_iterations": [2, 200]},
                 quantities: ["energy.total", "rods.beam.points[-1][1]"], output: "out")"#,
    )
    .unwrap();
    let o = run(&["--jobs", "2"], &sweep);
    assert_eq!(o.status.code(), Some(1), "{}", text(&o));
    let t = table(&d.join("out/sweep.csv"));
    assert_eq!(t[1][2], "false");
    assert!(!t[1].last().unwrap().is_empty(), "no message: {:?}", t[1]);
    assert_eq!(t[2][2], "true");
    // The elastica's tip deflection (networks/cantilever.ron): v/L = 0.49345748.
    let tip: f64 = t[2][t[0]
        .iter()
        .position(|h| h.starts_with("rods.beam.points"))
        .unwrap()]
    .parse()
    .unwrap();
    assert!((tip + 0.49345748).abs() < 2e-3, "{tip}");
}

#[test]
fn slurm_array_tasks_run_here_and_merge_into_the_local_table() {
    let d = tmpdir("slurm");
    let sweep = d.join("dome.ron");
    std::fs::write(&sweep, HEMISPHERE).unwrap();
    let array = d.join("array");
    let o = run(&["--emit", "slurm", array.to_str().unwrap()], &sweep);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    let script = std::fs::read_to_string(array.join("sweep.sbatch")).unwrap();
    assert!(script.contains("#SBATCH --array=0-3"), "{script}");
    assert!(!d.join("out").exists(), "--emit solved something");

    let task = |i: usize| {
        let o = Command::new("bash")
            .arg(array.join("sweep.sbatch"))
            .env("SLURM_ARRAY_TASK_ID", i.to_string())
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(0), "task {i}: {}", text(&o));
    };
    task(0);
    task(3);
    let merge = || {
        rodnet()
            .args(["sweep", "merge"])
            .arg(&array)
            .output()
            .unwrap()
    };
    let o = merge();
    assert_eq!(
        o.status.code(),
        Some(1),
        "missing points must fail: {}",
        text(&o)
    );
    assert!(
        text(&o).contains(
            "2 point(s) missing (no results file yet, or one solved from other inputs): 1 2"
        ),
        "{}",
        text(&o)
    );
    task(1);
    task(2);
    let o = merge();
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    assert!(!text(&o).contains("missing"), "{}", text(&o));
    let from_array = table(&d.join("out/sweep.csv"));

    // The same sweep run locally (into another folder) gives the same table but for times.
    let local = d.join("local.ron");
    std::fs::write(&local, HEMISPHERE.replace("\"out\"", "\"local\"")).unwrap();
    let o = run(&["--jobs", "2"], &local);
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    let here = table(&d.join("local/sweep.csv"));
    let seconds = here[0].iter().position(|h| h == "seconds [s]").unwrap();
    let energy = here[0]
        .iter()
        .position(|h| h == "energy.total [J]")
        .unwrap();
    assert_eq!(from_array.len(), here.len());
    for (a, b) in from_array.iter().zip(&here).skip(1) {
        for (k, (x, y)) in a.iter().zip(b).enumerate() {
            if k == seconds {
                continue;
            }
            match (x.parse::<f64>(), y.parse::<f64>()) {
                (Ok(x), Ok(y)) if k == energy => assert!((x - y).abs() <= 1e-9 * x.abs()),
                (Ok(x), Ok(y)) => {
                    assert!((x - y).abs() <= 1e-6 * x.abs().max(1e-12), "{k}: {x} {y}")
                }
                _ => assert_eq!(x, y),
            }
        }
    }
}
