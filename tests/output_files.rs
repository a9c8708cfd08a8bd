//! What every command does with its output paths (docs/cli.md, "Output files"): regular files
//! are replaced atomically and no temporary is left behind; what is not a regular file (a
//! device, a symbolic link) is written through, never replaced; a directory is refused; two
//! outputs to one file are refused by every command; nothing is created for rejected input.

use std::os::unix::fs::{symlink, FileTypeExt};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const SCENE: &str = "networks/cantilever.ron";

fn rodnet() -> Command {
    Command::new(env!("CARGO_BIN_EXE_rodnet"))
}

fn tmpdir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rodnet-out-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn run(args: &[&str], paths: &[&Path]) -> Output {
    let mut c = rodnet();
    c.args(args);
    for p in paths {
        c.arg(p);
    }
    c.output().unwrap()
}

/// Exit code 2 with one `error:` line containing `needle`, no panic.
fn assert_refused(what: &str, o: &Output, needle: &str) {
    let err = stderr(o);
    assert_eq!(o.status.code(), Some(2), "{what}: {err}");
    assert!(!err.contains("panicked"), "{what}: {err}");
    assert!(
        err.starts_with("error: ") && err.contains(needle),
        "{what}: {err}"
    );
}

/// Names in `d` that look like temporaries (`.NAME.tmpPID`).
fn temporaries(d: &Path) -> Vec<String> {
    std::fs::read_dir(d)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.contains(".tmp"))
        .collect()
}

#[test]
fn dev_null_stays_a_device() {
    let out = run(
        &[
            "solve",
            SCENE,
            "--quiet",
            "--json",
            "/dev/null",
            "--obj",
            "/dev/null",
        ],
        &[],
    );
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let meta = std::fs::symlink_metadata("/dev/null").unwrap();
    assert!(meta.file_type().is_char_device(), "/dev/null was replaced");
    assert_eq!(std::fs::read("/dev/null").unwrap(), b"");
    assert!(temporaries(Path::new("/dev")).is_empty());
}

