//! Cost of the hemisphere form finding against its floor, Newton iterations × one factorization,
//! over rods per family n and edges per spacing K (docs/performance.md):
//!
//! `cargo run --release --example perf_table -- [N,N,..] [K,K,..] [REPEATS]`
//!
//! For each (n, K): unknowns, Newton iterations, factorizations, the whole form finding (median
//! of REPEATS runs), and at the equilibrium the median of 21 (11 for factorizations) of: one
//! assembly (energy, gradient, Hessian), one numeric factorization with AMD and with geometric
//! nested dissection, and the non-zeros of both factors; then, with the faster factor, one
//! solve and one energy evaluation, and the bound: the ratio an iteration would have that did
//! nothing but one assembly, one factorization and one solve, 1 + (assembly + solve) / LLT.
//! Everything runs on a worker of the thread pool, as the solver does.
use std::time::Instant;

use rodnet::gridshell::footprint::{footprint, HemisphereSpec};
use rodnet::gridshell::formfind::DEFAULT_START_CAP;
use rodnet::gridshell::job::run;
use rodnet::network::assembly::{Assembly, HessianOut};
use rodnet::network::build::build;
use rodnet::solver::linalg::nested_dissection;
use rodnet::solver::linalg::SparseCholesky;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn list(arg: Option<String>, default: &[usize]) -> Vec<usize> {
    arg.map_or_else(
        || default.to_vec(),
        |a| a.split(',').map(|x| x.parse().unwrap()).collect(),
    )
}

fn main() {
    // Timed on a worker of the pool, as the solver runs them (`solver/pool.rs`): from outside
    // it, each parallel loop would also pay a wake-up.
    rodnet::solver::pool::in_pool(table);
}

fn table() {
    let mut args = std::env::args().skip(1);
    let ns = list(args.next(), &[8, 12, 16, 24]);
    let ks = list(args.next(), &[4, 8, 16, 32]);
    let repeats: usize = args.next().map_or(3, |r| r.parse().unwrap());
    println!(
        "| n | K | unknowns | its | facts | form finding s | assembly ms | LLT AMD ms | LLT ND ms | \
         nnz(L) AMD | nnz(L) ND | its × LLT s | ratio | solve ms | energy ms | bound |"
    );
    println!("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for &n in &ns {
        for &k in &ks {
            let spec = HemisphereSpec::new(1.0, n, k);
            let mut times = vec![];
            let mut last = None;
            for _ in 0..repeats {
                let r = run(
                    &spec,
                    DEFAULT_START_CAP,
                    None,
                    &rodnet::pipeline::Limits::NONE,
                )
                .unwrap();
                assert!(
                    r.results.converged,
                    "n {n} K {k}: {:?}",
                    r.results.solver.message
                );
                times.push(r.form.seconds);
                last = Some(r);
            }
            let r = last.unwrap();
            let total = median(times);
            // The pieces, at the equilibrium (the network of the last run).
            let mut model = build(&footprint(&spec).scene).unwrap().model;
            model.state = r.network.model.state.clone();
            model.set_load(1.0);
            let pairs = model.hessian_pattern();
            let nf = model.n_free;
            let pts = model.unknown_positions();
            let nd = nested_dissection(nf, &pairs, &pts);
            let (mut amd, slots) = SparseCholesky::new(nf, &pairs);
            let (mut ndc, _) = SparseCholesky::with_order(nf, &pairs, Some(&nd));
            let hs = model.hessian_slots(&slots);
            let mut g = vec![0.0; nf];
            let mut asm = vec![];
            for _ in 0..21 {
                let t = Instant::now();
                model.assemble(&mut Assembly {
                    grad: &mut g,
                    full_grad: None,
                    hess: Some(HessianOut {
                        values: &mut amd.values,
                        slots: &hs,
                    }),
                });
                asm.push(t.elapsed().as_secs_f64());
            }
            ndc.values.copy_from_slice(&amd.values);
            // A tiny shift as the solver may use; the cost is the same with or without.
            let shift = 1e-10 * amd.diagonal_scale();
            let time_factor = |c: &mut SparseCholesky| {
                median(
                    (0..11)
                        .map(|_| {
                            let t = Instant::now();
                            c.factor(shift).expect("positive definite");
                            t.elapsed().as_secs_f64()
                        })
                        .collect(),
                )
            };
            let (f_amd, f_nd) = (time_factor(&mut amd), time_factor(&mut ndc));
            let faster = if f_amd <= f_nd { &mut amd } else { &mut ndc };
            faster.factor(shift).expect("positive definite");
            let b: Vec<f64> = (0..nf).map(|i| (i as f64 * 0.37).sin()).collect();
            let mut x = b.clone();
            let solve = median(
                (0..21)
                    .map(|_| {
                        x.copy_from_slice(&b);
                        let t = Instant::now();
                        faster.solve(&mut x);
                        t.elapsed().as_secs_f64()
                    })
                    .collect(),
            );
            let energy = median(
                (0..21)
                    .map(|_| {
                        let t = Instant::now();
                        std::hint::black_box(model.energy());
                        t.elapsed().as_secs_f64()
                    })
                    .collect(),
            );
            let (llt, assembly) = (f_amd.min(f_nd), median(asm));
            let bound = 1.0 + (assembly + solve) / llt;
            let its = r.form.report.iterations;
            let floor = its as f64 * llt;
            println!(
                "| {n} | {k} | {nf} | {its} | {} | {total:.3} | {:.2} | {:.2} | {:.2} | {} | {} | {floor:.3} | {:.1} | {:.2} | {:.2} | {bound:.1} |",
                r.form.report.factorizations,
                1e3 * assembly,
                1e3 * f_amd,
                1e3 * f_nd,
                amd.factor_nnz(),
                ndc.factor_nnz(),
                total / floor,
                1e3 * solve,
                1e3 * energy,
            );
        }
    }
}
