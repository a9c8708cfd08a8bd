//! The symbolic analysis of a Hessian pattern (the stored upper triangle, the fill-reducing
//! ordering and faer's symbolic factorization), made once per pattern and shared through an
//! [`super::AnalysisCache`] by the memory estimate, the solve and later solves of the network.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::amd;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, simplicial, SymbolicCholesky, SymbolicCholeskyRaw,
    SymmetricOrdering,
};
use faer::sparse::SymbolicSparseColMat;
use faer::Side;

use super::cache::Key;
use super::cholesky::symbolic_params;
use super::ordering::{choose, Ordering};

/// A pattern's symbolic analysis, shared read-only by every factorization of that pattern.
pub struct Symbolic {
    /// The stored upper triangle: distinct pairs, rows sorted within each column.
    pub(super) pattern: SymbolicSparseColMat<usize>,
    /// Position of each diagonal entry in the pattern.
    pub(super) diag: Vec<usize>,
    /// The same matrix as the numeric factorization reads it (see [`Permuted`]).
    pub(super) permuted: Permuted,
    /// The analysis of the permuted matrix, in the identity order.
    pub(super) cholesky: SymbolicCholesky<usize>,
    /// The ordering chosen.
    pub ordering: Ordering,
    /// The ordering compared with it and not kept, if any (its structure is dropped).
    pub other: Option<Compared>,
    pub(super) key: Key,
}

/// The pattern renumbered to the elimination order and stored on the side faer's numeric
/// factorization works in (upper for simplicial, lower for supernodal factors): each
/// factorization then copies the values through `of_upper` instead of letting faer permute and
/// transpose them into a fresh matrix every time.
pub(super) struct Permuted {
    pub(super) pattern: SymbolicSparseColMat<usize>,
    pub(super) side: Side,
    /// For each entry of the upper-triangle pattern, its position in `pattern`.
    pub(super) of_upper: Vec<usize>,
    /// Position of unknown i's diagonal entry in `pattern`.
    pub(super) diag: Vec<usize>,
    /// `elimination[k]`: the unknown eliminated k-th (row k of the permuted matrix).
    pub(super) elimination: Vec<usize>,
}

/// What the memory estimate needs of the ordering not kept.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Compared {
    pub factor_nnz: usize,
    /// Bytes of what comparing it held (a renumbered pattern with its entries' positions, its
    /// column counts and elimination tree), alive while the two orderings are compared.
    pub structure_bytes: u64,
}

/// Bytes of a symbolic factorization's structure: its row indices (supernodal: and faer's
/// row-major copy of them) and about five words per column.
pub fn structure_bytes(sym: &SymbolicCholesky<usize>) -> u64 {
    let rows = match sym.raw() {
        SymbolicCholeskyRaw::Simplicial(s) => 8 * s.row_idx().len(),
        SymbolicCholeskyRaw::Supernodal(s) => 16 * s.row_idx().len(),
    };
    (rows + 40 * sym.nrows()) as u64
}

impl Symbolic {
    pub fn cholesky(&self) -> &SymbolicCholesky<usize> {
        &self.cholesky
    }

    /// Distinct non-zeros of the stored upper triangle.
    pub fn hessian_nnz(&self) -> usize {
        self.pattern.row_idx().len()
    }

    /// For each pair, its index in the stored upper triangle; `None` if some pair is not in the
    /// pattern or some stored entry is in no pair (the pairs describe another pattern).
    pub fn slots(&self, pairs: &[(usize, usize)]) -> Option<Vec<usize>> {
        let (cp, ri) = (self.pattern.col_ptr(), self.pattern.row_idx());
        let n = self.pattern.ncols();
        let mut hit = vec![false; ri.len()];
        let mut slots = Vec::with_capacity(pairs.len());
        for &(r, c) in pairs {
            if r > c || c >= n {
                return None;
            }
            let k = cp[c] + ri[cp[c]..cp[c + 1]].binary_search(&r).ok()?;
            hit[k] = true;
            slots.push(k);
        }
        hit.iter().all(|&h| h).then_some(slots)
    }
}

