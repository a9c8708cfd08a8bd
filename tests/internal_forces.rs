//! Internal forces at equilibrium against statics: in a cantilever loaded only at its tip, the
//! internal force at every section is the tip force, so the axial force of each edge is
//! N = F·t (tension positive, t the edge's unit tangent towards the tip). Bending and twisting
//! energies see an edge only through scale-free curvatures (κb = 2 e₁×e₂ / (|e₁||e₂| + e₁·e₂)
//! and frames of unit tangents), so they exert no force along an edge, and the edge's stretch
//! force carries the whole axial component. The only error is the solve's:
//! each node is in equilibrium to tolerance × |F|, and the edge force sums the nodes beyond it,
//! so |N − F·t| ≤ n · tolerance · |F| for n edges.

mod common;

use common::*;
use rodnet::math::vec::{dot, norm, normalize, sub};
use rodnet::pipeline::{settings_of, solve_scene};

/// Largest |N_e − F·t_e| / |F| over the edges of the cantilever with `n` edges, and the
/// tolerance of its solve.
fn axial_error(n: usize) -> (f64, f64) {
    let s = cantilever(n, 2.0);
    let sol = solve_scene(&s, &settings_of(&s)).unwrap();
    assert!(sol.report.converged);
    let force = match s.loads[0] {
        rodnet::scene::types::Load::Force { force, .. } => force,
        _ => unreachable!("a tip force"),
    };
    let rod = &sol.equilibrium.rods[0];
    assert_eq!(rod.axial_force.len(), rod.points.len() - 1);
    let err = rod
        .axial_force
        .iter()
        .enumerate()
        .map(|(e, &n_e)| {
            let t = normalize(sub(rod.points[e + 1], rod.points[e]));
            (n_e - dot(force, t)).abs() / norm(force)
        })
        .fold(0.0, f64::max);
    (err, sol.report.tolerance)
}

#[test]
fn cantilever_axial_force_is_the_tip_force_along_the_tangent() {
    for n in [20, 40, 80] {
        let (err, tol) = axial_error(n);
        println!(
            "{n} edges: max |N − F·t| / |F| = {err:.3e} (bound n·tol = {:.1e})",
            n as f64 * tol
        );
        assert!(err <= n as f64 * tol, "{n} edges: {err:.3e}");
    }
}

// ---------------------------------------------------------------------------------------------
// Per-edge internal forces (`forces`): docs/internal-forces.md. Each check states its tolerance;
// the measured errors are in docs/validation.md ("Internal forces").

use rodnet::network::equilibrium::EdgeForces;
use rodnet::pipeline::Solution;
use rodnet::scene::types::{Load, Section, SupportKind};

fn solved(s: &rodnet::scene::types::Scene) -> Solution {
    let sol = solve_scene(s, &settings_of(s)).unwrap();
    assert!(sol.report.converged, "{:?}", sol.report.message);
    sol
}

fn forces(sol: &Solution) -> &[EdgeForces] {
    &sol.equilibrium.rods[0].forces
}

/// A rod of length `l` along `dir` from the origin, clamped there, material `m`.
fn clamped_rod(
    m: rodnet::scene::types::Material,
    l: f64,
    dir: [f64; 3],
    n: usize,
) -> rodnet::scene::types::Scene {
    let mut s = scene(m, vec![rod("r", vec![[0.0; 3], dir.map(|d| d * l)], n)]);
    s.supports.push(support("r", 0, SupportKind::Clamp));
    s
}

fn steel(section: Section, density: f64) -> rodnet::scene::types::Material {
    rodnet::scene::types::Material {
        young_modulus: 2e11,
        poisson_ratio: Some(0.3),
        shear_modulus: None,
        density,
        section,
        yield_strength: None,
    }
}

