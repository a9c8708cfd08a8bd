//! Cost of a Newton iteration on a long chain against one factorization (docs/performance.md,
//! "Cost per iteration on long chains"):
//!
//! `cargo run --release --example chain_cost -- [N,N,..] [MAX_ITERATIONS]`
//!
//! `networks/cantilever.ron` (PL²/EI = 2) with its rod subdivided into N edges and at most
//! MAX_ITERATIONS Newton iterations (default 10⁴, 3·10⁴, 10⁵ edges; 30 iterations), solved as
//! the CLI solves it. Per iteration: the solve's wall time between the first and the last
//! progress report (every Newton iteration reports once, after its assembly; what lies
//! between two reports is one whole iteration: factorizations, solves, line search, length
//! repair, and any sub-step's end and start: stability checks, saddle escape, residual floor,
//! prediction), over the iterations between them. Then, at the state the solve ended at, the
//! median of 5 of: one numeric factorization (of H + 1e-10·diag scale·I, the shift the solver
//! starts its regularization with; the cost is the same with or without), one assembly
//! (energy, gradient, Hessian), one solve, one product H·x, one energy. The ratio is the iteration's wall time
//! over the factorization's. Everything runs on a worker of the thread pool, as the solver
//! does.
use std::sync::{Arc, Mutex};
use std::time::Instant;

use rodnet::network::assembly::{Assembly, HessianOut};
use rodnet::pipeline::{settings_of, solve_scene};
use rodnet::solver::linalg::SparseCholesky;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    rodnet::solver::pool::in_pool(table);
}

fn table() {
    let mut args = std::env::args().skip(1);
    let ns: Vec<usize> = args.next().map_or_else(
        || vec![10_000, 30_000, 100_000],
        |a| a.split(',').map(|x| x.parse().unwrap()).collect(),
    );
    let max_its: usize = args.next().map_or(30, |a| a.parse().unwrap());
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/networks/cantilever.ron");
    let (base, _) = rodnet::scene::load(std::path::Path::new(path)).unwrap();
    println!(
        "| edges | unknowns | its | facts | solve s | per iteration ms | LLT ms | ratio | \
         assembly ms | solve ms | H·x ms | energy ms | nnz(L) |"
    );
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for &n in &ns {
        let mut scene = base.clone();
        scene.rods[0].subdivide = n;
        scene.solver.max_iterations = max_its;
        let stamps = Arc::new(Mutex::new(Vec::new()));
        let log = stamps.clone();
        let settings = settings_of(&scene)
            .progress(move |_, _, _, _| log.lock().unwrap().push(Instant::now()));
        let t0 = Instant::now();
        let sol = match solve_scene(&scene, &settings) {
            Ok(sol) => sol,
            // A subdivision whose round-off floor leaves no useful answer is refused before
            // anything is allocated (`network/floor.rs`): its row says so.
            Err(e) => {
                println!("| {n} | refused: {e:?} |");
                continue;
            }
        };
        let total = t0.elapsed().as_secs_f64();
        let stamps = stamps.lock().unwrap();
        let per_iteration = match (stamps.first(), stamps.last()) {
            (Some(a), Some(b)) if stamps.len() > 1 => {
                (*b - *a).as_secs_f64() / (stamps.len() - 1) as f64
            }
            _ => f64::NAN,
        };
        let model = sol.network.model;
        let pairs = model.hessian_pattern();
        let nf = model.n_free;
        let (mut chol, slots) = SparseCholesky::new(nf, &pairs);
        let hs = model.hessian_slots(&slots);
        let mut g = vec![0.0; nf];
        let assembly = median(
            (0..5)
                .map(|_| {
                    let t = Instant::now();
                    model.assemble(&mut Assembly {
                        grad: &mut g,
                        full_grad: None,
                        hess: Some(HessianOut {
                            values: &mut chol.values,
                            slots: &hs,
                        }),
                    });
                    t.elapsed().as_secs_f64()
                })
                .collect(),
        );
        let shift = 1e-10 * chol.diagonal_scale();
        let factor = median(
            (0..5)
                .map(|_| {
                    let t = Instant::now();
                    let _ = chol.factor(shift);
                    t.elapsed().as_secs_f64()
                })
                .collect(),
        );
        // Far from equilibrium the shifted Hessian may still be indefinite: a larger shift then,
        // for the solve's timing only.
        let mut s = shift;
        while chol.factor(s).is_err() {
            s *= 100.0;
        }
        let b: Vec<f64> = (0..nf).map(|i| (i as f64 * 0.37).sin()).collect();
        let mut x = b.clone();
        let solve = median(
            (0..5)
                .map(|_| {
                    x.copy_from_slice(&b);
                    let t = Instant::now();
                    chol.solve(&mut x);
                    t.elapsed().as_secs_f64()
                })
                .collect(),
        );
        let mut y = vec![0.0; nf];
        let multiply = median(
            (0..5)
                .map(|_| {
                    let t = Instant::now();
                    chol.multiply(&b, &mut y);
                    t.elapsed().as_secs_f64()
                })
                .collect(),
        );
        let energy = median(
            (0..5)
                .map(|_| {
                    let t = Instant::now();
                    std::hint::black_box(model.energy());
                    t.elapsed().as_secs_f64()
                })
                .collect(),
        );
        let r = &sol.report;
        println!(
            "| {n} | {nf} | {} | {} | {total:.2} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} | {} |",
            r.iterations,
            r.factorizations,
            1e3 * per_iteration,
            1e3 * factor,
            per_iteration / factor,
            1e3 * assembly,
            1e3 * solve,
            1e3 * multiply,
            1e3 * energy,
            chol.factor_nnz(),
        );
    }
}
