//! Single-rod validation against analytic mechanics. Each test states its reference and the
//! error it measured; tolerances sit just above the measured errors' expected size, never above
//! the physics being checked.

mod common;
mod support;

use common::*;
use rodnet::network::assembly::Assembly;
use rodnet::network::build::build;
use rodnet::pipeline::{settings_of, solve_scene};
use rodnet::scene::types::*;

fn tip(s: &Scene) -> ([f64; 3], rodnet::pipeline::Solution) {
    let sol = solve_scene(s, &settings_of(s)).unwrap();
    assert!(sol.report.converged, "{:?}", sol.report.message);
    let p = *sol.results.rods[0].points.last().unwrap();
    (p, sol)
}

/// Euler–Bernoulli: v = PL³/(3EI). At PL²/EI = 1e-4 the geometric nonlinearity is ~1e-9
/// relative (elastica: v/L = p/3 (1 − 0.114 p²…)); what remains is discretization, O(1/N²).
/// Measured: relative error 3.1e-4 at N = 40 and 7.8e-5 at N = 80.
#[test]
fn cantilever_small_load_matches_euler_bernoulli() {
    let p = 1e-4;
    let mut errs = vec![];
    for n in [40, 80] {
        let (x, _) = tip(&cantilever(n, p));
        let v = -x[1];
        let err = (v - p / 3.0).abs() / (p / 3.0);
        errs.push(err);
    }
    println!("small-load relative errors (N = 40, 80): {errs:?}");
    assert!(errs[1] < 1e-4, "{errs:?}");
    assert!(errs[0] / errs[1] > 3.5, "not second order: {errs:?}");
}

/// Elastica, PL²/EI = 2: v/L = 0.49345748, u/L = 0.16064172 (Bisshopp & Drucker 1945; our
/// elliptic-integral solution agrees to 1e-12). The clamp acts exactly at the vertex, so the
/// error falls as 1/N²: the ratio of successive errors must approach 4.
#[test]
fn cantilever_large_load_converges_quadratically() {
    let reference = support::cantilever_tip_load(2.0);
    assert!((reference.deflection - 0.49345748).abs() < 5e-9);
    let mut table = vec![];
    for n in [10, 20, 40, 80] {
        let (x, sol) = tip(&cantilever(n, 2.0));
        let ev = (-x[1] - reference.deflection).abs();
        let eu = ((1.0 - x[0]) - reference.shortening).abs();
        println!(
            "N = {n:3}: v/L = {:.8} (err {ev:.3e}), u/L = {:.8} (err {eu:.3e}), {} iterations",
            -x[1],
            1.0 - x[0],
            sol.report.iterations
        );
        table.push((ev, eu));
    }
    for w in table.windows(2) {
        let (r1, r2) = (w[0].0 / w[1].0, w[0].1 / w[1].1);
        assert!(r1 > 3.5 && r1 < 4.5, "v error ratio {r1}");
        assert!(r2 > 3.5 && r2 < 4.5, "u error ratio {r2}");
    }
    assert!(table[3].0 < 1e-4 && table[3].1 < 1e-4, "{table:?}");
}