/// Hanging rod (clamped at the top, gravity along it): the axial force of each edge is the
/// weight below its midpoint, ρ A g (L − s), s the rest arc length of the midpoint (the lumped
/// weights below a cut through an edge are exactly that). No discretization error: the error
/// is the solve's, at most n · tolerance · weight.
#[test]
fn hanging_rod_carries_the_weight_below() {
    let (l, g, rho, r) = (2.0, 9.81, 7850.0, 0.01);
    let area = std::f64::consts::PI * r * r;
    for n in [10, 20, 40, 80] {
        let mut s = clamped_rod(
            steel(Section::Circle { radius: r }, rho),
            l,
            [0.0, 0.0, -1.0],
            n,
        );
        s.loads.push(Load::Gravity { g: [0.0, 0.0, -g] });
        let sol = solved(&s);
        let weight = rho * area * g * l;
        let h = l / n as f64;
        let mut err: f64 = 0.0;
        for (k, f) in forces(&sol).iter().enumerate() {
            let want = rho * area * g * (l - (k as f64 + 0.5) * h);
            err = err.max((f.axial - want).abs() / weight);
            assert!(f
                .shear
                .iter()
                .chain(&f.moment)
                .all(|v| v.abs() < 1e-9 * weight * l));
        }
        println!("hanging rod, {n} edges: max |N − weight below| / weight = {err:.2e}");
        assert!(err <= n as f64 * sol.report.tolerance, "{n}: {err:.2e}");
    }
}

/// Straight bar clamped at one end and pulled by F at the other: N = F, no shear, no moment, in
/// every edge; with a yield strength the utilization is (F/A)/σ_y.
#[test]
fn pulled_bar_has_axial_force_f() {
    let (f, r, yield_strength) = (1.0e4, 0.01, 2.5e8);
    for n in [1, 8, 64] {
        let mut m = steel(Section::Circle { radius: r }, 0.0);
        m.yield_strength = Some(yield_strength);
        let mut s = clamped_rod(m, 1.0, [1.0, 0.0, 0.0], n);
        s.loads.push(Load::Force {
            rod: "r".into(),
            vertex: 1,
            force: [f, 0.0, 0.0],
        });
        let sol = solved(&s);
        let err = forces(&sol)
            .iter()
            .map(|e| {
                let side = e
                    .shear
                    .iter()
                    .chain(&e.moment)
                    .fold(0.0f64, |a, v| a.max(v.abs()));
                ((e.axial - f).abs() / f).max(side / f)
            })
            .fold(0.0, f64::max);
        let u = f / (std::f64::consts::PI * r * r) / yield_strength;
        let util = sol.equilibrium.utilization.as_ref().unwrap();
        println!(
            "pulled bar, {n} edges: max |N − F| / F = {err:.2e}, utilization {:.6} (want {u:.6})",
            util.max
        );
        assert!(err <= n as f64 * sol.report.tolerance, "{n}: {err:.2e}");
        assert!((util.max - u).abs() <= n as f64 * sol.report.tolerance * u);
        assert_eq!(sol.equilibrium.rods[0].utilization, Some(util.max));
    }
}

/// Shaft clamped at both ends, the far clamp turned by φ about the axis (`rotate_by`): the
/// torsion of every edge is GJ φ / L, positive for a right-handed turn of the far end about t.
/// A straight shaft twists uniformly, so there is no discretization error; the rectangle also
/// exercises the anisotropic bending terms (which depend on θ but carry no moment here).
#[test]
fn twisted_shaft_torsion_is_gj_phi_over_l() {
    let (l, phi) = (1.5, 0.8);
    for section in [
        Section::Circle { radius: 0.01 },
        Section::Rectangle {
            width: 0.02,
            height: 0.01,
        },
    ] {
        for n in [4, 16, 64] {
            let m = steel(section, 0.0);
            let gj = m.shear() * section.torsion_constant();
            let mut s = clamped_rod(m, l, [1.0, 0.0, 0.0], n);
            let mut far = support("r", 1, SupportKind::Clamp);
            far.rotate_by = Some([phi, 0.0, 0.0]);
            s.supports.push(far);
            let sol = solved(&s);
            let want = gj * phi / l;
            let err = forces(&sol)
                .iter()
                .map(|f| (f.torsion - want).abs() / want)
                .fold(0.0, f64::max);
            println!("twisted shaft {section:?}, {n} edges: max |T − GJφ/L| / (GJφ/L) = {err:.2e}");
            assert!(err <= 1e-8, "{section:?} {n}: {err:.2e}");
            // The far clamp holds the part beyond every cut: its reaction moment is the torsion.
            let far_moment = sol.equilibrium.reactions[1].reaction.moment[0];
            assert!((far_moment - want).abs() <= 1e-8 * want, "{far_moment}");
        }
    }
}

