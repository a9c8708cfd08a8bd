//! The lowest eigenpairs of the Hessian, H u = λ W u in the solver's dimensionless metric W, by
//! subspace (block inverse) iteration with the factor of H + τW already computed, and a
//! Rayleigh–Ritz step on the subspace (`Newton::subspace`, also behind `spectrum.rs`). Used to
//! find zero-stiffness modes (mechanisms, gauge turns) at the start of a path and to tell when
//! dead loads make a free structure's rigid turn unstable.

use super::newton::Newton;
use super::problem::{ContinuationPath, Core, Gauge};

impl Newton {
    /// At a stationary point whose Hessian has no negative curvature but needed a shift: is
    /// every zero-stiffness mode a gauge mode of the problem (a rigid turn of an unsupported
    /// body that costs nothing)? Only then is the state stable: a neutral mode (a mechanism
    /// the loads leave alone) makes it merely neutrally stable, reported as not stable.
    /// Records the count of non-gauge zero modes in the report (`zero_modes`).
    ///
    /// No shortcut through `near_singular` here: on a shifted factor a zero mode grows only by
    /// 1/τ, which the probe's threshold cannot tell from a stiff one when τ ≥ 1e-10 of the scale.
    ///
    /// A mode counts as zero only while its eigenvalue is not resolved from zero
    /// (`spectrum::zero_band`): a slender rod's softest bending modes fall below 1e-10 of the
    /// scale (the stretch stiffness) at fine discretizations, so a fixed threshold would call a
    /// clamped slender rod neutral; for modes that deform rods neither the gradient's share of
    /// the band nor a round-off floor above the rods' physical stiffness applies
    /// (`spectrum::mode_band`).
    pub(super) fn gauge_modes_only<P: super::NewtonProblem>(&mut self, p: &mut P) -> bool {
        let scale = self.scaled_diagonal().max(f64::MIN_POSITIVE);
        let gradient = self.gradient_norm();
        let mut hv = vec![0.0; self.g.len()];
        let mut zero = Vec::new();
        for (l, u) in self.lowest_modes(4) {
            let residual = self.ritz_residual(l * scale, &u, &mut hv);
            // The gradient's share of the band is for a symmetry's zero mode, lifted by a state
            // off equilibrium; a mode that deforms its rods is no symmetry's, and costs bending.
            if l.abs() * scale < super::spectrum::mode_band(p, &u, residual, gradient, scale) {
                zero.push(u);
            }
        }
        let gauge = zero.is_empty() || p.gauge_only(&zero);
        self.report.zero_modes = if gauge { 0 } else { zero.len() };
        gauge
    }

    /// ‖g‖ in the W⁻¹ norm (the gradient's size in the solver's metric).
    pub(super) fn gradient_norm(&self) -> f64 {
        let (g, w) = (&self.g, &self.weights);
        (0..g.len()).map(|i| g[i] * g[i] / w[i]).sum::<f64>().sqrt()
    }

    /// ‖Hu − λWu‖ in the W⁻¹ norm for the W-unit pair (λ, u), λ absolute: the dual norm of its
    /// Ritz residual (an eigenvalue of H lies within it). Needs `chol`'s values holding H;
    /// `hv` is scratch.
    pub(super) fn ritz_residual(&mut self, lambda: f64, u: &[f64], hv: &mut [f64]) -> f64 {
        self.chol.multiply(u, hv);
        let w = &self.weights;
        (0..hv.len())
            .map(|i| (hv[i] - lambda * w[i] * u[i]).powi(2) / w[i])
            .sum::<f64>()
            .sqrt()
    }

