//! Sparse symmetric factorization with faer: the symbolic analysis (ordering, elimination tree,
//! supernodes) is done once per sparsity pattern; each Newton iteration refills values and
//! refactors numerically, optionally with a diagonal shift.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::ldlt::factor::LdltRegularization;
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::perm::PermRef;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, LdltRef, LltRef, SymbolicCholesky,
    SymmetricOrdering,
};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMat};
use faer::{Conj, MatMut, Par, Side};

/// The symbolic analysis's settings. faer's automatic choice (threshold 1) takes the supernodal
/// factorization when the factor's flops per non-zero exceed 40; on rod networks the supernodal
/// kernels win from half that: the n = 12 hemisphere's factorizations take 2.7× fewer
/// instructions (docs/performance.md), while rods and chains (few flops per non-zero) stay
/// simplicial, where the supernodal overhead would not pay.
pub fn symbolic_params() -> CholeskySymbolicParams<'static> {
    CholeskySymbolicParams {
        supernodal_flop_ratio_threshold: faer::sparse::linalg::SupernodalThreshold(0.5),
        ..Default::default()
    }
}

pub struct SparseCholesky {
    n: usize,
    pattern: SymbolicSparseColMat<usize>,
    /// Values of the upper triangle, in CSC order; callers fill them through slots.
    pub values: Vec<f64>,
    diag: Vec<usize>,
    shifted: Vec<f64>,
    symbolic: SymbolicCholesky<usize>,
    l: Vec<f64>,
    factor_mem: MemBuffer,
    solve_mem: MemBuffer,
    factored: bool,
    /// LDLᵀ factor values and scratch, allocated on first use (arc-length continuation).
    ldlt: Vec<f64>,
    ldlt_mem: MemBuffer,
    ldlt_factored: bool,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct NotPositiveDefinite;

impl SparseCholesky {
    /// Builds the pattern from upper-triangle pairs (duplicates allowed; every diagonal entry must
    /// be present). Returns the solver and, for each pair, its index into [`Self::values`].
    pub fn new(n: usize, pairs: &[(usize, usize)]) -> (SparseCholesky, Vec<usize>) {
        Self::with_order(n, pairs, None)
    }