/// The analysis with a given elimination order (position k: the unknown eliminated k-th;
/// `None`: AMD), not cached (tests, benchmarks, small auxiliary systems).
pub(super) fn with_order(
    n: usize,
    pairs: &[(usize, usize)],
    elimination: Option<&[usize]>,
) -> Option<Symbolic> {
    let key = Key {
        n,
        pairs: pairs.len(),
        hash: 0,
        ordering: Ordering::Amd,
    };
    let (pattern, diag) = upper_pattern(n, pairs);
    let order = match elimination {
        Some(e) => e.to_vec(),
        None => amd_order(&pattern)?,
    };
    let (permuted, cholesky) = permute(&pattern, &diag, order)?;
    let ordering = match elimination {
        Some(_) => Ordering::NestedDissection,
        None => Ordering::Amd,
    };
    Some(Symbolic {
        pattern,
        diag,
        permuted,
        cholesky,
        ordering,
        other: None,
        key,
    })
}

pub(super) fn analyse_uncached(
    n: usize,
    pairs: &[(usize, usize)],
    ordering: Ordering,
    positions: impl FnOnce() -> Option<Vec<[f64; 3]>>,
    key: Key,
) -> Option<Symbolic> {
    let (pattern, diag) = upper_pattern(n, pairs);
    let (elimination, chosen, other) = choose(
        &pattern,
        ordering,
        positions,
        || amd_order(&pattern),
        |order| factor_size(&pattern, order),
    )?;
    let (permuted, cholesky) = permute(&pattern, &diag, elimination)?;
    // What the comparison held besides the two orders, counted as if resident with the
    // factor: two words per entry (a renumbered pattern is made from lists of that size,
    // freed before the factor exists), its column counts and elimination tree.
    let compared_bytes = 8 * (2 * pattern.row_idx().len() + 4 * n) as u64;
    Some(Symbolic {
        pattern,
        diag,
        permuted,
        cholesky,
        ordering: chosen,
        other: other.map(|factor_nnz| Compared {
            factor_nnz,
            structure_bytes: compared_bytes,
        }),
        key,
    })
}

/// The elimination order AMD gives the upper triangle `pattern`, as faer's own analysis with
/// `SymmetricOrdering::Amd` makes it (same routine and parameters).
fn amd_order(pattern: &SymbolicSparseColMat<usize>) -> Option<Vec<usize>> {
    let n = pattern.ncols();
    let nnz = pattern.row_idx().len();
    let (mut fwd, mut inv) = (vec![0usize; n], vec![0usize; n]);
    let mut mem = MemBuffer::try_new(amd::order_maybe_unsorted_scratch::<usize>(n, nnz)).ok()?;
    amd::order_maybe_unsorted(
        &mut fwd,
        &mut inv,
        pattern.as_ref(),
        symbolic_params().amd_params,
        MemStack::new(&mut mem),
    )
    .ok()?;
    Some(fwd)
}

/// The Cholesky factor of the upper triangle `pattern` eliminated in `order` (position k: the
/// unknown eliminated k-th): its non-zeros and flops (Σ c², c its column counts), from the
/// column counts of its elimination tree; no symbolic structure is made. `None` on index
/// overflow.
fn factor_size(pattern: &SymbolicSparseColMat<usize>, order: &[usize]) -> Option<(usize, f64)> {
    let n = pattern.ncols();
    let upper = renumbered_pattern(pattern, &inverse(order), Side::Upper);
    let mut etree = vec![0isize; n];
    let mut counts = vec![0usize; n];
    let mut mem = MemBuffer::try_new(simplicial::prefactorize_symbolic_cholesky_scratch::<usize>(
        n,
        upper.row_idx().len(),
    ))
    .ok()?;
    simplicial::prefactorize_symbolic_cholesky(
        &mut etree,
        &mut counts,
        upper.as_ref(),
        MemStack::new(&mut mem),
    );
    let flops = counts.iter().map(|&c| (c as f64) * (c as f64)).sum();
    let nnz = counts.iter().try_fold(0usize, |a, &c| a.checked_add(c))?;
    Some((nnz, flops))
}