    /// Whether the full loads make a rigid turn of an unsupported structure unstable at its
    /// start (a free ring pinched by a balanced dead pair): then every state on the load path
    /// is a saddle. The turns' stiffness matrix is G_jk = r_jᵀ H r_k + gᵀ c_jk at λ = 1 (H and
    /// g there, c the turns' second-order motion); unstable when its lowest eigenvalue is
    /// negative beyond round-off.
    pub(super) fn turns_unstable_under_full_load<P: Core + ContinuationPath + Gauge>(
        &mut self,
        p: &mut P,
    ) -> bool {
        let Some(super::problem::TurnPaths { first, second }) = p.gauge_turns() else {
            return false;
        };
        if first.len() != 3 || second.len() != 6 {
            return false;
        }
        // The loads' part gᵀc first (a gradient only): the elastic part of a rigid turn is zero
        // at an equilibrium start, so without a negative load part there is nothing to find,
        // and the Hessian is assembled only when there is.
        p.set_continuation(1.0);
        let e = p.assemble(&mut self.g, None);
        p.set_continuation(0.0);
        if !e.is_finite() {
            return false;
        }
        let pairs = |f: &dyn Fn(usize, usize, usize) -> f64| {
            let mut m = vec![vec![0.0; 3]; 3];
            let mut idx = 0;
            for j in 0..3 {
                for k in j..3 {
                    (m[j][k], m[k][j]) = (f(j, k, idx), f(j, k, idx));
                    idx += 1;
                }
            }
            m
        };
        let load = pairs(&|_, _, i| dot(&self.g, &second[i]));
        let load_eigs = jacobi(load.clone()).0;
        let load_scale = load_eigs.iter().fold(0.0, |m: f64, v| m.max(v.abs()));
        if load_eigs.iter().all(|&v| v >= -1e-6 * load_scale) {
            return false;
        }
        p.set_continuation(1.0);
        p.assemble(&mut self.g, Some(&mut self.chol.values));
        p.set_continuation(0.0);
        let mut hv = vec![0.0; self.g.len()];
        let hr: Vec<Vec<f64>> = first
            .iter()
            .map(|r| {
                self.chol.multiply(r, &mut hv);
                hv.clone()
            })
            .collect();
        let elastic = pairs(&|j, k, _| dot(&first[j], &hr[k]));
        let total: Vec<Vec<f64>> = (0..3)
            .map(|j| (0..3).map(|k| elastic[j][k] + load[j][k]).collect())
            .collect();
        // r_kᵀHr_k of a rigid turn is round-off of the elastic scale (1e-12 of it, generously).
        let w_norm: f64 = first
            .iter()
            .map(|r| {
                r.iter()
                    .zip(&self.weights)
                    .map(|(x, w)| w * x * x)
                    .sum::<f64>()
            })
            .fold(0.0, f64::max);
        let noise = 1e-10 * self.scaled_diagonal() * w_norm;
        let lowest = jacobi(total).0.into_iter().fold(f64::INFINITY, f64::min);
        lowest < -(1e-6 * load_scale).max(noise)
    }

    /// One step of inverse iteration from a generic vector with the current factor: a growth
    /// beyond 1/ZERO of the scaled diagonal means an eigenvalue below ZERO (relative), which a
    /// Cholesky factorization of a singular matrix can hide behind a round-off pivot.
    ///
    /// `gauges` (W-orthonormal gauge modes of the problem) are projected out of the result
    /// first: an unsupported body's rigid turns would otherwise always trigger the full search.
    pub(super) fn near_singular(&mut self, gauges: &[Vec<f64>]) -> bool {
        const ZERO: f64 = 1e-10;
        // The corrections' buffers are free between iterations: no allocation at convergence.
        let (mut r, mut x) = (std::mem::take(&mut self.c), std::mem::take(&mut self.c2));
        let (s, w) = (&self.scales, &self.weights);
        for (i, v) in r.iter_mut().enumerate() {
            *v = (1.0 + 0.5 * ((i as f64) * 1.3).sin()) * s[i];
        }
        let wdot = |a: &[f64], b: &[f64]| wdot(a, b, w);
        for ((x, r), w) in x.iter_mut().zip(&r).zip(w) {
            *x = r * w;
        }
        self.chol.solve(&mut x);
        for q in gauges {
            let c = wdot(&x, q);
            x.iter_mut().zip(q).for_each(|(x, q)| *x -= c * q);
        }
        let growth = wdot(&x, &x).sqrt() / wdot(&r, &r).sqrt().max(f64::MIN_POSITIVE);
        (self.c, self.c2) = (r, x);
        growth * self.scaled_diagonal() > 1.0 / ZERO
    }

