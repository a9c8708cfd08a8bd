//! Tiny inputs that would eat the machine (issue 15, item 2), through the binary: each is
//! refused with exit 2 and one message naming the file and what drives its size, or stopped
//! by `--time-limit` with its last iterate written.

use std::path::PathBuf;
use std::process::{Command, Output};

fn rodnet() -> Command {
    Command::new(env!("CARGO_BIN_EXE_rodnet"))
}

fn tmpdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rodnet-limits-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Exit code 2, one `error:` line, no panic; returns the line.
fn refused(what: &str, o: &Output) -> String {
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(o.status.code(), Some(2), "{what}: {err}");
    assert!(!err.contains("panicked"), "{what}: {err}");
    let lines: Vec<&str> = err.lines().filter(|l| !l.trim().is_empty()).collect();
    assert_eq!(lines.len(), 1, "{what}: expected one message, got {err}");
    assert!(lines[0].starts_with("error: "), "{what}: {err}");
    lines[0].to_string()
}

/// The Nitinol cross with `subdivide: 50000` (200 000 nodes): refused from its sizes alone,
/// before anything is built, at the line of the rod's `subdivide`.
#[test]
fn a_scene_above_the_memory_limit_is_refused_from_its_sizes() {
    let d = tmpdir("nitinol");
    let text = std::fs::read_to_string("networks/extreme/nitinol_cross.ron").unwrap();
    let scene = d.join("nitinol_50000.ron");
    std::fs::write(&scene, text.replace("subdivide: 12", "subdivide: 50000")).unwrap();
    let json = d.join("r.json");
    let out = rodnet()
        .arg("solve")
        .arg(&scene)
        .args(["--quiet", "--max-memory", "512M", "--json"])
        .arg(&json)
        .output()
        .unwrap();
    let msg = refused("nitinol 50000", &out);
    let at = format!("error: {}:12:", scene.display());
    assert!(msg.starts_with(&at), "{msg}");
    for part in [
        "rods[1].subdivide",
        "too large for the memory limit",
        "200002 nodes need at least",
        "--max-memory 512.0 MiB",
    ] {
        assert!(msg.contains(part), "lacks {part:?}: {msg}");
    }
    assert!(!json.exists());
}

/// Past the check from sizes, the built network's estimate (with the factor's fill counted by
/// the symbolic analysis) is checked before the solve allocates it.
#[test]
fn a_network_above_the_memory_limit_is_refused_with_its_estimate() {
    let out = rodnet()
        .args([
            "solve",
            "networks/cantilever.ron",
            "--quiet",
            // Between the bound from its sizes (8.2 MiB) and the built network's estimate
            // (8.3 MiB), so that the estimate is what refuses it.
            "--max-memory",
            "8400K",
        ])
        .output()
        .unwrap();
    let msg = refused("cantilever", &out);
    assert!(
        msg.starts_with("error: networks/cantilever.ron:18:13: rods[0].subdivide:"),
        "{msg}"
    );
    assert!(msg.contains("160 unknowns"), "{msg}");
    assert!(msg.contains("non-zeros in the Cholesky factor"), "{msg}");
    // The same scene under a limit it fits.
    let out = rodnet()
        .args([
            "solve",
            "networks/cantilever.ron",
            "--quiet",
            "--max-memory",
            "1G",
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0));

    let d = tmpdir("gridshell-mem");
    let out = rodnet()
        .args(["gridshell", "hemisphere", "--quiet", "--max-memory", "12M"])
        .arg("--out-dir")
        .arg(&d)
        .output()
        .unwrap();
    let msg = refused("gridshell", &out);
    assert!(
        msg.starts_with(
            "error: --rods 12 --subdivide 4: the gridshell is too large for the memory limit"
        ),
        "{msg}"
    );
    assert!(!d.join("hemisphere.json").exists());

    for cmd in [
        vec!["buckle", "networks/euler_column.ron"],
        vec!["study", "convergence", "networks/cantilever.ron"],
    ] {
        let out = rodnet()
            .args(&cmd)
            .args(["--quiet", "--max-memory", "8M"])
            .output()
            .unwrap();
        let msg = refused(cmd[0], &out);
        assert!(msg.contains("too large for the memory limit"), "{msg}");
    }
}

