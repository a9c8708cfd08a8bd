//! Exports: the OBJ loads with `tobj` and gives back every rod's nodes; the per-rod energies
//! of the results add up to the global elastic energy and match beam theory.

use rodnet::io::{obj, results::Results};
use rodnet::{pipeline as job, scene};

fn solve(src: &str) -> Results {
    let sc = scene::parse("test.ron", src).expect("scene parses");
    let sol = job::solve_scene(&sc, &job::settings_of(&sc)).expect("scene builds");
    assert!(sol.results.converged, "{:?}", sol.results.solver.message);
    sol.results
}

/// An open rod clamped at one end and a closed ring pinned at one point, both loaded.
const TWO_RODS: &str = r#"Scene(
    materials: { "m": Material(young_modulus: 1e7, poisson_ratio: 0.3, section: Circle(radius: 0.01)) },
    rods: [
        Rod(name: "arm", material: "m", points: [(0.0, 0.0, 0.0), (0.5, 0.0, 0.0), (1.0, 0.2, 0.0)], subdivide: 6),
        Rod(name: "ring", material: "m", points: [(2.0, 0.0, 0.0), (3.0, 0.0, 0.0), (3.0, 1.0, 0.0), (2.0, 1.0, 0.0)],
            subdivide: 5, closed: true),
    ],
    supports: [
        Support(rod: "arm", vertex: 0, kind: Clamp),
        Support(rod: "ring", vertex: 0, kind: Pin),
        Support(rod: "ring", vertex: 1, kind: Pin),
        Support(rod: "ring", vertex: 3, kind: Pin),
    ],
    loads: [
        Force(rod: "arm", vertex: 2, force: (0.0, 0.0, -0.5)),
        Force(rod: "ring", vertex: 2, force: (0.3, 0.3, -0.2)),
    ],
)"#;

#[test]
fn obj_export_loads_in_tobj_with_every_node() {
    let r = solve(TWO_RODS);
    let text = obj::to_obj(&r);
    let opts = tobj::LoadOptions {
        single_index: false,
        triangulate: false,
        ignore_points: false,
        ignore_lines: false,
    };
    let (models, _) = tobj::load_obj_buf(&mut text.as_bytes(), &opts, |_| {
        Err(tobj::LoadError::OpenFileFailed)
    })
    .expect("tobj loads the export");
    assert_eq!(models.len(), r.rods.len());
    for (m, rod) in models.iter().zip(&r.rods) {
        assert_eq!(m.name, rod.name);
        let pos = &m.mesh.positions;
        assert_eq!(pos.len(), 3 * rod.points.len(), "{}", rod.name);
        // The deformed shape really differs from the rest shape, so this compares solved nodes.
        for (k, p) in rod.points.iter().enumerate() {
            for c in 0..3 {
                let got = pos[3 * k + c] as f64;
                // tobj stores f32 positions.
                assert!(
                    (got - p[c]).abs() <= 1e-6 * (1.0 + p[c].abs()),
                    "{} node {k}: {got} vs {}",
                    rod.name,
                    p[c]
                );
            }
        }
        // One polyline through the nodes in order; a closed rod returns to its first node.
        let closed = rod.points.len() == rod.twist.len();
        let mut expect: Vec<u32> = (0..rod.points.len() as u32).collect();
        if closed {
            expect.push(0);
        }
        assert_eq!(m.mesh.indices, expect, "{}", rod.name);
    }
    let arm = &r.rods[0];
    assert!(
        arm.points.last().unwrap()[2] < -1e-3,
        "the arm did not deflect"
    );
}

#[test]
fn rod_energies_add_up_to_the_elastic_energy() {
    // Two rods meeting at a rigid corner: their frame terms must be attributed too.
    let r = solve(
        r#"Scene(
    materials: { "m": Material(young_modulus: 1e7, poisson_ratio: 0.3, section: Ellipse(a: 0.01, b: 0.006)) },
    rods: [
        Rod(name: "post", material: "m", points: [(0.0, 0.0, 0.0), (0.0, 0.0, 1.0)], subdivide: 8),
        Rod(name: "beam", material: "m", points: [(0.0, 0.0, 1.0), (0.8, 0.0, 1.0), (0.8, 0.5, 1.0)], subdivide: 6),
    ],
    joints: [ Joint(name: "corner", at: [("post", 1), ("beam", 0)], kind: Rigid) ],
    supports: [ Support(rod: "post", vertex: 0, kind: Clamp) ],
    loads: [ Force(rod: "beam", vertex: 2, force: (0.1, -0.2, -0.4)) ],
)"#,
    );
    let e = &r.energy;
    let elastic = e.stretch + e.bend + e.twist;
    let parts = |f: fn(&rodnet::network::equilibrium::RodEnergy) -> f64| -> f64 {
        r.rods.iter().map(|rod| f(&rod.energy)).sum()
    };
    for (name, global, sum) in [
        ("stretch", e.stretch, parts(|x| x.stretch)),
        ("bend", e.bend, parts(|x| x.bend)),
        ("twist", e.twist, parts(|x| x.twist)),
        ("total", elastic, parts(|x| x.total)),
    ] {
        assert!(
            (global - sum).abs() <= 1e-12 * elastic,
            "{name}: global {global} vs sum over rods {sum}"
        );
    }
    for rod in &r.rods {
        assert!(
            rod.energy.bend > 0.0 && rod.energy.twist > 0.0,
            "{}",
            rod.name
        );
        assert_eq!(rod.bending_stress.len(), rod.points.len());
        let max = rod.bending_stress.iter().copied().fold(0.0, f64::max);
        assert_eq!(max, rod.max_bending_stress);
    }
}

