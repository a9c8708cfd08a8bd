//! Length projection of Newton steps (one step of "fast projection", Goldenthal et al. 2007).
//!
//! Position unknowns represent an edge's rotation to first order only: moving its end by Δe⊥
//! lengthens it by |Δe⊥|²/(2|e|). For slender rods (EA·|e|²/EI up to 1e8) that stretch costs far
//! more energy than the bending the step was meant to relieve, and line searches shrink the step
//! to nothing. The projection finds the smallest position correction c with
//! t'_e·(c_b − c_a) = −s_e for every edge, s_e = |e + Δe| − (|e| + t_e·Δe) the excess over the
//! linearized length: c = −Aᵀ(AAᵀ + δI)⁻¹ s. Because s grows as α², the line search follows the
//! curve x + α d + α² c, which is tangent to d and stays on the Newton model's lengths to third
//! order.

use crate::math::vec::{dot, norm, normalize, scalef, sub};
use crate::solver::linalg::SparseCholesky;
use crate::variables::Unknowns;

/// Edge–edge coupling through free nodes: the pattern of AAᵀ, built once.
pub struct Projector {
    chol: SparseCholesky,
    /// For each global edge: Hessian slots of (e, e) and of (e, f) pairs with their shared-node
    /// signs, recorded as (slot, e, f, node, sign product).
    diag: Vec<usize>,
    offdiag: Vec<(usize, usize, usize, usize, f64)>,
    /// Scratch of [`Self::correction`] and [`Self::restore_lengths`]: each edge's (moved)
    /// tangent and length excess (kept so that Newton iterations and the predictor's passes do
    /// not allocate).
    tn: Vec<[f64; 3]>,
    s: Vec<f64>,
}

impl Projector {
    pub fn new(u: Unknowns, edge_nodes: &[[usize; 2]]) -> Projector {
        let ne = edge_nodes.len();
        let free_node = |n: usize| (0..3).any(|k| u.of_node(n, k).is_some());
        let mut by_node: Vec<Vec<(usize, f64)>> = vec![Vec::new(); u.layout.n_nodes()];
        for (e, [a, b]) in edge_nodes.iter().enumerate() {
            if free_node(*a) {
                by_node[*a].push((e, -1.0));
            }
            if free_node(*b) {
                by_node[*b].push((e, 1.0));
            }
        }
        let mut pairs: Vec<(usize, usize)> = (0..ne).map(|e| (e, e)).collect();
        let mut meta = Vec::new();
        for (n, list) in by_node.iter().enumerate() {
            for i in 0..list.len() {
                for j in i + 1..list.len() {
                    let (e, se) = list[i];
                    let (f, sf) = list[j];
                    if e != f {
                        pairs.push((e.min(f), e.max(f)));
                        meta.push((e, f, n, se * sf));
                    }
                }
            }
        }
        let (chol, slots) = SparseCholesky::new(ne, &pairs);
        let offdiag = meta
            .into_iter()
            .enumerate()
            .map(|(k, (e, f, n, s))| (slots[ne + k], e, f, n, s))
            .collect();
        Projector {
            chol,
            diag: slots[..ne].to_vec(),
            offdiag,
            tn: vec![[0.0; 3]; ne],
            s: vec![0.0; ne],
        }
    }

    /// Writes the correction for step `d` (over free unknowns) into `c`. Returns false when there
    /// is nothing to correct.
    pub fn correction(
        &mut self,
        u: Unknowns,
        edge_nodes: &[[usize; 2]],
        q: &[f64],
        d: &[f64],
        c: &mut [f64],
    ) -> bool {
        let step = |n: usize| std::array::from_fn(|k| u.of_node(n, k).map_or(0.0, |f| d[f]));
        let (mut tn, mut s) = (std::mem::take(&mut self.tn), std::mem::take(&mut self.s));
        let mut any = false;
        for (e, &[a, b]) in edge_nodes.iter().enumerate() {
            let ev = sub(u.layout.position(q, b), u.layout.position(q, a));
            let de = sub(step(b), step(a));
            let l = norm(ev);
            let moved = [ev[0] + de[0], ev[1] + de[1], ev[2] + de[2]];
            let lin = l + dot(ev, de) / l;
            s[e] = norm(moved) - lin;
            tn[e] = normalize(moved);
            any |= s[e].abs() > 1e-14 * l;
        }
        c.iter_mut().for_each(|v| *v = 0.0);
        let r = any && self.min_norm(u, edge_nodes, &tn, &mut s, c);
        (self.tn, self.s) = (tn, s);
        r
    }