/// Pinned–pinned strut under end shortening d/L = 0.1 (prescribed move of one pin): the
/// elastica gives PL²/EI = 10.392564 and midspan deflection w/L = 0.194924. The straight state
/// is a saddle; the solver must leave it and find the buckled state.
#[test]
fn euler_postbuckled_strut() {
    let reference = support::euler_buckling_postbuckled(0.1);
    let mut errs = vec![];
    let mut vals = vec![];
    for n in [40, 80] {
        let mut s = scene(
            material_ei(1.0, 1e-3, 0.5),
            vec![rod("strut", vec![[0.0; 3], [1.0, 0.0, 0.0]], n)],
        );
        s.supports.push(support("strut", 0, SupportKind::Pin));
        let mut end = support("strut", 1, SupportKind::Pin);
        end.move_to = Some([0.9, 0.0, 0.0]);
        s.supports.push(end);
        s.solver.load_steps = 5;
        let sol = solve_scene(&s, &settings_of(&s)).unwrap();
        assert!(sol.report.converged, "{:?}", sol.report.message);
        let pts = &sol.results.rods[0].points;
        let w = pts
            .iter()
            .map(|p| (p[1] * p[1] + p[2] * p[2]).sqrt())
            .fold(0.0, f64::max);
        let load = sol.results.reactions[1].force[0].abs();
        let (el, ew) = (
            (load - reference.load).abs() / reference.load,
            (w - reference.midspan_deflection).abs() / reference.midspan_deflection,
        );
        println!(
            "N = {n}: PL²/EI = {load:.6} (rel err {el:.2e}), w/L = {w:.6} (rel err {ew:.2e}), \
             {} saddle escapes, stable {}",
            sol.report.saddle_escapes, sol.report.stable
        );
        errs.push((el, ew));
        vals.push((load, w));
        // A minimum up to its zero modes (the buckled strut may turn about the line through
        // its pins): neutral, which `stable` (positive definite only) does not call stable.
        assert!(
            sol.report.stable || sol.report.neutral(),
            "post-buckled state must be a minimum (up to zero modes)"
        );
    }
    // Second order: the errors fall by ~4 from N = 40 to 80, and the Richardson extrapolate
    // (4·f80 − f40)/3 matches the elastica far better than either.
    assert!(
        errs[0].0 / errs[1].0 > 3.5 && errs[0].1 / errs[1].1 > 3.5,
        "{errs:?}"
    );
    let rich_load = (4.0 * vals[1].0 - vals[0].0) / 3.0;
    let rich_w = (4.0 * vals[1].1 - vals[0].1) / 3.0;
    println!("Richardson: PL²/EI = {rich_load:.7}, w/L = {rich_w:.7}");
    assert!((rich_load - reference.load).abs() < 2e-5 * reference.load);
    assert!((rich_w - reference.midspan_deflection).abs() < 2e-5 * reference.midspan_deflection);
}

/// Critical load π²EI/L² of the pinned–pinned strut: the straight strut is shortened by a
/// prescribed end move so that its axial force EA·ε is 3 % below, then 3 % above π²EI/L².
/// Below, the straight state is a strict minimum (stable, no escape, no lateral deflection);
/// above, it is a saddle that the solver leaves, and the strut buckles. (The discrete critical
/// load of N = 40 is within 1e-3 of π²EI/L².)
#[test]
fn euler_critical_load_brackets_buckling() {
    let pc = support::euler_critical_load(1.0, 1.0);
    let ea = 4.0 / 1e-6; // E·πr² with EI = 1, r = 1e-3
    for (factor, buckles) in [(0.97, false), (1.03, true)] {
        let mut s = scene(
            material_ei(1.0, 1e-3, 0.5),
            vec![rod("strut", vec![[0.0; 3], [1.0, 0.0, 0.0]], 40)],
        );
        s.supports.push(support("strut", 0, SupportKind::Pin));
        let mut end = support("strut", 1, SupportKind::Pin);
        let strain = factor * pc / ea;
        end.move_to = Some([1.0 - strain, 0.0, 0.0]);
        s.supports.push(end);
        let sol = solve_scene(&s, &settings_of(&s)).unwrap();
        assert!(sol.report.converged, "{:?}", sol.report.message);
        let lateral = sol.results.rods[0]
            .points
            .iter()
            .map(|p| (p[1] * p[1] + p[2] * p[2]).sqrt())
            .fold(0.0, f64::max);
        println!(
            "EAε/Pc = {factor}: lateral {lateral:.3e}, escapes {}, axial force {:.6}",
            sol.report.saddle_escapes, sol.results.reactions[1].force[0]
        );
        if buckles {
            // Post-critical amplitude of the sine mode: the shortening beyond the critical
            // strain goes into bending, (π²A²)/(4L) = (ε − ε_c)L, so A = (2L/π)·sqrt(ε − ε_c).
            let expected = 2.0 / std::f64::consts::PI * ((factor - 1.0) * pc / ea).sqrt();
            println!("  expected amplitude {expected:.4e}");
            assert!(sol.report.saddle_escapes > 0, "did not leave the saddle");
            assert!(
                (lateral - expected).abs() < 0.05 * expected,
                "{lateral} vs {expected}"
            );
        } else {
            assert!(
                sol.report.saddle_escapes == 0 && lateral < 1e-12,
                "buckled below Pc"
            );
        }
    }
}