    /// As [`Self::new`], with an elimination order (position k: the unknown eliminated k-th)
    /// instead of AMD.
    pub fn with_order(
        n: usize,
        pairs: &[(usize, usize)],
        elimination: Option<&[usize]>,
    ) -> (SparseCholesky, Vec<usize>) {
        let mut order: Vec<usize> = (0..pairs.len()).collect();
        order.sort_unstable_by_key(|&k| (pairs[k].1, pairs[k].0));
        let mut col_ptr = vec![0usize; n + 1];
        let mut row_idx: Vec<usize> = Vec::with_capacity(pairs.len());
        let mut slot = vec![0usize; pairs.len()];
        let mut last: Option<(usize, usize)> = None;
        for &k in &order {
            let (r, c) = pairs[k];
            debug_assert!(r <= c && c < n);
            if last != Some((r, c)) {
                row_idx.push(r);
                col_ptr[c + 1] = row_idx.len();
                last = Some((r, c));
            }
            slot[k] = row_idx.len() - 1;
        }
        for c in 0..n {
            col_ptr[c + 1] = col_ptr[c + 1].max(col_ptr[c]);
        }
        let nnz = row_idx.len();
        let mut diag = vec![usize::MAX; n];
        for c in 0..n {
            for p in col_ptr[c]..col_ptr[c + 1] {
                if row_idx[p] == c {
                    diag[c] = p;
                }
            }
        }
        assert!(
            diag.iter().all(|&d| d != usize::MAX),
            "pattern lacks a diagonal entry"
        );
        let pattern = SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx);
        let inverse: Vec<usize> = elimination.map_or_else(Vec::new, |fwd| {
            let mut inv = vec![0; n];
            for (k, &i) in fwd.iter().enumerate() {
                inv[i] = k;
            }
            inv
        });
        let ordering = match elimination {
            Some(fwd) => SymmetricOrdering::Custom(PermRef::new_checked(fwd, &inverse, n)),
            None => SymmetricOrdering::Amd,
        };
        let symbolic =
            factorize_symbolic_cholesky(pattern.as_ref(), Side::Upper, ordering, symbolic_params())
                .expect("symbolic Cholesky analysis");
        let par = Par::Seq;
        let factor_mem =
            MemBuffer::new(symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default()));
        let solve_mem = MemBuffer::new(symbolic.solve_in_place_scratch::<f64>(1, par));
        let l = vec![0.0; symbolic.len_val()];
        (
            SparseCholesky {
                n,
                pattern,
                values: vec![0.0; nnz],
                diag,
                shifted: vec![0.0; nnz],
                symbolic,
                l,
                factor_mem,
                solve_mem,
                factored: false,
                ldlt: Vec::new(),
                ldlt_mem: MemBuffer::new(faer::dyn_stack::StackReq::EMPTY),
                ldlt_factored: false,
            },
            slot,
        )
    }

    pub fn dim(&self) -> usize {
        self.n
    }

    /// Non-zeros of the Cholesky factor (fill-in measure).
    pub fn factor_nnz(&self) -> usize {
        self.l.len()
    }

    /// Column pointers of the stored upper triangle (CSC).
    pub fn col_ptr(&self) -> &[usize] {
        self.pattern.col_ptr()
    }

    /// Row indices of the stored upper triangle (CSC, sorted within each column).
    pub fn row_idx(&self) -> &[usize] {
        self.pattern.row_idx()
    }

    /// Values of A + shift·I from the last call to [`Self::factor`] (successful or not), in the
    /// order of [`Self::row_idx`].
    pub fn shifted_values(&self) -> &[f64] {
        &self.shifted
    }

    /// Largest absolute diagonal value.
    pub fn diagonal_scale(&self) -> f64 {
        self.diag
            .iter()
            .map(|&p| self.values[p].abs())
            .fold(0.0, f64::max)
    }

    /// Diagonal value A_ii.
    pub fn diagonal(&self, i: usize) -> f64 {
        self.values[self.diag[i]]
    }

    /// The shift of the last factorization on each diagonal entry (shift·wᵢ; zeros unshifted).
    pub fn shift_diagonal(&self) -> Vec<f64> {
        self.diag
            .iter()
            .map(|&p| self.shifted[p] - self.values[p])
            .collect()
    }

    /// Numeric LLᵀ factorization of A + shift·I.
    pub fn factor(&mut self, shift: f64) -> Result<(), NotPositiveDefinite> {
        self.factor_weighted(shift, &[])
    }

    /// Numeric LLᵀ factorization of A + shift·W, W = diag(`weights`) (empty: the identity).
    pub fn factor_weighted(
        &mut self,
        shift: f64,
        weights: &[f64],
    ) -> Result<(), NotPositiveDefinite> {
        self.shifted.copy_from_slice(&self.values);
        for (i, &p) in self.diag.iter().enumerate() {
            self.shifted[p] += shift * weights.get(i).copied().unwrap_or(1.0);
        }
        let a = SparseColMatRef::new(self.pattern.as_ref(), &self.shifted);
        let r = self.symbolic.factorize_numeric_llt(
            &mut self.l,
            a,
            Side::Upper,
            LltRegularization::default(),
            Par::Seq,
            MemStack::new(&mut self.factor_mem),
            Default::default(),
        );
        self.factored = r.is_ok() && self.l.iter().all(|v| v.is_finite());
        if self.factored {
            Ok(())
        } else {
            Err(NotPositiveDefinite)
        }
    }

    /// Numeric LDLᵀ factorization of the unshifted A, without pivoting: A may be indefinite (an
    /// equilibrium path past a limit point), not singular. Kept apart from the LLᵀ factor.
    pub fn factor_ldlt(&mut self) -> Result<(), NotPositiveDefinite> {
        if self.ldlt.is_empty() {
            self.ldlt = vec![0.0; self.symbolic.len_val()];
            self.ldlt_mem = MemBuffer::new(
                self.symbolic
                    .factorize_numeric_ldlt_scratch::<f64>(Par::Seq, Default::default()),
            );
        }
        let a = SparseColMatRef::new(self.pattern.as_ref(), &self.values);
        let r = self.symbolic.factorize_numeric_ldlt(
            &mut self.ldlt,
            a,
            Side::Upper,
            LdltRegularization::default(),
            Par::Seq,
            MemStack::new(&mut self.ldlt_mem),
            Default::default(),
        );
        self.ldlt_factored = r.is_ok() && self.ldlt.iter().all(|v| v.is_finite());
        if self.ldlt_factored {
            Ok(())
        } else {
            Err(NotPositiveDefinite)
        }
    }

    /// Solves A x = rhs in place with the last successful LDLᵀ factorization.
    pub fn solve_ldlt(&mut self, rhs: &mut [f64]) {
        assert!(self.ldlt_factored, "solve without an LDLᵀ factorization");
        let f = LdltRef::<usize, f64>::new(&self.symbolic, &self.ldlt);
        let m = MatMut::from_column_major_slice_mut(rhs, self.n, 1);
        f.solve_in_place_with_conj(Conj::No, m, Par::Seq, MemStack::new(&mut self.solve_mem));
    }

    /// Solves (A + shift·I) x = rhs in place with the last successful factorization.
    pub fn solve(&mut self, rhs: &mut [f64]) {
        assert!(self.factored, "solve without a factorization");
        let llt = LltRef::<usize, f64>::new(&self.symbolic, &self.l);
        let m = MatMut::from_column_major_slice_mut(rhs, self.n, 1);
        llt.solve_in_place_with_conj(Conj::No, m, Par::Seq, MemStack::new(&mut self.solve_mem));
    }

    /// y = A x with the unshifted symmetric matrix (upper triangle stored).
    pub fn multiply(&self, x: &[f64], y: &mut [f64]) {
        self.multiply_with(&self.values, x, y);
    }

    /// y = A x for another matrix of the same pattern, given by its `values`.
    pub fn multiply_with(&self, values: &[f64], x: &[f64], y: &mut [f64]) {
        y.iter_mut().for_each(|v| *v = 0.0);
        let cp = self.pattern.col_ptr();
        let ri = self.pattern.row_idx();
        for c in 0..self.n {
            for p in cp[c]..cp[c + 1] {
                let r = ri[p];
                let v = values[p];
                y[r] += v * x[c];
                if r != c {
                    y[c] += v * x[r];
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solves_a_small_spd_system_and_rejects_an_indefinite_one() {
        // Tridiagonal [2 -1; -1 2 -1; -1 2], duplicates summed.
        let pairs = [(0, 0), (1, 1), (2, 2), (0, 1), (1, 2), (1, 1)];
        let (mut s, slot) = SparseCholesky::new(3, &pairs);
        let vals = [2.0, 1.0, 2.0, -1.0, -1.0, 1.0];
        for (k, v) in vals.iter().enumerate() {
            s.values[slot[k]] += v;
        }
        s.factor(0.0).unwrap();
        let mut b = [1.0, 0.0, 1.0];
        s.solve(&mut b);
        for v in b {
            assert!((v - 1.0).abs() < 1e-14);
        }
        let mut y = [0.0; 3];
        s.multiply(&[1.0, 1.0, 1.0], &mut y);
        assert_eq!(y, [1.0, 0.0, 1.0]);
        s.values.iter_mut().for_each(|v| *v = -*v);
        assert!(s.factor(0.0).is_err());
        assert!(s.factor(4.5).is_ok());
    }
}