    /// Moves the free nodes by the smallest displacement that brings every edge back to the
    /// length given in `lengths` to first order (one Gauss–Newton step of the projection).
    /// Returns the largest relative length error |l − lengths|/l before the step, or None when
    /// nothing was moved (every error at round-off, or AAᵀ not factored).
    pub fn restore_lengths(
        &mut self,
        u: Unknowns,
        edge_nodes: &[[usize; 2]],
        q: &[f64],
        lengths: &[f64],
        c: &mut [f64],
    ) -> Option<f64> {
        let (mut tn, mut s) = (std::mem::take(&mut self.tn), std::mem::take(&mut self.s));
        let mut worst = 0.0_f64;
        for (e, &[a, b]) in edge_nodes.iter().enumerate() {
            let ev = sub(u.layout.position(q, b), u.layout.position(q, a));
            let l = norm(ev);
            s[e] = l - lengths[e];
            tn[e] = scalef(ev, 1.0 / l);
            worst = worst.max(s[e].abs() / l);
        }
        c.iter_mut().for_each(|v| *v = 0.0);
        let moved =
            worst.is_finite() && worst > 1e-14 && self.min_norm(u, edge_nodes, &tn, &mut s, c);
        (self.tn, self.s) = (tn, s);
        moved.then_some(worst)
    }

    /// c = −Aᵀ(AAᵀ + δI)⁻¹ s, A the rows t'_e·(c_b − c_a) over free unknowns.
    fn min_norm(
        &mut self,
        u: Unknowns,
        edge_nodes: &[[usize; 2]],
        tn: &[[f64; 3]],
        s: &mut [f64],
        c: &mut [f64],
    ) -> bool {
        self.chol.values.iter_mut().for_each(|v| *v = 0.0);
        for (e, &[a, b]) in edge_nodes.iter().enumerate() {
            // |t'|² per free endpoint (partially fixed nodes count their free components).
            let mut dsum = 0.0;
            for n in [a, b] {
                for k in 0..3 {
                    if u.of_node(n, k).is_some() {
                        dsum += tn[e][k] * tn[e][k];
                    }
                }
            }
            self.chol.values[self.diag[e]] += dsum + 1e-10;
        }
        for &(slot, e, f, n, sign) in &self.offdiag {
            let mut v = 0.0;
            for k in 0..3 {
                if u.of_node(n, k).is_some() {
                    v += tn[e][k] * tn[f][k];
                }
            }
            self.chol.values[slot] += sign * v;
        }
        if self.chol.factor(0.0).is_err() {
            return false;
        }
        self.chol.solve(s);
        // c = −Aᵀ y.
        for (e, &[a, b]) in edge_nodes.iter().enumerate() {
            for k in 0..3 {
                let w = s[e] * tn[e][k];
                if let Some(fb) = u.of_node(b, k) {
                    c[fb] -= w;
                }
                if let Some(fa) = u.of_node(a, k) {
                    c[fa] += w;
                }
            }
        }
        true
    }
}

/// The stretch force that the higher-order length error of a step would create. For each edge,
/// k·s along its current tangent, with k = EA/l̄ (its axial stiffness) and s the excess of its
/// length after `trial` over the length that the linearization of `alpha · d` gives:
/// s = |e + Δe_trial| − (|e| + α t·Δe_d). The solver maps it through the (regularized) Hessian,
/// c = −H⁻¹f, which restores the lengths with the least energy of the Newton model instead of
/// the least Euclidean motion: with `trial` = d it gives the step's second-order correction,
/// with a corrected trial point the correction's own remaining error (`solver/step.rs`).
/// Returns the energy ½Σk·s² of the excess, 0 when every excess is at round-off.
pub fn excess_force(
    u: Unknowns,
    edge_nodes: &[[usize; 2]],
    stiffness: impl Iterator<Item = (usize, f64)>,
    q: &[f64],
    trial: &[f64],
    (d, alpha): (&[f64], f64),
    f: &mut [f64],
) -> f64 {
    let at = |v: &[f64], n: usize| -> [f64; 3] {
        std::array::from_fn(|k| u.of_node(n, k).map_or(0.0, |i| v[i]))
    };
    f.iter_mut().for_each(|v| *v = 0.0);
    let mut energy = 0.0;
    for (e, k) in stiffness {
        let [a, b] = edge_nodes[e];
        let ev = sub(u.layout.position(q, b), u.layout.position(q, a));
        let de = sub(at(trial, b), at(trial, a));
        let l = norm(ev);
        let moved = [ev[0] + de[0], ev[1] + de[1], ev[2] + de[2]];
        let linear = l + alpha * dot(ev, sub(at(d, b), at(d, a))) / l;
        let s = norm(moved) - linear;
        if s.abs() <= 1e-14 * l {
            continue;
        }
        energy += 0.5 * k * s * s;
        // Along the current tangent: the Hessian's axial stiffness acts there, and a component
        // across it would be met by bending stiffness alone.
        let t = scalef(ev, 1.0 / l);
        for j in 0..3 {
            if let Some(i) = u.of_node(b, j) {
                f[i] += k * s * t[j];
            }
            if let Some(i) = u.of_node(a, j) {
                f[i] -= k * s * t[j];
            }
        }
    }
    energy
}