/// Cantilever (EI = 1, L = 1) with a small tip load P (PL²/EI = 1e-3):
/// - statics at the cut: the edge's force is P (|(axial, shear)| = P to the solve's tolerance)
///   and its midpoint moment is (x_tip − x_mid) × P; these hold exactly for any load and n;
/// - small-deflection beam theory: shear = P and M = P (L − s) at the midpoint's rest arc
///   length s, up to O((PL²/EI)²) of geometric non-linearity;
/// - the end-vertex moments against the constitutive EI κ of the reported curvature
///   κ = 2 sin(φ/2)/l̄: the bending energy's moment is EI sin(φ)/l̄, a factor cos(φ/2) from it,
///   so the difference falls as h² (κh)²/8 — halving h divides it by 4.
#[test]
fn cantilever_moment_is_p_times_lever_arm() {
    let p = 1e-3;
    let mut previous = None;
    for n in [10, 20, 40, 80] {
        let s = cantilever(n, p);
        let sol = solved(&s);
        let rod = &sol.equilibrium.rods[0];
        let tip = *rod.points.last().unwrap();
        let h = 1.0 / n as f64;
        let (mut statics, mut beam, mut shear, mut constitutive): (f64, f64, f64, f64) =
            (0.0, 0.0, 0.0, 0.0);
        for (k, f) in rod.forces.iter().enumerate() {
            let mid = [
                0.5 * (rod.points[k][0] + rod.points[k + 1][0]),
                0.5 * (rod.points[k][1] + rod.points[k + 1][1]),
                0.0,
            ];
            // (x_tip − x_mid) × (0, −P, 0) has only a z component.
            let mz = -(tip[0] - mid[0]) * p;
            let m = f.moment[0].hypot(f.moment[1]);
            statics = statics.max((m - mz.abs()).abs() / p);
            statics = statics.max((f.axial.hypot(f.shear[0].hypot(f.shear[1])) - p).abs() / p);
            beam = beam.max((m - p * (1.0 - (k as f64 + 0.5) * h)).abs() / p);
            shear = shear.max((f.shear[0].hypot(f.shear[1]) - p).abs() / p);
            if k > 0 {
                let mk = f.end_moments[0][0].hypot(f.end_moments[0][1]);
                let want = rod.bending[k].curvature; // EI = 1
                constitutive = constitutive.max((mk - want).abs() / p);
            }
        }
        println!(
            "cantilever, {n} edges: statics {statics:.2e}, |M − P(L−s)|/P {beam:.2e}, |V − P|/P {shear:.2e}, |M_vertex − EIκ|/P {constitutive:.2e}"
        );
        assert!(
            statics <= n as f64 * sol.report.tolerance,
            "{n}: {statics:.2e}"
        );
        assert!(beam <= 1e-6 && shear <= 1e-6, "{n}: {beam:.2e} {shear:.2e}");
        if let Some(prev) = previous {
            // Second order (ratio 4), with room for round-off at the finest level.
            assert!(
                constitutive < prev / 3.0,
                "{n}: {constitutive:.2e} after {prev:.2e}"
            );
        }
        previous = Some(constitutive);
    }
}