/// The inverse of a permutation.
fn inverse(order: &[usize]) -> Vec<usize> {
    let mut inv = vec![0; order.len()];
    for (k, &i) in order.iter().enumerate() {
        inv[i] = k;
    }
    inv
}

/// The upper-triangle `pattern` renumbered to the elimination order `elimination` (position
/// k: the unknown eliminated k-th), on the side its kind of factor reads, and the analysis of
/// that matrix in the identity order: the one symbolic analysis of the ordering chosen.
fn permute(
    pattern: &SymbolicSparseColMat<usize>,
    diag: &[usize],
    elimination: Vec<usize>,
) -> Option<(Permuted, SymbolicCholesky<usize>)> {
    let rank = inverse(&elimination);
    // faer analyses a matrix in the identity order from its upper triangle whatever side it is
    // told; the supernodal factorization then reads the lower one.
    let (upper, of_upper) = renumbered(pattern, &rank, Side::Upper);
    let cholesky = factorize_symbolic_cholesky(
        upper.as_ref(),
        Side::Upper,
        SymmetricOrdering::Identity,
        symbolic_params(),
    )
    .ok()?;
    let (permuted, of_upper, side) = match cholesky.raw() {
        SymbolicCholeskyRaw::Simplicial(_) => (upper, of_upper, Side::Upper),
        SymbolicCholeskyRaw::Supernodal(_) => {
            drop((upper, of_upper));
            let (lower, of_upper) = renumbered(pattern, &rank, Side::Lower);
            (lower, of_upper, Side::Lower)
        }
    };
    let diag = diag.iter().map(|&p| of_upper[p]).collect();
    Some((
        Permuted {
            pattern: permuted,
            side,
            of_upper,
            diag,
            elimination,
        },
        cholesky,
    ))
}

/// The upper-triangle `pattern` with unknown i renumbered `rank[i]`, stored as the triangle
/// `side` (rows sorted within each column), and each entry's position in it.
fn renumbered(
    pattern: &SymbolicSparseColMat<usize>,
    rank: &[usize],
    side: Side,
) -> (SymbolicSparseColMat<usize>, Vec<usize>) {
    renumber(pattern, rank, side, true)
}

/// [`renumbered`] without the positions (the factor size of a candidate order).
fn renumbered_pattern(
    pattern: &SymbolicSparseColMat<usize>,
    rank: &[usize],
    side: Side,
) -> SymbolicSparseColMat<usize> {
    renumber(pattern, rank, side, false).0
}

/// [`renumbered`], the positions only if `positions` (else empty). Two counting passes, by
/// row and then by column, leave each column's rows in order without sorting them by keys
/// scattered over the entries; the entries are dealt to their columns from a row-major list
/// of (column, entry) read in order.
fn renumber(
    pattern: &SymbolicSparseColMat<usize>,
    rank: &[usize],
    side: Side,
    positions: bool,
) -> (SymbolicSparseColMat<usize>, Vec<usize>) {
    let n = pattern.ncols();
    let (cp, ri) = (pattern.col_ptr(), pattern.row_idx());
    let nnz = ri.len();
    let mut at = Vec::with_capacity(nnz);
    let mut by_row = vec![0usize; n + 1];
    let mut start = vec![0usize; n + 1];
    for c in 0..n {
        for &r in &ri[cp[c]..cp[c + 1]] {
            let (a, b) = (rank[r], rank[c]);
            let (lo, hi) = (a.min(b), a.max(b));
            let (row, col) = if side == Side::Upper {
                (lo, hi)
            } else {
                (hi, lo)
            };
            at.push((row, col));
            by_row[row + 1] += 1;
            start[col + 1] += 1;
        }
    }
    for c in 0..n {
        by_row[c + 1] += by_row[c];
        start[c + 1] += start[c];
    }
    let mut row_major = vec![(0usize, 0usize); nnz];
    for (k, &(row, col)) in at.iter().enumerate() {
        row_major[by_row[row]] = (col, k);
        by_row[row] += 1;
    }
    drop(at);
    // by_row[r] is now the end of row r.
    let mut fill = start.clone();
    let mut of_upper = vec![0usize; if positions { nnz } else { 0 }];
    let mut rows = vec![0usize; nnz];
    let mut begin = 0;
    for (row, &end) in by_row[..n].iter().enumerate() {
        for &(col, k) in &row_major[begin..end] {
            let p = fill[col];
            fill[col] += 1;
            rows[p] = row;
            if positions {
                of_upper[k] = p;
            }
        }
        begin = end;
    }
    (
        SymbolicSparseColMat::new_checked(n, n, start, None, rows),
        of_upper,
    )
}