#[test]
fn rod_energy_of_independent_cantilevers_matches_beam_theory() {
    // Linear range: tip deflection F L³/(3EI) ≈ 4e-4 L, so the stored energy is F² L³/(6EI)
    // up to the O((F L²/EI)²) geometric nonlinearity (~1e-7) and the discretization error of
    // the curvature, O(1/N²) with N = 40 edges.
    let (e, r, f) = (1e8_f64, 0.01_f64, 1e-3_f64);
    let ei = e * std::f64::consts::PI * r.powi(4) / 4.0;
    let res = solve(&format!(
        r#"Scene(
    materials: {{ "m": Material(young_modulus: {e:e}, poisson_ratio: 0.3, section: Circle(radius: {r})) }},
    rods: [
        Rod(name: "a", material: "m", points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0)], subdivide: 40),
        Rod(name: "b", material: "m", points: [(0.0, 1.0, 0.0), (1.0, 1.0, 0.0)], subdivide: 40),
    ],
    supports: [ Support(rod: "a", vertex: 0, kind: Clamp), Support(rod: "b", vertex: 0, kind: Clamp) ],
    loads: [ Force(rod: "a", vertex: 1, force: (0.0, 0.0, -{f:e})),
             Force(rod: "b", vertex: 1, force: (0.0, {:e}, 0.0)) ],
)"#,
        2.0 * f
    ));
    for (rod, force) in res.rods.iter().zip([f, 2.0 * f]) {
        let exact = force * force / (6.0 * ei);
        let got = rod.energy.total;
        assert!(
            ((got - exact) / exact).abs() < 1.0 / 1600.0,
            "rod {}: energy {got:e} vs beam theory {exact:e}",
            rod.name
        );
    }
}

#[test]
fn bending_stress_follows_the_moment_and_ignores_rest_curvature() {
    // Linear cantilever with a tip force: M(s) = F (L − s), σ = M r / I at every node, the
    // clamped node included. The vertex curvature is a centred difference (O(h²)); at the clamp
    // the half-stencil averages the curvature over [0, h/2], an O(h/L) = 1/40 · 1/4 bias.
    let (e, r, f, n) = (1e8_f64, 0.01_f64, 1e-3_f64, 40usize);
    let i = std::f64::consts::PI * r.powi(4) / 4.0;
    let res = solve(&format!(
        r#"Scene(
    materials: {{ "m": Material(young_modulus: {e:e}, poisson_ratio: 0.3, section: Circle(radius: {r})) }},
    rods: [ Rod(name: "a", material: "m", points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0)], subdivide: {n}) ],
    supports: [ Support(rod: "a", vertex: 0, kind: Clamp) ],
    loads: [ Force(rod: "a", vertex: 1, force: (0.0, 0.0, -{f:e})) ],
)"#
    ));
    let s = &res.rods[0].bending_stress;
    assert_eq!(s[n], 0.0, "free end");
    for (k, &got) in s.iter().enumerate().take(n - 1) {
        let exact = f * (1.0 - k as f64 / n as f64) * r / i;
        let tol = if k == 0 { 0.25 / n as f64 } else { 1e-3 };
        assert!(
            ((got - exact) / exact).abs() < tol,
            "node {k}: {got:e} vs {exact:e}"
        );
    }
    // A rod drawn as a bent polyline, held and unloaded, is at rest: no stress anywhere, though
    // its polyline corners have large curvature.
    let res = solve(
        r#"Scene(
    materials: { "m": Material(young_modulus: 1e9, poisson_ratio: 0.3, section: Rectangle(width: 0.02, height: 0.01)) },
    rods: [ Rod(name: "zig", material: "m", points: [(0.0, 0.0, 0.0), (1.0, 0.5, 0.0), (2.0, 0.0, 0.3), (3.0, 0.4, 0.0)], subdivide: 3) ],
    supports: [ Support(rod: "zig", vertex: 0, kind: Clamp) ],
)"#,
    );
    // Measured against the total curvature, the corners would carry E·c·κ ≈ E·c/l̄ ≈ 3e7 Pa;
    // what is left is round-off of the curvature, ~1e-16 of that.
    let rod = &res.rods[0];
    let corner_scale = 1e9 * 0.01 / 0.4;
    assert!(
        rod.max_bending_stress < 1e-12 * corner_scale,
        "{:?}",
        rod.bending_stress
    );
}
