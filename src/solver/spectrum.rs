//! Eigen-analysis at a state: the lowest eigenpairs of the Hessian (`rodnet solve --modes K`) and
//! linear buckling factors (`rodnet buckle`).
//!
//! Both are block inverse (subspace) iterations on the sparse Cholesky factor rodnet already
//! has, with a Rayleigh–Ritz step on the block each round. Chosen over shift-invert Lanczos for
//! robustness with clustered and repeated eigenvalues (the symmetric pairs of rings, columns
//! and gridshells), which a block resolves without reorthogonalization or restarts; the
//! price is a few more solves per converged pair (docs/stability.md).

use super::linalg::AnalysisCache;
use super::modes::{generalized, gram, orthonormalize, ritz_vectors, start_block, wdot};
use super::newton::Newton;
use super::problem::{Mechanisms, NewtonProblem};
use super::Ordering;

/// Rounds of subspace iteration before an eigen-solve gives up.
const MAX_ROUNDS: usize = 300;
/// Convergence: each wanted Ritz value moved by less than this fraction of itself (or of the
/// Hessian's scale, for values near zero).
const RITZ_TOLERANCE: f64 = 1e-8;

/// The lowest eigenpairs of H u = λ W u (W = diag(1/s²) of `unknown_scales`).
pub struct Spectrum {
    /// Ascending, in the energy unit (J): uᵀHu for a W-unit u.
    pub values: Vec<f64>,
    /// W-orthonormal, over the free unknowns.
    pub vectors: Vec<Vec<f64>>,
    /// The Hessian's scaled diagonal (J), the scale of round-off.
    pub scale: f64,
    /// Largest ‖Hu − λWu‖_W⁻¹ over the scale among the returned pairs.
    pub residual: f64,
    pub rounds: usize,
    /// The K lowest Ritz values settled before `MAX_ROUNDS` (else the values are the last
    /// round's, with `residual` saying how far off).
    pub converged: bool,
    /// The shift τ that made H + τW positive definite for the inverse iteration.
    pub shift: f64,
    /// Per pair, the band around zero (J) its eigenvalue must leave to count as not zero.
    pub zero_band: Vec<f64>,
}

impl Spectrum {
    /// Whether eigenvalue `i` is zero: not resolved from zero, and negligible against the
    /// structure's softest physical stiffness (see [`zero_band`]).
    pub fn is_zero(&self, i: usize) -> bool {
        self.values[i].abs() < self.zero_band[i]
    }
}

/// How far from zero an eigenvalue must be to count as resolved (J): above its Ritz residual
/// ‖Hu − λWu‖_W⁻¹ (an eigenvalue of H lies within it), above ten times the gradient's size
/// ‖g‖_W⁻¹ (`gradient`: a symmetry's zero mode at a state off equilibrium by g is lifted by
/// about ‖g‖ over the size of the symmetry's motion, itself at least about one in W's units)
/// and above round-off (1e-13 of the scale); at most 1e-10 of the scale, the solver's zero
/// elsewhere (`modes.rs`, `step.rs`). The cap alone would call a slender rod's soft bending
/// modes zero at fine discretizations, the scale being the stretch stiffness (∝ n) and the
/// soft modes' eigenvalues ∝ 1/n: near a stability threshold (an inverted shallow arch) a
/// resolved eigenvalue can lie below 1e-10 of the scale (docs/stability.md).
pub(super) fn zero_band(residual: f64, gradient: f64, scale: f64) -> f64 {
    (2.0 * residual)
        .max(10.0 * gradient)
        .max(1e-13 * scale)
        .min(1e-10 * scale)
}

/// [`zero_band`] of the W-unit mode `u` with Ritz residual `residual`, decided by what the mode
/// does. A mode that deforms a rod is no symmetry's (no gradient share) and costs bending
/// energy: its band is also capped at `Mechanisms::zero_stiffness`, a negligible fraction
/// of the softest stiffness a rod of the structure can have. Without that cap the round-off
/// part alone (1e-13 of a scale dominated by the stiffest, shortest stencils) would swallow a
/// refined rod's physical bending modes, whose eigenvalues fall as 1/n³ in W against a scale
/// that grows as n: at 10⁴ edges a clamped rod's lowest eigenvalue is far below 1e-13 of the
/// scale and yet accurate, and must not be called neutral (docs/stability.md).
pub(super) fn mode_band<P: Mechanisms>(
    p: &mut P,
    u: &[f64],
    residual: f64,
    gradient: f64,
    scale: f64,
) -> f64 {
    if p.deforms(u) {
        zero_band(residual, 0.0, scale).min(p.zero_stiffness())
    } else {
        zero_band(residual, gradient, scale)
    }
}

