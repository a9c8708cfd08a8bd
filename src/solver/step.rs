//! What a Newton iteration moves along besides −H⁻¹g: the corrections of the line search's curve,
//! the first predictor of a path, and the constrained (QP) step.

use std::time::Instant;

use super::linalg::SparseCholesky;
use super::newton::Newton;
use super::problem::{Constraints, Core, LengthRepair, NewtonProblem};

/// Lowest modes examined for zero stiffness at the start of a path (an unsupported body has
/// three gauge turns; a fourth would be a mechanism).
const ZERO_MODES: usize = 4;
/// Eigenvalue, relative to the Hessian's scaled diagonal, below which a mode counts as having
/// zero stiffness (round-off leaves about 1e-15; the softest bending mode of a fibre with
/// r/L = 1e-5 on 100 edges is about 2.5e-13, and the rigidity test of
/// `NewtonProblem::mechanism` separates the two).
const ZERO_EIGENVALUE: f64 = 1e-10;
/// Doublings of the lift's trial size (from 1e-4 of a small perturbation: up to 2⁴⁰ times it).
const LIFT_DOUBLINGS: usize = 40;
/// Golden sections of the lift's bracket (0.618⁸ ≈ 2 % of it).
const LIFT_SECTIONS: usize = 8;
/// Most passes of a trial point's length repair (on slender rods each removes all but a few
/// percent of the excess).
const REPAIR_PASSES: usize = 8;
/// A trial point is repaired while the energy of its length excess is above this share of the
/// step's predicted decrease α|gᵀd|: below, the repair cannot change the line search's verdict.
const REPAIR_SHARE: f64 = 1e-5;

/// The line search's second curve (its correction is in `Newton::c2`).
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub(super) enum Second {
    Absent,
    Ready,
    /// The problem's geometric correction of the step, not yet made.
    Deferred,
}

/// Repairs the lengths of the line search's trial point `trial` (a step from the current
/// iterate) to those the linearization of α·d gives, by passes c = −(H + τW)⁻¹f with f the
/// stretch force of the remaining excess (`NewtonProblem::excess_force`; `chol` holds the
/// step's factor, `f` is scratch). The curve x + αd + α²c restores lengths to second order
/// only: where a step turns edges by a large fraction of a radian (a slender rod's first steps
/// under a large load), the rest of the excess still carries stretch energy EA/EI ≈ (L/r)²
/// times the bending the step relieves, and the line search would cut the step many-fold.
/// Passes stop once the excess energy is below `REPAIR_SHARE` of the predicted decrease, or
/// when a pass removes less than three quarters of it. Returns whether `trial` was moved.
pub(super) fn repair_lengths<P: LengthRepair>(
    p: &mut P,
    (chol, f): (&mut SparseCholesky, &mut [f64]),
    (d, slope): (&[f64], f64),
    alpha: f64,
    trial: &mut [f64],
) -> bool {
    let enough = REPAIR_SHARE * alpha * slope.abs();
    let mut last = f64::INFINITY;
    let mut moved = false;
    for _ in 0..REPAIR_PASSES {
        let excess = p.excess_force(trial, (d, alpha), f);
        if excess <= enough || excess > 0.25 * last {
            break;
        }
        last = excess;
        chol.solve(f);
        trial.iter_mut().zip(f.iter()).for_each(|(t, c)| *t -= c);
        moved = true;
    }
    moved
}