    /// Up to `k` lowest eigenpairs (λ relative to the Hessian's scaled diagonal, W-normalized
    /// vectors), ascending. Needs `chol` factored (with any shift) and its values holding H.
    pub(super) fn lowest_modes(&mut self, k: usize) -> Vec<(f64, Vec<f64>)> {
        // Eigenvalues are needed to tell zero (|λ| < 1e-10 of the scale) from not: settled
        // when the small ones, and how many they are, moved by less than 1e-6 of themselves or
        // of 1e-12 of the scale. A zero one is amplified by 1/τ and shows within two rounds.
        let scale = self.scaled_diagonal().max(f64::MIN_POSITIVE);
        let floor = 1e-12 * scale;
        let small = move |v: &[f64]| v.iter().filter(|&&a| a.abs() < 1e4 * floor).count();
        let settled = move |now: &[f64], last: &[f64]| {
            small(now) == small(last)
                && now
                    .iter()
                    .zip(last)
                    .filter(|(a, _)| a.abs() < 1e4 * floor)
                    .all(|(a, b)| (a - b).abs() <= 1e-6 * a.abs().max(floor))
        };
        let ritz = self.subspace(k, k, 30, settled);
        ritz.pairs
            .into_iter()
            .map(|(l, v)| (l / scale, v))
            .collect()
    }

    /// Block inverse iteration v ← (H + τW)⁻¹Wv with a Rayleigh–Ritz step each round, on a
    /// block of `block` vectors, until `settled(now, last)` holds for the `k` lowest Ritz
    /// values of two rounds (from the third) or `max_rounds` pass. Needs `chol` factored (with
    /// any shift) and its values holding H. Returns the `k` lowest pairs (absolute eigenvalues,
    /// W-normalized vectors), ascending.
    pub(super) fn subspace(
        &mut self,
        k: usize,
        block: usize,
        max_rounds: usize,
        settled: impl Fn(&[f64], &[f64]) -> bool,
    ) -> Ritz {
        let n = self.g.len();
        let k = k.min(n);
        if k == 0 {
            return Ritz {
                pairs: Vec::new(),
                rounds: 0,
                settled: true,
            };
        }
        let w = self.weights.clone();
        let mut v = start_block(&self.scales, block.clamp(k, n));
        let mut scratch = vec![0.0; n];
        // H v for the start only: after it, v = (H + τW)⁻¹Wx, so Hv = Wx − τWv comes without a
        // product.
        let mut hv: Vec<Vec<f64>> = v
            .iter()
            .map(|x| {
                self.chol.multiply(x, &mut scratch);
                scratch.clone()
            })
            .collect();
        // The factor may be of H + τW (an indefinite H): then Hv = Wx − τWv.
        let shift = self.chol.shift_diagonal();
        let mut last: Vec<f64> = vec![f64::INFINITY; k];
        let mut pairs: Vec<(f64, Vec<f64>)> = Vec::new();
        for round in 1..=max_rounds {
            pairs = self.rayleigh_ritz(&mut v, &mut hv, &w);
            let now: Vec<f64> = pairs.iter().take(k).map(|p| p.0).collect();
            if round > 2 && now.len() == last.len() && settled(&now, &last) {
                pairs.truncate(k);
                return Ritz {
                    pairs,
                    rounds: round,
                    settled: true,
                };
            }
            last = now;
            v.clear();
            hv.clear();
            for p in &pairs {
                let wx: Vec<f64> = p.1.iter().zip(&w).map(|(x, w)| x * w).collect();
                let mut y = wx.clone();
                self.chol.solve(&mut y);
                let h: Vec<f64> = (0..n).map(|i| wx[i] - shift[i] * y[i]).collect();
                v.push(y);
                hv.push(h);
            }
        }
        pairs.truncate(k);
        Ritz {
            pairs,
            rounds: max_rounds,
            settled: false,
        }
    }

    /// Ritz pairs of H on span(v), W-orthonormal, ascending, from the small generalized
    /// problem (VᵀHV)c = λ(VᵀWV)c; where VᵀWV is too ill-conditioned to factor, v is
    /// orthonormalized first (and Hv recomputed).
    fn rayleigh_ritz(
        &mut self,
        v: &mut Vec<Vec<f64>>,
        hv: &mut Vec<Vec<f64>>,
        w: &[f64],
    ) -> Vec<(f64, Vec<f64>)> {
        let wv: Vec<Vec<f64>> = v
            .iter()
            .map(|x| x.iter().zip(w).map(|(a, b)| a * b).collect())
            .collect();
        let mut pairs = match generalized(gram(v, &wv), gram(v, hv)) {
            Ok((vals, coef)) => ritz_vectors(v, &vals, &coef),
            Err(_) => {
                orthonormalize(v, w);
                let mut scratch = vec![0.0; w.len()];
                *hv = v
                    .iter()
                    .map(|x| {
                        self.chol.multiply(x, &mut scratch);
                        scratch.clone()
                    })
                    .collect();
                let (vals, vecs) = jacobi(gram(v, hv));
                ritz_vectors(v, &vals, &vecs)
            }
        };
        pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
        pairs
    }
}