/// Uniform twist between clamps: the far clamp is rotated by φ about the axis; the reaction
/// torque is GJφ/L exactly (any N), and the twist angle grows linearly along the rod.
#[test]
fn uniform_twist_is_exact_for_any_n() {
    let phi = 2.5;
    for n in [1, 3, 10] {
        let mat = material_ei(1.0, 1e-2, 0.3);
        let gj = mat.shear() * std::f64::consts::PI * 1e-8 / 2.0;
        let mut s = scene(mat, vec![rod("bar", vec![[0.0; 3], [2.0, 0.0, 0.0]], n)]);
        s.supports.push(support("bar", 0, SupportKind::Clamp));
        let mut end = support("bar", 1, SupportKind::Clamp);
        end.rotate_by = Some([phi, 0.0, 0.0]);
        s.supports.push(end);
        s.solver.load_steps = 3;
        let sol = solve_scene(&s, &settings_of(&s)).unwrap();
        assert!(sol.report.converged);
        let expected = support::uniform_twist_torque(gj, phi, 2.0);
        let m0 = sol.results.reactions[0].moment[0];
        let m1 = sol.results.reactions[1].moment[0];
        println!("N = {n}: torque {m1:.12e}, expected {expected:.12e}");
        assert!(
            (m1 - expected).abs() < 1e-9 * expected,
            "{m1} vs {expected}"
        );
        assert!((m0 + expected).abs() < 1e-9 * expected);
        let tw = &sol.results.rods[0].twist;
        for (e, t) in tw.iter().enumerate() {
            let exact = phi * (e as f64 + 0.5) / n as f64;
            assert!((t - exact).abs() < 1e-9, "edge {e}: {t} vs {exact}");
        }
    }
}

/// A naturally curved and twisted rod (helix, anisotropic section) released from rest stays
/// at its rest shape with zero force: the first residual is at round-off and nothing moves.
#[test]
fn released_curved_rod_stays_at_rest() {
    let pts: Vec<[f64; 3]> = (0..12)
        .map(|k| {
            let t = k as f64 * 0.6;
            [t.cos(), t.sin(), 0.15 * t]
        })
        .collect();
    let mut mat = material_ei(1.0, 1e-2, 0.3);
    mat.section = Section::Ellipse { a: 0.02, b: 0.01 };
    let mut r = rod("helix", pts.clone(), 3);
    r.normal = Some([0.0, 0.0, 1.0]);
    let mut s = scene(mat, vec![r]);
    s.supports.push(support("helix", 0, SupportKind::Clamp));
    s.supports.push(support("helix", 7, SupportKind::Pin));
    let sol = solve_scene(&s, &settings_of(&s)).unwrap();
    assert!(sol.report.converged);
    assert_eq!(
        sol.report.iterations, 0,
        "rest state should already be in equilibrium"
    );
    let out = &sol.results.rods[0].points;
    for (k, p) in pts.iter().enumerate() {
        let q = out[3 * k];
        for c in 0..3 {
            assert!((p[c] - q[c]).abs() < 1e-14);
        }
    }
    for r in &sol.results.reactions {
        for v in r.force.iter().chain(&r.moment) {
            assert!(v.abs() < 1e-10, "{r:?}");
        }
    }
}

