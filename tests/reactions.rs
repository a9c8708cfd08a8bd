//! Support reactions balance the loads: over all supports, Σ reactions + Σ loads (+ contact
//! forces) = 0, also when several supports hold one node (they share its reaction instead of
//! each reporting all of it), and contradictory supports on one node or frame are refused.

use rodnet::network::assembly::Assembly;
use rodnet::network::equilibrium::Equilibrium;
use rodnet::network::model::FIXED;
use rodnet::network::Network;
use rodnet::pipeline::{settings_of, solve_scene, Solution};

fn solve(name: &str, text: &str) -> Solution {
    let scene = rodnet::scene::parse(name, text).unwrap();
    let sol = solve_scene(&scene, &settings_of(&scene)).unwrap();
    assert!(sol.results.converged, "{name}: {:?}", sol.report.message);
    sol
}

/// (Σ reactions + Σ loads + Σ contact forces, the sum of their magnitudes), N.
fn force_balance(net: &Network, eq: &Equilibrium) -> ([f64; 3], f64) {
    let m = &net.model;
    let lambda = m.state.load_factor;
    let mut sum = [0.0; 3];
    let mut scale = 0.0;
    let mut add = |f: [f64; 3]| {
        for k in 0..3 {
            sum[k] += f[k];
        }
        scale += f.iter().map(|x| x * x).sum::<f64>().sqrt();
    };
    for r in eq.reactions.iter().map(|s| &s.reaction) {
        add(r.force);
    }
    for l in &m.terms.loads {
        add(l.force.map(|f| lambda * f));
    }
    for c in eq.constraints.iter().flat_map(|c| &c.contacts) {
        add(c.force);
    }
    (sum, scale)
}

/// The net force the solve left unbalanced on the free nodes (the residual the tolerance
/// allows, summed), N: Σ over free node coordinates of ∇E, less the contact forces there.
fn leftover(net: &Network, eq: &Equilibrium) -> [f64; 3] {
    let m = &net.model;
    let mut grad = vec![0.0; m.n_free];
    let mut full = vec![0.0; m.state.q.len()];
    m.assemble(&mut Assembly {
        grad: &mut grad,
        full_grad: Some(&mut full),
        hess: None,
    });
    let mut sum = [0.0; 3];
    for n in 0..net.n_nodes() {
        for (k, v) in m.layout.node(n).into_iter().enumerate() {
            if m.free[v] != FIXED {
                sum[k] += full[v];
            }
        }
    }
    for c in eq.constraints.iter().flat_map(|c| &c.contacts) {
        for (s, f) in sum.iter_mut().zip(c.force) {
            *s -= f;
        }
    }
    sum
}

/// Σ reactions + Σ loads + Σ contact forces vanishes to `rel` of their magnitudes, beyond
/// what the solve's own residual leaves unbalanced.
fn assert_balanced(name: &str, sol: &Solution, rel: f64) {
    let (sum, scale) = force_balance(&sol.network, &sol.equilibrium);
    let off = sum.iter().map(|x| x * x).sum::<f64>().sqrt();
    let left = leftover(&sol.network, &sol.equilibrium);
    let residual = left.iter().map(|x| x * x).sum::<f64>().sqrt();
    // What is not balanced is exactly what the solve left on the free nodes.
    let bookkeeping = (0..3)
        .map(|k| (sum[k] + left[k]).powi(2))
        .sum::<f64>()
        .sqrt();
    println!(
        "{name}: |Σ| = {off:.2e} N of {scale:.3e} N (free residual {residual:.2e} N, \
         difference {bookkeeping:.1e} N)"
    );
    assert!(
        off <= rel * scale + residual,
        "{name}: reactions + loads = {sum:?} N (scale {scale:e} N, residual {residual:e} N)"
    );
    assert!(
        bookkeeping <= 1e-12 * scale,
        "{name}: reactions + loads = {sum:?} N, but the residual on free nodes is {left:?} N"
    );
}

/// A tripod: three legs from the ground to a ball joint at the top, loaded there by 100 N;
/// `supports` holds the feet.
fn tripod(supports: &str) -> String {
    format!(
        r#"Scene(
    materials: {{ "steel": Material(young_modulus: 2e11, poisson_ratio: 0.3, section: Circle(radius: 0.01)) }},
    rods: [
        Rod(name: "a", material: "steel", points: [(1.0, 0.0, 0.0), (0.0, 0.0, 1.0)], subdivide: 8),
        Rod(name: "b", material: "steel", points: [(-0.5, 0.8660254037844386, 0.0), (0.0, 0.0, 1.0)], subdivide: 8),
        Rod(name: "c", material: "steel", points: [(-0.5, -0.8660254037844386, 0.0), (0.0, 0.0, 1.0)], subdivide: 8),
    ],
    joints: [Joint(name: "top", at: [("a", 1), ("b", 1), ("c", 1)], kind: Ball)],
    supports: [{supports}],
    loads: [Force(rod: "a", vertex: 1, force: (20.0, 0.0, -100.0))],
)"#
    )
}