/// The `k` lowest eigenpairs of the problem's Hessian at its current state.
pub fn lowest_modes<P: NewtonProblem>(
    p: &mut P,
    k: usize,
    ordering: Ordering,
    analyses: &AnalysisCache,
) -> Result<Spectrum, String> {
    let mut nt = newton_for(p, ordering, analyses);
    let n = nt.g.len();
    let k = k.min(n);
    let e = p.assemble(&mut nt.g, Some(&mut nt.chol.values));
    if !e.is_finite() {
        return Err("the energy is not finite at this state".into());
    }
    let shift = nt
        .factor_regularized()
        .ok_or("the Hessian could not be factored even with a shift")?;
    let scale = nt.scaled_diagonal().max(f64::MIN_POSITIVE);
    let settled = |now: &[f64], last: &[f64]| {
        now.iter()
            .zip(last)
            .all(|(a, b)| (a - b).abs() <= RITZ_TOLERANCE * a.abs().max(1e-8 * scale))
    };
    let ritz = nt.subspace(k, k + k.div_ceil(2) + 2, MAX_ROUNDS, settled);
    let (pairs, rounds, converged) = (ritz.pairs, ritz.rounds, ritz.settled);
    let mut hv = vec![0.0; n];
    let mut residual: f64 = 0.0;
    let gradient = nt.gradient_norm();
    let mut band = Vec::with_capacity(pairs.len());
    for (l, u) in &pairs {
        let r = nt.ritz_residual(*l, u, &mut hv);
        residual = residual.max(r / scale);
        band.push(mode_band(p, u, r, gradient, scale));
    }
    Ok(Spectrum {
        values: pairs.iter().map(|p| p.0).collect(),
        vectors: pairs.into_iter().map(|p| p.1).collect(),
        scale,
        residual,
        rounds,
        converged,
        shift,
        zero_band: band,
    })
}

/// Critical load factors of linear buckling about the start: λ with (K₀ + λK₁)u = 0, K₀ the
/// Hessian at the start (λ = 0), K₁ = d/dλ of the Hessian along the linear response to the load.
pub struct Buckling {
    /// Positive factors, ascending.
    pub factors: Vec<f64>,
    /// Their modes, W-normalized, over the free unknowns.
    pub modes: Vec<Vec<f64>>,
    pub rounds: usize,
    /// The load factor of the central difference that gave K₁.
    pub step: f64,
    /// The wanted factors settled before `MAX_ROUNDS`.
    pub converged: bool,
}