impl Newton {
    /// Second-order corrections of the step `d` for the line search's curves x + αd + α²c, in
    /// `c` and `c2`; returns whether `c` holds one, and what of `c2`. First the energy-optimal
    /// one, c = −(H + τW)⁻¹f with f the stretch force the step's first-order length error would
    /// create: it restores lengths the way the structure's stiffness prefers. Then the problem's own geometric correction (the
    /// smallest motion restoring lengths), which is better where a step turns edges by large
    /// angles (a rod near a fold) but moves whole chains rigidly near clamps, more so the finer
    /// the rod (docs/design.md).
    ///
    /// On a shifted (indefinite) Hessian the order is reversed, so that the line search keeps
    /// the geometric curve unless the other is clearly better: (H + τW)⁻¹ amplifies round-off
    /// along soft and zero-energy modes, and on near-ties the choice would follow round-off
    /// (scaled copies of a problem would end apart). The stretch correction is still tried on
    /// shifted Hessians: strongly bent networks do not converge without it.
    ///
    /// Neither is made where the plain step keeps every length to round-off (the excess force
    /// is zero: Newton's last iterations): there is nothing for either curve to restore, and
    /// they would only cost the geometric correction and their trial energies. (Not merely
    /// where the excess energy is small against the predicted decrease: the excess force can
    /// still dominate the residual there, and dropping the curves costs iterations.)
    ///
    /// On Newton's own step (`on_newton_model`: the line search may skip the second curve, see
    /// `line_search`), the geometric correction behind the energy-optimal one is not made here
    /// but returned as [`Second::Deferred`], for the line search to make if it tries that curve.
    pub(super) fn corrections<P: LengthRepair + Constraints>(
        &mut self,
        p: &mut P,
        shift: f64,
    ) -> (bool, Second) {
        if p.excess_force(&self.d, (&self.d, 1.0), &mut self.c) == 0.0 {
            return (false, Second::Absent);
        }
        self.chol.solve(&mut self.c);
        self.c.iter_mut().for_each(|x| *x = -*x);
        p.limit_correction(&self.d, &mut self.c);
        // A correction is second order: one larger than the step itself (in dimensionless
        // unknowns) comes from H⁻¹ amplifying round-off along a soft or zero-energy mode.
        let w = &self.weights;
        let norm = |v: &[f64]| v.iter().zip(w).map(|(x, w)| w * x * x).sum::<f64>();
        let stretch = norm(&self.c) <= norm(&self.d);
        if stretch && self.on_newton_model(shift) {
            return (true, Second::Deferred);
        }
        let buf = if stretch { &mut self.c2 } else { &mut self.c };
        let made = p.step_correction(&self.d, buf);
        match (stretch, made) {
            (false, made) => (made, Second::Absent),
            (true, false) => (true, Second::Absent),
            (true, true) => {
                if shift > 0.0 {
                    std::mem::swap(&mut self.c, &mut self.c2);
                }
                (true, Second::Ready)
            }
        }
    }

    /// First sub-step of the path, from an equilibrium at `lam`: moves the free unknowns by the
    /// linear response to the increment, δ = −H⁻¹ (g(λ_next) − g(λ)) at fixed free unknowns, so
    /// that prescribed ends do not start by crushing their first edges. Kept only if it lowers
    /// the energy at `next`. Later sub-steps use the secant through two equilibria instead (a
    /// tangent predictor there leads a strut shortened past buckling onto its straight saddle;
    /// docs/design.md).
    ///
    /// Returns whether the linear response held over the increment: taken whole (not cut by
    /// the rotation limit of `max_step`) and lowering the energy. On a buckling path the
    /// prediction is then lifted (`lift`), unless it did not hold and `cut_if_not_held`.
    ///
    /// With the Hessian at `lam` factored, this is also where zero-stiffness modes of the start
    /// are looked for (`check_modes`; not when the caller has already looked at this state):
    /// a mechanism that the loads excite is returned as Err with its description
    /// (`NewtonProblem::mechanism`).
    pub(super) fn tangent_predict<P: NewtonProblem>(
        &mut self,
        p: &mut P,
        (lam, next): (f64, f64),
        cut_if_not_held: bool,
        check_modes: bool,
    ) -> Result<bool, String> {
        let n = self.g.len();
        if self.qp.is_some() {
            // The linear response ignores contact and bounds: it could jump through an obstacle.
            // (Nor are mechanisms looked for: contact is what holds a rod lying on a floor.)
            p.set_continuation(next);
            return Ok(true);
        }
        p.set_continuation(lam);
        let e0 = p.assemble(&mut self.g, Some(&mut self.chol.values));
        let shift = if e0.is_finite() {
            self.factor_regularized()
        } else {
            None
        };
        // On a shifted factor a zero mode grows only by 1/τ, which the probe cannot tell from
        // a stiff mode when τ ≥ 1e-10 of the scale: a shifted start looks at the modes.
        let suspect = check_modes
            && match shift {
                Some(0.0) => self.near_singular(&p.gauge_modes()),
                Some(_) => true,
                None => false,
            };
        // Zero modes that the problem calls excited mechanisms, each with its description.
        let mut mechanisms: Vec<(String, Vec<f64>)> = Vec::new();
        if suspect {
            for (_, v) in self
                .lowest_modes(ZERO_MODES)
                .into_iter()
                .filter(|(l, _)| l.abs() < ZERO_EIGENVALUE)
            {
                if let Some(m) = p.mechanism(std::slice::from_ref(&v)) {
                    mechanisms.push((m, v));
                }
            }
        }
        p.set_continuation(next);
        if shift.is_none() || n == 0 {
            return match mechanisms.into_iter().next() {
                Some((m, _)) => Err(m),
                None => Ok(true),
            };
        }
        let e1 = p.assemble(&mut self.d, None);
        for i in 0..n {
            self.d[i] = self.g[i] - self.d[i];
        }
        let load = (!mechanisms.is_empty()).then(|| self.d.clone());
        self.chol.solve(&mut self.d);
        if let Some(load) = load {
            let modes: Vec<&[f64]> = mechanisms.iter().map(|(_, v)| v.as_slice()).collect();
            if !self.stiffened(p, (lam, next), &load, &modes) {
                return Err(mechanisms.swap_remove(0).0);
            }
        }
        let alpha = p.max_step(&self.d).min(1.0);
        let e = p.trial_energy(&self.d, alpha);
        let lowered = e.is_finite() && e < e1;
        if lowered {
            p.accept(&self.d, alpha);
        }
        let held = lowered && alpha == 1.0;
        // A buckling path's prediction is lifted, unless the increment is about to be cut
        // (`cut_if_not_held`) and predicted again.
        if !p.bias().is_empty() && (held || !cut_if_not_held) {
            self.lift(p);
        }
        Ok(held)
    }

