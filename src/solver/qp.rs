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
//! (KKT pattern and symbolic factorization) and every later step only overwrites values. That
//! requires presolve off and no dropped structural zeros (Clarabel refuses updates otherwise).
//! The interior-point solution is then polished to the exact solution on its active set, using
//! the Cholesky factor of H + τI that the Newton iteration has computed anyway.

use std::time::Instant;

use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettings, DefaultSettingsBuilder, DefaultSolver, IPSolver, NonnegativeConeT,
    SolverStatus,
};

use super::linalg::SparseCholesky;

mod dual;

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
    /// Clarabel's slacks s = c + J d of the last QP.
    slack: Vec<f64>,
    /// QPs whose interior-point solution was replaced by the exact solution on its active set.
    pub polished: usize,
    solver: Option<DefaultSolver<f64>>,
    pub solves: usize,
    /// QPs that stopped short of full accuracy (Clarabel's AlmostSolved, InsufficientProgress,
    /// MaxIterations).
    pub inexact: usize,
    /// Steps for which the QP was not needed (see `admits`).
    pub skipped: usize,
    pub iterations: usize,
    pub seconds: f64,
}

/// Largest active set that is polished: the dense Schur complement costs a² memory and a³/3
/// flops (3e8 at a = 1000), and P⁻¹J_Aᵀ a·n memory and a triangular solve per row.
const POLISH_MAX_ACTIVE: usize = 1000;
/// Largest a·n (80 MB of P⁻¹J_Aᵀ columns).
const POLISH_MAX_ENTRIES: usize = 10_000_000;
/// Active-set corrections tried before the interior-point solution is kept.
const POLISH_ROUNDS: usize = 6;

/// In-place Cholesky factor (lower triangle, row-major, a × a) of a symmetric positive
/// definite matrix given by its lower triangle; false if it is not numerically positive
/// definite.
pub(super) fn dense_cholesky(s: &mut [f64], a: usize) -> bool {
    for j in 0..a {
        let mut dj = s[j * a + j];
        for k in 0..j {
            dj -= s[j * a + k] * s[j * a + k];
        }
        if dj.is_nan() || dj <= 0.0 || !dj.is_finite() {
            return false;
        }
        let dj = dj.sqrt();
        s[j * a + j] = dj;
        for i in j + 1..a {
            let mut v = s[i * a + j];
            for k in 0..j {
                v -= s[i * a + k] * s[j * a + k];
            }
            s[i * a + j] = v / dj;
        }
    }
    true
}

/// Solves L Lᵀ x = b in place with the factor from [`dense_cholesky`].
fn dense_cholesky_solve(l: &[f64], a: usize, b: &mut [f64]) {
    for i in 0..a {
        let mut v = b[i];
        for k in 0..i {
            v -= l[i * a + k] * b[k];
        }
        b[i] = v / l[i * a + i];
    }
    for i in (0..a).rev() {
        let mut v = b[i];
        for k in i + 1..a {
            v -= l[k * a + i] * b[k];
        }
        b[i] = v / l[i * a + i];
    }
}