/// The stored upper triangle of `pairs` (distinct, rows sorted within each column) and the
/// position of each diagonal entry. Bucketed by column, so that only each column's few rows
/// are sorted.
fn upper_pattern(n: usize, pairs: &[(usize, usize)]) -> (SymbolicSparseColMat<usize>, Vec<usize>) {
    let mut start = vec![0usize; n + 1];
    for &(r, c) in pairs {
        assert!(
            r <= c && c < n,
            "pair ({r}, {c}) outside the upper triangle"
        );
        start[c + 1] += 1;
    }
    for c in 0..n {
        start[c + 1] += start[c];
    }
    let mut rows = vec![0usize; pairs.len()];
    let mut fill = start.clone();
    for &(r, c) in pairs {
        rows[fill[c]] = r;
        fill[c] += 1;
    }
    drop(fill);
    let mut col_ptr = vec![0usize; n + 1];
    let mut len = 0;
    for c in 0..n {
        rows[start[c]..start[c + 1]].sort_unstable();
        let mut last = usize::MAX;
        for k in start[c]..start[c + 1] {
            if rows[k] != last {
                last = rows[k];
                rows[len] = last;
                len += 1;
            }
        }
        col_ptr[c + 1] = len;
    }
    rows.truncate(len);
    rows.shrink_to_fit();
    let diag: Vec<usize> = (0..n)
        .map(|c| {
            let col = &rows[col_ptr[c]..col_ptr[c + 1]];
            col.last()
                .filter(|&&r| r == c)
                .map(|_| col_ptr[c + 1] - 1)
                .expect("pattern lacks a diagonal entry")
        })
        .collect();
    let pattern = SymbolicSparseColMat::new_checked(n, n, col_ptr, None, rows);
    (pattern, diag)
}

#[cfg(test)]
mod tests {
    use super::super::ordering::{grid_graph, AUTO_FLOPS_RATIO};
    use super::*;

    /// Unknowns, pairs, pattern and a permutation.
    type ScrambledGrid = (
        usize,
        Vec<(usize, usize)>,
        SymbolicSparseColMat<usize>,
        Vec<usize>,
    );

    /// An m × m grid's unknowns, pairs and pattern, and a scrambled permutation of them.
    fn scrambled_grid(m: usize) -> ScrambledGrid {
        let n = m * m;
        let (pairs, _) = grid_graph(m);
        let (pattern, _) = upper_pattern(n, &pairs);
        let order = (0..n).map(|k| (7 * k + 3) % n).collect();
        (n, pairs, pattern, order)
    }