    /// Whether the loads of the increment stiffen every combination of the zero modes `modes`
    /// of the start (W-orthonormal) instead of driving them: a prestressed structure (a spoked
    /// wheel tensioned by its hub, a net pulled taut) has modes of zero elastic stiffness that
    /// its stress makes stiff, while a mechanism that the loads load only at second order (a
    /// frame on a line of pins under a vertical load: an inverted pendulum) is softened by them
    /// or left at zero. `load` is minus the increment's change of the gradient, the linear
    /// response to it is in `d`. Loads that work on a mode (their component along it above 1e-6
    /// of their size) excite it at first order: a mechanism. Otherwise the rate at which the
    /// loads change the stiffness matrix K = VᵀHV over the modes decides: K at the states
    /// ±ε·d along the increment's linear response (loads at λ ± ε·Δλ, ε·d at most 1e-4 of the
    /// length scale: central differences, so that a response that is far from linear over the
    /// whole increment does not matter), with HV from central differences of the gradient
    /// (step 1e-6 in the dimensionless unknowns). Stiff at the end of the increment beyond the
    /// zero band of the start (Δλ·K' − 1e-10·scale·I positive definite): no mechanism.
    fn stiffened<P: NewtonProblem>(
        &mut self,
        p: &mut P,
        (lam, next): (f64, f64),
        load: &[f64],
        modes: &[&[f64]],
    ) -> bool {
        const WORK: f64 = 1e-6;
        const H: f64 = 1e-6;
        let w = &self.weights;
        let size = load
            .iter()
            .zip(w)
            .map(|(f, w)| f * f / w)
            .sum::<f64>()
            .sqrt();
        let works = |v: &[f64]| load.iter().zip(v).map(|(f, v)| f * v).sum::<f64>().abs();
        if modes.iter().any(|v| works(v) > WORK * size) {
            return false;
        }
        // What the response holds of the modes is the shifted factor's 1/τ amplification of
        // round-off in the loads: removed, here and from the prediction.
        for v in modes {
            let c: f64 = (0..v.len()).map(|i| w[i] * v[i] * self.d[i]).sum();
            self.d
                .iter_mut()
                .zip(v.iter())
                .for_each(|(d, v)| *d -= c * v);
        }
        let eps = (1e-2 * p.perturbation_size(&self.d)).min(1.0);
        let (n, m) = (load.len(), modes.len());
        let (mut step, mut gp, mut gm) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        let mut rate = vec![0.0; m * m];
        for side in [1.0, -1.0] {
            p.set_continuation(lam + side * eps * (next - lam));
            for (j, v) in modes.iter().enumerate() {
                let mut at = |sign: f64, g: &mut [f64]| {
                    for i in 0..n {
                        step[i] = side * eps * self.d[i] + sign * H * v[i];
                    }
                    p.trial_gradient(&step, 1.0, g).is_finite()
                };
                if !(at(1.0, &mut gp) && at(-1.0, &mut gm)) {
                    p.set_continuation(next);
                    return false;
                }
                for (i, u) in modes.iter().enumerate() {
                    let k: f64 = (0..n).map(|l| u[l] * (gp[l] - gm[l])).sum::<f64>() / (2.0 * H);
                    rate[i * m + j] += side * k / (2.0 * eps);
                }
            }
        }
        p.set_continuation(next);
        // Symmetrized, over the increment, less the zero band: positive definite when its
        // Cholesky factor exists.
        let band = ZERO_EIGENVALUE * self.scaled_diagonal();
        let mut s: Vec<f64> = (0..m * m)
            .map(|ij| {
                let (i, j) = (ij / m, ij % m);
                let k = 0.5 * (rate[i * m + j] + rate[j * m + i]) * (next - lam);
                k - if i == j { band } else { 0.0 }
            })
            .collect();
        super::qp::dense_cholesky(&mut s, m)
    }

