//! Bad input through the binary: every case must exit with code 2 and one located message, never
//! panic, and write nothing. The scene corpus is `tests/bad_scenes/*.ron`, listed with the
//! expected line and message fragment in `tests/bad_scenes/expected.txt`.

use std::path::PathBuf;
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