/// The small generalized problem B y = μ A y, A positive definite: μ and the A-orthonormal y
/// (columns), through A = LLᵀ and the symmetric L⁻¹BL⁻ᵀ.
pub(super) fn generalized(
    a: Vec<Vec<f64>>,
    b: Vec<Vec<f64>>,
) -> Result<(Vec<f64>, Vec<Vec<f64>>), String> {
    let m = a.len();
    let mut l = vec![vec![0.0; m]; m];
    for j in 0..m {
        let d = a[j][j] - (0..j).map(|t| l[j][t] * l[j][t]).sum::<f64>();
        if d.is_nan() || d <= 0.0 {
            return Err("the stiffness at the start is not positive on the search space".into());
        }
        l[j][j] = d.sqrt();
        for i in j + 1..m {
            l[i][j] = (a[i][j] - (0..j).map(|t| l[i][t] * l[j][t]).sum::<f64>()) / l[j][j];
        }
    }
    // C = L⁻¹ B L⁻ᵀ: solve L Z = B, then C = L⁻¹ Zᵀ (Z is L⁻¹B, and (L⁻¹B)L⁻ᵀ = (L⁻¹(L⁻¹B)ᵀ)ᵀ).
    let lsolve = |col: Vec<f64>| -> Vec<f64> {
        let mut y = col;
        for i in 0..m {
            let s: f64 = (0..i).map(|t| l[i][t] * y[t]).sum();
            y[i] = (y[i] - s) / l[i][i];
        }
        y
    };
    let z: Vec<Vec<f64>> = (0..m)
        .map(|j| lsolve((0..m).map(|i| b[i][j]).collect()))
        .collect(); // z[j] = column j of L⁻¹B
    let c: Vec<Vec<f64>> = (0..m)
        .map(|i| lsolve((0..m).map(|j| z[j][i]).collect()))
        .collect(); // c[i] = column i of L⁻¹ (L⁻¹B)ᵀ
    let c: Vec<Vec<f64>> = (0..m)
        .map(|i| (0..m).map(|j| 0.5 * (c[i][j] + c[j][i])).collect())
        .collect();
    let (mu, q) = jacobi(c);
    // y = L⁻ᵀ q, column by column (back substitution).
    let mut y = vec![vec![0.0; m]; m];
    for col in 0..m {
        let mut x: Vec<f64> = (0..m).map(|r| q[r][col]).collect();
        for i in (0..m).rev() {
            let s: f64 = (i + 1..m).map(|t| l[t][i] * x[t]).sum();
            x[i] = (x[i] - s) / l[i][i];
        }
        for r in 0..m {
            y[r][col] = x[r];
        }
    }
    Ok((mu, y))
}

/// The result of `Newton::subspace`.
pub(super) struct Ritz {
    pub pairs: Vec<(f64, Vec<f64>)>,
    pub rounds: usize,
    pub settled: bool,
}

/// Deterministic, generic starting vectors, scaled like the unknowns.
pub(super) fn start_block(scales: &[f64], m: usize) -> Vec<Vec<f64>> {
    (0..m)
        .map(|j| {
            scales
                .iter()
                .enumerate()
                .map(|(i, s)| (1.0 + 0.5 * ((i as f64) * (0.7 + 0.31 * j as f64)).sin()) * s)
                .collect()
        })
        .collect()
}

/// The small symmetric matrix [xᵢ · yⱼ] for y = Ax, A symmetric: symmetric up to round-off,
/// so each pair is computed once (i ≤ j) and mirrored.
pub(super) fn gram(x: &[Vec<f64>], y: &[Vec<f64>]) -> Vec<Vec<f64>> {
    let m = x.len();
    let mut g = vec![vec![0.0; m]; m];
    for i in 0..m {
        for j in i..m {
            let v = dot(&x[i], &y[j]);
            g[i][j] = v;
            g[j][i] = v;
        }
    }
    g
}

