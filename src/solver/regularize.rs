//! Regularization of an indefinite Hessian (modified Newton) and the escape from saddles along
//! negative curvature.

use std::time::Instant;

use super::linalg::SparseCholesky;
use super::newton::Newton;
use super::problem::{NewtonProblem, NonConservative};

/// What the search for negative curvature at a stationary point found.
pub(super) enum Saddle {
    /// Only zero-energy modes (rigid rotations, free spin): a minimum up to those modes.
    ZeroModesOnly,
    Escaped,
    /// Negative curvature, but no energy decrease along it within round-off.
    NoDecrease,
    /// Negative curvature of the energy's Hessian that the loads' skew stiffness (dead moments)
    /// is large enough to move off the negative axis: the energy cannot tell whether the state
    /// is unstable, and leaving it along that direction would leave an equilibrium.
    Undecided,
}

impl Newton {
    /// Factors H + τW with the first τ of the sequence 0, τ₀, gτ₀, g²τ₀, … that succeeds.
    /// After a shifted iteration, τ₀ is a tenth of its shift and g = 10. Without that memory,
    /// τ₀ is the floor, 1e-10 of the diagonal scale, and the magnitude is unknown: g = 100
    /// finds a shift in about half the failed factorizations, overshooting by at most 100×
    /// instead of 10×, which the memory's start at τ/10 corrects on the next indefinite
    /// iteration (docs/performance.md).
    ///
    /// The unshifted attempt is made at every iteration, even while it keeps failing: skipping
    /// it would save a factorization per indefinite iteration, but the shift would then linger
    /// (it decays ×10 per iteration) and turn Newton's final quadratic convergence linear.
    pub(super) fn factor_regularized(&mut self) -> Option<f64> {
        let ts = Instant::now();
        let r = self.factor_regularized_inner();
        self.report.factor_seconds += ts.elapsed().as_secs_f64();
        r
    }

    fn factor_regularized_inner(&mut self) -> Option<f64> {
        self.report.factorizations += 1;
        if self.chol.factor(0.0).is_ok() {
            self.shift_memory *= 0.1;
            return Some(0.0);
        }
        let scale = self.scaled_diagonal().max(f64::MIN_POSITIVE);
        let floor = 1e-10 * scale;
        let remembered = 0.1 * self.shift_memory;
        let growth = if remembered > floor { 10.0 } else { 100.0 };
        let mut tau = floor.max(remembered);
        while tau < 1e12 * scale {
            self.report.factorizations += 1;
            if self.chol.factor_weighted(tau, &self.weights).is_ok() {
                self.shift_memory = tau;
                return Some(tau);
            }
            tau *= growth;
        }
        None
    }

    /// With non-conservative loads (`NonConservative::skew_stiffness`), a stationary point is an
    /// equilibrium whatever the inertia of the energy's Hessian H, which is only the symmetric
    /// part of the tangent; where H stays indefinite up to the equilibrium, the shifted step
    /// (H + τW) would converge only linearly. Puts Newton's own step −H⁻¹g in `d` (LDLᵀ) when it
    /// is accurate and descends the merit energy; false otherwise (the shifted step is used).
    pub(super) fn indefinite_step<P: NonConservative>(&mut self, p: &P) -> bool {
        if p.skew_stiffness() == 0.0 {
            return false;
        }
        let ts = Instant::now();
        self.report.factorizations += 1;
        let ok = self.chol.factor_ldlt().is_ok() && {
            self.d.iter_mut().zip(&self.g).for_each(|(d, g)| *d = -g);
            self.chol.solve_ldlt(&mut self.d);
            // Without pivoting, an indefinite factorization can lose accuracy: check the solve.
            self.chol.multiply(&self.d, &mut self.trial);
            let norm2 = |v: &mut dyn Iterator<Item = f64>| v.map(|x| x * x).sum::<f64>();
            let err = norm2(&mut self.trial.iter().zip(&self.g).map(|(a, g)| a + g));
            let slope: f64 = self.g.iter().zip(&self.d).map(|(g, d)| g * d).sum();
            err.is_finite() && err <= 1e-16 * norm2(&mut self.g.iter().copied()) && slope < 0.0
        };
        self.report.factor_seconds += ts.elapsed().as_secs_f64();
        ok
    }

