//! `rodnet states`: the equilibria of a scene that pushes from its own equilibrium reach.

use std::process::Command;

fn rodnet() -> Command {
    Command::new(env!("CARGO_BIN_EXE_rodnet"))
}

#[test]
fn a_buckled_strip_has_two_mirror_states_and_the_straight_one() {
    let d = std::env::temp_dir().join(format!("rodnet-states-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    let out = rodnet()
        .args([
            "states",
            "networks/buckled_strip.ron",
            "--quiet",
            "--out-dir",
        ])
        .arg(&d)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let s: serde_json::Value =
        serde_json::from_slice(&std::fs::read(d.join("states.json")).unwrap()).unwrap();
    let all = s["states"].as_array().unwrap();
    assert_eq!(all.len(), 3, "{s}");
    // The third is the strip held straight, found by residual Newton from rest: uniformly
    // compressed by 10 %, energy ½·EA·ε²·L = 100 J, unstable (many negative eigenvalues).
    let straight = &all[2];
    assert_eq!(straight["stable"], false);
    assert!(straight["index"].as_u64().unwrap() >= 1);
    let e2 = straight["energy"].as_f64().unwrap();
    let ea = 1e9 * 0.01 * 0.002;
    assert!((e2 - 0.5 * ea * 0.01).abs() < 1e-9 * e2, "{e2}");
    assert_eq!(straight["found_by"], "residual Newton from rest");
    let states = &all[..2];
    let e: Vec<f64> = states
        .iter()
        .map(|x| x["energy"].as_f64().unwrap())
        .collect();
    assert!((e[0] - e[1]).abs() < 1e-9 * e[0], "{e:?}");
    let mid_z = |k: usize| {
        let r: serde_json::Value = serde_json::from_slice(
            &std::fs::read(d.join(states[k]["results"].as_str().unwrap())).unwrap(),
        )
        .unwrap();
        assert!(r["converged"].as_bool().unwrap());
        r["rods"][0]["points"][20][2].as_f64().unwrap()
    };
    let (z0, z1) = (mid_z(0), mid_z(1));
    assert!(z0 > 0.1 && (z0 + z1).abs() < 1e-6 * z0, "{z0} {z1}");
    for st in states {
        assert_eq!(st["stable"], true);
        assert_eq!(st["index"], 0);
        assert!(st["lowest_eigenvalue"].as_f64().unwrap() > 0.0);
    }
    assert_eq!(states[0]["found_by"], "scene");
    // The second is a copy of the first under a symmetry (its mirror image); the straight one
    // is no one's.
    assert_eq!(states[1]["symmetric_to"], 0);
    // Up and down: the crown moves by twice its height.
    let d1 = states[1]["distance_to_first"].as_f64().unwrap();
    assert!((d1 - 2.0 * z0).abs() < 1e-6 * z0, "{d1} {z0}");
    assert!(states[0].get("symmetric_to").is_none() && straight.get("symmetric_to").is_none());
    // --max bounds the search.
    let out = rodnet()
        .args([
            "states",
            "networks/buckled_strip.ron",
            "--quiet",
            "--max",
            "1",
            "--out-dir",
        ])
        .arg(&d)
        .output()
        .unwrap();
    assert!(out.status.success());
    let s: serde_json::Value =
        serde_json::from_slice(&std::fs::read(d.join("states.json")).unwrap()).unwrap();
    assert_eq!(s["states"].as_array().unwrap().len(), 1);
}

#[test]
fn states_refuses_what_it_cannot_search() {
    let d = std::env::temp_dir().join(format!("rodnet-states-bad-{}", std::process::id()));
    let out = rodnet()
        .args(["states", "networks/rod_over_sphere.ron", "--out-dir"])
        .arg(&d)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("contact"), "{err}");
    assert!(!d.exists(), "nothing is created on bad input");
}
