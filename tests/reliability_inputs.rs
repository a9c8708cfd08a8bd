//! Issue 39, the small cases: values that were accepted and then lost or misread are refused at
//! their place. The bad-scene corpus (tests/bad_scenes, `rod_name_control_character`,
//! `rod_far_from_the_others`) holds the scene-file cases; these are the OBJ network and sweep ones.

mod common;

use common::cli::{rodnet, text, tmpdir};

/// An OBJ network whose coordinates are beyond the scene limit (1e100 m) is refused at the
/// vertex's line: the default weld tolerance (1e-6 × the bounding box's diagonal) overflowed to
/// infinity there and reported every segment as zero-length "within the weld tolerance inf m".
#[test]
fn obj_vertices_beyond_the_scene_limit_are_refused_at_their_line() {
    let d = tmpdir("rel-in", "obj");
    for (x, line) in [("1e200", 2), ("1e308", 2)] {
        let obj = d.join("big.obj");
        std::fs::write(&obj, format!("v 0 0 0\nv {x} 0 0\nv 0 1 0\nl 1 3\nl 3 2\n")).unwrap();
        let o = rodnet()
            .args(["solve", "--network"])
            .arg(&obj)
            .args([
                "--young-modulus",
                "1e9",
                "--radius",
                "0.01",
                "--poisson-ratio",
                "0.3",
                "--quiet",
            ])
            .output()
            .unwrap();
        let t = text(&o);
        assert_eq!(o.status.code(), Some(2), "{x}: {t}");
        assert!(t.contains(&format!("big.obj:{line}:")), "{x}: {t}");
        assert!(t.contains("vertex 2: coordinate"), "{x}: {t}");
        assert!(!t.contains("inf m"), "{x}: {t}");
    }
}

/// The sweep option `vtk` (an output of `rodnet gridshell hemisphere`) chose a file that no
/// point wrote; a sweep refuses it, naming it, before any solve.
#[test]
fn a_sweep_refuses_the_vtk_output_option_by_name() {
    let d = tmpdir("rel-in", "vtk");
    let sweep = d.join("dome.ron");
    std::fs::write(
        &sweep,
        r#"Sweep(
    hemisphere: {"subdivide": 2, "vtk": "dome.vtp"},
    grid: {"rods": [4, 6]},
    output: "out",
)
"#,
    )
    .unwrap();
    let o = rodnet().arg("sweep").arg(&sweep).output().unwrap();
    let t = text(&o);
    assert_eq!(o.status.code(), Some(2), "{t}");
    assert!(t.contains("dome.ron:2:"), "{t}");
    assert!(
        t.contains("not an option of the hemisphere generator"),
        "{t}"
    );
    assert!(!d.join("out").exists(), "a refused sweep solved something");
}

/// A scene's `Mesh` target: a relative path that leads out of the scene's folder (by `..` or a
/// symbolic link) is refused at `target.path` before anything is read, and a mesh's bad record
/// is named by its line without quoting the file's text (a scene from elsewhere must not read
/// or show the user's other files). A mesh beside the scene, or named by an absolute path, is
/// read as before.
#[test]
fn a_mesh_target_stays_in_the_scene_folder_and_is_never_quoted() {
    let d = tmpdir("rel-in", "mesh");
    let scenes = d.join("scenes");
    std::fs::create_dir_all(&scenes).unwrap();
    std::fs::write(d.join("secret.txt"), "f hunter2secret\n").unwrap();
    std::fs::write(scenes.join("inside.txt"), "v 0 0 0\nf hunter2secret\n").unwrap();
    #[cfg(unix)]
    std::os::unix::fs::symlink(d.join("secret.txt"), scenes.join("link.obj")).unwrap();
    let scene = |path: &str| {
        let text = std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/networks/cantilever.ron"
        ))
        .unwrap()
        .replace(
            "solver: Solver(",
            &format!("target: Some(Mesh(path: {path:?})),\n    solver: Solver("),
        );
        let f = scenes.join("s.ron");
        std::fs::write(&f, text).unwrap();
        rodnet()
            .args(["solve", "--quiet", "--json"])
            .arg(d.join("out.json"))
            .arg(&f)
            .output()
            .unwrap()
    };
    let mut cases = vec![("../secret.txt", true)];
    if cfg!(unix) {
        cases.push(("link.obj", true));
    }
    cases.push(("inside.txt", false));
    for (path, outside) in cases {
        let o = scene(path);
        let t = text(&o);
        assert_eq!(o.status.code(), Some(2), "{path}: {t}");
        assert!(!t.contains("hunter2"), "{path}: {t}");
        assert!(!d.join("out.json").exists(), "{path}");
        if outside {
            assert!(
                t.contains("target.path") && t.contains("outside the scene file's folder"),
                "{path}: {t}"
            );
        } else {
            assert!(
                t.contains("inside.txt:2:1") && t.contains("face corner"),
                "{t}"
            );
        }
    }
    // Absolute: read (and its bad record named, not quoted).
    let abs = d.join("secret.txt").display().to_string();
    let t = text(&scene(&abs));
    assert!(
        t.contains("secret.txt:1:1") && !t.contains("hunter2"),
        "{t}"
    );
}

