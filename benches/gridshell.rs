//! Hemisphere form finding over rods per family n and edges per spacing K, and the pieces of
//! one Newton iteration at the n = 12, K = 8 equilibrium (docs/performance.md).
//!
//! `cargo bench --bench gridshell` (all), `cargo bench --bench gridshell -- form_finding`.
//! The larger cases take seconds per run: each is sampled 3 times.

mod common;

use rodnet::gridshell::footprint::{footprint, HemisphereSpec};
use rodnet::gridshell::formfind::DEFAULT_START_CAP;
use rodnet::gridshell::job::run;
use rodnet::network::assembly::HessianSlots;
use rodnet::network::build::build;
use rodnet::network::model::Model;
use rodnet::pipeline::{settings_of, solve_scene};
use rodnet::solver::linalg::nested_dissection;
use rodnet::solver::linalg::SparseCholesky;

fn main() {
    divan::main();
}

fn spec(case: &str) -> HemisphereSpec {
    let (n, k) = case.split_once('x').unwrap();
    HemisphereSpec::new(1.0, n.parse().unwrap(), k.parse().unwrap())
}

/// The whole form finding from the footprint (generation, cap path, Newton), "n x K".
#[divan::bench(
    args = ["8x4", "12x4", "16x4", "24x4", "8x8", "12x8", "16x8", "24x8", "8x16", "12x16",
            "16x16", "24x16", "8x32", "12x32"],
    sample_count = 3,
    sample_size = 1
)]
fn form_finding(case: &str) -> bool {
    run(
        &spec(case),
        DEFAULT_START_CAP,
        None,
        &rodnet::pipeline::Limits::NONE,
    )
    .unwrap()
    .results
    .converged
}

/// From the analytic net of the hemisphere (`--start-cap 1`).
#[divan::bench(args = ["12x4", "12x8", "24x8"], sample_count = 5, sample_size = 1)]
fn from_analytic_net(case: &str) -> bool {
    run(&spec(case), 1.0, None, &rodnet::pipeline::Limits::NONE)
        .unwrap()
        .results
        .converged
}

/// The flat footprint solved as a user's scene with only `buckle_toward: Some((0, 0, 1))` added
/// (no cap path: the buckling path from flat, docs/design.md), "n x K".
#[divan::bench(args = ["12x4", "12x8"], sample_count = 5, sample_size = 1)]
fn footprint_buckle_toward(bencher: divan::Bencher, case: &str) {
    let mut scene = footprint(&spec(case)).scene;
    scene.solver.buckle_toward = Some([0.0, 0.0, 1.0]);
    let settings = settings_of(&scene);
    bencher.bench_local(|| solve_scene(&scene, &settings).unwrap().report.converged);
}

/// The n = 12, K = 8 model at its equilibrium, with its Hessian pattern.
fn equilibrium() -> (Model, Vec<(usize, usize)>) {
    let s = spec("12x8");
    let r = run(&s, DEFAULT_START_CAP, None, &rodnet::pipeline::Limits::NONE).unwrap();
    let mut m = build(&footprint(&s).scene).unwrap().model;
    m.state = r.network.model.state.clone();
    m.set_load(1.0);
    let pairs = m.hessian_pattern();
    (m, pairs)
}

fn assembled(nd: bool) -> (Model, HessianSlots, SparseCholesky) {
    let (m, pairs) = equilibrium();
    let order = nd.then(|| nested_dissection(m.n_free, &pairs, &m.unknown_positions()));
    let (mut chol, slots) = SparseCholesky::with_order(m.n_free, &pairs, order.as_deref());
    let hs = m.hessian_slots(&slots);
    let mut g = vec![0.0; m.n_free];
    common::assemble(&m, &mut g, &mut chol, &hs);
    (m, hs, chol)
}

#[divan::bench]
fn hemisphere_assembly(bencher: divan::Bencher) {
    let (m, hs, mut chol) = assembled(false);
    let mut g = vec![0.0; m.n_free];
    bencher.bench_local(|| common::assemble(&m, &mut g, &mut chol, &hs));
}

#[divan::bench(args = [false, true])]
fn hemisphere_symbolic(bencher: divan::Bencher, nd: bool) {
    let (m, pairs) = equilibrium();
    bencher.bench_local(|| {
        let order = nd.then(|| nested_dissection(m.n_free, &pairs, &m.unknown_positions()));
        SparseCholesky::with_order(m.n_free, &pairs, order.as_deref())
            .0
            .factor_nnz()
    });
}

#[divan::bench(args = [false, true])]
fn hemisphere_factorization(bencher: divan::Bencher, nd: bool) {
    let (_, _, mut chol) = assembled(nd);
    let shift = 1e-10 * chol.diagonal_scale();
    bencher.bench_local(|| chol.factor(shift).is_ok());
}

/// One solve with the factor (forward and back substitution): the supernodal factor's own
/// loops (`solver/supernodal_solve.rs`).
#[divan::bench(args = [false, true])]
fn hemisphere_solve(bencher: divan::Bencher, nd: bool) {
    let (m, _, mut chol) = assembled(nd);
    chol.factor(1e-10 * chol.diagonal_scale()).unwrap();
    let b: Vec<f64> = (0..m.n_free).map(|i| (i as f64 * 0.37).sin()).collect();
    let mut x = b.clone();
    bencher.bench_local(|| {
        x.copy_from_slice(&b);
        chol.solve(&mut x);
        x[0]
    });
}

/// Assembly, factorization, solve, length projection, one trial energy and the update.
#[divan::bench]
fn hemisphere_newton_iteration(bencher: divan::Bencher) {
    let (m0, hs, mut chol) = assembled(false);
    let shift = 1e-10 * chol.diagonal_scale();
    common::bench_newton_iteration(bencher, &m0, &hs, &mut chol, shift);
}