/// Utilization: the cantilever's most stressed section is at the clamp, where the end-vertex
/// moment is P·L (statics, to the solve's tolerance) and σ = P L r / I (N ≈ 0); the twisted
/// circular shaft has τ = T r / J everywhere and utilization √3 τ / σ_y (von Mises).
#[test]
fn utilization_is_von_mises_over_yield() {
    let (p, yield_strength) = (1e-3, 2e6);
    let mut s = cantilever(40, p);
    s.materials.get_mut("m").unwrap().yield_strength = Some(yield_strength);
    let sol = solved(&s);
    let Section::Circle { radius } = s.materials["m"].section else {
        unreachable!()
    };
    let i = std::f64::consts::PI * radius.powi(4) / 4.0;
    let tip_x = sol.equilibrium.rods[0].points.last().unwrap()[0];
    let want = p * tip_x * radius / i / yield_strength;
    let u = sol.equilibrium.utilization.clone().unwrap();
    println!(
        "cantilever utilization {:.9} at edge {} (want {want:.9})",
        u.max, u.edge
    );
    assert_eq!((u.rod.as_str(), u.edge), ("beam", 0));
    assert!((u.max - want).abs() <= 1e-6 * want, "{} vs {want}", u.max);

    let (l, phi, r) = (1.0, 0.1, 0.01);
    let mut m = steel(Section::Circle { radius: r }, 0.0);
    m.yield_strength = Some(2.5e8);
    let gj = m.shear() * std::f64::consts::PI * r.powi(4) / 2.0;
    let mut s = clamped_rod(m, l, [1.0, 0.0, 0.0], 8);
    let mut far = support("r", 1, SupportKind::Clamp);
    far.rotate_by = Some([phi, 0.0, 0.0]);
    s.supports.push(far);
    let sol = solved(&s);
    let tau = gj * phi / l * r / (std::f64::consts::PI * r.powi(4) / 2.0);
    let want = 3f64.sqrt() * tau / 2.5e8;
    let got = sol.equilibrium.rods[0].utilization.unwrap();
    println!("twisted shaft utilization {got:.9} (want {want:.9})");
    assert!((got - want).abs() <= 1e-9 * want);
}