/// A sweep's `output` is a folder next to the sweep file: a relative one that climbs out of it
/// is refused (exit 2, at `output`) before anything is solved or created. `sweep merge` writes
/// its table only into the manifest's own folder or one holding the manifest's points, and only
/// from point files whose inputs (fingerprints) are the manifest's: a hand-edited manifest
/// cannot make it write elsewhere, and points solved from an earlier version of the base scene
/// are listed missing, not merged.
#[test]
fn sweep_outputs_stay_home_and_merge_takes_only_current_points() {
    let d = tmpdir("rel-in", "sweep-out");
    let beam = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/networks/cantilever.ron"
    ))
    .unwrap();
    let home = d.join("home");
    std::fs::create_dir_all(&home).unwrap();
    std::fs::write(home.join("beam.ron"), &beam).unwrap();
    let sweep = |out: &str| {
        format!(
            "Sweep(scene: \"beam.ron\", grid: {{\"materials.steel.young_modulus\": [1e8, 2e8]}}, \
             output: {out:?})"
        )
    };
    std::fs::write(home.join("away.ron"), sweep("../elsewhere")).unwrap();
    let o = rodnet()
        .arg("sweep")
        .arg(home.join("away.ron"))
        .output()
        .unwrap();
    let t = text(&o);
    assert_eq!(o.status.code(), Some(2), "{t}");
    assert!(
        t.contains("output") && t.contains("outside the sweep file's folder"),
        "{t}"
    );
    assert!(!d.join("elsewhere").exists());

    std::fs::write(home.join("s.ron"), sweep("out")).unwrap();
    let o = rodnet()
        .arg("sweep")
        .arg(home.join("s.ron"))
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    let merge =
        |dir: &std::path::Path| rodnet().args(["sweep", "merge"]).arg(dir).output().unwrap();

    // The manifest's points, solved from another base scene: stale, so missing.
    std::fs::write(
        home.join("beam.ron"),
        beam.replace("-1.5707963267948966", "-3.0"),
    )
    .unwrap();
    let array = home.join("array");
    let o = rodnet()
        .arg("sweep")
        .arg(home.join("s.ron"))
        .args(["--emit", "slurm"])
        .arg(&array)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    let o = merge(&array);
    let t = text(&o);
    assert_ne!(o.status.code(), Some(0), "{t}");
    assert!(t.contains("2 point(s) missing"), "{t}");

    // A manifest edited to name another folder: nothing written there.
    let victim = d.join("victim");
    std::fs::create_dir_all(&victim).unwrap();
    let manifest = home.join("out/manifest.json");
    let text_m = std::fs::read_to_string(&manifest).unwrap();
    let mut m: serde_json::Value = serde_json::from_str(&text_m).unwrap();
    m["output"] = serde_json::json!(victim);
    let edited = d.join("edited");
    std::fs::create_dir_all(&edited).unwrap();
    std::fs::write(edited.join("manifest.json"), m.to_string()).unwrap();
    let o = merge(&edited);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert_eq!(std::fs::read_dir(&victim).unwrap().count(), 0);
    // And point names that reach other folders are refused.
    m["output"] = serde_json::json!(home.join("out"));
    m["points"][0]["name"] = serde_json::json!("../../victim/x");
    std::fs::write(edited.join("manifest.json"), m.to_string()).unwrap();
    let o = merge(&edited);
    let t = text(&o);
    assert_eq!(o.status.code(), Some(2), "{t}");
    assert!(t.contains("not a plain file name"), "{t}");
}

/// A sweep whose point file cannot be written where it is (a directory stands at its path) is
/// refused before any point is solved (exit 2, naming the path), instead of exiting 2 after
/// solving every point.
#[test]
fn a_sweep_refuses_an_unwritable_point_file_before_solving() {
    let d = tmpdir("rel-in", "sweep-dir");
    std::fs::write(
        d.join("beam.ron"),
        std::fs::read_to_string(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/networks/cantilever.ron"
        ))
        .unwrap(),
    )
    .unwrap();
    let sweep = |name: &str| {
        let f = d.join(format!("{name}.ron"));
        std::fs::write(
            &f,
            format!(
                "Sweep(scene: \"beam.ron\", grid: {{\"materials.steel.young_modulus\": [1e8, \
                 2e8]}}, output: \"{name}\")"
            ),
        )
        .unwrap();
        rodnet().arg("sweep").arg(f).output().unwrap()
    };
    let o = sweep("first");
    assert_eq!(o.status.code(), Some(0), "{}", text(&o));
    let mut names: Vec<String> = std::fs::read_dir(d.join("first"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".json") && n != "manifest.json")
        .collect();
    names.sort();
    assert_eq!(names.len(), 2, "{names:?}");
    std::fs::create_dir_all(d.join("second").join(&names[1])).unwrap();
    let o = sweep("second");
    let t = text(&o);
    assert_eq!(o.status.code(), Some(2), "{t}");
    assert!(t.contains(&names[1]) && t.contains("directory"), "{t}");
    assert!(
        !d.join("second").join(&names[0]).exists(),
        "a point was solved: {t}"
    );
}