    /// The factor's non-zeros and flops from the elimination tree's column counts, against
    /// elimination by hand (each eliminated unknown joins its remaining neighbours), on a grid
    /// in a scrambled order.
    #[test]
    fn factor_size_counts_the_fill_of_an_elimination() {
        let (n, pairs, pattern, order) = scrambled_grid(6);
        let mut adj = vec![std::collections::BTreeSet::new(); n];
        for &(r, c) in &pairs {
            if r != c {
                adj[r].insert(c);
                adj[c].insert(r);
            }
        }
        let (mut nnz, mut flops, mut gone) = (0, 0.0, vec![false; n]);
        for &v in &order {
            let later: Vec<usize> = adj[v].iter().copied().filter(|&u| !gone[u]).collect();
            for &a in &later {
                for &b in &later {
                    if a != b {
                        adj[a].insert(b);
                    }
                }
            }
            gone[v] = true;
            let c = later.len() + 1;
            nnz += c;
            flops += (c * c) as f64;
        }
        assert_eq!(factor_size(&pattern, &order), Some((nnz, flops)));
    }

    /// The renumbered triangle holds every entry once, at the position it reports, with rows
    /// increasing within each column, on both sides of a scrambled grid.
    #[test]
    fn renumbered_keeps_every_entry_in_sorted_columns() {
        let (n, _, pattern, rank) = scrambled_grid(9);
        let (cp, ri) = (pattern.col_ptr(), pattern.row_idx());
        for side in [Side::Upper, Side::Lower] {
            let (out, of_upper) = renumbered(&pattern, &rank, side);
            let (ocp, ori) = (out.col_ptr(), out.row_idx());
            assert_eq!(ori.len(), ri.len());
            let lean = renumbered_pattern(&pattern, &rank, side);
            assert_eq!((lean.col_ptr(), lean.row_idx()), (ocp, ori));
            for c in 0..n {
                assert!(ori[ocp[c]..ocp[c + 1]].windows(2).all(|w| w[0] < w[1]));
            }
            let mut seen = vec![false; ri.len()];
            for c in 0..n {
                for e in cp[c]..cp[c + 1] {
                    let (a, b) = (rank[ri[e]], rank[c]);
                    let (row, col) = match side {
                        Side::Upper => (a.min(b), a.max(b)),
                        Side::Lower => (a.max(b), a.min(b)),
                    };
                    let p = of_upper[e];
                    assert!(!seen[p]);
                    seen[p] = true;
                    assert_eq!(ori[p], row);
                    assert!(ocp[col] <= p && p < ocp[col + 1]);
                }
            }
        }
    }

    /// `Auto` keeps the dissection only when its flops are under `AUTO_FLOPS_RATIO` of AMD's,
    /// and does not make it when AMD's flops are too few for that (its positions not asked).
    #[test]
    fn auto_keeps_the_dissection_only_for_a_large_saving_in_flops() {
        let m = 150;
        let (pairs, pts) = grid_graph(m);
        let (pattern, _) = upper_pattern(m * m, &pairs);
        let amd = amd_order(&pattern).unwrap();
        let amd_size = factor_size(&pattern, &amd).unwrap();
        let with = |share: f64, amd_flops: f64| {
            let size = |o: &[usize]| {
                let (nnz, _) = factor_size(&pattern, o)?;
                Some(if o == &amd[..] {
                    (nnz, amd_flops)
                } else {
                    (nnz, share * amd_size.1)
                })
            };
            let asked = std::cell::Cell::new(false);
            let positions = || {
                asked.set(true);
                Some(pts.clone())
            };
            let (_, chosen, _) = choose(
                &pattern,
                Ordering::Auto,
                positions,
                || Some(amd.clone()),
                size,
            )
            .unwrap();
            (chosen, asked.get())
        };
        let f = amd_size.1;
        assert_eq!(
            with(0.9 * AUTO_FLOPS_RATIO, f),
            (Ordering::NestedDissection, true)
        );
        assert_eq!(with(1.1 * AUTO_FLOPS_RATIO, f), (Ordering::Amd, true));
        let least = (pattern.row_idx().len() as f64).powi(2) / (m * m) as f64;
        assert_eq!(with(0.0, least / AUTO_FLOPS_RATIO), (Ordering::Amd, false));
    }
}
