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
/// values `l` of `sym`, in `scratch` (see [`Scratch::new`]). With a `split`, its two groups of
/// subtrees are solved in parallel.
pub fn solve_in_place(
    sym: &SymbolicSupernodalCholesky<usize>,
    l: &[f64],
    x: &mut [f64],
    split: Option<&Split>,
    scratch: &mut Scratch,
) {
    match split {
        None => {
            let n = x.len();
            forward(
                sym,
                l,
                0..sym.n_supernodes(),
                part(x, 0, &mut [], n),
                &mut scratch.tmp,
            );
            backward(
                sym,
                l,
                0..sym.n_supernodes(),
                part_ref(x, 0, &[], n),
                &mut scratch.tmp,
            );
        }
        Some(split) => {
            forward_split(sym, l, x, split, scratch);
            backward_split(sym, l, x, split, scratch);
        }
    }
}

/// Scratch of [`solve_in_place`], kept between solves (no allocation once grown).
#[derive(Default)]
pub struct Scratch {
    /// A supernode's pattern rows (the first group's, with a split).
    tmp: Vec<f64>,
    /// The second group's.
    tmp2: Vec<f64>,
    /// The second group's updates of the top rows (forward solve).
    acc: Vec<f64>,
}

/// Two groups of sibling subtrees of the supernodal elimination tree, for two threads: in the
/// postorder, supernodes `first..mid` and `mid..top` are the subtrees of the children of
/// supernode `top` (split between two children), solved in parallel; the others sequentially.
/// Chosen from the structure alone, so that the arithmetic does not depend on the threads.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Split {
    first: usize,
    mid: usize,
    top: usize,
}

/// Factor values below which a solve stays on one thread: on gridshells' factors the split
/// solve was measured slower below about a million values (docs/performance.md).
const PARALLEL_VALUES: usize = 1_200_000;
/// Least share of the factor's values in the smaller group for a split to pay.
const SMALLER_GROUP: f64 = 0.2;

impl Split {
    /// The split that balances the two groups best, if the factor has `PARALLEL_VALUES` and
    /// one puts at least `SMALLER_GROUP` of them in each (none if the supernodes are not in
    /// postorder).
    pub fn new(sym: &SymbolicSupernodalCholesky<usize>) -> Option<Split> {
        Self::from_values(sym, PARALLEL_VALUES)
    }

    /// [`Self::new`] for factors of at least `least` values.
    pub(super) fn from_values(
        sym: &SymbolicSupernodalCholesky<usize>,
        least: usize,
    ) -> Option<Split> {
        let ns = sym.n_supernodes();
        let vp = sym.col_ptr_for_val();
        let total = vp[ns];
        if total < least {
            return None;
        }
        let parent = supernode_parents(sym);
        // First descendant of each supernode; subtrees must be the ranges first..=s.
        let mut first: Vec<usize> = (0..ns).collect();
        let mut size = vec![1usize; ns];
        for s in 0..ns {
            if let Some(p) = parent[s] {
                if p <= s {
                    return None;
                }
                first[p] = first[p].min(first[s]);
                size[p] += size[s];
            }
        }
        if (0..ns).any(|s| s + 1 - first[s] != size[s]) {
            return None;
        }
        let work = |a: usize, b: usize| vp[b] - vp[a];
        let mut best: Option<(usize, Split)> = None;
        // A split after child c of `top`: the children's subtrees are consecutive ranges.
        for (c, p) in parent.iter().enumerate() {
            let Some(top) = *p else { continue };
            let (f, mid) = (first[top], c + 1);
            if mid == top || f == mid {
                continue;
            }
            let smaller = work(f, mid).min(work(mid, top));
            if best.as_ref().is_none_or(|(w, _)| smaller > *w) {
                best = Some((smaller, Split { first: f, mid, top }));
            }
        }
        best.filter(|(w, _)| *w as f64 >= SMALLER_GROUP * total as f64)
            .map(|(_, s)| s)
    }

    /// First column of the first group, of the second group and of the top.
    fn columns(&self, sym: &SymbolicSupernodalCholesky<usize>) -> [usize; 3] {
        let begin = sym.supernode_begin();
        [begin[self.first], begin[self.mid], begin[self.top]]
    }
}

