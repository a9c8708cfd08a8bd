//! `rodnet solve --extrapolate`: the Richardson extrapolate of a solve and its doubled
//! subdivision, checked against an independent solution of the extensible elastica.

use std::process::Command;

use rodnet::pipeline::settings_of;
use rodnet::scene::Scene;
use rodnet::study::extrapolate;

const CANTILEVER: &str = "networks/cantilever.ron";
/// networks/cantilever.ron: E = 1e8 Pa, r = 0.01 m, L = 1 m.
const EI: f64 = 1e8 * std::f64::consts::PI * 1e-8 / 4.0;
const EA: f64 = 1e8 * std::f64::consts::PI * 1e-4;
/// PL²/EI of the test (the cantilever).
const LOAD: f64 = 5.0;

/// The cantilever with its tip load raised to PL²/EI = `LOAD`, default solver settings.
fn cantilever(subdivide: usize) -> Scene {
    let text = std::fs::read_to_string(CANTILEVER)
        .unwrap()
        .replace("subdivide: 40", &format!("subdivide: {subdivide}"))
        .replace("-1.5707963267948966", &format!("{}", -LOAD * EI))
        .replace("solver: Solver(max_iterations: 200, load_steps: 1),", "");
    rodnet::scene::parse(CANTILEVER, &text).unwrap()
}

/// Tip position of the extensible elastica clamped at the origin along +x with a tip force
/// P = LOAD·EI/L² along −y: θ' = κ (per rest length), EI κ' = −P (1 + ε) cos θ, ε = P sin θ/EA
/// (the tension along the tangent), x' = (1 + ε) cos θ, y' = −(1 + ε) sin θ; shooting on κ(0)
/// for κ(L) = 0 with classical Runge–Kutta in `n` steps.
fn elastica_tip(n: usize) -> [f64; 2] {
    let p = LOAD * EI;
    let f = |y: [f64; 4]| {
        let eps = p * y[0].sin() / EA;
        [
            y[1],
            -p / EI * (1.0 + eps) * y[0].cos(),
            (1.0 + eps) * y[0].cos(),
            -(1.0 + eps) * y[0].sin(),
        ]
    };
    let shoot = |k0: f64| {
        let h = 1.0 / n as f64;
        let mut y = [0.0, k0, 0.0, 0.0];
        let step = |y: [f64; 4], k: [f64; 4], s: f64| std::array::from_fn(|i| y[i] + s * k[i]);
        for _ in 0..n {
            let k1 = f(y);
            let k2 = f(step(y, k1, h / 2.0));
            let k3 = f(step(y, k2, h / 2.0));
            let k4 = f(step(y, k3, h));
            y = std::array::from_fn(|i| {
                y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i])
            });
        }
        y
    };
    // κ(L) grows with κ(0); bisection on [0, 2·LOAD].
    let (mut lo, mut hi) = (0.0, 2.0 * LOAD);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if shoot(mid)[1] > 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let y = shoot(0.5 * (lo + hi));
    [y[2], y[3]]
}

