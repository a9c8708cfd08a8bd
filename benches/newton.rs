//! Cost of the pieces of a Newton iteration and of whole solves.
//!
//! `cargo bench --bench newton` (add `RAYON_NUM_THREADS=1` to measure serial assembly).
//! - `grid_*`: a 20×20 grid of crossing rods (Ball joints at 400 crossings, pinned ends, gravity),
//!   subdivide 4: energy+gradient+Hessian assembly, symbolic analysis, numeric factorization, and
//!   one full Newton iteration (assembly, factorization, solve, length projection, line search).
//! - `kernel_*`: the fused bend-and-twist kernels alone, one thread, no scatter: every
//!   rod-interior stencil of that grid (`BendTwist`), every half-stencil of the same grid with
//!   rigid joints (`FrameBendTwist`).
//! - `cantilever_solve`: the large-deflection cantilever (PL²/EI = 2) from rest, N edges.
//! - `chain_*`: `networks/cantilever.ron` subdivided into 10⁴, 3·10⁴ and 10⁵ edges, at rest under
//!   its full load: assembly, numeric factorization, and one Newton iteration as for the grid,
//!   on H + τI with the first τ of 1e-10, 1e-8, … of the diagonal scale that factors (whole
//!   solves per iteration: `examples/chain_cost.rs`; docs/performance.md, "Cost per iteration
//!   on long chains").

mod common;

use std::collections::BTreeMap;

use rodnet::energy::Term;
use rodnet::network::assembly::HessianSlots;
use rodnet::network::build::build;
use rodnet::network::model::Model;
use rodnet::scene::types::*;
use rodnet::solver::linalg::SparseCholesky;
use rodnet::solver::NewtonSettings;

fn main() {
    divan::main();
}

fn material(r: f64) -> Material {
    Material {
        young_modulus: 4.0 / (std::f64::consts::PI * r.powi(4)),
        poisson_ratio: Some(0.3),
        shear_modulus: None,
        density: 1000.0,
        section: Section::Circle { radius: r },
        yield_strength: None,
    }
}

fn grid_scene(n: usize, subdivide: usize) -> Scene {
    grid_scene_with(n, subdivide, JointKind::Ball)
}

fn grid_scene_with(n: usize, subdivide: usize, kind: JointKind) -> Scene {
    let mut materials = BTreeMap::new();
    materials.insert("m".to_string(), material(0.01));
    let mut rods = Vec::new();
    let mut joints = Vec::new();
    let mut supports = Vec::new();
    let len = (n + 1) as f64;
    for k in 0..n {
        let c = (k + 1) as f64;
        let xs: Vec<[f64; 3]> = (0..=n + 1).map(|i| [i as f64, c, 0.0]).collect();
        let ys: Vec<[f64; 3]> = (0..=n + 1).map(|i| [c, i as f64, 0.0]).collect();
        for (name, pts) in [(format!("x{k}"), xs), (format!("y{k}"), ys)] {
            supports.push(Support {
                rod: name.clone(),
                vertex: 0,
                kind: SupportKind::Pin,
                move_to: None,
                rotate_by: None,
            });
            supports.push(Support {
                rod: name.clone(),
                vertex: n + 1,
                kind: SupportKind::Pin,
                move_to: None,
                rotate_by: None,
            });
            rods.push(Rod {
                name,
                material: "m".into(),
                points: pts,
                subdivide,
                closed: false,
                normal: None,
                end_correction: true,
            });
        }
    }
    for i in 0..n {
        for j in 0..n {
            joints.push(Joint {
                name: format!("j{i}_{j}"),
                at: vec![(format!("x{j}"), i + 1), (format!("y{i}"), j + 1)],
                kind: kind.clone(),
                normal: None,
            });
        }
    }
    let _ = len;
    Scene {
        materials,
        rods,
        joints,
        supports,
        loads: vec![Load::Gravity {
            g: [0.0, 0.0, -9.81],
        }],
        obstacles: vec![],
        bounds: vec![],
        target: None,
        reference: None,
        stages: vec![],
        solver: Solver::default(),
    }
}

fn grid_model() -> (Model, HessianSlots, SparseCholesky) {
    let mut m = build(&grid_scene(20, 4)).unwrap().model;
    m.set_load(1.0);
    let (chol, slots) = SparseCholesky::new(m.n_free, &m.hessian_pattern());
    let hs = m.hessian_slots(&slots);
    (m, hs, chol)
}

#[divan::bench]
fn grid_assembly(bencher: divan::Bencher) {
    let (m, hs, mut chol) = grid_model();
    let mut g = vec![0.0; m.n_free];
    bencher.bench_local(|| common::assemble(&m, &mut g, &mut chol, &hs));
}

