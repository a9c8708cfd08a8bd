//! Zero modes decided by physics (docs/stability.md): a refined cantilever stays stable, a ring
//! closed by two clamps keeps its neutral turn, a rod spun about its axis by a torque is a
//! mechanism, and `solve --modes` prints the eigenvalues.

use std::path::PathBuf;
use std::process::{Command, Output};

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rodnet-zero-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// `rodnet solve SCENE --json OUT --modes k`: the output and the results JSON.
fn solve(name: &str, scene: &str, k: usize) -> (Output, serde_json::Value) {
    let d = dir(name);
    let (s, j) = (d.join("scene.ron"), d.join("out.json"));
    std::fs::write(&s, scene).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_rodnet"))
        .args(["solve", s.to_str().unwrap(), "--json", j.to_str().unwrap()])
        .args(["--modes", &k.to_string()])
        .output()
        .unwrap();
    let r = serde_json::from_slice(&std::fs::read(&j).unwrap()).unwrap();
    (out, r)
}

fn cantilever(n: usize) -> String {
    std::fs::read_to_string("networks/cantilever.ron")
        .unwrap()
        .replace("subdivide: 40", &format!("subdivide: {n}"))
}

fn eigenvalues(r: &serde_json::Value) -> Vec<f64> {
    r["stability"]["eigenvalues"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect()
}

/// The clamped cantilever of networks/cantilever.ron (r/L = 1e-2, PL²/EI = 2) is stable at 10
/// to 10⁴ edges, in the solver's verdict and the eigen-analysis alike (10⁴ edges: 0.7 s). Its lowest eigenvalue,
/// in N/m against a unit motion of all nodes, is that of the bending mode with ∫w² spread over
/// n nodes: n·λ₁ tends to a constant (the continuum's Rayleigh quotient times L), which the
/// test checks to 3 % from 100 edges on against 2000 — the refined modes are physical, not
/// zeros. At 10⁴ edges the soft pair (1.3e-3 N/m) is 2.7e-16 of the Hessian's scaled diagonal,
/// under the band's round-off floor (1e-13 of it), and was "neutral" before the band of a
/// deforming mode was capped by the rods' bending stiffness (docs/stability.md).
#[test]
fn refined_cantilevers_are_stable() {
    let reference = {
        let (_, r) = solve("c2000", &cantilever(2000), 4);
        2000.0 * eigenvalues(&r)[0]
    };
    for n in [10, 100, 1000, 2000, 10_000] {
        let (out, r) = solve(&format!("c{n}"), &cantilever(n), 4);
        assert!(out.status.success(), "{n} edges: {out:?}");
        assert_eq!(r["converged"], true);
        assert_eq!(r["solver"]["stable"], true, "{n} edges: solver verdict");
        assert_eq!(
            r["stability"]["stable"], true,
            "{n} edges: {}",
            r["stability"]
        );
        assert_eq!(r["stability"]["zero_modes"]["count"], 0);
        let l = eigenvalues(&r);
        assert!(l.iter().all(|&x| x > 0.0), "{n} edges: {l:?}");
        if n >= 100 {
            let ratio = n as f64 * l[0] / reference;
            assert!((ratio - 1.0).abs() < 0.03, "{n} edges: n·λ₁ ratio {ratio}");
        }
    }
}

/// Michell's ring (networks/extreme/michell.ron: one rod closed by clamping both ends at the
/// same point with the same tangent) keeps exactly one zero mode, the turn of its plane about
/// the common tangent: neutral, not stable.
#[test]
fn michell_ring_is_neutral() {
    let scene = std::fs::read_to_string("networks/extreme/michell.ron").unwrap();
    let (out, r) = solve("michell", &scene, 3);
    assert!(out.status.success(), "{out:?}");
    assert_eq!(r["stability"]["stable"], false);
    assert_eq!(r["stability"]["zero_modes"]["count"], 1);
    let kind = r["stability"]["zero_modes"]["kind"].as_str().unwrap();
    assert!(kind.starts_with("neutral"), "{kind}");
    // The neutral turn is orders of magnitude below the ring's softest bending mode.
    let l = eigenvalues(&r);
    assert!(l[0].abs() < 1e-6 * l[1], "{l:?}");
}

/// A free ring (no supports, no loads: the gauge holds one node) at 40, 400 and 4000 edges has
/// exactly its three rigid turns as zero modes (gauge: stable), and its lowest bending mode
/// stays physical: n·λ₄ agrees between 400 and 4000 edges to 1e-3 (a zero would not scale).
#[test]
fn free_rings_have_only_their_rigid_turns_as_zero_modes() {
    let ring = |n: usize| {
        let pts: Vec<String> = (0..n)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / n as f64;
                format!("({:.17}, {:.17}, 0.0)", 0.5 * a.cos(), 0.5 * a.sin())
            })
            .collect();
        format!(
            r#"Scene(
                materials: {{ "steel": Material(young_modulus: 1e9, poisson_ratio: 0.3, section: Circle(radius: 0.01)) }},
                rods: [ Rod(name: "ring", material: "steel", points: [{}], closed: true) ],
            )"#,
            pts.join(", ")
        )
    };
    let mut scaled = Vec::new();
    for n in [40, 400, 4000] {
        let (out, r) = solve(&format!("ring{n}"), &ring(n), 6);
        assert!(out.status.success(), "{out:?}");
        assert_eq!(r["stability"]["stable"], true, "{n}: {}", r["stability"]);
        assert_eq!(r["stability"]["zero_modes"]["count"], 3, "{n}");
        let kind = r["stability"]["zero_modes"]["kind"].as_str().unwrap();
        assert!(kind.starts_with("gauge"), "{kind}");
        scaled.push(n as f64 * eigenvalues(&r)[3]);
    }
    assert!((scaled[1] / scaled[2] - 1.0).abs() < 1e-3, "{scaled:?}");
}