/// The Ritz vectors Σᵣ x_r c_{r,j} for each column j of `coef`, with their values.
pub(super) fn ritz_vectors(
    x: &[Vec<f64>],
    vals: &[f64],
    coef: &[Vec<f64>],
) -> Vec<(f64, Vec<f64>)> {
    let n = x.first().map_or(0, Vec::len);
    (0..vals.len())
        .map(|c| {
            let mut u = vec![0.0; n];
            for (r, xr) in x.iter().enumerate() {
                let f = coef[r][c];
                u.iter_mut().zip(xr).for_each(|(u, y)| *u += f * y);
            }
            (vals[c], u)
        })
        .collect()
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// The W inner product Σ wᵢ aᵢ bᵢ.
pub(super) fn wdot(a: &[f64], b: &[f64], w: &[f64]) -> f64 {
    a.iter().zip(b).zip(w).map(|((x, y), w)| w * x * y).sum()
}

/// Gram–Schmidt in the W inner product; vectors that vanish are dropped.
pub(super) fn orthonormalize(v: &mut Vec<Vec<f64>>, w: &[f64]) {
    let wdot = |a: &[f64], b: &[f64]| wdot(a, b, w);
    let mut out: Vec<Vec<f64>> = Vec::with_capacity(v.len());
    for mut x in v.drain(..) {
        for _ in 0..2 {
            for q in &out {
                let c = wdot(&x, q);
                x.iter_mut().zip(q).for_each(|(x, q)| *x -= c * q);
            }
        }
        let nx = wdot(&x, &x).sqrt();
        if nx > 1e-300 && nx.is_finite() {
            x.iter_mut().for_each(|y| *y /= nx);
            out.push(x);
        }
    }
    *v = out;
}

/// Eigenvalues and eigenvectors (columns) of a small symmetric matrix, cyclic Jacobi.
pub(super) fn jacobi(mut a: Vec<Vec<f64>>) -> (Vec<f64>, Vec<Vec<f64>>) {
    let k = a.len();
    let mut e: Vec<Vec<f64>> = (0..k)
        .map(|i| (0..k).map(|j| f64::from(i == j)).collect())
        .collect();
    for _ in 0..50 {
        let off: f64 = (0..k)
            .flat_map(|i| (0..k).filter(move |&j| j != i).map(move |j| (i, j)))
            .map(|(i, j)| a[i][j] * a[i][j])
            .sum();
        let diag: f64 = (0..k).map(|i| a[i][i] * a[i][i]).sum();
        if off <= 1e-30 * diag.max(1e-300) {
            break;
        }
        for p in 0..k {
            for q in p + 1..k {
                // An off-diagonal entry below round-off of its diagonal pair is zero: rotating
                // by it would overflow θ and stall the sweep.
                if a[p][q].abs() <= 1e-18 * (a[p][p].abs() + a[q][q].abs()) {
                    a[p][q] = 0.0;
                    a[q][p] = 0.0;
                    continue;
                }
                let theta = 0.5 * (a[q][q] - a[p][p]) / a[p][q];
                let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
                let t = if theta == 0.0 { 1.0 } else { t };
                let c = 1.0 / (t * t + 1.0).sqrt();
                let s = t * c;
                for r in 0..k {
                    let (arp, arq) = (a[r][p], a[r][q]);
                    a[r][p] = c * arp - s * arq;
                    a[r][q] = s * arp + c * arq;
                }
                for r in 0..k {
                    let (apr, aqr) = (a[p][r], a[q][r]);
                    a[p][r] = c * apr - s * aqr;
                    a[q][r] = s * apr + c * aqr;
                }
                for r in 0..k {
                    let (erp, erq) = (e[r][p], e[r][q]);
                    e[r][p] = c * erp - s * erq;
                    e[r][q] = s * erp + c * erq;
                }
            }
        }
    }
    ((0..k).map(|i| a[i][i]).collect(), e)
}

#[cfg(test)]
mod tests {
    use super::jacobi;

    #[test]
    fn jacobi_diagonalizes_a_symmetric_matrix() {
        let a = vec![
            vec![4.0, 1.0, 0.5],
            vec![1.0, 3.0, 0.2],
            vec![0.5, 0.2, 1.0],
        ];
        let (vals, vecs) = jacobi(a.clone());
        for c in 0..3 {
            for r in 0..3 {
                let av: f64 = (0..3).map(|j| a[r][j] * vecs[j][c]).sum();
                assert!((av - vals[c] * vecs[r][c]).abs() < 1e-12);
            }
        }
    }
}
