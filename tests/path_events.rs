//! Path events of load-controlled solves (issue 37, item 1): a clamped–free column loaded past
//! Euler's load reports one bifurcation at the critical load factor; a stable path reports none.
//! (The shallow arch's bifurcation and snap: tests/bistable_arch.rs.)

mod common;

use std::f64::consts::PI;

use common::*;
use rodnet::pipeline::{settings_of, solve_scene, Limits};
use rodnet::scene::types::*;
use rodnet::solver::path_events::EventKind;

/// Euler's load π²EI/4L² of the weak axis is reached at the load factor P_cr/P: the event is
/// there within the discretization's error (measured: −2.0e-4 at 32 edges, −5e-5 at 64), once,
/// and the column ends buckled and stable.
#[test]
fn euler_column_bifurcates_at_the_critical_load_factor() {
    let ei = COLUMN_EI;
    let p_cr = PI * PI * ei / 4.0;
    for (factor, n, arc) in [
        (1.52, 32, false),
        (3.0, 32, false),
        (1.52, 64, false),
        (1.52, 32, true),
    ] {
        let mut s = column(factor * p_cr, n);
        if arc {
            // Arc length passes the bifurcation on the straight branch, sees the Hessian turn
            // indefinite between two steps and bisects the arc for it; the final Newton
            // iteration at λ = 1 then escapes to the buckled state.
            s.solver.continuation = Continuation::ArcLength;
        }
        let sol = solve_scene(&s, &settings_of(&s)).unwrap();
        let r = &sol.results;
        assert!(r.converged && r.solver.stable, "{:?}", r.solver.message);
        let ev = &r.path_events;
        assert_eq!(ev.len(), 1, "{ev:?}");
        assert_eq!(ev[0].kind, EventKind::Bifurcation);
        let err = ev[0].load_factor * factor - 1.0;
        println!(
            "P = {factor} P_cr, {n} edges: event at {:.6} ({err:.2e})",
            ev[0].load_factor
        );
        assert!(err.abs() < 1e-3, "{ev:?}");
        let tip = r.rods[0].points.last().unwrap();
        assert!(tip[0].hypot(tip[1]) > 0.2, "not buckled: {tip:?}");
    }
}

/// Below Euler's load, and on a bending path that softens but stays stable (the large-load
/// cantilever), no event.
#[test]
fn stable_paths_have_no_events() {
    let ei = COLUMN_EI;
    let s = column(0.9 * PI * PI * ei / 4.0, 32);
    let sol = solve_scene(&s, &settings_of(&s)).unwrap();
    assert!(sol.results.path_events.is_empty());
    let (s, _) = rodnet::scene::load(std::path::Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/networks/cantilever_elastica.ron"
    )))
    .unwrap();
    let sol = solve_scene(&s, &settings_of(&s)).unwrap();
    assert!(sol.results.converged);
    assert!(
        sol.results.path_events.is_empty(),
        "{:?}",
        sol.results.path_events
    );
}

/// A slender, finely divided cantilever (L/r = 3333, 5000 edges) under PL²/EI = 2 in one load
/// step: near the round-off floor its Newton iterates need shifted factorizations and the
/// shifted linear response is short, which reported a snap; the path is smooth and stable
/// (Bisshopp & Drucker's tip, v/L = 0.49345748, u/L = 0.16064172). Measured: no event, tip
/// within 5e-8.
#[test]
fn a_fine_slender_cantilever_does_not_snap() {
    let (mut s, _) = rodnet::scene::load(std::path::Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/networks/cantilever.ron"
    )))
    .unwrap();
    let r = 3e-4;
    let rodnet::rod::section::Section::Circle { radius } =
        &mut s.materials.get_mut("steel").unwrap().section
    else {
        panic!("circle")
    };
    *radius = r;
    s.rods[0].subdivide = 5000;
    let ei = 1e8 * PI * r.powi(4) / 4.0;
    let Load::Force { force, .. } = &mut s.loads[0] else {
        panic!("force")
    };
    *force = [0.0, -2.0 * ei, 0.0];
    let sol = solve_scene(&s, &settings_of(&s)).unwrap();
    let res = &sol.results;
    assert!(res.converged, "{:?}", res.solver.message);
    assert!(res.path_events.is_empty(), "{:?}", res.path_events);
    let tip = res.rods[0].points.last().unwrap();
    assert!((-tip[1] - 0.49345748).abs() < 1e-6, "{tip:?}");
    assert!((1.0 - tip[0] - 0.16064172).abs() < 1e-6, "{tip:?}");
}

/// `buckle` on a staged column: a base stage preloading it to half Euler's load and a stage
/// "more" adding Euler's load again. About the preloaded equilibrium, the stage's load is
/// critical at the factor 0.5 (P₀ + μ·ΔP = P_cr); `--stage base` scales the preload about rest
/// (factor 2). Before, every stage's loads were scaled together about rest (factor 2/3).
#[test]
fn buckle_linearizes_about_the_stage_before_the_scaled_one() {
    let ei = COLUMN_EI;
    let p_cr = PI * PI * ei / 4.0;
    let mut s = column(0.5 * p_cr, 64);
    s.stages.push(Stage {
        name: "more".into(),
        loads: vec![Load::Force {
            rod: "column".into(),
            vertex: 1,
            force: [0.0, 0.0, -p_cr],
        }],
        continuation: None,
    });
    for (stage, about, factor) in [
        (None, "base", 0.5),
        (Some("more"), "base", 0.5),
        (Some("base"), "rest", 2.0),
    ] {
        let b =
            rodnet::jobs::buckle(&s, 2, true, stage, &Limits::NONE).unwrap_or_else(|_| panic!());
        let f = b.json.critical_load_factors[0];
        println!(
            "--stage {stage:?}: about {:?}, factor {f:.6}",
            b.json.about_stage
        );
        assert_eq!(b.json.about_stage.as_deref(), Some(about));
        assert!((f / factor - 1.0).abs() < 1e-3, "{f} vs {factor}");
    }
    assert!(rodnet::jobs::buckle(&s, 2, true, Some("nope"), &Limits::NONE).is_err());
}

/// A stage may follow its own path under arc length while the rest of the scene stays under
/// load control (`Stage(continuation: Some(ArcLength))`), and a scene-wide arc length may be
/// turned back to load control for one stage. The stage's results say which ran.
#[test]
fn a_stage_follows_its_own_continuation() {
    let ei = COLUMN_EI;
    let p_cr = PI * PI * ei / 4.0;
    let staged = |own: Option<Continuation>, scene_wide: Continuation| {
        let mut s = column(0.5 * p_cr, 32);
        s.solver.continuation = scene_wide;
        s.stages.push(Stage {
            name: "more".into(),
            loads: vec![Load::Force {
                rod: "column".into(),
                vertex: 1,
                force: [0.0, 0.0, -0.3 * p_cr],
            }],
            continuation: own,
        });
        let sol = solve_scene(&s, &settings_of(&s)).unwrap();
        assert!(sol.results.converged, "{:?}", sol.results.solver.message);
        sol.results.continuation.map(|c| c.kind)
    };
    assert_eq!(
        staged(Some(Continuation::ArcLength), Continuation::Load).as_deref(),
        Some("arc_length")
    );
    assert_eq!(staged(None, Continuation::Load), None);
    assert_eq!(
        staged(Some(Continuation::Load), Continuation::ArcLength),
        None
    );
    assert_eq!(
        staged(None, Continuation::ArcLength).as_deref(),
        Some("arc_length")
    );
}