/// A straight rod held by a Pin (or a Ball joint) at one end and turned about its own axis by
/// a torque at the other: nothing resists the spin. Named a mechanism at the start (exit 1), not 1000 Newton
/// iterations without convergence.
#[test]
fn rod_spun_on_a_pin_is_a_mechanism() {
    let scene = r#"Scene(
        materials: { "steel": Material(young_modulus: 1e9, poisson_ratio: 0.3, section: Circle(radius: 0.01)) },
        rods: [ Rod(name: "shaft", material: "steel", points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0)], subdivide: 20) ],
        supports: [ Support(rod: "shaft", vertex: 0, kind: Pin) ],
        loads: [ Torque(rod: "shaft", vertex: 1, torque: (1.0, 0.0, 0.0)) ],
    )"#;
    let (out, r) = solve("spun", scene, 2);
    assert_eq!(out.status.code(), Some(1), "{out:?}");
    assert_eq!(r["converged"], false);
    let d = r["mechanism"]["description"].as_str().unwrap();
    assert!(d.contains("spin of rod \"shaft\""), "{d}");
    assert!(r["iterations"].as_u64().unwrap() < 10);
    // The same shaft on a Ball joint atop a clamped post, its far end on a Roller: the spin
    // is free as on the Pin.
    let ball = r#"Scene(
        materials: { "steel": Material(young_modulus: 1e9, poisson_ratio: 0.3, section: Circle(radius: 0.01)) },
        rods: [
            Rod(name: "post", material: "steel", points: [(0.0, 0.0, -1.0), (0.0, 0.0, 0.0)], subdivide: 10),
            Rod(name: "shaft", material: "steel", points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0)], subdivide: 20),
        ],
        joints: [ Joint(name: "ball", at: [("post", 1), ("shaft", 0)], kind: Ball) ],
        supports: [
            Support(rod: "post", vertex: 0, kind: Clamp),
            Support(rod: "shaft", vertex: 1, kind: Roller(normal: (0.0, 0.0, 1.0))),
        ],
        loads: [ Torque(rod: "shaft", vertex: 1, torque: (1.0, 0.0, 0.0)) ],
    )"#;
    let (out, r) = solve("spun-ball", ball, 2);
    assert_eq!(out.status.code(), Some(1), "{out:?}");
    let d = r["mechanism"]["description"].as_str().unwrap();
    assert!(d.contains("spin of rod \"shaft\""), "{d}");
    // With the spin held by a clamp instead, the same torque twists the rod: no mechanism.
    let held = scene.replace("kind: Pin", "kind: Clamp");
    let (out, r) = solve("spun-held", &held, 2);
    assert!(out.status.success(), "{out:?}");
    assert!(r.get("mechanism").is_none() || r["mechanism"].is_null());
}

/// `solve --modes K` prints the K eigenvalues (N/m) on stderr, the JSON's to 7 digits.
#[test]
fn modes_print_their_eigenvalues() {
    let (out, r) = solve("print", &cantilever(40), 3);
    assert!(out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    let line = err
        .lines()
        .find(|l| l.contains("eigenvalue(s) (N/m):"))
        .unwrap_or_else(|| panic!("no eigenvalue line in {err}"));
    let printed: Vec<f64> = line
        .split("(N/m): ")
        .nth(1)
        .unwrap()
        .split(';')
        .next()
        .unwrap()
        .split(", ")
        .map(|x| x.parse().unwrap())
        .collect();
    let l = eigenvalues(&r);
    assert_eq!(printed.len(), 3);
    for (p, x) in printed.iter().zip(&l) {
        assert!((p - x).abs() <= 1e-6 * x.abs(), "{p} vs {x}");
    }
    assert!(line.ends_with("stable"), "{line}");
}