/// Parent of each supernode in the elimination tree: the supernode of its first pattern row.
fn supernode_parents(sym: &SymbolicSupernodalCholesky<usize>) -> Vec<Option<usize>> {
    let ns = sym.n_supernodes();
    let (begin, end) = (sym.supernode_begin(), sym.supernode_end());
    let mut of_col = vec![0; end.last().copied().unwrap_or(0)];
    for s in 0..ns {
        of_col[begin[s]..end[s]].iter_mut().for_each(|c| *c = s);
    }
    (0..ns)
        .map(|s| sym.supernode(s).pattern().iter().min().map(|&r| of_col[r]))
        .collect()
}

/// The unknowns a range of supernodes writes: its own columns `own` (starting at column `off`)
/// and the rows from `top_off` on, in `top`.
struct Part<'a> {
    own: &'a mut [f64],
    off: usize,
    top: &'a mut [f64],
    top_off: usize,
}

impl Part<'_> {
    fn at(&mut self, r: usize) -> &mut f64 {
        if r < self.top_off {
            &mut self.own[r - self.off]
        } else {
            &mut self.top[r - self.top_off]
        }
    }
}

/// As [`Part`], with the top rows only read (the backward solve).
struct PartRef<'a> {
    own: &'a mut [f64],
    off: usize,
    top: &'a [f64],
    top_off: usize,
}

impl PartRef<'_> {
    fn at(&self, r: usize) -> f64 {
        if r < self.top_off {
            self.own[r - self.off]
        } else {
            self.top[r - self.top_off]
        }
    }
}

/// A group's unknowns: its columns from `off`, the top rows from `top_off` (all of `x`:
/// `part(x, 0, &mut [], n)`).
fn part<'a>(own: &'a mut [f64], off: usize, top: &'a mut [f64], top_off: usize) -> Part<'a> {
    Part {
        own,
        off,
        top,
        top_off,
    }
}

/// [`part`], reading the top rows.
fn part_ref<'a>(own: &'a mut [f64], off: usize, top: &'a [f64], top_off: usize) -> PartRef<'a> {
    PartRef {
        own,
        off,
        top,
        top_off,
    }
}

/// `x` cut after `a` and after `a + b` values.
fn three(x: &mut [f64], a: usize, b: usize) -> (&mut [f64], &mut [f64], &mut [f64]) {
    let (left, rest) = x.split_at_mut(a);
    let (right, top) = rest.split_at_mut(b);
    (left, right, top)
}

/// The forward solve: the supernodes before the groups, the groups in parallel (the second
/// one's updates of the top rows summed apart, then added), then the top.
fn forward_split(
    sym: &SymbolicSupernodalCholesky<usize>,
    l: &[f64],
    x: &mut [f64],
    split: &Split,
    scratch: &mut Scratch,
) {
    let (n, ns) = (x.len(), sym.n_supernodes());
    let [c0, c1, c2] = split.columns(sym);
    forward(
        sym,
        l,
        0..split.first,
        part(x, 0, &mut [], n),
        &mut scratch.tmp,
    );
    let (left, right, top) = three(&mut x[c0..], c1 - c0, c2 - c1);
    let Scratch { tmp, tmp2, acc } = scratch;
    acc.clear();
    acc.resize(top.len(), 0.0);
    rayon::join(
        || forward(sym, l, split.first..split.mid, part(left, c0, top, c2), tmp),
        || forward(sym, l, split.mid..split.top, part(right, c1, acc, c2), tmp2),
    );
    x[c2..]
        .iter_mut()
        .zip(acc.iter())
        .for_each(|(x, a)| *x += a);
    forward(
        sym,
        l,
        split.top..ns,
        part(x, 0, &mut [], n),
        &mut scratch.tmp,
    );
}

