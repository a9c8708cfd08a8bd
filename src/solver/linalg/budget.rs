//! What the sparse Cholesky factorization of a pattern will cost, known before any numeric
//! array is allocated: faer's symbolic analysis is cheap (linear in the pattern, plus the
//! ordering) and gives the factor's non-zeros exactly, so a scene too large for the machine can
//! be refused instead of aborting in the allocator (docs/performance.md).

use faer::sparse::linalg::cholesky::{SymbolicCholesky, SymbolicCholeskyRaw};
use faer::Par;

use super::cache::AnalysisCache;
use super::ordering::Ordering;
use super::symbolic::structure_bytes;

/// The cost of factoring one Hessian pattern the way the solver will.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FactorCost {
    /// Unknowns (the matrix dimension).
    pub unknowns: usize,
    /// Pairs the problem lists (duplicates included), each held while the pattern is built.
    pub pairs: usize,
    /// Distinct non-zeros of the stored upper triangle.
    pub hessian_nnz: usize,
    /// Non-zeros of the factor under the ordering the solver will choose.
    pub factor_nnz: usize,
    /// Floating-point operations of one numeric factorization, Σ (column count)².
    pub flops: f64,
    /// Peak resident bytes of the factorization objects: the pattern arrays, the factor kept,
    /// its structure and scratch, and the structure of the factor compared with it.
    pub bytes: u64,
    /// Non-zeros of the factor of the ordering compared and not kept (0 where only one
    /// ordering is analysed). Only its structure is made, never its values.
    pub other_factor_nnz: usize,
    /// The ordering chosen.
    pub ordering: Ordering,
}

/// One symbolic analysis and what its numeric objects will take.
struct Analysis {
    factor_nnz: usize,
    flops: f64,
    /// The factor's values.
    values: u64,
    /// Its symbolic structure and the pattern's arrays.
    structure: u64,
    /// Numeric factorization and solve scratch.
    scratch: u64,
}

/// The cost of factoring the pattern `pairs` (upper-triangle pairs, as
/// [`crate::solver::NewtonProblem::hessian_pattern`] lists them) of an `n`-unknown problem with
/// `ordering`, unknowns placed at `positions` (for the nested dissection; `None`: AMD only,
/// as the solver does when the problem gives no positions). The symbolic analysis is kept in
/// `analyses`, where a solve sharing that cache then finds it.
pub fn factor_cost(
    n: usize,
    pairs: &[(usize, usize)],
    positions: impl FnOnce() -> Option<Vec<[f64; 3]>>,
    ordering: Ordering,
    analyses: &AnalysisCache,
) -> FactorCost {
    let Some(symbolic) = analyses.analyse_pattern(n, pairs, ordering, positions) else {
        // The symbolic analysis failed (index overflow): nothing this large can be factored.
        return FactorCost {
            unknowns: n,
            pairs: pairs.len(),
            hessian_nnz: pairs.len(),
            factor_nnz: usize::MAX,
            flops: f64::INFINITY,
            bytes: u64::MAX,
            other_factor_nnz: 0,
            ordering,
        };
    };
    let nnz = symbolic.hessian_nnz();
    // The pattern arrays of the solve: the pairs' slots and their bucketing, row indices,
    // values and shifted values, column pointers and diagonal positions; the pattern renumbered
    // to the elimination order (its row indices and each entry's position in it, column
    // pointers, diagonal positions, the order), and the solve's renumbered right-hand side and
    // diagonal shifts.
    let pattern_bytes = 8 * (2 * pairs.len() + 5 * nnz + 8 * n) as u64;
    let chosen = analysis(symbolic.cholesky());
    let other = symbolic.other;
    // The other ordering's structure is alive while the two are compared.
    let resident = [
        pattern_bytes,
        chosen.values,
        chosen.structure,
        chosen.scratch,
        other.map_or(0, |o| o.structure_bytes),
    ]
    .iter()
    .fold(0u64, |a, &b| a.saturating_add(b));
    FactorCost {
        unknowns: n,
        pairs: pairs.len(),
        hessian_nnz: nnz,
        factor_nnz: chosen.factor_nnz,
        flops: chosen.flops,
        bytes: resident,
        other_factor_nnz: other.map_or(0, |o| o.factor_nnz),
        ordering: symbolic.ordering,
    }
}

/// Non-zeros, work and bytes of the numeric objects of one symbolic analysis: the factor's
/// values, its symbolic structure, and the numeric and solve scratch.
fn analysis(sym: &SymbolicCholesky<usize>) -> Analysis {
    let flops = match sym.raw() {
        SymbolicCholeskyRaw::Simplicial(s) => {
            let cp = s.col_ptr();
            cp.windows(2).map(|w| ((w[1] - w[0]) as f64).powi(2)).sum()
        }
        SymbolicCholeskyRaw::Supernodal(s) => {
            let (begin, end) = (s.supernode_begin(), s.supernode_end());
            let rows = s.col_ptr_for_row_idx();
            let mut flops = 0.0;
            for k in 0..s.n_supernodes() {
                let cols = (end[k] - begin[k]) as f64;
                let below = (rows[k + 1] - rows[k]) as f64;
                // Column j of the supernode has (cols − j) + below entries.
                flops += (1..=cols as usize)
                    .map(|j| (j as f64 + below).powi(2))
                    .sum::<f64>();
            }
            flops
        }
    };
    let scratch = sym
        .factorize_numeric_llt_scratch::<f64>(Par::Seq, Default::default())
        .unaligned_bytes_required()
        + sym
            .solve_in_place_scratch::<f64>(1, Par::Seq)
            .unaligned_bytes_required()
        + super::supernodal_solve::scratch_bytes(sym) as usize;
    let factor_nnz = sym.len_val();
    Analysis {
        factor_nnz,
        flops,
        values: 8 * factor_nnz as u64,
        structure: structure_bytes(sym),
        scratch: scratch as u64,
    }
}

#[cfg(test)]
mod tests {
    use super::super::ordering::{grid_graph, nested_dissection};
    use super::super::SparseCholesky;
    use super::*;

    /// The symbolic count is the factor the solver allocates, on a 2-D grid with both
    /// orderings.
    #[test]
    fn counts_the_factor_the_solver_allocates() {
        let m = 30;
        let n = m * m;
        let (pairs, pts) = grid_graph(m);
        let cache = AnalysisCache::default();
        let amd = factor_cost(n, &pairs, || Some(pts.clone()), Ordering::Amd, &cache);
        assert_eq!(
            amd.factor_nnz,
            SparseCholesky::new(n, &pairs).0.factor_nnz()
        );
        assert_eq!(amd.hessian_nnz, pairs.len());
        let nd = factor_cost(
            n,
            &pairs,
            || Some(pts.clone()),
            Ordering::NestedDissection,
            &cache,
        );
        let order = nested_dissection(n, &pairs, &pts);
        let solver = SparseCholesky::with_order(n, &pairs, Some(&order)).0;
        assert_eq!(nd.factor_nnz, solver.factor_nnz());
        assert!(amd.flops >= amd.factor_nnz as f64);
    }
}