/// Every scene in `networks/`: each rod's `forces` has one finite entry per edge with the
/// contract's four keys, and at each open rod end that is not in a joint, the end edge balances
/// what acts on the end node (and its frame) alone: F = −(loads + reactions + contact forces)
/// at the first node, F = +(…) at the last (what lies beyond the cut), and the end-vertex moment
/// likewise with the reaction moments and torques. Supported ends balance to round-off (a
/// reaction is the gradient there); free ends to the solve's tolerance. The axial component and
/// the torsion are checked with their signs (t from the end's edge), the rest by magnitude.
#[test]
fn networks_balance_at_their_free_rod_ends() {
    let mut checked = 0;
    let mut paths: Vec<_> = std::fs::read_dir("networks")
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "ron"))
        .collect();
    paths.sort();
    for path in paths {
        let (s, _) = rodnet::scene::load(&path).unwrap();
        let sol = solved(&s);
        let name = path.display();
        let json: serde_json::Value = serde_json::to_value(&sol.results).unwrap();
        let m = &sol.network.model;
        let (fs, ls) = (m.force_scale, m.length_scale);
        let tol = sol.report.tolerance;
        for (r, (rod, info)) in sol
            .equilibrium
            .rods
            .iter()
            .zip(&sol.network.rods)
            .enumerate()
        {
            let entries = json["rods"][r]["forces"].as_array().unwrap();
            assert_eq!(entries.len(), info.edges.len(), "{name} {}", rod.name);
            for e in entries {
                let keys: Vec<&str> = e.as_object().unwrap().keys().map(|k| k.as_str()).collect();
                // The contract's four, and each edge's utilization (extension) exactly when its
                // material has a yield strength.
                let (util, contract): (Vec<&str>, Vec<&str>) =
                    keys.into_iter().partition(|k| *k == "utilization");
                assert_eq!(contract, ["axial", "moment", "shear", "torsion"], "{name}");
                assert_eq!(!util.is_empty(), info.yield_strength.is_some(), "{name}");
            }
            assert!(rod.forces.iter().all(|f| [f.axial, f.torsion]
                .iter()
                .chain(&f.shear)
                .chain(&f.moment)
                .all(|v| v.is_finite())));
            if info.closed {
                continue;
            }
            let last_vertex = s.rods[r].points.len() - 1;
            for (end, vertex) in [(0usize, 0usize), (1, last_vertex)] {
                let in_joint = s
                    .joints
                    .iter()
                    .any(|j| j.at.iter().any(|(n, v)| *n == rod.name && *v == vertex));
                if in_joint {
                    continue;
                }
                let node = if end == 0 { 0 } else { rod.points.len() - 1 };
                let k = if end == 0 { 0 } else { rod.forces.len() - 1 };
                let e = info.edges[k];
                // What acts on the end node: point loads, lumped weight, reactions, contacts.
                let mut force = [0.0; 3];
                let mut moment = [0.0; 3];
                let add = |a: &mut [f64; 3], v: [f64; 3]| (0..3).for_each(|i| a[i] += v[i]);
                // A staged scene ends under every stage's loads.
                for l in &s.all_stages().loads {
                    match l {
                        Load::Force {
                            rod: n,
                            vertex: v,
                            force: f,
                        } if *n == rod.name && *v == vertex => add(&mut force, *f),
                        Load::Torque {
                            rod: n,
                            vertex: v,
                            torque,
                        } if *n == rod.name && *v == vertex => add(&mut moment, *torque),
                        Load::Gravity { g } => {
                            let w = 0.5 * info.stiffness.mass_per_length * m.rest_lengths[e];
                            add(&mut force, g.map(|c| c * w));
                        }
                        _ => {}
                    }
                }
                for s in &sol.equilibrium.reactions {
                    if s.rod == rod.name && s.vertex == vertex {
                        add(&mut force, s.reaction.force);
                        add(&mut moment, s.reaction.moment);
                    }
                }
                for c in sol.equilibrium.constraints.iter().flat_map(|c| &c.contacts) {
                    if c.rod == rod.name && c.node == node {
                        add(&mut force, c.force);
                    }
                }
                // F acts on the part before the cut: at the first node it balances that node,
                // at the last node it is what acts beyond the cut.
                let sign = if end == 0 { -1.0 } else { 1.0 };
                let t = normalize(sub(rod.points[k + 1], rod.points[k]));
                let f = &rod.forces[k];
                let em = f.end_moments[end];
                let f_err = (f.axial - sign * dot(force, t))
                    .abs()
                    .max((norm([f.axial, f.shear[0], f.shear[1]]) - norm(force)).abs());
                let m_err = (f.torsion - sign * dot(moment, t))
                    .abs()
                    .max((norm([em[0], em[1], f.torsion]) - norm(moment)).abs());
                println!(
                    "{name} {} vertex {vertex}: |F| = {:.3e} N, force error {:.1e} F_s, |M| = {:.3e} N·m, moment error {:.1e} F_s·L_s",
                    rod.name,
                    norm(force),
                    f_err / fs,
                    norm(moment),
                    m_err / (fs * ls)
                );
                assert!(f_err <= 10.0 * tol * fs, "{name} {}: {f_err:.2e}", rod.name);
                assert!(
                    m_err <= 10.0 * tol * fs * ls,
                    "{name} {}: {m_err:.2e}",
                    rod.name
                );
                checked += 1;
            }
        }
    }
    println!("{checked} rod ends checked");
    assert!(checked >= 50, "{checked} rod ends checked");
}
