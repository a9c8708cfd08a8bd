//! The constrained Newton step as a convex QP, solved by Clarabel (interior point, sparse):
//!
//!   min ½ dᵀ(H + τI)d + gᵀd   subject to   c(x) + J d ≥ 0,
//!
//! with the same shift τ that makes the Cholesky factorization of H + τI succeed, so the QP is
//! convex exactly when the unconstrained step would be a descent direction. In Clarabel's form
//! (A d + s = b, s ≥ 0) that is A = −J and b = c(x). Its dual variables z ≥ 0 are the constraint
//! forces: stationarity reads g − Jᵀz = −(H + τI)d, so at a converged iterate (d → 0) each
//! z_j is the force (N) with which constraint j pushes along its unit gradient.
//!
//! The patterns of H and J never change during a solve, so the Clarabel solver is built once
//! (equilibration, KKT symbolic factorization) and every later step only overwrites values.
//! That requires presolve off and no dropped structural zeros (Clarabel refuses updates
//! otherwise).

use std::time::Instant;

use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettings, DefaultSettingsBuilder, DefaultSolver, IPSolver, NonnegativeConeT,
    SolverStatus,
};

use super::linalg::SparseCholesky;

pub struct StepQp {
    n: usize,
    m: usize,
    /// Jacobian pattern (constraint row, free unknown), in the problem's order.
    pattern: Vec<(usize, usize)>,
    /// Position of each pattern entry in A's CSC values.
    to_csc: Vec<usize>,
    a_col_ptr: Vec<usize>,
    a_row: Vec<usize>,
    a_val: Vec<f64>,
    p_val: Vec<f64>,
    q: Vec<f64>,
    /// Jacobi scaling d = S y with S = diag(H + τI)^(-1/2).
    scale: Vec<f64>,
    /// Constraint values c(x) at the current iterate.
    pub c: Vec<f64>,
    /// Jacobian values in pattern order.
    pub jac: Vec<f64>,
    /// Multipliers of the last solved QP (N for unit-gradient constraints).
    pub z: Vec<f64>,
    solver: Option<DefaultSolver<f64>>,
    pub solves: usize,
    pub iterations: usize,
    pub seconds: f64,
}

fn settings() -> DefaultSettings<f64> {
    // Newton converges only as far as its steps are accurate, and the stationarity residual it
    // reports is the QP's dual residual at the last iterate: both need the QP well below the
    // Newton tolerance (1e-9 of the force scale by default), hence 1e-12 instead of 1e-8.
    DefaultSettingsBuilder::default()
        .verbose(false)
        .presolve_enable(false)
        .input_sparse_dropzeros(false)
        .tol_gap_abs(1e-16)
        .tol_gap_rel(1e-14)
        .tol_feas(1e-12)
        .max_iter(200)
        .static_regularization_constant(1e-11)
        .build()
        .expect("valid Clarabel settings")
}

impl StepQp {
    pub fn new(n: usize, m: usize, pattern: Vec<(usize, usize)>) -> StepQp {
        let mut order: Vec<usize> = (0..pattern.len()).collect();
        order.sort_by_key(|&k| (pattern[k].1, pattern[k].0));
        let mut a_col_ptr = vec![0usize; n + 1];
        let mut a_row = Vec::with_capacity(pattern.len());
        let mut to_csc = vec![0usize; pattern.len()];
        for (pos, &k) in order.iter().enumerate() {
            let (r, c) = pattern[k];
            assert!(r < m && c < n, "constraint pattern out of range");
            a_row.push(r);
            a_col_ptr[c + 1] += 1;
            to_csc[k] = pos;
        }
        for c in 0..n {
            a_col_ptr[c + 1] += a_col_ptr[c];
        }
        StepQp {
            n,
            m,
            to_csc,
            a_col_ptr,
            a_row,
            a_val: vec![0.0; pattern.len()],
            p_val: Vec::new(),
            q: vec![0.0; n],
            scale: vec![1.0; n],
            c: vec![0.0; m],
            jac: vec![0.0; pattern.len()],
            z: vec![0.0; m],
            pattern,
            solver: None,
            solves: 0,
            iterations: 0,
            seconds: 0.0,
        }
    }

    pub fn len(&self) -> usize {
        self.m
    }

    pub fn is_empty(&self) -> bool {
        self.m == 0
    }