/// The fused kernels alone (derivatives of every stencil of one kind, no scatter, one thread):
/// `BendTwist` on the grid's rod interiors, `FrameBendTwist` on the same grid with rigid joints.
#[divan::bench]
fn kernel_bend_twist(bencher: divan::Bencher) {
    let m = build(&grid_scene(20, 4)).unwrap().model;
    let st = &m.state;
    bencher.bench_local(|| {
        let mut s = 0.0;
        for t in &m.terms.bend_twist {
            s += t.derivatives(st, &t.gather(&st.q)).h[0][10];
        }
        s
    });
}

#[divan::bench]
fn kernel_frame_bend_twist(bencher: divan::Bencher) {
    let m = build(&grid_scene_with(20, 4, JointKind::Rigid))
        .unwrap()
        .model;
    let st = &m.state;
    assert!(!m.terms.frame_bend_twist.is_empty());
    bencher.bench_local(|| {
        let mut s = 0.0;
        for t in &m.terms.frame_bend_twist {
            s += t.derivatives(st, &t.gather(&st.q)).h[0][10];
        }
        s
    });
}

#[divan::bench]
fn grid_symbolic(bencher: divan::Bencher) {
    let (m, _, _) = grid_model();
    let pairs = m.hessian_pattern();
    bencher.bench_local(|| SparseCholesky::new(m.n_free, &pairs).1.len());
}

#[divan::bench]
fn grid_factorization(bencher: divan::Bencher) {
    let (m, hs, mut chol) = grid_model();
    let mut g = vec![0.0; m.n_free];
    common::assemble(&m, &mut g, &mut chol, &hs);
    bencher.bench_local(|| chol.factor(0.0).is_ok());
}

#[divan::bench]
fn grid_newton_iteration(bencher: divan::Bencher) {
    let (m0, hs, mut chol) = grid_model();
    common::bench_newton_iteration(bencher, &m0, &hs, &mut chol, 0.0);
}

#[divan::bench(args = [10, 40, 160, 640])]
fn cantilever_solve(bencher: divan::Bencher, n: usize) {
    let mut materials = BTreeMap::new();
    materials.insert("m".to_string(), material(1e-3));
    let s = Scene {
        materials,
        rods: vec![Rod {
            name: "b".into(),
            material: "m".into(),
            points: vec![[0.0; 3], [1.0, 0.0, 0.0]],
            subdivide: n,
            closed: false,
            normal: None,
            end_correction: true,
        }],
        joints: vec![],
        supports: vec![Support {
            rod: "b".into(),
            vertex: 0,
            kind: SupportKind::Clamp,
            move_to: None,
            rotate_by: None,
        }],
        loads: vec![Load::Force {
            rod: "b".into(),
            vertex: 1,
            force: [0.0, -2.0, 0.0],
        }],
        obstacles: vec![],
        bounds: vec![],
        target: None,
        reference: None,
        stages: vec![],
        solver: Solver::default(),
    };
    let settings = NewtonSettings::default();
    bencher.bench_local(|| {
        let mut net = build(&s).unwrap();
        rodnet::network::solve(&mut net.model, &settings).converged
    });
}

/// The chain of `edges` edges at rest under its full load, its slot map, a factorization object
/// on its pattern with the Hessian's values in it, and the shift that factors it.
fn chain_model(edges: usize) -> (Model, HessianSlots, SparseCholesky, f64) {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/networks/cantilever.ron");
    let (mut scene, _) = rodnet::scene::load(std::path::Path::new(path)).unwrap();
    scene.rods[0].subdivide = edges;
    let mut m = build(&scene).unwrap().model;
    m.set_load(1.0);
    let (mut chol, slots) = SparseCholesky::new(m.n_free, &m.hessian_pattern());
    let hs = m.hessian_slots(&slots);
    let mut g = vec![0.0; m.n_free];
    common::assemble(&m, &mut g, &mut chol, &hs);
    let mut shift = 1e-10 * chol.diagonal_scale();
    while chol.factor(shift).is_err() {
        shift *= 100.0;
    }
    (m, hs, chol, shift)
}

#[divan::bench(args = [10_000, 30_000, 100_000], sample_count = 10)]
fn chain_assembly(bencher: divan::Bencher, edges: usize) {
    let (m, hs, mut chol, _) = chain_model(edges);
    let mut g = vec![0.0; m.n_free];
    bencher.bench_local(|| common::assemble(&m, &mut g, &mut chol, &hs));
}

#[divan::bench(args = [10_000, 30_000, 100_000], sample_count = 10)]
fn chain_factorization(bencher: divan::Bencher, edges: usize) {
    let (_, _, mut chol, shift) = chain_model(edges);
    bencher.bench_local(|| chol.factor(shift).is_ok());
}

#[divan::bench(args = [10_000, 30_000, 100_000], sample_count = 10)]
fn chain_newton_iteration(bencher: divan::Bencher, edges: usize) {
    let (m0, hs, mut chol, shift) = chain_model(edges);
    common::bench_newton_iteration(bencher, &m0, &hs, &mut chol, shift);
}
