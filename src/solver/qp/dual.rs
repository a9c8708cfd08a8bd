//! The polish's fallback: the step QP's exact solution by the active-set method of Lawson and
//! Hanson on its dual, min ½zᵀSz − zᵀ(J P⁻¹g − c) over z ≥ 0 with S = J P⁻¹Jᵀ.
//!
//! The primal-dual rounds of [`StepQp::polish`] change many rows at once and can cycle: where
//! a free motion (a structure pinned at one point and resting on an obstacle, free to spin)
//! leaves the shifted Hessian nearly singular, Clarabel can stop with InsufficientProgress and
//! the active set oscillate between rounds without settling, so that the interior point's
//! inaccurate step, possibly an ascent direction, would stand at every iteration
//! (tests/drape_over_sphere.rs). Lawson–Hanson adds one row at a time (the most violated
//! linearized constraint, i.e. the dual's steepest coordinate) and, when a multiplier would turn
//! negative, moves back to the boundary and drops it; the dual energy falls at every step, so it
//! cannot cycle, and it ends at the exact solution. It only ever needs the active rows' columns
//! of P⁻¹Jᵀ: the dual gradient of a row is minus its linearized gap at the primal step.

use std::collections::HashMap;
use std::ops::Range;

use super::StepQp;
use crate::solver::linalg::SparseCholesky;

/// Row additions allowed per row of the starting active set (plus a few): each addition is one
/// dense Schur factorization.
const ADDITIONS_PER_ROW: usize = 4;

impl StepQp {
    /// P⁻¹J_jᵀ for row `j`.
    pub(super) fn column(
        &self,
        j: usize,
        rows: &[Range<usize>],
        chol: &mut SparseCholesky,
    ) -> Vec<f64> {
        let mut col = vec![0.0; self.n];
        for k in rows[j].clone() {
            col[self.pattern[k].1] += self.jac[k];
        }
        chol.solve(&mut col);
        col
    }

    /// The exact solution (step, active rows, their multipliers), starting from the rows in
    /// `start` (the interior point's active set, a warm start only); None if the budget of
    /// additions runs out or a Schur complement is not positive definite.
    #[allow(clippy::type_complexity)]
    pub(super) fn dual_active_set(
        &self,
        start: &[usize],
        rows: &[Range<usize>],
        columns: &mut HashMap<usize, Vec<f64>>,
        (chol, g, u): (&mut SparseCholesky, &[f64], &[f64]),
        slack_tol: f64,
    ) -> Option<(Vec<f64>, Vec<usize>, Vec<f64>)> {
        let jrow = |j: usize, v: &[f64]| -> f64 {
            rows[j]
                .clone()
                .map(|k| self.jac[k] * v[self.pattern[k].1])
                .sum()
        };
        let mut active: Vec<usize> = Vec::new();
        let mut z: Vec<f64> = Vec::new();
        let mut d: Vec<f64> = u.iter().map(|v| -v).collect();
        let mut pending = start.to_vec();
        for _ in 0..ADDITIONS_PER_ROW * (start.len() + 8) {
            if pending.is_empty() {
                let mut worst: Option<(usize, f64)> = None;
                let mut is_active = vec![false; self.m];
                active.iter().for_each(|&j| is_active[j] = true);
                for j in (0..self.m).filter(|&j| !is_active[j]) {
                    let gap = self.c[j] + jrow(j, &d);
                    if gap < -slack_tol && worst.is_none_or(|(_, w)| gap < w) {
                        worst = Some((j, gap));
                    }
                }
                match worst {
                    None => return Some((d, active, z)),
                    Some((j, _)) => pending.push(j),
                }
            }
            if active.len() + pending.len() > super::POLISH_MAX_ACTIVE {
                return None;
            }
            for j in pending.drain(..) {
                if let std::collections::hash_map::Entry::Vacant(slot) = columns.entry(j) {
                    slot.insert(self.column(j, rows, chol));
                }
                active.push(j);
                z.push(0.0);
            }
            // Solve on the active set; while a multiplier would be negative, move from z
            // towards the solution up to the first multiplier reaching zero and drop the rows
            // at zero that the solution would push negative.
            loop {
                let (dp, zeta) = self.solve_on(&active, rows, columns, chol, g, u)?;
                if zeta.iter().all(|&v| v > 0.0) {
                    (d, z) = (dp, zeta);
                    break;
                }
                let alpha = (0..active.len())
                    .filter(|&i| zeta[i] <= 0.0)
                    .map(|i| {
                        let a = z[i] / (z[i] - zeta[i]);
                        if a.is_finite() {
                            a
                        } else {
                            0.0
                        }
                    })
                    .fold(1.0f64, f64::min);
                let zmax = z.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                let mut kept = (Vec::new(), Vec::new());
                for i in 0..active.len() {
                    let zi = z[i] + alpha * (zeta[i] - z[i]);
                    if zeta[i] > 0.0 || zi > 1e-14 * zmax {
                        kept.0.push(active[i]);
                        kept.1.push(zi.max(0.0));
                    }
                }
                if kept.0.len() == active.len() {
                    return None;
                }
                (active, z) = kept;
            }
        }
        None
    }
}