#[test]
fn a_symlink_output_stays_a_link_and_its_target_gets_the_content() {
    let d = tmpdir("link");
    let target = d.join("target.json");
    std::fs::write(&target, "old").unwrap();
    let link = d.join("link.json");
    symlink("target.json", &link).unwrap();
    let direct = d.join("direct.json");
    let out = run(&["solve", SCENE, "--quiet", "--json"], &[&link]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let meta = std::fs::symlink_metadata(&link).unwrap();
    assert!(meta.file_type().is_symlink(), "the link was replaced");
    assert_eq!(std::fs::read_link(&link).unwrap(), Path::new("target.json"));
    run(&["solve", SCENE, "--quiet", "--json"], &[&direct]);
    let (through, expected) = (
        std::fs::read_to_string(&target).unwrap(),
        std::fs::read_to_string(&direct).unwrap(),
    );
    let v: serde_json::Value = serde_json::from_str(&through).unwrap();
    assert_eq!(v["converged"], true);
    // The same results (but for the timing).
    let strip = |s: &str| -> Vec<String> {
        s.lines()
            .filter(|l| !l.contains("seconds"))
            .map(String::from)
            .collect()
    };
    assert_eq!(strip(&through), strip(&expected));
    // The plot writes through links too.
    let png = d.join("view.png");
    std::fs::write(&png, "").unwrap();
    let png_link = d.join("view-link.png");
    symlink(&png, &png_link).unwrap();
    let out = run(&["plot"], &[&direct, Path::new("-o"), &png_link]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(std::fs::symlink_metadata(&png_link)
        .unwrap()
        .file_type()
        .is_symlink());
    assert!(std::fs::read(&png).unwrap().starts_with(b"\x89PNG"));
    assert!(temporaries(&d).is_empty(), "{:?}", temporaries(&d));
}

#[test]
fn an_output_link_to_an_input_or_to_another_output_is_refused() {
    let d = tmpdir("alias");
    let scene = d.join("scene.ron");
    std::fs::copy(SCENE, &scene).unwrap();
    let link = d.join("scene-link.json");
    symlink(&scene, &link).unwrap();
    let out = run(&["solve", "--quiet"], &[&scene, Path::new("--json"), &link]);
    assert_refused("link to input", &out, "is an input file");
    assert_eq!(
        std::fs::read(&scene).unwrap(),
        std::fs::read(SCENE).unwrap()
    );
    let a = d.join("a.json");
    let b = d.join("b.obj");
    symlink(&a, &b).unwrap();
    std::fs::write(&a, "").unwrap();
    let out = run(
        &["solve", SCENE, "--quiet", "--json"],
        &[&a, Path::new("--obj"), &b],
    );
    assert_refused("two names of one file", &out, "same file as --json");
}

#[test]
fn directories_and_links_to_nowhere_are_refused() {
    let d = tmpdir("dirs");
    let sub = d.join("sub");
    std::fs::create_dir(&sub).unwrap();
    let to_dir = d.join("to-dir.json");
    symlink(&sub, &to_dir).unwrap();
    let dangling = d.join("dangling.json");
    symlink(d.join("nothing"), &dangling).unwrap();
    for (p, needle) in [
        (&sub, "is a directory"),
        (&to_dir, "is a symbolic link to a directory"),
        (&dangling, "dangling"),
    ] {
        let out = run(&["solve", SCENE, "--quiet", "--json"], &[p]);
        assert_refused(&p.display().to_string(), &out, needle);
        assert!(out.stdout.is_empty(), "solved anyway");
        let out = run(&["gridshell", "hemisphere", "--quiet", "--json"], &[p]);
        assert_refused(&p.display().to_string(), &out, needle);
    }
    assert!(std::fs::read_dir(&sub).unwrap().next().is_none());
    assert!(!d.join("nothing").exists());
}

#[test]
fn runs_leave_no_temporaries_and_remove_stale_ones() {
    let d = tmpdir("temps");
    // A temporary of a process that no longer runs (a pid above Linux's largest, 2^22), and
    // one of a process that does (this test's): only the first is stale.
    let stale = d.join(".r.json.tmp4194305");
    let live = d.join(format!(".r.json.tmp{}", std::process::id()));
    let other = d.join(".notes.txt.tmp4194305");
    for p in [&stale, &live, &other] {
        std::fs::write(p, "half-written").unwrap();
    }
    let (json, obj, csv) = (d.join("r.json"), d.join("r.obj"), d.join("r.csv"));
    for _ in 0..2 {
        let out = run(
            &["solve", SCENE, "--quiet", "--json"],
            &[&json, Path::new("--obj"), &obj, Path::new("--csv"), &csv],
        );
        assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    }
    assert!(!stale.exists(), "stale temporary left");
    assert!(live.exists(), "a live process's temporary was removed");
    assert!(other.exists(), "another file's temporary was removed");
    std::fs::remove_file(&live).unwrap();
    std::fs::remove_file(&other).unwrap();
    assert!(temporaries(&d).is_empty(), "{:?}", temporaries(&d));
    let v: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
    assert_eq!(v["converged"], true);
    assert!(std::fs::read_to_string(&obj).unwrap().contains("\nl "));
}

#[test]
fn gridshell_refuses_two_outputs_to_one_file() {
    let d = tmpdir("gridshell-same");
    let a = d.join("a.json");
    let out = run(
        &[
            "gridshell",
            "hemisphere",
            "--rods",
            "2",
            "--quiet",
            "--json",
        ],
        &[&a, Path::new("--obj"), &a],
    );
    assert_refused("--json a --obj a", &out, "same file as --json");
    assert!(out.stdout.is_empty(), "solved anyway");
    assert!(!a.exists());
    // An explicit path that collides with a default name in --out-dir.
    let out_dir = d.join("out");
    let out = run(
        &[
            "gridshell",
            "hemisphere",
            "--rods",
            "2",
            "--quiet",
            "--out-dir",
        ],
        &[
            &out_dir,
            Path::new("--report"),
            &out_dir.join("hemisphere.json"),
        ],
    );
    assert_refused("--report over the default JSON", &out, "same file as");
    assert!(!out_dir.exists(), "--out-dir created for rejected input");
    let out = run(
        &[
            "gridshell",
            "hemisphere",
            "--rods",
            "2",
            "--quiet",
            "--scene-out",
        ],
        &[&a, Path::new("--report"), &a],
    );
    assert_refused("--scene-out a --report a", &out, "same file as --scene-out");
}

#[test]
fn gridshell_creates_no_out_dir_for_rejected_input() {
    let d = tmpdir("gridshell-outdir");
    let out_dir = d.join("new");
    let cases: Vec<(Vec<PathBuf>, &str)> = vec![
        // A section whose rigidities underflow: the generated scene is refused.
        (
            vec!["--section".into(), "circle:1e-90".into()],
            "the generated scene is invalid",
        ),
        (
            vec!["--json".into(), d.join("missing/r.json")],
            "does not exist",
        ),
        (vec!["--rods".into(), "0".into()], "--rods"),
    ];
    for (extra, needle) in cases {
        let mut c = rodnet();
        c.args(["gridshell", "hemisphere", "--quiet", "--out-dir"])
            .arg(&out_dir)
            .args(&extra);
        let out = c.output().unwrap();
        assert_refused(needle, &out, needle);
        assert!(!out_dir.exists(), "{needle}: --out-dir created");
    }
    // A file where the directory should be.
    let file = d.join("file");
    std::fs::write(&file, "").unwrap();
    let out = run(
        &["gridshell", "hemisphere", "--quiet", "--out-dir"],
        &[&file],
    );
    assert_refused("--out-dir over a file", &out, "not a directory");
}

#[test]
fn study_refuses_two_outputs_to_one_file() {
    let d = tmpdir("study-same");
    let a = d.join("a.out");
    let out = run(
        &[
            "study",
            "convergence",
            SCENE,
            "--levels",
            "3",
            "--quiet",
            "--csv",
        ],
        &[&a, Path::new("--plot"), &a],
    );
    assert_refused("--csv a --plot a", &out, "same file as --csv");
    assert!(!a.exists());
}

#[test]
fn study_writes_the_csv_when_the_plot_cannot_be_drawn() {
    // An unloaded rod stays at rest at every level: every error is zero, and a log-log plot
    // has nothing to show.
    let d = tmpdir("study-plot");
    let scene = d.join("rest.ron");
    std::fs::write(
        &scene,
        r#"Scene(
    materials: { "m": Material(young_modulus: 1e7, poisson_ratio: 0.3, section: Circle(radius: 0.01)) },
    rods: [ Rod(name: "a", material: "m", points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0)], subdivide: 2) ],
    supports: [ Support(rod: "a", vertex: 0, kind: Clamp) ],
)"#,
    )
    .unwrap();
    let (csv, png) = (d.join("s.csv"), d.join("s.png"));
    let out = run(
        &["study", "convergence", "--levels", "3", "--quiet"],
        &[&scene, Path::new("--csv"), &csv, Path::new("--plot"), &png],
    );
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains("cannot draw") && err.contains("s.csv was written"),
        "{err}"
    );
    let text = std::fs::read_to_string(&csv).expect("the CSV is written");
    assert!(text.starts_with("level,subdivide"), "{text}");
    assert_eq!(text.lines().count(), 4, "{text}");
    assert!(!png.exists());
}
