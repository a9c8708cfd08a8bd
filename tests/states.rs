//! `rodnet states`: the equilibria of a scene that pushes from its own equilibrium reach.

mod support;

use std::process::Command;

use support::euler_buckling_postbuckled_at_load;

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
    assert_eq!(all.len(), 4, "{s}");
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
    // The fourth is the barrier between up and down, found where the force holding the crown
    // changes sign on the path between them: the S-shaped (mode 2) strip, index 1, its crown
    // at the clamps' height and each half the other's image turned about the midpoint. Its
    // energy is (P₂/P₁ = 2.046, the ratio of the clamped strut's second and first buckling
    // loads) that of the bowed states in the limit of small shortening; 2.024 at 10 %.
    let s_shape = &all[3];
    assert_eq!(s_shape["index"], 1, "{s_shape}");
    assert_eq!(s_shape["stable"], false);
    assert!(s_shape["found_by"]
        .as_str()
        .unwrap()
        .starts_with("residual Newton from the path between states 0 and 1"));
    let r: serde_json::Value = serde_json::from_slice(
        &std::fs::read(d.join(s_shape["results"].as_str().unwrap())).unwrap(),
    )
    .unwrap();
    let p = r["rods"][0]["points"].as_array().unwrap();
    let z = |i: usize| p[i][2].as_f64().unwrap();
    assert!(z(20).abs() < 1e-9 * z0, "{}", z(20));
    let turned = (0..=40)
        .map(|i| (z(i) + z(40 - i)).abs())
        .fold(0.0, f64::max);
    assert!(
        turned < 1e-9 * z0 && (0..=40).any(|i| z(i).abs() > 0.25 * z0),
        "{turned}"
    );
    let ratio = s_shape["energy"].as_f64().unwrap() / e[0];
    assert!((1.9..2.1).contains(&ratio), "{ratio}");
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

/// The post-buckled Euler column of `networks/euler_column_postbuckled.ron` (clamped base,
/// tip force P = 1.52 P_c about the weak axis): bent one way (the scene's own solve, toward +y)
/// and the other (reversed), with the elastica's tip deflection and energy, and the straight
/// column, index 1 (only the weak-axis mode is past its critical load). The cantilever is half
/// of a pinned–pinned strut of length 2L: P(2L)²/EI = 15 gives its modulus k, tip angle
/// 2 asin k, tip deflection (w/L')·2L and shortening (d/L')·L; its energy, bending EI/2 ∫θ'²
/// = P(x_tip − L cos α) plus the load's −P(L − x_tip), is P(2 x_tip − L(1 + cos α)). Errors at
/// 32 edges: tip deflection +6.1e-4, energy +2.9e-3; second order (64 edges: 1.5e-4, 7.3e-4;
/// 16: 2.3e-3, 1.1e-2); the rod's extension changes them by 1e-6.
#[test]
fn the_post_buckled_euler_column_has_two_mirror_states_and_the_straight_one() {
    let (e, b, t, l, p): (f64, f64, f64, f64, f64) = (1e9, 0.004, 0.002, 1.0, 0.01);
    let (ei, ea) = (e * b * t.powi(3) / 12.0, e * b * t);
    let (strut, shortening) = euler_buckling_postbuckled_at_load(p * (2.0 * l).powi(2) / ei);
    let tip = strut.midspan_deflection * 2.0 * l;
    let x_tip = l * (1.0 - shortening);
    let energy = p * (2.0 * x_tip - l * (1.0 + strut.end_angle.cos()));
    let d = std::env::temp_dir().join(format!("rodnet-states-euler-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    let mut errors = Vec::new();
    for n in [32, 64] {
        let src = std::fs::read_to_string("networks/euler_column_postbuckled.ron")
            .unwrap()
            .replace("subdivide: 32", &format!("subdivide: {n}"));
        let scene = d.with_extension(format!("{n}.ron"));
        std::fs::write(&scene, src).unwrap();
        let out = rodnet()
            .args(["states", "--quiet", "--out-dir"])
            .arg(&d)
            .arg(&scene)
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
        let tip_of = |k: usize| {
            let r: serde_json::Value = serde_json::from_slice(
                &std::fs::read(d.join(all[k]["results"].as_str().unwrap())).unwrap(),
            )
            .unwrap();
            let last = r["rods"][0]["points"]
                .as_array()
                .unwrap()
                .last()
                .unwrap()
                .clone();
            [last[1].as_f64().unwrap(), last[2].as_f64().unwrap()]
        };
        let (up, down, straight) = (tip_of(0), tip_of(1), tip_of(2));
        for bent in &all[..2] {
            assert_eq!(bent["stable"], true, "{bent}");
            assert_eq!(bent["index"], 0);
        }
        assert_eq!(all[1]["symmetric_to"], 0);
        assert!((up[0] + down[0]).abs() < 1e-9 * tip && (up[1] - down[1]).abs() < 1e-9);
        let e0 = all[0]["energy"].as_f64().unwrap();
        assert!((all[1]["energy"].as_f64().unwrap() - e0).abs() < 1e-9 * e0.abs());
        errors.push([up[0] / tip - 1.0, e0 / energy - 1.0]);
        // Straight, shortened by PL/EA: energy ½EAε²L − P·PL/EA = −P²L/(2EA), one negative
        // eigenvalue (the weak-axis bending mode).
        assert_eq!(all[2]["found_by"], "residual Newton from rest");
        assert_eq!(all[2]["index"], 1, "{}", all[2]);
        assert_eq!(all[2]["index_at_least"], false);
        assert!(straight[0].abs() < 1e-12 && (straight[1] - (l - p * l / ea)).abs() < 1e-12);
        let e2 = all[2]["energy"].as_f64().unwrap();
        let exact = -p * p * l / (2.0 * ea);
        assert!((e2 - exact).abs() < 1e-9 * exact.abs(), "{e2} vs {exact}");
        assert!(e2 > e0);
    }
    eprintln!("euler column: relative errors (tip, energy) at 32 and 64 edges {errors:?}");
    for k in 0..2 {
        assert!(
            errors[0][k] > 0.0 && errors[0][k] < [1e-3, 4e-3][k],
            "{errors:?}"
        );
        let ratio = errors[0][k] / errors[1][k];
        assert!((3.5..4.5).contains(&ratio), "{errors:?}");
    }
    let _ = std::fs::remove_dir_all(&d);
}