fn settings() -> DefaultSettings<f64> {
    // Newton converges only as far as its steps are accurate, and near convergence the steps
    // and the multipliers are small against the data, which Clarabel's default tolerances
    // (1e-8, absolute in its scaled units) do not resolve: tight gap tolerances, and a smaller
    // static regularization than the default 1e-8 because the τ-shifted Hessian's zero modes
    // (rigid spins, free rotations about a pin) sit at 1e-10 of its unit diagonal. Clarabel's
    // own equilibration is off: the Jacobi scaling below already gives P a unit diagonal, and
    // rescaling on top of it can leave QPs after a continuation predictor stopping with
    // InsufficientProgress (docs/design.md).
    DefaultSettingsBuilder::default()
        .verbose(false)
        .presolve_enable(false)
        .input_sparse_dropzeros(false)
        .tol_gap_abs(1e-16)
        .tol_gap_rel(1e-14)
        .tol_feas(1e-12)
        .max_iter(200)
        .static_regularization_constant(1e-11)
        .equilibrate_enable(false)
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
            slack: vec![0.0; m],
            polished: 0,
            pattern,
            solver: None,
            solves: 0,
            skipped: 0,
            inexact: 0,
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
    pub fn solve(
        &mut self,
        chol: &mut SparseCholesky,
        g: &[f64],
        d: &mut [f64],
    ) -> Result<(), String> {
        let t0 = Instant::now();
        // Position and angle unknowns differ in stiffness by up to 1e8 (EA/l against GJ/l), more
        // than Clarabel's equilibration bounds (1e±4) can even out; in the Jacobi-scaled
        // unknowns y = S⁻¹d every diagonal of P is 1. The multipliers are unchanged by it.
        let (cp, ri) = (chol.col_ptr(), chol.row_idx());
        chol.shifted_values_into(&mut self.p_val);
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
        self.slack.copy_from_slice(&sol.s);
        self.solves += 1;
        self.iterations += its as usize;
        self.seconds += t0.elapsed().as_secs_f64();
        // A QP stopped for lack of progress or iterations still usually holds a useful step;
        // the line search judges it (descent and feasibility), so only infeasibility
        // certificates and numerical failures are errors.
        let usable = matches!(
            status,
            SolverStatus::Solved
                | SolverStatus::AlmostSolved
                | SolverStatus::InsufficientProgress
                | SolverStatus::MaxIterations
        );
        if !usable || !d.iter().chain(&self.z).all(|v| v.is_finite()) {
            return Err(format!(
                "the step QP was not solved (Clarabel status {status:?} after {its} iterations)"
            ));
        }
        if !matches!(status, SolverStatus::Solved) {
            self.inexact += 1;
        }
        if self.polish(chol, g, d) {
            self.polished += 1;
        }
        self.make_feasible(d);
        Ok(())
    }

    /// Replaces the interior-point solution by the exact solution of the equality-constrained
    /// QP on an active set, starting from the interior point's A = {j : z_j > s_j} (as OSQP
    /// polishes). Interior-point steps and multipliers carry errors of the order of the QP's
    /// tolerances relative to its data, which near convergence is most of the step; with the
    /// exact active-set solution Newton converges quadratically and the multipliers balance the
    /// gradient to round-off. With P = H + τI factored already, the active-set system reduces to
    /// the dense Schur complement S = J_A P⁻¹ J_Aᵀ: S z_A = J_A P⁻¹ g − c_A,
    /// d = P⁻¹(J_Aᵀ z_A − g). Constraints that touch with (almost) no force are degenerate for
    /// the interior point and land on either side of z = s; a few primal-dual active-set
    /// rounds (drop rows with z < 0, add violated rows) settle them; when they cycle, the dual
    /// active-set method (`qp/dual.rs`) finds the exact solution. False if neither does; the
    /// interior-point solution then stands.
    fn polish(&mut self, chol: &mut SparseCholesky, g: &[f64], d: &mut [f64]) -> bool {
        let mut active: Vec<usize> = (0..self.m).filter(|&j| self.z[j] > self.slack[j]).collect();
        let start = active.clone();
        let rows = self.row_ranges();
        let n = self.n;
        let mut u = g.to_vec();
        chol.solve(&mut u);
        let mut columns: std::collections::HashMap<usize, Vec<f64>> = Default::default();
        let slack_tol = 1e-12 * self.c.iter().fold(1.0f64, |m, v| m.max(v.abs()));
        for _ in 0..POLISH_ROUNDS {
            if active.len() > POLISH_MAX_ACTIVE || active.len() * n > POLISH_MAX_ENTRIES {
                return false;
            }
            // W = P⁻¹ J_Aᵀ, one column per active row, kept across rounds.
            for &j in &active {
                if let std::collections::hash_map::Entry::Vacant(slot) = columns.entry(j) {
                    slot.insert(self.column(j, &rows, chol));
                }
            }
            let Some((dp, z)) = self.solve_on(&active, &rows, &columns, chol, g, &u) else {
                return false;
            };
            let zmax = z.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let mut is_active = vec![false; self.m];
            for &j in &active {
                is_active[j] = true;
            }
            let jrow = |j: usize, v: &[f64]| -> f64 {
                rows[j]
                    .clone()
                    .map(|k| self.jac[k] * v[self.pattern[k].1])
                    .sum()
            };
            let violated: Vec<usize> = (0..self.m)
                .filter(|&j| !is_active[j] && self.c[j] + jrow(j, &dp) < -slack_tol)
                .collect();
            let negative: Vec<bool> = z.iter().map(|&v| v < -1e-12 * zmax).collect();
            if violated.is_empty() && !negative.contains(&true) {
                d.copy_from_slice(&dp);
                self.z.iter_mut().for_each(|v| *v = 0.0);
                for (i, &j) in active.iter().enumerate() {
                    self.z[j] = z[i].max(0.0);
                }
                return true;
            }
            let mut next: Vec<usize> = active
                .iter()
                .zip(&negative)
                .filter(|(_, &neg)| !neg)
                .map(|(&j, _)| j)
                .collect();
            next.extend(violated);
            next.sort_unstable();
            active = next;
        }
        if start.len() > POLISH_MAX_ACTIVE || start.len() * n > POLISH_MAX_ENTRIES {
            return false;
        }
        let exact = self.dual_active_set(&start, &rows, &mut columns, (chol, g, &u), slack_tol);
        let Some((dp, active, z)) = exact else {
            return false;
        };
        d.copy_from_slice(&dp);
        self.z.iter_mut().for_each(|v| *v = 0.0);
        for (&j, &zj) in active.iter().zip(&z) {
            self.z[j] = zj;
        }
        true
    }

    /// The equality-constrained QP on `active` (see [`Self::polish`]), with iterative
    /// refinement: the τ-regularized zero modes make P⁻¹g large against d, so d carries
    /// cancellation error that refinement on the KKT residual removes.
    fn solve_on(
        &self,
        active: &[usize],
        rows: &[std::ops::Range<usize>],
        columns: &std::collections::HashMap<usize, Vec<f64>>,
        chol: &mut SparseCholesky,
        g: &[f64],
        u: &[f64],
    ) -> Option<(Vec<f64>, Vec<f64>)> {
        let (a, n) = (active.len(), self.n);
        let jrow = |j: usize, v: &[f64]| -> f64 {
            rows[j]
                .clone()
                .map(|k| self.jac[k] * v[self.pattern[k].1])
                .sum()
        };
        let w: Vec<&Vec<f64>> = active.iter().map(|j| &columns[j]).collect();
        let mut schur = vec![0.0; a * a];
        let mut z = vec![0.0; a];
        for (r, &jr) in active.iter().enumerate() {
            for c in 0..=r {
                schur[r * a + c] = jrow(jr, w[c]);
            }
            z[r] = jrow(jr, u) - self.c[jr];
        }
        if !dense_cholesky(&mut schur, a) {
            return None;
        }
        dense_cholesky_solve(&schur, a, &mut z);
        let mut dp: Vec<f64> = u.iter().map(|v| -v).collect();
        for (i, zi) in z.iter().enumerate() {
            for k in 0..n {
                dp[k] += w[i][k] * zi;
            }
        }
        let mut rd = vec![0.0; n];
        let mut last = f64::INFINITY;
        for _ in 0..4 {
            chol.multiply_shifted(&dp, &mut rd);
            for k in 0..n {
                rd[k] += g[k];
            }
            for (i, &j) in active.iter().enumerate() {
                for k in rows[j].clone() {
                    rd[self.pattern[k].1] -= self.jac[k] * z[i];
                }
            }
            let size = rd.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            if size.is_nan() || size >= 0.5 * last {
                break;
            }
            last = size;
            chol.solve(&mut rd);
            let mut dz: Vec<f64> = active
                .iter()
                .map(|&j| jrow(j, &rd) - (self.c[j] + jrow(j, &dp)))
                .collect();
            dense_cholesky_solve(&schur, a, &mut dz);
            for k in 0..n {
                dp[k] -= rd[k];
            }
            for (i, dzi) in dz.iter().enumerate() {
                z[i] += dzi;
                for k in 0..n {
                    dp[k] += w[i][k] * dzi;
                }
            }
        }
        Some((dp, z))
    }

    /// Pattern entries of each constraint row (rows are contiguous in the pattern).
    fn row_ranges(&self) -> Vec<std::ops::Range<usize>> {
        let mut out = vec![0..0; self.m];
        let mut start = 0;
        while start < self.pattern.len() {
            let row = self.pattern[start].0;
            let mut end = start;
            while end < self.pattern.len() && self.pattern[end].0 == row {
                end += 1;
            }
            out[row] = start..end;
            start = end;
        }
        out
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

    /// Whether step `d` satisfies every linearized constraint c + J d ≥ 0.
    pub fn admits(&self, d: &[f64]) -> bool {
        let mut lin = self.c.clone();
        for (k, &(row, col)) in self.pattern.iter().enumerate() {
            lin[row] += self.jac[k] * d[col];
        }
        lin.iter().all(|&v| v >= 0.0)
    }

    /// g − Jᵀz: the KKT stationarity residual with the last multipliers.
    pub fn stationarity(&self, g: &[f64], out: &mut [f64]) {
        out.copy_from_slice(g);
        for (k, &(row, col)) in self.pattern.iter().enumerate() {
            out[col] -= self.jac[k] * self.z[row];
        }
    }
}