/// Linear buckling of the problem about its state at λ = 0: the `k` smallest positive factors.
pub fn linear_buckling<P: NewtonProblem>(
    p: &mut P,
    k: usize,
    ordering: Ordering,
    analyses: &AnalysisCache,
) -> Result<Buckling, String> {
    let mut nt = newton_for(p, ordering, analyses);
    let n = nt.g.len();
    p.set_continuation(0.0);
    let e0 = p.assemble(&mut nt.g, Some(&mut nt.chol.values));
    if !e0.is_finite() {
        return Err("the energy is not finite at the start".into());
    }
    let k0 = nt.chol.values.clone();
    if nt.chol.factor(0.0).is_err() {
        return Err(
            "the Hessian at the start is not positive definite (an unstable start, or a \
                    mechanism: check the supports); linear buckling needs a stable start"
                .into(),
        );
    }
    // The linear response v to the whole load (prescribed motions included).
    let g0 = nt.g.clone();
    p.set_continuation(1.0);
    p.assemble(&mut nt.d, None);
    p.set_continuation(0.0);
    let mut v: Vec<f64> = g0.iter().zip(&nt.d).map(|(a, b)| a - b).collect();
    nt.chol.solve(&mut v);
    let reach = v
        .iter()
        .zip(&nt.scales)
        .map(|(v, s)| (v / s).abs())
        .fold(0.0, f64::max);
    if !reach.is_finite() || v.iter().any(|x| !x.is_finite()) {
        return Err(
            "the linear response to the loads is not finite (prescribed motions too large \
                    to linearize about the start, e.g. a clamp turned by half a turn): follow the \
                    path instead (rodnet solve --modes at load steps)"
                .into(),
        );
    }
    if reach == 0.0 {
        return Err(
            "the loads do nothing to the structure at its start (no loads or prescribed \
                    motions), so no load factor makes it buckle"
                .into(),
        );
    }
    // A step that moves nothing by more than 1e-3 of its size: small enough for the central
    // difference's O(ε²) error, large enough that K₁ε stands out of K₀'s round-off.
    let eps = (1e-3 / reach).min(1.0);
    let hess_at = |p: &mut P, nt: &mut Newton, t: f64| {
        let snap = p.snapshot();
        p.set_continuation(t);
        p.accept(&v, t);
        p.assemble(&mut nt.g, Some(&mut nt.chol.values));
        let h = nt.chol.values.clone();
        p.restore(&snap);
        p.set_continuation(0.0);
        h
    };
    let hp = hess_at(p, &mut nt, eps);
    let hm = hess_at(p, &mut nt, -eps);
    // B = −K₁: the eigenproblem K₀u = λBu; μ = 1/λ are the eigenvalues of K₀⁻¹B.
    let b: Vec<f64> = hp
        .iter()
        .zip(&hm)
        .map(|(a, c)| -(a - c) / (2.0 * eps))
        .collect();
    nt.chol.values.copy_from_slice(&k0);
    if nt.chol.factor(0.0).is_err() {
        return Err("the Hessian at the start could not be factored again".into());
    }
    let k = k.min(n);
    let block = (2 * k + 4).min(n);
    let w = nt.weights.clone();
    let mut x = start_block(&nt.scales, block);
    let mut tmp = vec![0.0; n];
    let mut last = vec![f64::INFINITY; k];
    let mut found: Vec<(f64, Vec<f64>)> = Vec::new();
    let mut rounds = 0;
    let mut converged = false;
    while rounds < MAX_ROUNDS {
        rounds += 1;
        orthonormalize(&mut x, &w);
        let kx: Vec<Vec<f64>> = x
            .iter()
            .map(|u| {
                nt.chol.multiply_with(&k0, u, &mut tmp);
                tmp.clone()
            })
            .collect();
        let bx: Vec<Vec<f64>> = x
            .iter()
            .map(|u| {
                nt.chol.multiply_with(&b, u, &mut tmp);
                tmp.clone()
            })
            .collect();
        let (mus, ys) = generalized(gram(&x, &kx), gram(&x, &bx))?;
        let mut pairs = ritz_vectors(&x, &mus, &ys);
        // Largest μ first: the smallest positive factors λ = 1/μ.
        pairs.sort_by(|a, b| b.0.total_cmp(&a.0));
        let now: Vec<f64> = pairs
            .iter()
            .filter(|p| p.0 > 0.0)
            .take(k)
            .map(|p| p.0)
            .collect();
        let done = rounds > 2
            && now.len() == last.len()
            && now
                .iter()
                .zip(&last)
                .all(|(a, b)| (a - b).abs() <= RITZ_TOLERANCE * a.abs());
        last = now;
        found = pairs;
        if done {
            converged = true;
            break;
        }
        // x ← K₀⁻¹ B x on the Ritz vectors.
        x = found
            .iter()
            .map(|(_, u)| {
                nt.chol.multiply_with(&b, u, &mut tmp);
                let mut y = tmp.clone();
                nt.chol.solve(&mut y);
                y
            })
            .collect();
    }
    let mut modes = Vec::new();
    let mut factors = Vec::new();
    for (mu, mut u) in found.into_iter().filter(|p| p.0 > 0.0).take(k) {
        let nu = wdot(&u, &u, &w).sqrt();
        u.iter_mut().for_each(|x| *x /= nu);
        factors.push(1.0 / mu);
        modes.push(u);
    }
    Ok(Buckling {
        factors,
        modes,
        rounds,
        step: eps,
        converged,
    })
}

/// fᵀH⁻¹f at the problem's current state: the displacement along a unit force f per unit of
/// it, with every other unknown free (its inverse is the stiffness against f). An H that is
/// not positive definite (an unstable or neutral state) has no such stiffness.
pub fn compliance<P: NewtonProblem>(
    p: &mut P,
    f: &[f64],
    ordering: Ordering,
    analyses: &AnalysisCache,
) -> Result<f64, String> {
    let mut nt = newton_for(p, ordering, analyses);
    let e = p.assemble(&mut nt.g, Some(&mut nt.chol.values));
    if !e.is_finite() {
        return Err("the energy is not finite at this state".into());
    }
    if nt.chol.factor(0.0).is_err() {
        return Err(
            "the Hessian is not positive definite here (an unstable or neutral state): \
                    no stiffness"
                .into(),
        );
    }
    let mut x = f.to_vec();
    nt.chol.solve(&mut x);
    Ok(x.iter().zip(f).map(|(a, b)| a * b).sum())
}

/// A Newton workspace over `p` with its Hessian pattern (analysed in, or taken from,
/// `analyses`), factor and unknown scales.
pub(super) fn newton_for<P: NewtonProblem>(
    p: &mut P,
    ordering: Ordering,
    analyses: &AnalysisCache,
) -> Newton {
    let n = p.num_free();
    let pairs = p.hessian_pattern();
    let (chol, slots) = analyses.factorization(n, &pairs, ordering, || p.unknown_positions());
    p.set_hessian_slots(&slots);
    let mut nt = Newton::new(chol, None, n);
    p.unknown_scales(&mut nt.scales);
    for (w, s) in nt.weights.iter_mut().zip(&nt.scales) {
        *w = 1.0 / (s * s);
    }
    nt
}