    /// Largest |H_ii|·s_i²: the diagonal scale of the Hessian of the dimensionless unknowns.
    pub(super) fn scaled_diagonal(&self) -> f64 {
        (0..self.scales.len())
            .map(|i| self.chol.diagonal(i).abs() * self.scales[i] * self.scales[i])
            .fold(0.0, f64::max)
    }

    /// With H + τW factored (W = diag(1/s²)), finds the most negative curvature direction of
    /// H for the dimensionless unknowns q/s by inverse iteration (the generalized eigenproblem
    /// H u = λ W u) and moves downhill along it.
    pub(super) fn escape_saddle<P: NewtonProblem>(&mut self, p: &mut P, e0: f64) -> Saddle {
        let n = self.g.len();
        if n == 0 {
            return Saddle::ZeroModesOnly;
        }
        // The corrections' buffers are free here (each iteration recomputes them): no
        // allocation inside the Newton loop.
        let (mut v, mut hv) = (std::mem::take(&mut self.c), std::mem::take(&mut self.c2));
        let saddle = self.escape_with(p, e0, &mut v, &mut hv);
        (self.c, self.c2) = (v, hv);
        saddle
    }

    /// [`Self::escape_saddle`] with buffers for the direction and its image.
    fn escape_with<P: NewtonProblem>(
        &mut self,
        p: &mut P,
        e0: f64,
        v: &mut [f64],
        hv: &mut [f64],
    ) -> Saddle {
        let n = v.len();
        let (s, w) = (&self.scales, &self.weights);
        // W-norm: the Euclidean norm of the dimensionless vector.
        let norm_w = |v: &[f64]| v.iter().zip(w).map(|(x, w)| w * x * x).sum::<f64>().sqrt();
        // Deterministic, generic start vector (in dimensionless unknowns).
        for (i, x) in v.iter_mut().enumerate() {
            *x = (1.0 + 0.5 * ((i as f64) * 0.7).sin()) * s[i];
        }
        let mut lambda = 0.0;
        for _ in 0..50 {
            let nv = norm_w(v);
            v.iter_mut().for_each(|x| *x /= nv);
            self.chol.multiply(v, hv);
            let new_lambda: f64 = v.iter().zip(hv.iter()).map(|(a, b)| a * b).sum();
            let done = (new_lambda - lambda).abs() <= 1e-6 * new_lambda.abs();
            lambda = new_lambda;
            if done {
                break;
            }
            v.iter_mut().zip(w).for_each(|(x, w)| *x *= w);
            self.chol.solve(v);
        }
        let nv = norm_w(v);
        v.iter_mut().for_each(|x| *x /= nv);
        let scale = self.scaled_diagonal();
        if lambda >= -1e-12 * scale {
            return Saddle::ZeroModesOnly;
        }
        if skew_stabilizes(&mut self.chol, p, (v, hv), -lambda) {
            return Saddle::Undecided;
        }
        // The side the problem prefers (`buckle_toward`), else a deterministic sign: largest
        // dimensionless component positive.
        let side = p.orientation(v);
        let flip = if side != 0.0 {
            side < 0.0
        } else {
            let imax = (0..n)
                .max_by(|&a, &b| (v[a] / s[a]).abs().total_cmp(&(v[b] / s[b]).abs()))
                .unwrap();
            v[imax] < 0.0
        };
        if flip {
            v.iter_mut().for_each(|x| *x = -*x);
        }
        let size = p.perturbation_size(v);
        v.iter_mut().for_each(|x| *x *= size);
        let mut alpha = p.max_step(v);
        let constrained = self.qp.is_some();
        for _ in 0..30 {
            if constrained {
                let scaled: Vec<f64> = v.iter().map(|x| alpha * x).collect();
                if !p.feasible(&scaled) {
                    alpha *= 0.5;
                    continue;
                }
            }
            let e = p.trial_energy(v, alpha);
            if e.is_finite() && e < e0 - 1e-12 * e0.abs() {
                p.accept(v, alpha);
                if self.escaped.is_none() {
                    self.escaped = Some((v.iter().map(|x| x / size).collect(), lambda));
                }
                return Saddle::Escaped;
            }
            alpha *= 0.5;
        }
        Saddle::NoDecrease
    }
}