/// The backward solve: the top, the groups in parallel (they only read the top), then the
/// supernodes before them.
fn backward_split(
    sym: &SymbolicSupernodalCholesky<usize>,
    l: &[f64],
    x: &mut [f64],
    split: &Split,
    scratch: &mut Scratch,
) {
    let (n, ns) = (x.len(), sym.n_supernodes());
    let [c0, c1, c2] = split.columns(sym);
    backward(
        sym,
        l,
        split.top..ns,
        part_ref(x, 0, &[], n),
        &mut scratch.tmp,
    );
    let (left, right, top) = three(&mut x[c0..], c1 - c0, c2 - c1);
    let (top, tmp, tmp2) = (&*top, &mut scratch.tmp, &mut scratch.tmp2);
    rayon::join(
        || {
            backward(
                sym,
                l,
                split.first..split.mid,
                part_ref(left, c0, top, c2),
                tmp,
            )
        },
        || {
            backward(
                sym,
                l,
                split.mid..split.top,
                part_ref(right, c1, top, c2),
                tmp2,
            )
        },
    );
    backward(
        sym,
        l,
        0..split.first,
        part_ref(x, 0, &[], n),
        &mut scratch.tmp,
    );
}

/// Most pattern rows of one supernode.
fn widest(s: &SymbolicSupernodalCholesky<usize>) -> usize {
    (0..s.n_supernodes())
        .map(|k| s.supernode(k).pattern().len())
        .max()
        .unwrap_or(0)
}

/// Bytes of the [`Scratch`] of a factorization object of `sym`, at most (with a split).
pub fn scratch_bytes(sym: &faer::sparse::linalg::cholesky::SymbolicCholesky<usize>) -> u64 {
    match sym.raw() {
        SymbolicCholeskyRaw::Supernodal(s) => 8 * (2 * widest(s) + sym.nrows()) as u64,
        SymbolicCholeskyRaw::Simplicial(_) => 0,
    }
}

impl Scratch {
    /// Scratch grown once for every solve with `sym` (and `split`).
    pub fn new(
        sym: &faer::sparse::linalg::cholesky::SymbolicCholesky<usize>,
        split: Option<&Split>,
    ) -> Scratch {
        let SymbolicCholeskyRaw::Supernodal(s) = sym.raw() else {
            return Scratch::default();
        };
        let widest = widest(s);
        let top = split.map_or(0, |p| sym.nrows() - s.supernode_begin()[p.top]);
        Scratch {
            tmp: Vec::with_capacity(widest),
            tmp2: Vec::with_capacity(if split.is_some() { widest } else { 0 }),
            acc: Vec::with_capacity(top),
        }
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

/// L y = b over the supernodes `range`: each supernode's columns, then its pattern rows updated
/// once from the sums.
fn forward(
    sym: &SymbolicSupernodalCholesky<usize>,
    l: &[f64],
    range: std::ops::Range<usize>,
    mut x: Part<'_>,
    tmp: &mut Vec<f64>,
) {
    for s in range {
        let b = block(sym, l, s);
        let own = &mut x.own[b.start - x.off..b.start - x.off + b.ncols];
        tmp.clear();
        tmp.resize(b.pattern.len(), 0.0);
        for j in 0..b.ncols {
            let (diag, below) = b.column(j);
            let xj = own[j] / diag[j];
            own[j] = xj;
            for (xi, lij) in own[j + 1..].iter_mut().zip(&diag[j + 1..]) {
                *xi -= lij * xj;
            }
            for (t, lij) in tmp.iter_mut().zip(below) {
                *t += lij * xj;
            }
        }
        for (&r, t) in b.pattern.iter().zip(tmp.iter()) {
            *x.at(r) -= t;
        }
    }
}

/// Lᵀ x = y over the supernodes `range`, in reverse: the pattern's values gathered once per
/// supernode.
fn backward(
    sym: &SymbolicSupernodalCholesky<usize>,
    l: &[f64],
    range: std::ops::Range<usize>,
    x: PartRef<'_>,
    tmp: &mut Vec<f64>,
) {
    for s in range.rev() {
        let b = block(sym, l, s);
        tmp.clear();
        tmp.extend(b.pattern.iter().map(|&r| x.at(r)));
        let own = &mut x.own[b.start - x.off..b.start - x.off + b.ncols];
        for j in (0..b.ncols).rev() {
            let (diag, below) = b.column(j);
            let inside = dot(&diag[j + 1..], &own[j + 1..]);
            let outside = dot(below, tmp);
            own[j] = (own[j] - inside - outside) / diag[j];
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
