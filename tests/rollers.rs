//! Rollers with a general normal (kept by projection, `network/roller.rs`) against rollers along
//! the axes (kept by elimination): a scene with axis-aligned rollers, turned as a whole by a
//! general rotation, must give the turned equilibrium: positions, reactions, energy. Plus a
//! propped cantilever on an inclined roller against linear beam theory.

use rodnet::jobs::analyse_modes;
use rodnet::pipeline::{settings_of, solve_scene, Solution};
use rodnet::scene::parse;

type M3 = [[f64; 3]; 3];

fn rotation(w: [f64; 3]) -> M3 {
    let id = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    // Columns are the turned axes.
    rodnet::math::vec::frame_rotate(w, &id)
}

fn turn(r: &M3, v: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| r[0][i] * v[0] + r[1][i] * v[1] + r[2][i] * v[2])
}

fn t(v: [f64; 3]) -> String {
    format!("({:e}, {:e}, {:e})", v[0], v[1], v[2])
}

/// A bent rod clamped at one end, its other end held by `rollers` (normals) and moved to
/// `to`, a force on its corner; everything turned by `r`.
fn scene(r: &M3, rollers: &[[f64; 3]], to: [f64; 3]) -> String {
    let p = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 0.8, 0.0]].map(|x| turn(r, x));
    let supports: Vec<String> = rollers
        .iter()
        .map(|n| {
            format!(
                "Support(rod: \"r\", vertex: 2, kind: Roller(normal: {}), move_to: Some({}))",
                t(turn(r, *n)),
                t(turn(r, to))
            )
        })
        .collect();
    format!(
        "Scene(materials: {{\"m\": Material(young_modulus: 1e8, poisson_ratio: 0.3, \
         section: Circle(radius: 0.01))}},
         rods: [Rod(name: \"r\", material: \"m\", points: [{}, {}, {}], subdivide: 12)],
         supports: [Support(rod: \"r\", vertex: 0, kind: Clamp), {}],
         loads: [Force(rod: \"r\", vertex: 1, force: {})])",
        t(p[0]),
        t(p[1]),
        t(p[2]),
        supports.join(", "),
        t(turn(r, [0.0, 0.0, -0.4]))
    )
}

fn solve(text: &str) -> Solution {
    let sc = parse("rollers.ron", text).unwrap_or_else(|e| panic!("{e}"));
    let s = solve_scene(&sc, &settings_of(&sc)).unwrap();
    assert!(s.results.converged, "{:?}", s.results.solver.message);
    s
}

fn compare(rollers: &[[f64; 3]], to: [f64; 3]) {
    let id = rotation([0.0; 3]);
    let r = rotation([0.7, -0.4, 1.1]);
    let mut axis = solve(&scene(&id, rollers, to));
    let mut slanted = solve(&scene(&r, rollers, to));
    let (pa, ps) = (
        &axis.results.rods[0].points,
        &slanted.results.rods[0].points,
    );
    let mut worst: f64 = 0.0;
    for (a, s) in pa.iter().zip(ps) {
        let want = turn(&r, *a);
        worst = (0..3).map(|k| (want[k] - s[k]).abs()).fold(worst, f64::max);
    }
    println!(
        "{} roller(s): largest position difference {worst:.2e} m; iterations {} (axes) and {} \
         (turned)",
        rollers.len(),
        axis.results.iterations,
        slanted.results.iterations
    );
    assert!(worst < 1e-9, "{worst}");
    // The moved end really moved (a roller that held nothing would also agree).
    let end = *pa.last().unwrap();
    assert!(end[2] > 0.05, "{end:?}");
    for (ra, rs) in axis
        .results
        .reactions
        .iter()
        .zip(&slanted.results.reactions)
    {
        let want = turn(&r, ra.force);
        let scale = ra.force.iter().fold(1e-3f64, |m, x| m.max(x.abs()));
        for k in 0..3 {
            assert!(
                (want[k] - rs.force[k]).abs() < 1e-7 * scale,
                "{:?} {:?}",
                want,
                rs.force
            );
        }
    }
    let (ea, es) = (axis.results.energy.total, slanted.results.energy.total);
    assert!((ea - es).abs() < 1e-9 * ea.abs(), "{ea} {es}");
    // The lowest modes do not see the normal stiffness that holds the slanted planes.
    let la = analyse_modes(&mut axis, 4).unwrap().eigenvalues;
    let ls = analyse_modes(&mut slanted, 4).unwrap().eigenvalues;
    println!("lowest eigenvalues {la:?} (axes), {ls:?} (turned)");
    for (a, b) in la.iter().zip(&ls) {
        assert!((a - b).abs() < 1e-6 * a.abs(), "{la:?} {ls:?}");
    }
}

/// One plane, moving: the end slides on a plane that rises by 0.1 m.
#[test]
fn a_turned_plane_gives_the_turned_equilibrium() {
    compare(&[[0.0, 0.0, 1.0]], [1.0, 0.8, 0.1]);
}

/// Two planes: the end runs along their line, which moves.
#[test]
fn a_turned_line_support_gives_the_turned_equilibrium() {
    compare(&[[0.0, 0.0, 1.0], [1.0, 0.0, 0.0]], [1.0, 0.8, 0.1]);
}

/// A cantilever of length L whose tip rests on a plane inclined at α, tip load P across it:
/// the plane takes the load's normal part, the tip moves along the plane by
/// P sin α · L³/3EI, and the reaction is P cos α along the normal (linear theory, order h²).
#[test]
fn an_inclined_prop_takes_the_normal_part_of_the_load() {
    let (l, ei) = (1.0f64, 1e8 * std::f64::consts::PI * 1e-8 / 4.0);
    let p = 1e-4 * ei / (l * l);
    let a = 30f64.to_radians();
    let n = [0.0, a.cos(), a.sin()];
    let text = format!(
        "Scene(materials: {{\"m\": Material(young_modulus: 1e8, poisson_ratio: 0.3, \
         section: Circle(radius: 0.01))}},
         rods: [Rod(name: \"r\", material: \"m\", points: [(0,0,0), ({l},0,0)], subdivide: 32)],
         supports: [Support(rod: \"r\", vertex: 0, kind: Clamp),
                    Support(rod: \"r\", vertex: 1, kind: Roller(normal: {}))],
         loads: [Force(rod: \"r\", vertex: 1, force: (0, {}, 0))])",
        t(n),
        -p
    );
    let s = solve(&text);
    let tip = *s.results.rods[0].points.last().unwrap();
    let along = [0.0, -a.sin(), a.cos()];
    let want = p * a.sin() * l.powi(3) / (3.0 * ei);
    let moved: f64 = (0..3).map(|k| tip[k] * along[k]).sum();
    let off: f64 = (0..3).map(|k| tip[k] * n[k]).sum();
    println!("tip along the plane {moved:.9e}, theory {want:.9e}; off the plane {off:.1e}");
    assert!(((moved - want) / want).abs() < 1e-3, "{moved} {want}");
    assert!(off.abs() < 1e-15, "{off}");
    let r = s.results.reactions[1].force;
    for k in 0..3 {
        assert!((r[k] - p * a.cos() * n[k]).abs() < 1e-6 * p, "{r:?}");
    }
}

/// A third independent normal on one node would hold it entirely: refused at that Roller, with
/// its line; a repeated plane (parallel normals) is one plane and accepted.
#[test]
fn three_independent_roller_normals_are_refused_at_the_third() {
    let text = |third: &str| {
        format!(
            "Scene(materials: {{\"m\": Material(young_modulus: 1e9, poisson_ratio: 0.3, \
             section: Circle(radius: 0.01))}},
 rods: [Rod(name: \"r\", material: \"m\", points: [(0,0,0), (1,0,0)])],
 supports: [Support(rod: \"r\", vertex: 0, kind: Clamp),
  Support(rod: \"r\", vertex: 1, kind: Roller(normal: (1, 1, 0))),
  Support(rod: \"r\", vertex: 1, kind: Roller(normal: (0, 1, 1))),
  Support(rod: \"r\", vertex: 1, kind: Roller(normal: {third}))])"
        )
    };
    let e = parse("r.ron", &text("(1, 0, 1)"))
        .expect_err("refused")
        .to_string();
    assert!(
        e.contains("r.ron:6:") && e.contains("supports[3].kind"),
        "{e}"
    );
    parse("r.ron", &text("(2, 2, 0)")).unwrap();
}
