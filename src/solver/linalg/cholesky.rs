//! Sparse symmetric factorization with faer: the symbolic analysis (ordering, elimination tree,
//! supernodes) is done once per sparsity pattern; each Newton iteration refills values and
//! refactors numerically, optionally with a diagonal shift.

use std::sync::Arc;

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::ldlt::factor::LdltRegularization;
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, LdltRef, LltRef, SymbolicCholeskyRaw,
};
use faer::sparse::SparseColMatRef;
use faer::{Conj, MatMut, Par};

use super::supernodal_solve;
use super::symbolic::{self, Symbolic};

/// The symbolic analysis's settings. faer's automatic choice (threshold 1) takes the supernodal
/// factorization when the factor's flops per non-zero exceed 40; on rod networks the supernodal
/// kernels already win from half that (measured on gridshells: docs/performance.md), while rods
/// and chains (few flops per non-zero) stay simplicial, where the supernodal overhead would not
/// pay.
pub fn symbolic_params() -> CholeskySymbolicParams<'static> {
    CholeskySymbolicParams {
        supernodal_flop_ratio_threshold: faer::sparse::linalg::SupernodalThreshold(0.5),
        ..Default::default()
    }
}

pub struct SparseCholesky {
    n: usize,
    /// The pattern's analysis, shared with every other factorization of the pattern.
    pub(super) symbolic: Arc<Symbolic>,
    /// Values of the upper triangle, in CSC order; callers fill them through slots.
    pub values: Vec<f64>,
    /// A + shift·W of the last factorization, in the permuted pattern faer reads.
    shifted: Vec<f64>,
    /// shift·wᵢ of the last factorization on each diagonal entry.
    diag_shift: Vec<f64>,
    /// A right-hand side in the elimination order.
    permuted_rhs: Vec<f64>,
    l: Vec<f64>,
    factor_mem: MemBuffer,
    solve_mem: MemBuffer,
    /// Scratch of the supernodal solve.
    solve_scratch: supernodal_solve::Scratch,
    /// The supernodes' division for a solve on two threads, if it pays.
    solve_split: Option<supernodal_solve::Split>,
    factored: bool,
    /// Whether [`Self::solve`] uses faer's own solve on a supernodal factor too (see
    /// [`faer_solve_asked`]).
    faer_solve: bool,
    /// LDLᵀ factor values, its input in the permuted pattern, and scratch, allocated on first
    /// use (arc-length continuation).
    ldlt: Vec<f64>,
    ldlt_input: Vec<f64>,
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
        let symbolic =
            symbolic::with_order(n, pairs, elimination).expect("symbolic Cholesky analysis");
        let slots = symbolic
            .slots(pairs)
            .expect("the pattern holds its own pairs");
        (Self::from_symbolic(Arc::new(symbolic)), slots)
    }

    /// The numeric objects of a factorization on an analysed pattern.
    pub(super) fn from_symbolic(symbolic: Arc<Symbolic>) -> SparseCholesky {
        let par = Par::Seq;
        let sym = symbolic.cholesky();
        let factor_mem =
            MemBuffer::new(sym.factorize_numeric_llt_scratch::<f64>(par, Default::default()));
        let solve_mem = MemBuffer::new(sym.solve_in_place_scratch::<f64>(1, par));
        let l = vec![0.0; sym.len_val()];
        let solve_split = match sym.raw() {
            SymbolicCholeskyRaw::Supernodal(s) => supernodal_solve::Split::new(s),
            SymbolicCholeskyRaw::Simplicial(_) => None,
        };
        let solve_scratch = supernodal_solve::Scratch::new(sym, solve_split.as_ref());
        let nnz = symbolic.hessian_nnz();
        SparseCholesky {
            n: symbolic.pattern.ncols(),
            values: vec![0.0; nnz],
            shifted: vec![0.0; nnz],
            diag_shift: vec![0.0; symbolic.pattern.ncols()],
            permuted_rhs: vec![0.0; symbolic.pattern.ncols()],
            symbolic,
            l,
            factor_mem,
            solve_mem,
            solve_scratch,
            solve_split,
            factored: false,
            faer_solve: faer_solve_asked(),
            ldlt: Vec::new(),
            ldlt_input: Vec::new(),
            ldlt_mem: MemBuffer::new(faer::dyn_stack::StackReq::EMPTY),
            ldlt_factored: false,
        }
    }

    pub fn dim(&self) -> usize {
        self.n
    }

    /// Non-zeros of the Cholesky factor (fill-in measure).
    pub fn factor_nnz(&self) -> usize {
        self.l.len()
    }

    /// Whether solves split the factor over two threads (`supernodal_solve::Split`).
    pub fn solves_in_parallel(&self) -> bool {
        self.solve_split.is_some() && !self.faer_solve
    }

    /// Solves with faer's own routine (`true`) instead of the supernodal loops of
    /// `supernodal_solve.rs`, which read faer's factor storage by its layout: the fallback
    /// should a faer version store it otherwise. Default: `RODNET_FAER_SOLVE`.
    pub fn use_faer_solve(&mut self, on: bool) {
        self.faer_solve = on;
    }

    /// Column pointers of the stored upper triangle (CSC).
    pub fn col_ptr(&self) -> &[usize] {
        self.symbolic.pattern.col_ptr()
    }

    /// Row indices of the stored upper triangle (CSC, sorted within each column).
    pub fn row_idx(&self) -> &[usize] {
        self.symbolic.pattern.row_idx()
    }

    /// Values of A + shift·W from the last call to [`Self::factor_weighted`] (successful or
    /// not), in the order of [`Self::row_idx`], written to `out`.
    pub fn shifted_values_into(&self, out: &mut Vec<f64>) {
        out.clear();
        out.extend(
            self.symbolic
                .permuted
                .of_upper
                .iter()
                .map(|&p| self.shifted[p]),
        );
    }

    /// Largest absolute diagonal value.
    pub fn diagonal_scale(&self) -> f64 {
        self.symbolic
            .diag
            .iter()
            .map(|&p| self.values[p].abs())
            .fold(0.0, f64::max)
    }

    /// Diagonal value A_ii.
    pub fn diagonal(&self, i: usize) -> f64 {
        self.values[self.symbolic.diag[i]]
    }

    /// The shift of the last factorization on each diagonal entry (shift·wᵢ; zeros unshifted).
    pub fn shift_diagonal(&self) -> Vec<f64> {
        self.diag_shift.clone()
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
        let pm = &self.symbolic.permuted;
        permute_values(&self.values, &pm.of_upper, &mut self.shifted);
        for (i, &p) in pm.diag.iter().enumerate() {
            self.diag_shift[i] = shift * weights.get(i).copied().unwrap_or(1.0);
            self.shifted[p] += self.diag_shift[i];
        }
        let a = SparseColMatRef::new(pm.pattern.as_ref(), &self.shifted);
        let r = self.symbolic.cholesky.factorize_numeric_llt(
            &mut self.l,
            a,
            pm.side,
            LltRegularization::default(),
            Par::Seq,
            MemStack::new(&mut self.factor_mem),
            Default::default(),
        );
        self.factored = r.is_ok() && all_finite(&self.l);
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
            self.ldlt = vec![0.0; self.symbolic.cholesky.len_val()];
            self.ldlt_input = vec![0.0; self.values.len()];
            self.ldlt_mem = MemBuffer::new(
                self.symbolic
                    .cholesky
                    .factorize_numeric_ldlt_scratch::<f64>(Par::Seq, Default::default()),
            );
        }
        let pm = &self.symbolic.permuted;
        permute_values(&self.values, &pm.of_upper, &mut self.ldlt_input);
        let a = SparseColMatRef::new(pm.pattern.as_ref(), &self.ldlt_input);
        let r = self.symbolic.cholesky.factorize_numeric_ldlt(
            &mut self.ldlt,
            a,
            pm.side,
            LdltRegularization::default(),
            Par::Seq,
            MemStack::new(&mut self.ldlt_mem),
            Default::default(),
        );
        self.ldlt_factored = r.is_ok() && all_finite(&self.ldlt);
        if self.ldlt_factored {
            Ok(())
        } else {
            Err(NotPositiveDefinite)
        }
    }

    /// Solves A x = rhs in place with the last successful LDLᵀ factorization.
    pub fn solve_ldlt(&mut self, rhs: &mut [f64]) {
        assert!(self.ldlt_factored, "solve without an LDLᵀ factorization");
        let f = LdltRef::<usize, f64>::new(&self.symbolic.cholesky, &self.ldlt);
        in_elimination_order(
            &self.symbolic.permuted.elimination,
            &mut self.permuted_rhs,
            rhs,
            |b| {
                f.solve_in_place_with_conj(
                    Conj::No,
                    b,
                    Par::Seq,
                    MemStack::new(&mut self.solve_mem),
                )
            },
        );
    }

    /// Solves (A + shift·I) x = rhs in place with the last successful factorization.
    pub fn solve(&mut self, rhs: &mut [f64]) {
        assert!(self.factored, "solve without a factorization");
        if let (SymbolicCholeskyRaw::Supernodal(sym), false) =
            (self.symbolic.cholesky.raw(), self.faer_solve)
        {
            let order = &self.symbolic.permuted.elimination;
            let b = &mut self.permuted_rhs;
            order
                .iter()
                .zip(b.iter_mut())
                .for_each(|(&i, b)| *b = rhs[i]);
            let split = self.solve_split.as_ref();
            supernodal_solve::solve_in_place(sym, &self.l, b, split, &mut self.solve_scratch);
            order.iter().zip(b.iter()).for_each(|(&i, b)| rhs[i] = *b);
        } else {
            self.solve_with_faer(rhs);
        }
    }

    /// [`Self::solve`] by faer's own routine (the simplicial factor; the supernodal one with
    /// [`Self::use_faer_solve`], and in tests as the reference of [`supernodal_solve`]).
    fn solve_with_faer(&mut self, rhs: &mut [f64]) {
        let llt = LltRef::<usize, f64>::new(&self.symbolic.cholesky, &self.l);
        in_elimination_order(
            &self.symbolic.permuted.elimination,
            &mut self.permuted_rhs,
            rhs,
            |b| {
                llt.solve_in_place_with_conj(
                    Conj::No,
                    b,
                    Par::Seq,
                    MemStack::new(&mut self.solve_mem),
                )
            },
        );
    }

    /// Splits supernodal solves over two threads whatever the factor's size (`on`), or never;
    /// whether a split was found. For the tests of the split's arithmetic on small factors.
    #[cfg(test)]
    pub(super) fn force_split(&mut self, on: bool) -> bool {
        let SymbolicCholeskyRaw::Supernodal(sym) = self.symbolic.cholesky.raw() else {
            return false;
        };
        self.solve_split = if on {
            supernodal_solve::Split::from_values(sym, 0)
        } else {
            None
        };
        self.solve_scratch =
            supernodal_solve::Scratch::new(&self.symbolic.cholesky, self.solve_split.as_ref());
        self.solve_split.is_some()
    }

    /// y = (A + shift·W) x with the matrix of the last factorization.
    pub fn multiply_shifted(&self, x: &[f64], y: &mut [f64]) {
        self.multiply(x, y);
        for ((y, x), s) in y.iter_mut().zip(x).zip(&self.diag_shift) {
            *y += s * x;
        }
    }

    /// y = A x with the unshifted symmetric matrix (upper triangle stored).
    pub fn multiply(&self, x: &[f64], y: &mut [f64]) {
        self.multiply_with(&self.values, x, y);
    }

    /// y = A x for another matrix of the same pattern, given by its `values`.
    ///
    /// Column by column, each entry of the upper triangle (rows sorted, r ≤ c) added to its row
    /// and to its column. A column's own sum is kept in a register: y_c is still zero when its
    /// column is reached (later columns add to it only after), so the sums are those of adding
    /// to y_c in memory, to the last bit (tests/sparse_product.rs), without a load and a store
    /// of y_c per entry.
    pub fn multiply_with(&self, values: &[f64], x: &[f64], y: &mut [f64]) {
        y.iter_mut().for_each(|v| *v = 0.0);
        let cp = self.symbolic.pattern.col_ptr();
        let ri = self.symbolic.pattern.row_idx();
        for c in 0..self.n {
            let xc = x[c];
            let mut own = y[c];
            for p in cp[c]..cp[c + 1] {
                let (r, v) = (ri[p], values[p]);
                if r == c {
                    own += v * xc;
                } else {
                    y[r] += v * xc;
                    own += v * x[r];
                }
            }
            y[c] = own;
        }
    }
}