    /// The first prediction of a buckling path (`buckle_toward`): the linear response leaves a
    /// symmetric structure in its symmetric, compressed state, which past the bifurcation is a
    /// saddle far above the buckled states in energy. The prediction is moved along the bias's
    /// linear response w = H⁻¹b (the softest shape, on the chosen side) by the amount that
    /// minimizes the energy: a bracket by doubling from a small size, then golden sections.
    /// (The factor of H at the path's start is still in `chol`.)
    fn lift<P: NewtonProblem>(&mut self, p: &mut P) {
        let mut w = p.bias().to_vec();
        self.chol.solve(&mut w);
        let e0 = p.energy();
        let energy = |p: &mut P, a: f64| {
            let e = p.trial_energy(&w, a);
            if e.is_finite() {
                e
            } else {
                f64::INFINITY
            }
        };
        // Doubling from 1e-4 of a small perturbation until the energy rises.
        let mut a = 1e-4 * p.perturbation_size(&w);
        let (mut lo, mut best) = (0.0, (0.0, e0));
        for _ in 0..LIFT_DOUBLINGS {
            let e = energy(p, a);
            if e > best.1 {
                break;
            }
            lo = best.0;
            best = (a, e);
            a *= 2.0;
        }
        if best.0 == 0.0 {
            return;
        }
        // The minimum lies in [lo, a]; golden sections narrow it to a few per cent.
        let (mut x0, mut x1) = (lo, a);
        const G: f64 = 0.618_033_988_749_894_9;
        for _ in 0..LIFT_SECTIONS {
            let (c, d) = (x1 - G * (x1 - x0), x0 + G * (x1 - x0));
            let (ec, ed) = (energy(p, c), energy(p, d));
            for (x, e) in [(c, ec), (d, ed)] {
                if e < best.1 {
                    best = (x, e);
                }
            }
            if ec < ed {
                x1 = d;
            } else {
                x0 = c;
            }
        }
        p.accept(&w, best.0);
    }

    /// Factors H + τI as for an unconstrained step, then solves the step QP with it at the
    /// current iterate. Returns the shift and the relative stationarity residual.
    pub(super) fn constrained_step<P: Core + Constraints>(
        &mut self,
        p: &mut P,
    ) -> Result<(f64, f64), String> {
        let shift = self
            .factor_regularized()
            .ok_or_else(|| "Hessian could not be regularized".to_string())?;
        for i in 0..self.d.len() {
            self.d[i] = -self.g[i];
        }
        let ts = Instant::now();
        self.chol.solve(&mut self.d);
        self.report.factor_seconds += ts.elapsed().as_secs_f64();
        let qp = self.qp.as_mut().expect("constrained problem");
        p.constraints(&mut qp.c, &mut qp.jac);
        // The QP is convex: when the unconstrained minimizer of its model satisfies the
        // linearized constraints, it is the QP's solution, with zero multipliers. Then Clarabel
        // is not needed, and a constraint that is never active leaves every iterate exactly as
        // without it.
        if qp.admits(&self.d) {
            qp.z.fill(0.0);
            qp.skipped += 1;
            self.qp_used = false;
            return Ok((shift, p.relative_residual(&self.g)));
        }
        qp.solve(&mut self.chol, &self.g, &mut self.d)?;
        self.qp_used = true;
        qp.stationarity(&self.g, &mut self.r);
        Ok((shift, p.relative_residual(&self.r)))
    }
}