#[test]
fn bad_memory_limits_are_usage_errors() {
    for bad in ["4X", "0", "-1G", "1e30T"] {
        let out = rodnet()
            .args(["solve", "networks/cantilever.ron", "--max-memory", bad])
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{bad}");
    }
    let out = rodnet()
        .args(["solve", "networks/cantilever.ron", "--time-limit", "0"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
}

/// Options whose derived sizes overflowed the footprint generator (--radius 1e200 once asked
/// for endless subdivisions) are refused before it runs.
#[test]
fn gridshell_sizes_that_cannot_be_generated_are_refused() {
    for (args, fragment) in [
        (
            vec!["--radius", "1e200", "--rods", "4"],
            "--radius must lie in",
        ),
        (vec!["--radius", "1e-9"], "--radius must lie in"),
        (vec!["--section", "circle:1e300"], "--section dimensions"),
        (
            vec!["--rods", "4", "--subdivide", "100000000000"],
            "above the limit of 2000000",
        ),
        (vec!["--young-modulus", "1e300"], "--young-modulus"),
    ] {
        let out = rodnet()
            .args([
                "gridshell",
                "hemisphere",
                "--scene-out",
                "/nonexistent/s.ron",
            ])
            .args(&args)
            .output()
            .unwrap();
        let msg = refused(&format!("{args:?}"), &out);
        assert!(msg.contains(fragment), "{args:?}: {msg}");
    }
}

fn network_args(path: &str) -> Vec<String> {
    [
        "solve",
        "--network",
        path,
        "--young-modulus",
        "1e9",
        "--radius",
        "0.01",
        "--poisson-ratio",
        "0.3",
    ]
    .map(String::from)
    .to_vec()
}

/// Inputs that never end or never come: devices are refused, a FIFO nobody writes to reads as
/// empty instead of blocking, whichever command reads it.
#[test]
fn endless_inputs_are_refused() {
    if !std::path::Path::new("/dev/zero").exists() {
        return;
    }
    let d = tmpdir("endless");
    let fifo = d.join("fifo");
    let made = Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .is_ok_and(|s| s.success());
    let mut cases: Vec<(Vec<String>, &str)> = vec![
        (
            vec!["solve".into(), "/dev/zero".into()],
            "/dev/zero: cannot read scene file: it is a character device",
        ),
        (
            network_args("/dev/zero"),
            "/dev/zero: cannot read network file: it is a character device",
        ),
        (
            vec![
                "plot".into(),
                "/dev/zero".into(),
                "--output".into(),
                d.join("p.png").display().to_string(),
            ],
            "it is a character device",
        ),
        (
            vec!["buckle".into(), "/dev/zero".into()],
            "it is a character device",
        ),
    ];
    if made {
        let f = fifo.display().to_string();
        cases.push((
            vec!["solve".into(), f.clone()],
            "is a FIFO with nothing written to it",
        ));
        cases.push((network_args(&f), "is a FIFO with nothing written to it"));
    }
    for (args, fragment) in cases {
        let out = rodnet().args(&args).output().unwrap();
        let msg = refused(&format!("{args:?}"), &out);
        assert!(msg.contains(fragment), "{args:?}: {msg}");
    }
}

/// A FIFO with a writer is read to its end (process substitution, a pipe from a generator).
#[test]
fn a_fifo_with_a_writer_is_read() {
    let d = tmpdir("fifo-writer");
    let fifo = d.join("scene");
    if !Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .is_ok_and(|s| s.success())
    {
        return;
    }
    let text = std::fs::read("networks/cantilever.ron").unwrap();
    let path = fifo.clone();
    let writer = std::thread::spawn(move || std::fs::write(path, text));
    // The writer's open waits for this reader; give it time to be there first.
    std::thread::sleep(std::time::Duration::from_millis(200));
    let out = rodnet()
        .arg("solve")
        .arg(&fifo)
        .arg("--quiet")
        .output()
        .unwrap();
    writer.join().unwrap().unwrap();
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// 1e5 load steps stop at `--time-limit` with the last iterate written, whatever the scene
/// says (it has no time limit of its own).
#[test]
fn the_time_limit_option_stops_a_long_solve() {
    let d = tmpdir("time");
    let text = std::fs::read_to_string("networks/cantilever_elastica.ron").unwrap();
    let scene = d.join("steps.ron");
    std::fs::write(
        &scene,
        text.replace("solver: Solver(", "solver: Solver(load_steps: 100000, "),
    )
    .unwrap();
    let json = d.join("r.json");
    let out = rodnet()
        .arg("solve")
        .arg(&scene)
        .args(["--quiet", "--time-limit", "0.3", "--json"])
        .arg(&json)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let r: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
    assert_eq!(r["converged"], false);
    assert_eq!(r["stopped"], "time limit");

    // The form finding's time limit holds for all its cap steps together.
    let out = rodnet()
        .args([
            "gridshell",
            "hemisphere",
            "--rods",
            "24",
            "--quiet",
            "--time-limit",
            "0.01",
            "--json",
        ])
        .arg(d.join("g.json"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(1));
    let r: serde_json::Value =
        serde_json::from_slice(&std::fs::read(d.join("g.json")).unwrap()).unwrap();
    assert_eq!(r["converged"], false);
    assert_eq!(r["stopped"], "time limit");
}
