//! `--modes` with contact: the active constraints are held (`network/active_set.rs`). A beam
//! lying on a floor under its weight has the modes of the same beam on Rollers at its nodes
//! (eliminated, an independent path); a rod pressed onto a ball has, along its lowest held
//! mode, the second derivative of the energy along a path that keeps the pressed node on the
//! ball (the curvature term −μ/d).

use rodnet::jobs::analyse_modes;
use rodnet::math::vec::{add, norm, scalef, sub};
use rodnet::network::active_set::hold_active;
use rodnet::network::assembly::Assembly;
use rodnet::network::stability::analyse;
use rodnet::pipeline::{settings_of, solve_scene, Solution};
use rodnet::scene::parse;

const R: f64 = 0.01;

fn solve(text: &str) -> Solution {
    let sc = parse("contact_modes.ron", text).unwrap_or_else(|e| panic!("{e}"));
    let s = solve_scene(&sc, &settings_of(&sc)).unwrap();
    assert!(s.results.converged, "{:?}", s.results.solver.message);
    s
}

fn material() -> String {
    format!(
        "materials: {{\"m\": Material(young_modulus: 1e9, poisson_ratio: 0.3, density: 8000.0, \
         section: Circle(radius: {R}))}},"
    )
}

/// A beam along x at height r (touching the floor z = 0), clamped at x = 0, eleven vertices.
fn beam(supports: &str, obstacles: &str) -> String {
    let pts: Vec<String> = (0..=10)
        .map(|i| format!("({}, 0, {R})", i as f64 * 0.1))
        .collect();
    format!(
        "Scene({} rods: [Rod(name: \"b\", material: \"m\", points: [{}])],
         supports: [Support(rod: \"b\", vertex: 0, kind: Clamp), {supports}],
         loads: [Gravity(g: (0, 0, -9.81))],
         obstacles: [{obstacles}])",
        material(),
        pts.join(", ")
    )
}

#[test]
fn a_beam_on_a_floor_has_the_modes_of_a_beam_on_rollers() {
    let rollers: Vec<String> = (1..=10)
        .map(|v| format!("Support(rod: \"b\", vertex: {v}, kind: Roller(normal: (0, 0, 1)))"))
        .collect();
    let mut on_rollers = solve(&beam(&rollers.join(", "), ""));
    let mut on_floor = solve(&beam("", "Plane(point: (0, 0, 0), normal: (0, 0, 1))"));
    let held = on_floor
        .equilibrium
        .constraints
        .as_ref()
        .unwrap()
        .contacts
        .len();
    assert_eq!(held, 10, "every free node presses on the floor");
    let a = analyse_modes(&mut on_rollers, 5).unwrap();
    let b = analyse_modes(&mut on_floor, 5).unwrap();
    println!(
        "on rollers {:?}\non the floor {:?}",
        a.eigenvalues, b.eigenvalues
    );
    assert!(b.stable && b.converged);
    for (x, y) in a.eigenvalues.iter().zip(&b.eigenvalues) {
        assert!(
            (x - y).abs() < 1e-6 * x.abs(),
            "{:?} {:?}",
            a.eigenvalues,
            b.eigenvalues
        );
    }
}

/// A vertical rod clamped at its top and pushed down onto a ball by a load at its foot.
fn on_a_ball(p: f64) -> String {
    let d = 0.05;
    format!(
        "Scene({} rods: [Rod(name: \"c\", material: \"m\", points: [(0, 0, 0.5), (0, 0, {R})], subdivide: 20)],
         supports: [Support(rod: \"c\", vertex: 0, kind: Clamp)],
         loads: [Force(rod: \"c\", vertex: 1, force: (0, 0, {}))],
         obstacles: [Sphere(center: (0, 0, {}), radius: {d})])",
        material().replace("density: 8000.0", "density: 0.0"),
        -p,
        -d
    )
}

#[test]
fn a_rod_pressed_onto_a_ball_loses_mu_over_d_along_it() {
    let p = 2.0;
    let sol = solve(&on_a_ball(p));
    let forces = sol.equilibrium.constraints.as_ref().unwrap();
    assert_eq!(forces.contacts.len(), 1);
    let mu = forces.contacts[0].force[2];
    assert!((mu - p).abs() < 1e-6 * p, "{mu}");
    let (mut held, n) = hold_active(&sol.network, forces);
    assert_eq!(n, 1);
    let st = analyse(&mut held, 2).unwrap();
    // The energy of the scene itself (no constraint terms) along the lowest held mode u, the
    // foot kept on the ball by radial projection, by a central difference; against u·Hu of the
    // held Hessian (projected, with the curvature term), from a central difference of its
    // gradient along u.
    let u = &st.modes[0];
    let foot = sol.network.rods[0].nodes.last().copied().unwrap();
    let center = [0.0, 0.0, -0.05];
    let d0 = norm(sub(sol.network.model.position(foot), center));
    let energy_at = |s: f64| {
        let mut m = sol.network.model.clone();
        m.displace(u, s);
        let r = sub(m.position(foot), center);
        let on = add(center, scalef(r, d0 / norm(r)));
        let mut q = m.state.q.clone();
        m.layout.set_position(&mut q, foot, on);
        m.state.q = q;
        m.energy()
    };
    let h = 1e-4;
    let second = (energy_at(h) + energy_at(-h) - 2.0 * energy_at(0.0)) / (h * h);
    let gradient_at = |s: f64| {
        let mut m = held.model.clone();
        m.displace(u, s);
        let mut grad = vec![0.0; m.n_free];
        m.assemble(&mut Assembly {
            grad: &mut grad,
            full_grad: None,
            hess: None,
        });
        grad
    };
    let (gp, gm) = (gradient_at(1e-6), gradient_at(-1e-6));
    let uhu: f64 = (0..u.len()).map(|i| u[i] * (gp[i] - gm[i]) / 2e-6).sum();
    let mu_d = mu / d0;
    println!("along the lowest held mode: FD {second:.9e}, u·Hu {uhu:.9e}, μ/d = {mu_d:.4e}");
    assert!((second - uhu).abs() < 1e-4 * uhu.abs(), "{second} {uhu}");
    // Without the curvature term the two would differ by about μ/d times the foot's share.
    let m = &held.model;
    let foot_motion: f64 = (0..3)
        .map(|k| m.unknowns().of_node(foot, k).map_or(0.0, |v| u[v] * u[v]))
        .sum();
    assert!(
        mu_d * foot_motion > 1e-2 * uhu.abs(),
        "the test must see the term"
    );
}