#[test]
fn two_supports_on_one_node_share_its_reaction() {
    let feet =
        "Support(rod: \"b\", vertex: 0, kind: Clamp), Support(rod: \"c\", vertex: 0, kind: Clamp)";
    let single = solve(
        "single.ron",
        &tripod(&format!(
            "Support(rod: \"a\", vertex: 0, kind: Clamp), {feet}"
        )),
    );
    for (name, first) in [("pin_then_clamp", "Pin"), ("clamp_then_pin", "Clamp")] {
        let second = if first == "Pin" { "Clamp" } else { "Pin" };
        let text = tripod(&format!(
            "Support(rod: \"a\", vertex: 0, kind: {first}), \
             Support(rod: \"a\", vertex: 0, kind: {second}), {feet}"
        ));
        let sol = solve(name, &text);
        assert_balanced(name, &sol, 1e-8);
        let r = &sol.equilibrium.reactions;
        assert_eq!(r.len(), 4);
        // The node's force is reported once, by the first support; the clamp's moment by the
        // clamp; together they are the single clamp's reaction.
        let one = single.equilibrium.reactions[0].reaction;
        let (p, q) = (r[0].reaction, r[1].reaction);
        for k in 0..3 {
            assert!((p.force[k] + q.force[k] - one.force[k]).abs() <= 1e-9 * 100.0);
            assert!((p.moment[k] + q.moment[k] - one.moment[k]).abs() <= 1e-9 * 100.0);
        }
        assert_eq!(
            q.force, [0.0; 3],
            "{name}: the second support repeats the force"
        );
        let pin = if first == "Pin" { p } else { q };
        assert_eq!(pin.moment, [0.0; 3]);
        // The vertical reactions carry the 100 N.
        let up: f64 = r.iter().map(|x| x.reaction.force[2]).sum();
        assert!((up - 100.0).abs() < 1e-6, "{name}: Σ Rz = {up}");
    }
    // The same clamp twice, and two pins.
    for (name, pair) in [("clamp_twice", "Clamp"), ("pin_twice", "Pin")] {
        let text = tripod(&format!(
            "Support(rod: \"a\", vertex: 0, kind: {pair}), \
             Support(rod: \"a\", vertex: 0, kind: {pair}), {feet}"
        ));
        assert_balanced(name, &solve(name, &text), 1e-8);
    }
}

#[test]
fn clamps_on_the_rods_of_one_joint_balance_the_loads() {
    // A portal whose two posts and beam meet at rigid and hinge joints, clamped at the corner
    // on two rods (one frame), and pinned feet.
    for kind in ["Rigid", "Hinge", "Ball"] {
        let text = format!(
            r#"Scene(
    materials: {{ "m": Material(young_modulus: 1e9, poisson_ratio: 0.3, section: Circle(radius: 0.02)) }},
    rods: [
        Rod(name: "post", material: "m", points: [(0.0, 0.0, 0.0), (0.0, 0.0, 1.0)], subdivide: 6),
        Rod(name: "beam", material: "m", points: [(0.0, 0.0, 1.0), (1.0, 0.0, 1.0)], subdivide: 6),
        Rod(name: "leg", material: "m", points: [(1.0, 0.0, 1.0), (1.0, 0.0, 0.0)], subdivide: 6),
    ],
    joints: [
        Joint(name: "corner", at: [("post", 1), ("beam", 0)], kind: {kind}, normal: Some((0.0, 1.0, 0.0))),
        Joint(name: "knee", at: [("beam", 1), ("leg", 0)], kind: Rigid),
    ],
    supports: [
        Support(rod: "post", vertex: 1, kind: Clamp),
        Support(rod: "beam", vertex: 0, kind: Clamp),
        Support(rod: "post", vertex: 0, kind: Pin),
        Support(rod: "leg", vertex: 1, kind: Clamp),
    ],
    loads: [Force(rod: "beam", vertex: 1, force: (3.0, 1.0, -10.0)), Torque(rod: "leg", vertex: 1, torque: (0.0, 0.5, 0.0))],
)"#
        );
        assert_balanced(kind, &solve(kind, &text), 1e-8);
    }
}

#[test]
fn every_reference_network_with_supports_balances_its_loads() {
    let mut checked = 0;
    let mut paths: Vec<_> = std::fs::read_dir("networks")
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "ron"))
        .collect();
    paths.sort();
    for p in paths {
        let (scene, _) = rodnet::scene::load(&p).unwrap();
        if scene.supports.is_empty() {
            continue;
        }
        let sol = solve_scene(&scene, &settings_of(&scene)).unwrap();
        let name = p.display().to_string();
        assert!(sol.results.converged, "{name}");
        assert_balanced(&name, &sol, 1e-8);
        checked += 1;
    }
    assert!(checked >= 8, "only {checked} networks checked");
}

