//! `rodnet solve --initial`: a results file must belong to the scene, the scene's supports hold
//! whatever the file says, and values the solver cannot hold are refused (issue 39).

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const CANTILEVER: &str = "networks/cantilever.ron";

fn temp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rodnet-rel-initial-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn solve(scene: &Path, out: &Path, initial: Option<&Path>) -> Output {
    let mut c = Command::new(env!("CARGO_BIN_EXE_rodnet"));
    c.arg("solve")
        .arg(scene)
        .args(["--quiet", "--json"])
        .arg(out);
    if let Some(i) = initial {
        c.arg("--initial").arg(i);
    }
    c.output().unwrap()
}

fn json(p: &Path) -> serde_json::Value {
    serde_json::from_slice(&std::fs::read(p).unwrap()).unwrap()
}

fn err(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// The cantilever's text with `edit` applied, written to `dir/name.ron`.
fn variant(dir: &Path, name: &str, edit: impl Fn(String) -> String) -> PathBuf {
    let p = dir.join(format!("{name}.ron"));
    std::fs::write(&p, edit(std::fs::read_to_string(CANTILEVER).unwrap())).unwrap();
    p
}

/// Results of versions whose clamp was elsewhere (the other end; the whole beam 0.5 m higher)
/// restart to the cantilever's own equilibrium: the clamp is where the scene puts it and the
/// energy is the fresh solve's (−0.4436 J, the elastica of P L²/EI = 2).
#[test]
fn a_restart_holds_the_scenes_supports_not_the_files() {
    let d = temp("supports");
    let fresh = d.join("fresh.json");
    assert!(solve(Path::new(CANTILEVER), &fresh, None).status.success());
    let e_fresh = json(&fresh)["energy"]["total"].as_f64().unwrap();
    let other_end = variant(&d, "other_end", |t| {
        t.replace("vertex: 0, kind: Clamp", "vertex: 1, kind: Clamp")
            .replace(
                "Force(rod: \"beam\", vertex: 1",
                "Force(rod: \"beam\", vertex: 0",
            )
    });
    let higher = variant(&d, "higher", |t| {
        t.replace(
            "(0.0, 0.0, 0.0), (1.0, 0.0, 0.0)",
            "(0.0, 0.5, 0.0), (1.0, 0.5, 0.0)",
        )
    });
    for old in [other_end, higher] {
        let old_out = d.join("old.json");
        assert!(solve(&old, &old_out, None).status.success());
        let again = d.join("again.json");
        let o = solve(Path::new(CANTILEVER), &again, Some(&old_out));
        assert!(o.status.success(), "{old:?}: {}", err(&o));
        let j = json(&again);
        let e = j["energy"]["total"].as_f64().unwrap();
        assert!(
            (e - e_fresh).abs() <= 1e-9 * e_fresh.abs(),
            "{old:?}: restart energy {e} J, fresh {e_fresh} J"
        );
        let clamp = &j["rods"][0]["points"][0];
        for k in 0..3 {
            assert_eq!(clamp[k].as_f64().unwrap(), 0.0, "{old:?}: clamp at {clamp}");
        }
    }
}

/// Rewrites the first rod of a results file with `edit` and restarts the cantilever from it.
fn restart_edited(name: &str, edit: impl Fn(&mut serde_json::Value)) -> Output {
    let d = temp(name);
    let a = d.join("a.json");
    assert!(solve(Path::new(CANTILEVER), &a, None).status.success());
    let mut j = json(&a);
    edit(&mut j);
    // serde_json writes NaN as null: the NaN case is written by hand below.
    let text = serde_json::to_string(&j).unwrap().replace("\"NAN\"", "NaN");
    std::fs::write(&a, text).unwrap();
    solve(Path::new(CANTILEVER), &d.join("b.json"), Some(&a))
}

/// A twist of 1e19 rad, a NaN twist (null, as serde_json writes it), a point 1e19 m away:
/// refused with exit 2, naming the rod and the entry; a literal NaN (as Python writes it) is
/// not JSON: refused with its line and column.
#[test]
fn values_a_state_cannot_hold_are_refused_with_their_place() {
    let cases: [(&str, serde_json::Value, &str); 4] = [
        ("twist", serde_json::json!(1e19), "beam\"].twist[3]"),
        ("twist", serde_json::Value::Null, "beam\"].twist[3]"),
        ("twist", serde_json::json!("NAN"), "column"),
        (
            "points",
            serde_json::json!([1e19, 0.0, 0.0]),
            "beam\"].points[3]",
        ),
    ];
    for (i, (key, value, place)) in cases.into_iter().enumerate() {
        let o = restart_edited(&format!("value{i}"), |j| {
            j["rods"][0][key][3] = value.clone();
        });
        let e = err(&o);
        assert_eq!(o.status.code(), Some(2), "{key} = {value}: {e}");
        assert!(e.contains(place), "{key} = {value}: {e}");
    }
}

/// Results with an extra rod or a different set of joints are another scene's.
#[test]
fn results_with_other_rods_or_joints_are_refused() {
    let o = restart_edited("extra_rod", |j| {
        let mut other = j["rods"][0].clone();
        other["name"] = serde_json::json!("ghost");
        j["rods"].as_array_mut().unwrap().push(other);
    });
    assert_eq!(o.status.code(), Some(2), "{}", err(&o));
    assert!(err(&o).contains("2 rods"), "{}", err(&o));
    let o = restart_edited("extra_joint", |j| {
        j["joints"] = serde_json::json!([{"name": "J", "position": [0.0, 0.0, 0.0]}]);
    });
    assert_eq!(o.status.code(), Some(2), "{}", err(&o));
    assert!(err(&o).contains("joint \"J\""), "{}", err(&o));
}