fn distance(a: [f64; 3], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

#[test]
fn the_elastica_reference_is_converged() {
    let (a, b) = (elastica_tip(1000), elastica_tip(2000));
    assert!(distance([a[0], a[1], 0.0], b) < 1e-10, "{a:?} {b:?}");
    // Inextensible limit (EA → ∞) would be (0.61237164, −0.71379152); stretching moves the tip
    // by about P/EA·L.
    assert!(
        (b[0] - 0.6123942).abs() < 1e-6 && (b[1] + 0.7138801).abs() < 1e-6,
        "{b:?}"
    );
}

/// The extrapolate removes the h² error: it is at least 4× closer to the elastica than the
/// finer solve and shrinks faster than h² under refinement; at 12 edges it is within 1e-4·L.
/// The error estimate of the finer solve is its actual error up to the next term, O(h): within
/// 1.5/n relative. Measured (8, 12, 16 edges): extrapolate 5.0, 7.5, 10× closer; estimate
/// 15.3, 10.7, 8.0 % under (1.22–1.28/n). With the plain Voronoi weights the finer solve was
/// 2.5× less accurate and the extrapolate 1.1–1.2× (it was 11.6× closer than the finer solve,
/// the estimate 8.6–4.9 % under): the end correction removed most of the h² term that the
/// extrapolate removes, and what it leaves at these n is the h³ term.
#[test]
fn extrapolated_cantilever_converges_faster_than_h_squared() {
    let reference = elastica_tip(2000);
    let mut errors = Vec::new();
    for n in [8, 12, 16] {
        let s = cantilever(n);
        let sol = extrapolate::solve(&s, &settings_of(&s)).unwrap();
        let r = &sol.results;
        assert!(r.converged, "{n}: {:?}", r.solver.message);
        let x = r.extrapolation.as_ref().expect("extrapolation block");
        assert_eq!(x.subdivide, vec![[n, 2 * n]]);
        let fine_error = distance(*r.rods[0].points.last().unwrap(), reference);
        let extrapolated_error = distance(*x.rods[0].points.last().unwrap(), reference);
        assert_eq!(x.rods[0].points.len(), n + 1);
        assert!(
            (x.error_estimate / fine_error - 1.0).abs() < 1.5 / n as f64,
            "{n}: estimate {:.3e}, actual {fine_error:.3e}",
            x.error_estimate
        );
        assert!(
            extrapolated_error < 0.25 * fine_error,
            "{n}: extrapolate {extrapolated_error:.3e}, finer solve {fine_error:.3e}"
        );
        // The finer solve starts from the coarse equilibrium: a few Newton iterations.
        assert!(x.fine_iterations <= 6, "{n}: {}", x.fine_iterations);
        errors.push(extrapolated_error);
    }
    // 8 → 16 edges: an h² error would fall 4×; the extrapolate's falls more than 2^2.5.
    assert!(errors[0] / errors[2] > 2f64.powf(2.5), "{errors:?}");
    assert!(errors[1] < 1e-4, "12 edges: {:.3e}", errors[1]);
}

/// Three levels (×1, ×2, ×4) remove the h² and the h³ terms: on the cantilever, whose error
/// has both, the extrapolate is more than 50× closer to the elastica than the finest solve and
/// more than 20× closer than the two-level extrapolate of the same coarse subdivision. The
/// finest solve's error estimate is its error to within 1.5/n of the finest n, and the
/// extrapolate's own estimate bounds its actual error. Measured (8, 12, 16 coarse edges):
/// 139, 222, 310× closer than the finest solve, 104, 113, 120× closer than two levels; the
/// finest solve's estimate 0.5, 0.1, 0.03 % off; observed order 1.79, 1.86, 1.89.
#[test]
fn three_levels_remove_the_h_cubed_term_too() {
    let reference = elastica_tip(2000);
    for n in [8, 12, 16] {
        let s = cantilever(n);
        let settings = settings_of(&s);
        let two = extrapolate::solve_levels(&s, &settings, 2).unwrap();
        let three = extrapolate::solve_levels(&s, &settings, 3).unwrap();
        let (x2, x3) = (
            two.results.extrapolation.as_ref().unwrap(),
            three.results.extrapolation.as_ref().unwrap(),
        );
        assert_eq!((x2.levels, x3.levels), (2, 3));
        assert_eq!(x3.subdivide, vec![[n, 4 * n]]);
        assert_eq!(three.results.rods[0].points.len(), 4 * n + 1);
        let tip = |p: &[[f64; 3]]| distance(*p.last().unwrap(), reference);
        let finest = tip(&three.results.rods[0].points);
        let (e2, e3) = (tip(&x2.rods[0].points), tip(&x3.rods[0].points));
        assert!(
            e3 < finest / 50.0,
            "{n}: extrapolate {e3:.3e}, finest {finest:.3e}"
        );
        assert!(e3 < e2 / 20.0, "{n}: three levels {e3:.3e}, two {e2:.3e}");
        assert!(
            (x3.error_estimate / finest - 1.0).abs() < 1.5 / (4 * n) as f64,
            "{n}: estimate {:.3e}, actual {finest:.3e}",
            x3.error_estimate
        );
        let own = x3.extrapolate_error_estimate.unwrap();
        assert!(own >= e3, "{n}: own estimate {own:.3e} < actual {e3:.3e}");
        let p = x3.observed_order.unwrap();
        assert!((1.5..2.5).contains(&p), "{n}: observed order {p}");
        assert!(x3.middle_iterations.unwrap() <= 6 && x3.fine_iterations <= 6);
    }
}

/// The L-frame (networks/l_frame.ron, 20 edges per rod), a linear problem whose tip error is
/// O(h³) once the end-corrected weights remove the h² term at the clamp and the corner: two
/// levels over-correct (the extrapolate is 1.33× as far off as the finer solve), three remove
/// both terms. Measured: tip deflection errors 3.75e-6 (two levels) and 7.5e-11 (three) of the
/// exact P(a³ + b³)/(3EI) + Pab²/GJ; energy −Pδ/2 to 4e-11.
#[test]
fn three_levels_fix_the_over_correction_of_a_third_order_frame() {
    let path = "networks/l_frame.ron";
    let s = rodnet::scene::parse(path, &std::fs::read_to_string(path).unwrap()).unwrap();
    let exact = s.reference.as_ref().unwrap().position[2];
    let settings = settings_of(&s);
    let z = |levels: usize| {
        let sol = extrapolate::solve_levels(&s, &settings, levels).unwrap();
        let x = sol.results.extrapolation.unwrap();
        (x.rods[1].points.last().unwrap()[2], x.energy)
    };
    let ((z2, _), (z3, energy3)) = (z(2), z(3));
    let (e2, e3) = (((z2 - exact) / exact).abs(), ((z3 - exact) / exact).abs());
    assert!(e2 > 1e-6, "two levels: {e2:.3e}");
    assert!(
        e3 < 1e-8 && e3 < 1e-3 * e2,
        "three levels {e3:.3e}, two {e2:.3e}"
    );
    let p = 1e-5;
    assert!(
        (energy3 / (-0.5 * p * exact) - 1.0).abs() < 1e-8,
        "{energy3:e}"
    );
}

fn rodnet() -> Command {
    Command::new(env!("CARGO_BIN_EXE_rodnet"))
}

#[test]
fn extrapolate_on_the_command_line() {
    let d = std::env::temp_dir().join(format!("rodnet-extrapolate-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    let json = d.join("r.json");
    let out = rodnet()
        .args([
            "solve",
            "networks/extreme/ring.ron",
            "--extrapolate",
            "--json",
        ])
        .arg(&json)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0), "{out:?}");
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains("extrapolated from subdivisions"),
        "{stdout}"
    );
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    // A closed rod (its points end with the first again): the extrapolate has the coarse
    // nodes, the results the fine ones, and the finer solve restarted from the coarse state.
    let x = &v["extrapolation"];
    let coarse = x["rods"][0]["points"].as_array().unwrap().len();
    let fine = v["rods"][0]["points"].as_array().unwrap().len();
    assert_eq!(fine, 2 * coarse - 1, "{coarse} {fine}");
    assert!(x["fine_iterations"].as_u64().unwrap() <= 10, "{x}");
    assert!(x["error_estimate"].as_f64().unwrap() > 0.0);

    // Three levels: the extra fields, the (coarse, finest) subdivisions.
    let json3 = d.join("r3.json");
    let out = rodnet()
        .args([
            "solve",
            "networks/l_frame.ron",
            "--extrapolate",
            "--levels",
            "3",
            "--json",
        ])
        .arg(&json3)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0), "{out:?}");
    assert!(String::from_utf8_lossy(&out.stdout).contains("×1, ×2 and ×4"));
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json3).unwrap()).unwrap();
    let x = &v["extrapolation"];
    assert_eq!(x["levels"], 3);
    assert_eq!(x["order"], 3.0);
    assert_eq!(x["subdivide"], serde_json::json!([[20, 80], [20, 80]]));
    for key in [
        "middle_iterations",
        "observed_order",
        "extrapolate_error_estimate",
    ] {
        assert!(x[key].is_number(), "{key}: {x}");
    }
    // A finest level above the memory limit is refused before anything is written, naming the
    // level (the cantilever at ×4 needs about 9.2 MiB; its ×1 and ×2 levels fit in 9 MiB).
    let big = d.join("big.json");
    let out = rodnet()
        .args([
            "solve",
            "networks/cantilever.ron",
            "--extrapolate",
            "--levels",
            "3",
        ])
        .args(["--max-memory", "9M", "--json"])
        .arg(&big)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2), "{out:?}");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("level 3 of --extrapolate") && err.contains("subdivide"),
        "{err}"
    );
    assert!(!big.exists());

    // --levels takes 2 or 3, and only with --extrapolate.
    for args in [
        &["--extrapolate", "--levels", "4"][..],
        &["--levels", "3"][..],
    ] {
        let bad = rodnet()
            .args(["solve", "networks/l_frame.ron"])
            .args(args)
            .output()
            .unwrap();
        assert_eq!(bad.status.code(), Some(2), "{args:?}");
        assert!(String::from_utf8_lossy(&bad.stderr).contains("--levels"));
    }

    // A staged scene (an arch erected by its clamps, then loaded at its crown) is extrapolated
    // at its last stage, each level solved through the stages: two and three levels agree on
    // the crown to a tenth of the finer solve's estimated error (measured 2.2e-6 m against
    // 2.5e-4 m).
    let crown = |levels: &str| {
        let out = d.join(format!("staged{levels}.json"));
        let o = rodnet()
            .args(["solve", "networks/arch_erect_then_load.ron", "--quiet"])
            .args(["--extrapolate", "--levels", levels, "--json"])
            .arg(&out)
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(0), "{o:?}");
        let v: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
        assert_eq!(v["stage"]["name"], "crown_load");
        let x = &v["extrapolation"];
        (
            x["rods"][0]["points"][16][2].as_f64().unwrap(),
            x["error_estimate"].as_f64().unwrap(),
        )
    };
    let ((z2, estimate2), (z3, _)) = (crown("2"), crown("3"));
    assert!(
        (z2 - z3).abs() < 0.1 * estimate2,
        "{z2} vs {z3}, estimate {estimate2:e}"
    );

    // --initial is another start: refused with exit 2.
    let both = rodnet()
        .args([
            "solve",
            "networks/cantilever.ron",
            "--extrapolate",
            "--initial",
        ])
        .arg(&json)
        .output()
        .unwrap();
    assert_eq!(both.status.code(), Some(2));
    std::fs::remove_dir_all(&d).ok();
}