fn refused(text: &str) -> rodnet::scene::SceneError {
    let scene = rodnet::scene::parse("bad.ron", text);
    match scene {
        Err(e) => e,
        Ok(s) => match rodnet::network::build(&s) {
            Err(e) => rodnet::scene::SceneError::from_field("bad.ron", text, &e),
            Ok(_) => panic!("accepted: {text}"),
        },
    }
}

#[test]
fn contradictory_supports_on_one_node_are_refused() {
    let feet =
        "Support(rod: \"b\", vertex: 0, kind: Pin), Support(rod: \"c\", vertex: 0, kind: Pin)";
    let cases = [
        (
            "Support(rod: \"a\", vertex: 0, kind: Pin, move_to: Some((1.0, 0.0, 0.1))),\n\
             Support(rod: \"a\", vertex: 0, kind: Clamp, move_to: Some((1.0, 0.0, 0.2)))",
            "supports[1].move_to",
            "contradicts supports[0]",
        ),
        (
            "Support(rod: \"a\", vertex: 0, kind: Pin),\n\
             Support(rod: \"a\", vertex: 0, kind: Clamp, move_to: Some((1.0, 0.0, 0.2)))",
            "supports[1].move_to",
            "holds it at its rest position",
        ),
        (
            "Support(rod: \"a\", vertex: 0, kind: Clamp, rotate_by: Some((0.0, 0.1, 0.0))),\n\
             Support(rod: \"a\", vertex: 0, kind: Clamp, rotate_by: Some((0.0, 0.2, 0.0)))",
            "supports[1].rotate_by",
            "rotates it by [0.0, 0.1, 0.0], not [0.0, 0.2, 0.0]",
        ),
        (
            "Support(rod: \"a\", vertex: 0, kind: Clamp, rotate_by: Some((0.0, 0.1, 0.0))),\n\
             Support(rod: \"a\", vertex: 0, kind: Clamp)",
            "supports[1].kind",
            "but this clamp holds it",
        ),
    ];
    for (supports, field, needle) in cases {
        let text = tripod(&format!("{supports},\n{feet}"));
        let e = refused(&text);
        let msg = e.to_string();
        assert!(msg.starts_with("bad.ron:"), "{msg}");
        assert_eq!(e.line, Some(10), "{msg}");
        assert!(msg.contains(field) && msg.contains(needle), "{msg}");
    }
    // Agreeing pairs are accepted: the same move, the same rotation, a pin beside a rotated
    // clamp (a pin leaves rotations free).
    for supports in [
        "Support(rod: \"a\", vertex: 0, kind: Pin, move_to: Some((1.0, 0.0, 0.1))),\n\
         Support(rod: \"a\", vertex: 0, kind: Clamp, move_to: Some((1.0, 0.0, 0.1)))",
        "Support(rod: \"a\", vertex: 0, kind: Clamp, rotate_by: Some((0.0, 0.1, 0.0))),\n\
         Support(rod: \"a\", vertex: 0, kind: Clamp, rotate_by: Some((0.0, 0.1, 0.0)))",
        "Support(rod: \"a\", vertex: 0, kind: Pin),\n\
         Support(rod: \"a\", vertex: 0, kind: Clamp, rotate_by: Some((0.0, 0.1, 0.0)))",
    ] {
        let text = tripod(&format!("{supports},\n{feet}"));
        let sol = solve("agree.ron", &text);
        assert_balanced("agree", &sol, 1e-8);
    }
}

#[test]
fn clamps_of_one_rigid_joint_must_turn_it_alike() {
    let text = r#"Scene(
    materials: { "m": Material(young_modulus: 1e9, poisson_ratio: 0.3, section: Circle(radius: 0.02)) },
    rods: [
        Rod(name: "p", material: "m", points: [(0.0, 0.0, 0.0), (0.0, 0.0, 1.0)], subdivide: 4),
        Rod(name: "q", material: "m", points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0)], subdivide: 4),
    ],
    joints: [Joint(name: "j", at: [("p", 0), ("q", 0)], kind: Rigid)],
    supports: [
        Support(rod: "p", vertex: 0, kind: Clamp, rotate_by: Some((0.0, 0.0, 0.3))),
        Support(rod: "q", vertex: 0, kind: Clamp),
    ],
)"#;
    let e = refused(text);
    assert_eq!(e.line, Some(10), "{e}");
    assert!(e.to_string().contains("supports[1].kind"), "{e}");
    assert!(
        e.to_string()
            .contains("supports[0] clamps the same vertex frame"),
        "{e}"
    );
}
