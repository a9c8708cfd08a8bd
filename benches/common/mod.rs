//! Shared by the benchmarks: one assembly into a factorization object, and one Newton
//! iteration measured the same way everywhere.

use rodnet::network::assembly::{Assembly, HessianOut, HessianSlots};
use rodnet::network::model::Model;
use rodnet::network::NetworkProblem;
use rodnet::solver::linalg::SparseCholesky;
use rodnet::solver::problem::{LengthRepair, Steps};

/// Assembles `m`'s gradient into `g` and its Hessian into `chol`'s values through the slot map
/// `hs`; returns the energy.
pub fn assemble(m: &Model, g: &mut [f64], chol: &mut SparseCholesky, hs: &HessianSlots) -> f64 {
    m.assemble(&mut Assembly {
        grad: g,
        full_grad: None,
        hess: Some(HessianOut {
            values: &mut chol.values,
            slots: hs,
        }),
    })
}

/// Benchmarks one full Newton iteration from a fresh copy of `m0` each time: assembly,
/// factorization of H + shift·I, solve, length projection, one trial energy and the update.
/// `chol` must be built on `m0`'s Hessian pattern, `hs` its slot map.
pub fn bench_newton_iteration(
    bencher: divan::Bencher,
    m0: &Model,
    hs: &HessianSlots,
    chol: &mut SparseCholesky,
    shift: f64,
) {
    let n = m0.n_free;
    let (mut g, mut d, mut c) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    bencher
        .with_inputs(|| m0.clone())
        .bench_local_values(|mut m: Model| {
            let e0 = assemble(&m, &mut g, chol, hs);
            chol.factor(shift).expect("positive definite");
            for i in 0..n {
                d[i] = -g[i];
            }
            chol.solve(&mut d);
            let mut p = NetworkProblem::new(&mut m);
            p.step_correction(&d, &mut c);
            let e1 = p.trial_energy(&d, 1.0);
            p.accept(&d, 1.0);
            (e0, e1)
        });
}
