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