/// Energy is invariant and the gradient orthogonal under rigid motions: for an infinitesimal
/// rotation a and translation b, δx = a × x + b, edge angles δθ = a·t (time-parallel transport
/// carries no twist), frame increments δω = a.
#[test]
fn rigid_motion_invariance() {
    let mut rng = Rng::new(9);
    let pts: Vec<[f64; 3]> = (0..8)
        .map(|k| {
            let t = k as f64 * 0.5;
            [t, 0.3 * t.sin(), 0.2 * t.cos()]
        })
        .collect();
    let mut s = scene(material_ei(1.0, 1e-2, 0.3), vec![rod("r", pts.clone(), 4)]);
    s.rods
        .push(rod("s", vec![pts[3], [1.5, 1.0, 0.5], [1.0, 2.0, 0.0]], 4));
    s.joints.push(Joint {
        name: "j".into(),
        at: vec![("r".into(), 3), ("s".into(), 0)],
        kind: JointKind::Rigid,
        normal: None,
    });
    s.loads.push(Load::Torque {
        rod: "r".into(),
        vertex: 7,
        torque: [0.0; 3],
    });
    let mut net = build(&s).unwrap();
    let m = &mut net.model;
    // Deform: random node displacements, twist angles and frame increments.
    for v in 0..m.state.q.len() - 1 {
        m.state.q[v] += 0.05 * rng.range(-1.0, 1.0);
    }
    m.commit();
    for v in 0..m.state.q.len() - 1 {
        m.state.q[v] += 0.02 * rng.range(-1.0, 1.0);
    }
    // Infinitesimal rigid motions carry δθ = a·t only when tangents equal their time-parallel
    // references, i.e. at an accepted iterate.
    m.commit();
    let mut g = vec![0.0; m.n_free];
    let mut full = vec![0.0; m.state.q.len()];
    m.assemble(&mut Assembly {
        grad: &mut g,
        full_grad: Some(&mut full),
        hess: None,
    });
    let n_nodes = m.layout.n_nodes();
    let a = rng.vec3(1.0);
    let b = rng.vec3(1.0);
    let q = m.state.q.clone();
    let mut dq = vec![0.0; q.len()];
    for n in 0..n_nodes {
        let x = [q[3 * n], q[3 * n + 1], q[3 * n + 2]];
        let r = [
            a[1] * x[2] - a[2] * x[1],
            a[2] * x[0] - a[0] * x[2],
            a[0] * x[1] - a[1] * x[0],
        ];
        for k in 0..3 {
            dq[3 * n + k] = r[k] + b[k];
        }
    }
    for (e, [na, nb]) in m.edge_nodes.iter().enumerate() {
        let d: Vec<f64> = (0..3).map(|k| q[3 * nb + k] - q[3 * na + k]).collect();
        let l = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        dq[3 * n_nodes + e] = (a[0] * d[0] + a[1] * d[1] + a[2] * d[2]) / l;
    }
    for f in 0..m.state.frames.len() {
        let v = m.layout.frame(f)[0];
        dq[v..v + 3].copy_from_slice(&a);
    }
    let dot: f64 = full.iter().zip(&dq).map(|(x, y)| x * y).sum();
    let gn = full.iter().map(|x| x * x).sum::<f64>().sqrt();
    let dn = dq.iter().map(|x| x * x).sum::<f64>().sqrt();
    println!("|g·δq| / (|g||δq|) = {:.3e}", dot.abs() / (gn * dn));
    assert!(gn > 1e-3, "the deformed state should carry forces");
    assert!(dot.abs() < 1e-10 * gn * dn);
    // Finite rotation: energy unchanged.
    let e0 = m.energy();
    let w = [0.3, -0.7, 0.4];
    let rot = |x: [f64; 3]| rodnet::math::vec::rotate(w, x);
    for n in 0..n_nodes {
        let x = rot([q[3 * n], q[3 * n + 1], q[3 * n + 2]]);
        m.state.q[3 * n..3 * n + 3].copy_from_slice(&x);
    }
    for r in m.state.edges.iter_mut() {
        r.t = rot(r.t);
        r.u = rot(r.u);
    }
    for f in m.state.frames.iter_mut() {
        f.rotation = rodnet::math::vec::frame_rotate(w, &f.rotation);
    }
    let vars: Vec<usize> = (0..m.state.frames.len())
        .map(|f| m.layout.frame(f)[0])
        .collect();
    for v in vars {
        let x = rot([m.state.q[v], m.state.q[v + 1], m.state.q[v + 2]]);
        m.state.q[v..v + 3].copy_from_slice(&x);
    }
    let e1 = m.energy();
    println!("energy before {e0:.15e}, after rotation {e1:.15e}");
    assert!((e1 - e0).abs() < 1e-12 * e0.abs());
}
