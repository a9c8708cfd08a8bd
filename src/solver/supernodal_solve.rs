//! Triangular solves with faer's supernodal LLᵀ factor, written as plain loops over each
//! supernode's dense block. faer's own solve calls its general dense kernels (a triangular solve
//! and a matrix product) once per supernode; on rod networks supernodes are a few columns
//! wide, and that dispatch costs more than the arithmetic (docs/performance.md).
//!
//! Layout (faer 0.24): supernode s owns the columns `begin[s] .. end[s]`; its values are a
//! column-major block of `ncols + pattern.len()` rows, the lower-triangular diagonal block on
//! top of the rows of its pattern (`supernode(s).pattern()`, outside the supernode).

use faer::sparse::linalg::cholesky::supernodal::SymbolicSupernodalCholesky;
use faer::sparse::linalg::cholesky::SymbolicCholeskyRaw;

/// Solves L Lᵀ x = b in place (`x` holds b, in the elimination order) with the supernodal factor
/// values `l` of `sym`; `tmp` is scratch of any length (grown as needed).
pub fn solve_in_place(
    sym: &SymbolicSupernodalCholesky<usize>,
    l: &[f64],
    x: &mut [f64],
    tmp: &mut Vec<f64>,
) {
    forward(sym, l, x, tmp);
    backward(sym, l, x, tmp);
}

/// The most pattern rows of one supernode: the scratch [`solve_in_place`] needs (0 for a
/// simplicial factor).
pub fn scratch_len(sym: &faer::sparse::linalg::cholesky::SymbolicCholesky<usize>) -> usize {
    match sym.raw() {
        SymbolicCholeskyRaw::Supernodal(s) => (0..s.n_supernodes())
            .map(|k| s.supernode(k).pattern().len())
            .max()
            .unwrap_or(0),
        SymbolicCholeskyRaw::Simplicial(_) => 0,
    }
}

/// One supernode: its first column, width, pattern rows outside it and dense block.
struct Block<'a> {
    start: usize,
    ncols: usize,
    pattern: &'a [usize],
    values: &'a [f64],
}

impl Block<'_> {
    fn rows(&self) -> usize {
        self.ncols + self.pattern.len()
    }

    /// Column j of the block: the diagonal block's rows, then the pattern's.
    fn column(&self, j: usize) -> (&[f64], &[f64]) {
        let col = &self.values[j * self.rows()..(j + 1) * self.rows()];
        col.split_at(self.ncols)
    }
}

fn block<'a>(sym: &'a SymbolicSupernodalCholesky<usize>, l: &'a [f64], s: usize) -> Block<'a> {
    let (start, end) = (sym.supernode_begin()[s], sym.supernode_end()[s]);
    let vp = sym.col_ptr_for_val();
    Block {
        start,
        ncols: end - start,
        pattern: sym.supernode(s).pattern(),
        values: &l[vp[s]..vp[s + 1]],
    }
}

/// L y = b: each supernode's columns, then its pattern rows updated once from the sums.
fn forward(sym: &SymbolicSupernodalCholesky<usize>, l: &[f64], x: &mut [f64], tmp: &mut Vec<f64>) {
    for s in 0..sym.n_supernodes() {
        let b = block(sym, l, s);
        tmp.clear();
        tmp.resize(b.pattern.len(), 0.0);
        for j in 0..b.ncols {
            let (diag, below) = b.column(j);
            let xj = x[b.start + j] / diag[j];
            x[b.start + j] = xj;
            for (xi, lij) in x[b.start + j + 1..b.start + b.ncols]
                .iter_mut()
                .zip(&diag[j + 1..])
            {
                *xi -= lij * xj;
            }
            for (t, lij) in tmp.iter_mut().zip(below) {
                *t += lij * xj;
            }
        }
        for (&r, t) in b.pattern.iter().zip(tmp.iter()) {
            x[r] -= t;
        }
    }
}

/// Lᵀ x = y: supernodes in reverse, the pattern's values gathered once per supernode.
fn backward(sym: &SymbolicSupernodalCholesky<usize>, l: &[f64], x: &mut [f64], tmp: &mut Vec<f64>) {
    for s in (0..sym.n_supernodes()).rev() {
        let b = block(sym, l, s);
        tmp.clear();
        tmp.extend(b.pattern.iter().map(|&r| x[r]));
        for j in (0..b.ncols).rev() {
            let (diag, below) = b.column(j);
            let inside = dot(&diag[j + 1..], &x[b.start + j + 1..b.start + b.ncols]);
            let outside = dot(below, tmp);
            x[b.start + j] = (x[b.start + j] - inside - outside) / diag[j];
        }
    }
}

/// Dot product in four interleaved sums (vectorizable).
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut acc = [0.0; 4];
    let (ca, cb) = (a.chunks_exact(4), b.chunks_exact(4));
    let rest: f64 = ca
        .remainder()
        .iter()
        .zip(cb.remainder())
        .map(|(x, y)| x * y)
        .sum();
    for (x, y) in ca.zip(cb) {
        for k in 0..4 {
            acc[k] += x[k] * y[k];
        }
    }
    (acc[0] + acc[1]) + (acc[2] + acc[3]) + rest
}