    /// Solves the step QP with `chol`'s last shifted matrix H + τI, gradient `g`, and the
    /// constraint values and Jacobian in `self.c`, `self.jac`. The step goes to `d`, the
    /// multipliers to `self.z`.
    pub fn solve(&mut self, chol: &SparseCholesky, g: &[f64], d: &mut [f64]) -> Result<(), String> {
        let t0 = Instant::now();
        // Position and angle unknowns differ in stiffness by up to 1e8 (EA/l against GJ/l), more
        // than Clarabel's equilibration bounds (1e±4) can even out; in the Jacobi-scaled
        // unknowns y = S⁻¹d every diagonal of P is 1. The multipliers are unchanged by it.
        let (cp, ri) = (chol.col_ptr(), chol.row_idx());
        self.p_val.clear();
        self.p_val.extend_from_slice(chol.shifted_values());
        for c in 0..self.n {
            let diag = self.p_val[cp[c + 1] - 1];
            self.scale[c] = if diag > 0.0 { diag.sqrt().recip() } else { 1.0 };
        }
        for c in 0..self.n {
            for k in cp[c]..cp[c + 1] {
                self.p_val[k] *= self.scale[ri[k]] * self.scale[c];
            }
        }
        for (k, &v) in self.jac.iter().enumerate() {
            self.a_val[self.to_csc[k]] = -v * self.scale[self.pattern[k].1];
        }
        for i in 0..self.n {
            self.q[i] = g[i] * self.scale[i];
        }
        let solver = match &mut self.solver {
            Some(s) => {
                let err = |e| format!("Clarabel rejected a data update: {e}");
                s.update_P(&self.p_val).map_err(err)?;
                s.update_q(&self.q).map_err(err)?;
                s.update_A(&self.a_val).map_err(err)?;
                s.update_b(&self.c).map_err(err)?;
                s
            }
            None => {
                let p = CscMatrix::new(
                    self.n,
                    self.n,
                    chol.col_ptr().to_vec(),
                    chol.row_idx().to_vec(),
                    self.p_val.clone(),
                );
                let a = CscMatrix::new(
                    self.m,
                    self.n,
                    self.a_col_ptr.clone(),
                    self.a_row.clone(),
                    self.a_val.clone(),
                );
                let s = DefaultSolver::new(
                    &p,
                    &self.q,
                    &a,
                    &self.c,
                    &[NonnegativeConeT(self.m)],
                    settings(),
                )
                .map_err(|e| format!("Clarabel setup failed: {e}"))?;
                self.solver.insert(s)
            }
        };
        solver.solve();
        let sol = &solver.solution;
        let (status, its) = (sol.status, sol.iterations);
        for i in 0..self.n {
            d[i] = sol.x[i] * self.scale[i];
        }
        self.z.copy_from_slice(&sol.z);
        self.solves += 1;
        self.iterations += its as usize;
        self.seconds += t0.elapsed().as_secs_f64();
        if !matches!(status, SolverStatus::Solved | SolverStatus::AlmostSolved) {
            return Err(format!(
                "the step QP was not solved (Clarabel status {status:?} after {its} iterations)"
            ));
        }
        self.make_feasible(d);
        Ok(())
    }

    /// Interior-point solutions satisfy the linearized constraints only to the QP's tolerance;
    /// the line search needs them exactly, or a node resting on an obstacle could never move.
    /// Each violated row moves its unknowns along its gradient by the violation (one sweep; rows
    /// of different nodes do not interact).
    fn make_feasible(&self, d: &mut [f64]) {
        let mut start = 0;
        while start < self.pattern.len() {
            let row = self.pattern[start].0;
            let mut end = start;
            while end < self.pattern.len() && self.pattern[end].0 == row {
                end += 1;
            }
            let mut lin = self.c[row];
            let mut g2 = 0.0;
            for k in start..end {
                lin += self.jac[k] * d[self.pattern[k].1];
                g2 += self.jac[k] * self.jac[k];
            }
            if lin < 0.0 && g2 > 0.0 {
                for k in start..end {
                    d[self.pattern[k].1] -= lin * self.jac[k] / g2;
                }
            }
            start = end;
        }
    }

    /// g − Jᵀz: the KKT stationarity residual with the last multipliers.
    pub fn stationarity(&self, g: &[f64], out: &mut [f64]) {
        out.copy_from_slice(g);
        for (k, &(row, col)) in self.pattern.iter().enumerate() {
            out[col] -= self.jac[k] * self.z[row];
        }
    }
}