/// Whether the environment asks for faer's solve on supernodal factors
/// (`RODNET_FAER_SOLVE` set and not `0`), read once per process.
fn faer_solve_asked() -> bool {
    static ASKED: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    *ASKED.get_or_init(|| std::env::var_os("RODNET_FAER_SOLVE").is_some_and(|v| v != "0"))
}

/// Whether every value is finite, in one pass the compiler vectorizes (x·0 is NaN exactly for
/// infinite or NaN x), unlike a short-circuiting test, over a factor's every value.
fn all_finite(v: &[f64]) -> bool {
    let mut acc = [0.0; 8];
    let chunks = v.chunks_exact(8);
    let rest = chunks.remainder();
    for c in chunks {
        for (a, x) in acc.iter_mut().zip(c) {
            *a += x * 0.0;
        }
    }
    acc.iter().all(|a| !a.is_nan()) && rest.iter().all(|x| x.is_finite())
}

/// The values of the upper triangle copied into the permuted pattern's order (`of_upper`).
fn permute_values(values: &[f64], of_upper: &[usize], out: &mut [f64]) {
    for (&v, &p) in values.iter().zip(of_upper) {
        out[p] = v;
    }
}

/// Runs `solve` on `rhs` renumbered into the elimination order (in the buffer `b`) and writes
/// the solution back in the unknowns' order.
fn in_elimination_order(
    order: &[usize],
    b: &mut [f64],
    rhs: &mut [f64],
    solve: impl FnOnce(MatMut<'_, f64>),
) {
    order
        .iter()
        .zip(b.iter_mut())
        .for_each(|(&i, b)| *b = rhs[i]);
    let n = b.len();
    solve(MatMut::from_column_major_slice_mut(b, n, 1));
    order.iter().zip(b.iter()).for_each(|(&i, b)| rhs[i] = *b);
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

    #[test]
    fn all_finite_finds_a_non_finite_value_anywhere() {
        for n in [0, 1, 7, 8, 9, 23] {
            let mut v: Vec<f64> = (0..n).map(|i| (i as f64 - 4.0) * 1e300).collect();
            assert!(all_finite(&v));
            for i in 0..n {
                for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
                    let keep = v[i];
                    v[i] = bad;
                    assert!(!all_finite(&v), "n {n}, index {i}, {bad}");
                    v[i] = keep;
                }
            }
        }
    }

    /// The supernodal solve against faer's on a pattern faer factors supernodally: a 2-D grid
    /// of nodes with three unknowns each, coupled to their neighbours (a rod network's shape).
    #[test]
    fn supernodal_solve_is_faers() {
        solve_grid_against_faer(24, false);
    }

    /// As [`supernodal_solve_is_faers`], with the solve split for two threads (on a factor
    /// below the size where the split pays).
    #[test]
    fn split_supernodal_solve_is_faers() {
        solve_grid_against_faer(24, true);
    }

    fn solve_grid_against_faer(w: usize, split: bool) {
        let dofs = 3;
        let n = w * w * dofs;
        let node = |i: usize, j: usize| (i * w + j) * dofs;
        let mut pairs = vec![];
        let mut vals = vec![];
        for i in 0..w {
            for j in 0..w {
                for a in 0..dofs {
                    for b in a..dofs {
                        pairs.push((node(i, j) + a, node(i, j) + b));
                        vals.push(if a == b { 20.0 } else { 0.3 });
                    }
                }
                for (di, dj) in [(0, 1), (1, 0), (1, 1)] {
                    if i + di < w && j + dj < w {
                        for a in 0..dofs {
                            for b in 0..dofs {
                                let (p, q) = (node(i, j) + a, node(i + di, j + dj) + b);
                                pairs.push((p.min(q), p.max(q)));
                                vals.push(-0.5 - 0.1 * ((p + 7 * q) % 5) as f64);
                            }
                        }
                    }
                }
            }
        }
        let (mut s, slot) = SparseCholesky::new(n, &pairs);
        assert!(matches!(
            s.symbolic.cholesky.raw(),
            SymbolicCholeskyRaw::Supernodal(_)
        ));
        let SymbolicCholeskyRaw::Supernodal(sym) = s.symbolic.cholesky.raw() else {
            unreachable!()
        };
        s.solve_split = if split {
            supernodal_solve::Split::from_values(sym, 0)
        } else {
            None
        };
        assert_eq!(s.solve_split.is_some(), split);
        s.solve_scratch =
            supernodal_solve::Scratch::new(&s.symbolic.cholesky, s.solve_split.as_ref());
        for (k, v) in vals.iter().enumerate() {
            s.values[slot[k]] += v;
        }
        s.use_faer_solve(false);
        s.factor(0.0).unwrap();
        let b: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).sin()).collect();
        let (mut own, mut reference) = (b.clone(), b.clone());
        s.solve(&mut own);
        s.solve_with_faer(&mut reference);
        let scale = reference.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        for (x, y) in own.iter().zip(&reference) {
            assert!((x - y).abs() <= 1e-13 * scale, "{x} vs {y}");
        }
        let mut ax = vec![0.0; n];
        s.multiply(&own, &mut ax);
        for (a, b) in ax.iter().zip(&b) {
            assert!((a - b).abs() < 1e-12, "{a} vs {b}");
        }
        // The same bits on one thread and on two.
        let on = |threads: usize, s: &mut SparseCholesky| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let mut x = b.clone();
            pool.install(|| s.solve(&mut x));
            x
        };
        let (one, two) = (on(1, &mut s), on(2, &mut s));
        assert!(one
            .iter()
            .zip(&two)
            .all(|(x, y)| x.to_bits() == y.to_bits()));
        assert!(one
            .iter()
            .zip(&own)
            .all(|(x, y)| x.to_bits() == y.to_bits()));
    }
}
