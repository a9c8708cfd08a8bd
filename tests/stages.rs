//! `stages`: loads added stage by stage, each from the previous stage's equilibrium.
//! Checked against one-shot solves (a conservative elastic rod reaches the same equilibrium
//! whichever way its loads are applied, when only one is near), against restarts (the staged
//! state is an equilibrium of the full load case), and through the command line (each stage's
//! files written, bad stages refused at their field).

use std::path::PathBuf;
use std::process::Command;

use rodnet::pipeline::{settings_of, solve_scene, solve_scene_from, solve_stages, Solution};
use rodnet::scene::{parse, Scene};

fn scene(text: &str) -> Scene {
    parse("stages.ron", text).unwrap_or_else(|e| panic!("{e}"))
}

fn solve(sc: &Scene) -> Solution {
    let s = solve_scene(sc, &settings_of(sc)).unwrap();
    assert!(s.results.converged, "{:?}", s.results.solver.message);
    s
}

fn cantilever(loads: &str, stages: &str) -> String {
    format!(
        "Scene(materials: {{\"m\": Material(young_modulus: 1e8, poisson_ratio: 0.5, \
         section: Circle(radius: 0.01))}},
         rods: [Rod(name: \"beam\", material: \"m\", points: [(0,0,0), (0.5,0,0), (1,0,0)], subdivide: 16)],
         supports: [Support(rod: \"beam\", vertex: 0, kind: Clamp)],
         loads: [{loads}],
         stages: [{stages}])"
    )
}

fn tip(s: &Solution) -> [f64; 3] {
    *s.results.rods[0].points.last().unwrap()
}

fn close(a: [f64; 3], b: [f64; 3], tol: f64) -> bool {
    (0..3).all(|k| (a[k] - b[k]).abs() <= tol)
}

const P: &str = "Force(rod: \"beam\", vertex: 2, force: (0.0, -0.8, 0.0))";
const Q: &str = "Force(rod: \"beam\", vertex: 1, force: (0.0, 0.0, -0.6))";
const T: &str = "Torque(rod: \"beam\", vertex: 1, torque: (0.3, 0.0, 0.0))";

/// Two stages of large loads (the tip moves 0.3 L), the second with a torque on a vertex that
/// had no frame before (the network gains a variable block): the same state as all loads at
/// once, and the stages reported in order.
#[test]
fn stages_reach_the_one_shot_equilibrium() {
    let staged = scene(&cantilever(
        P,
        &format!("Stage(name: \"side\", loads: [{Q}]), Stage(name: \"twist\", loads: [{T}])"),
    ));
    let one_shot = scene(&cantilever(&format!("{P}, {Q}, {T}"), ""));
    let mut seen = Vec::new();
    let s = solve_stages(&staged, &settings_of(&staged), |sol| {
        let st = sol.results.stage.clone().unwrap();
        assert!(st.converged);
        seen.push((st.index, st.name));
    })
    .unwrap();
    assert!(s.results.converged, "{:?}", s.results.solver.message);
    assert_eq!(seen, [(0, "base".to_string()), (1, "side".to_string())]);
    let names: Vec<&str> = s.results.stages.iter().map(|s| s.name.as_str()).collect();
    assert_eq!(names, ["base", "side", "twist"]);
    assert_eq!(s.results.stage.as_ref().unwrap().index, 2);
    let o = solve(&one_shot);
    let (a, b) = (tip(&s), tip(&o));
    println!("staged tip {a:?}, one shot {b:?}");
    assert!(b[1] < -0.25, "the loads are large: {b:?}");
    assert!(close(a, b, 1e-8), "{a:?} {b:?}");
    // The stored (elastic) energy agrees; the total does not have to: a dead torque's
    // potential −T·ψ depends on the path its frame turned along (docs/design.md).
    let elastic = |s: &Solution| {
        let e = &s.results.energy;
        e.stretch + e.bend + e.twist + e.joints
    };
    let (ea, eb) = (elastic(&s), elastic(&o));
    assert!((ea - eb).abs() <= 1e-8 * ea.abs(), "{ea} {eb}");
}

/// A stage that takes a load away (its opposite at the same node) returns the rod to rest.
#[test]
fn a_stage_can_take_a_load_away() {
    let undo = "Force(rod: \"beam\", vertex: 2, force: (0.0, 0.8, 0.0))";
    let s = solve(&scene(&cantilever(
        P,
        &format!("Stage(name: \"unload\", loads: [{undo}])"),
    )));
    assert!(close(tip(&s), [1.0, 0.0, 0.0], 1e-9), "{:?}", tip(&s));
    assert!(s.results.stages[0].energy < -1e-2, "{:?}", s.results.stages);
}

fn arch() -> Scene {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/networks/arch_erect_then_load.ron"
    );
    rodnet::scene::load(std::path::Path::new(path)).unwrap().0
}

/// Erect, then load (`networks/arch_erect_then_load.ron`): the arch rises, the crown load
/// lowers it, and the loaded arch is an equilibrium of the whole load case: a restart from it
/// on the scene with every load at once converges at once to the same energy.
#[test]
fn an_erected_arch_takes_its_crown_load() {
    let sc = arch();
    let s = solve(&sc);
    let crown = |s: &Solution| s.results.rods[0].points[16][2];
    let base = s.results.stages[0].clone();
    assert!(base.converged && s.results.solver.stable);
    let all = sc.all_stages();
    let rods = rodnet::io::initial::of_results(&s.results);
    let again = solve_scene_from(&all, &settings_of(&all), &rods).unwrap_or_else(|_| panic!());
    assert!(again.results.converged);
    assert!(
        again.results.iterations <= 2,
        "{}",
        again.results.iterations
    );
    let (a, b) = (s.results.energy.total, again.results.energy.total);
    assert!((a - b).abs() <= 1e-9 * a.abs(), "{a} {b}");
    // The erected arch stands 0.53 m high; the crown load presses it down, not through.
    let erected = {
        let mut only = sc.clone();
        only.stages.clear();
        crown(&solve(&only))
    };
    println!("crown: erected {erected:.6} m, loaded {:.6} m", crown(&s));
    assert!(erected > 0.5);
    assert!(crown(&s) < erected && crown(&s) > 0.5, "{}", crown(&s));
}

fn rodnet() -> Command {
    Command::new(env!("CARGO_BIN_EXE_rodnet"))
}

fn temp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rodnet-stages-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Each stage but the last writes OUT.STAGE.json (and .obj); the last writes OUT.json with
/// every stage listed.
#[test]
fn each_stage_writes_its_results() {
    let d = temp("cli");
    let scene = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/networks/arch_erect_then_load.ron"
    );
    let out = rodnet()
        .arg("solve")
        .arg(scene)
        .arg("--json")
        .arg(d.join("arch.json"))
        .arg("--obj")
        .arg(d.join("arch.obj"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0), "{out:?}");
    let read = |f: &str| -> serde_json::Value {
        serde_json::from_str(&std::fs::read_to_string(d.join(f)).unwrap()).unwrap()
    };
    let base = read("arch.base.json");
    assert_eq!(base["stage"]["name"], "base");
    assert!(base.get("stages").is_none());
    let last = read("arch.json");
    assert_eq!(last["stage"]["name"], "crown_load");
    assert_eq!(last["stages"].as_array().unwrap().len(), 2);
    assert!(d.join("arch.base.obj").exists());
    assert!(!d.join("arch.crown_load.json").exists());
}

#[test]
fn bad_stages_are_refused_at_their_field() {
    let d = temp("bad");
    for (stages, want) in [
        ("Stage(name: \"a b\", loads: [])", "stages[0].name"),
        ("Stage(name: \"base\", loads: [])", "stages[0].name"),
        (
            "Stage(name: \"a\", loads: []), Stage(name: \"a\", loads: [])",
            "stages[1].name",
        ),
        (
            "Stage(name: \"a\", loads: [\n Force(rod: \"beam\", vertex: 2, force: (0, 0, 1)),\n Force(rod: \"nope\", vertex: 0, force: (0, 0, 1))])",
            ":7:",
        ),
    ] {
        let text = cantilever(P, stages);
        let p = d.join("s.ron");
        std::fs::write(&p, &text).unwrap();
        let out = rodnet().arg("solve").arg(&p).output().unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(err.contains(want), "{stages}: {err}");
    }
    // The located load error names the stage's load and its field.
    let text = cantilever(
        P,
        "Stage(name: \"a\", loads: [\n Force(rod: \"beam\", vertex: 2, force: (0, 0, 1)),\n Force(rod: \"nope\", vertex: 0, force: (0, 0, 1))])",
    );
    let p = d.join("s.ron");
    std::fs::write(&p, &text).unwrap();
    let out = rodnet().arg("solve").arg(&p).output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("stages[0].loads[1].rod"), "{err}");
    assert!(err.contains(":7:8:"), "{err}");
}