/// Whether the dead moments' skew stiffness S may lift the negative curvature `kappa` of H
/// along `v` (W-normalized, H v = −κ W v) off the negative axis. H + S is the whole tangent;
/// to second order, S moves the eigenvalue −κ by Σⱼ (uⱼᵀS v)²/(λⱼ + κ) toward positive
/// (vᵀS v = 0: S is skew), over the other eigenpairs (λⱼ, uⱼ) of H. With H + τW factored
/// (τ > κ), wᵀ(H + τW)⁻¹w for w = S v is a lower bound of that sum: where even the bound
/// reaches κ, the energy cannot tell an unstable state (a rod rolled into a ring by a dead
/// end moment: the in-plane equilibrium is unique at every moment, yet H turns indefinite
/// out of plane once M·L/GJ passes about π). Below it, S leaves the instability (a column
/// past buckling with a small dead torque on its top). `w`: scratch.
fn skew_stabilizes<P: NonConservative>(
    chol: &mut SparseCholesky,
    p: &P,
    (v, w): (&[f64], &mut [f64]),
    kappa: f64,
) -> bool {
    if p.skew_stiffness() == 0.0 {
        return false;
    }
    p.skew_image(v, w);
    let mut x = w.to_vec();
    chol.solve(&mut x);
    let lift: f64 = w.iter().zip(&x).map(|(a, b)| a * b).sum();
    lift >= kappa
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solver::linalg::SparseCholesky;

    /// A Newton solver on diag(1, 1, h).
    fn diagonal(h: f64) -> Newton {
        let pairs = [(0, 0), (1, 1), (2, 2)];
        let (mut chol, slots) = SparseCholesky::new(3, &pairs);
        for (slot, v) in slots.into_iter().zip([1.0, 1.0, h]) {
            chol.values[slot] = v;
        }
        Newton::new(chol, None, 3)
    }

    /// The factorizations and the shift of one regularized factorization of diag(1, 1, h).
    fn ladder(newton: &mut Newton, h: f64) -> (usize, Option<f64>) {
        let slot = newton.chol.values.len() - 1;
        newton.chol.values[slot] = h;
        let before = newton.report.factorizations;
        let shift = newton.factor_regularized();
        (newton.report.factorizations - before, shift)
    }

    /// Without memory the shift climbs ×100 from 1e-10 of the diagonal scale; after a shifted
    /// factorization it starts from a tenth of that shift and climbs ×10.
    #[test]
    fn the_shift_climbs_by_hundreds_without_memory_and_by_tens_with_it() {
        let close = |s: Option<f64>, t: f64| (s.unwrap() / t - 1.0).abs() < 1e-9;
        let mut newton = diagonal(1.0);
        assert_eq!(ladder(&mut newton, 1.0), (1, Some(0.0)));
        // Needs τ > 3e-7: 1e-10, 1e-8 fail, 1e-6 holds.
        let (facts, shift) = ladder(&mut newton, -3e-7);
        assert!(facts == 4 && close(shift, 1e-6), "{facts} {shift:?}");
        // From memory: 1e-7 fails, 1e-6 holds.
        let (facts, shift) = ladder(&mut newton, -3e-7);
        assert!(facts == 3 && close(shift, 1e-6), "{facts} {shift:?}");
        // Needs τ > 3e-6: 1e-7, 1e-6 fail, 1e-5 holds.
        let (facts, shift) = ladder(&mut newton, -3e-6);
        assert!(facts == 4 && close(shift, 1e-5), "{facts} {shift:?}");
        // Positive definite: unshifted, the memory decays to 1e-6, 1e-7, … 1e-10 and below.
        for _ in 0..5 {
            assert_eq!(ladder(&mut newton, 1.0), (1, Some(0.0)));
        }
        let (facts, shift) = ladder(&mut newton, -3e-7);
        assert!(facts == 4 && close(shift, 1e-6), "{facts} {shift:?}");
    }
}
