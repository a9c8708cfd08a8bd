//! Fill-reducing orderings for the sparse Cholesky factorization.
//!
//! faer offers AMD (and custom permutations). On the 2-D meshes that rod networks and gridshells
//! form, AMD can leave much more fill than nested dissection (docs/performance.md), and faer has
//! no METIS.
//! rodnet knows where each unknown sits in space, so it dissects geometrically: split the
//! unknowns at the median of their longest bounding-box axis, take as separator the unknowns of
//! the smaller boundary (those with a neighbour on the other side), order both halves
//! recursively and the separator last.

use std::sync::atomic::Ordering::Relaxed;
use std::sync::atomic::{AtomicU32, AtomicU8};

use faer::sparse::SymbolicSparseColMat;

/// Below this many unknowns a part is not split further.
const LEAF: usize = 64;

/// Which ordering the factorization uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Ordering {
    /// AMD, or from [`AUTO_MIN_UNKNOWNS`] unknowns the nested dissection when its factorization
    /// takes less than [`AUTO_FLOPS_RATIO`] of AMD's flops.
    #[default]
    Auto,
    Amd,
    NestedDissection,
}

/// Below this many unknowns `Auto` is AMD without trying the dissection (its symbolic analysis
/// would cost more than it could save).
pub const AUTO_MIN_UNKNOWNS: usize = 20_000;

/// The dissection pays only when it saves much work: rods between crossings are chains, which
/// AMD orders well, and AMD's factor, with fewer non-zeros in larger supernodes, factors faster
/// than a dissection with half its flops. On gridshells the dissection was measured faster
/// from 0.20 of AMD's flops down and slower from 0.52 up (docs/performance.md).
pub const AUTO_FLOPS_RATIO: f64 = 0.3;

/// Geometric nested dissection of the graph of `pairs` (upper-triangle (row, column) entries,
/// duplicates and the diagonal allowed) over unknowns placed at `points`. Returns the
/// elimination order: position k holds the unknown eliminated k-th.
pub fn nested_dissection(n: usize, pairs: &[(usize, usize)], points: &[[f64; 3]]) -> Vec<usize> {
    dissection(n, || pairs.iter().copied(), points)
}

/// [`nested_dissection`] of a stored upper triangle: its distinct pairs give the same order as
/// the problem's pairs with their duplicates, from a third of the adjacency.
fn dissection_of_pattern(pattern: &SymbolicSparseColMat<usize>, points: &[[f64; 3]]) -> Vec<usize> {
    let (cp, ri) = (pattern.col_ptr(), pattern.row_idx());
    let pairs = || {
        (0..pattern.ncols()).flat_map(move |c| ri[cp[c]..cp[c + 1]].iter().map(move |&r| (r, c)))
    };
    dissection(pattern.ncols(), pairs, points)
}

fn dissection<I: Iterator<Item = (usize, usize)>>(
    n: usize,
    pairs: impl Fn() -> I,
    points: &[[f64; 3]],
) -> Vec<usize> {
    assert_eq!(points.len(), n);
    let mut start = vec![0usize; n + 1];
    for (r, c) in pairs() {
        if r != c {
            start[r + 1] += 1;
            start[c + 1] += 1;
        }
    }
    for i in 0..n {
        start[i + 1] += start[i];
    }
    let mut fill = start.clone();
    let mut adj = vec![0usize; start[n]];
    for (r, c) in pairs() {
        if r != c {
            adj[fill[r]] = c;
            fill[r] += 1;
            adj[fill[c]] = r;
            fill[c] += 1;
        }
    }
    let d = Dissection {
        points,
        start,
        adj,
        side: (0..n).map(|_| AtomicU8::new(0)).collect(),
        stamp: (0..n).map(|_| AtomicU32::new(0)).collect(),
        calls: AtomicU32::new(0),
    };
    let mut order = vec![0; n];
    d.dissect((0..n).collect(), &mut order);
    order
}

/// Parts at least this large are dissected beside their sibling (`rayon::join`).
const PARALLEL_PART: usize = 4096;

struct Dissection<'a> {
    points: &'a [[f64; 3]],
    start: Vec<usize>,
    adj: Vec<usize>,
    /// 1 or 2: the half of the current split an unknown is in (valid where `stamp` matches).
    /// Sibling parts run in parallel on disjoint unknowns; a part reads the marks of the other's
    /// unknowns only across its boundary, and those never carry its own split's stamp, so
    /// relaxed atomics suffice and the order does not depend on the timing.
    side: Vec<AtomicU8>,
    stamp: Vec<AtomicU32>,
    calls: AtomicU32,
}

impl Dissection<'_> {
    /// Orders the unknowns `ids` into `out` (of the same length): each half, then the
    /// separator.
    fn dissect(&self, mut ids: Vec<usize>, out: &mut [usize]) {
        if ids.len() <= LEAF {
            out.copy_from_slice(&ids);
            return;
        }
        let axis = self.longest_axis(&ids);
        let mid = ids.len() / 2;
        let pts = self.points;
        // Ties along the axis (a rod lying across it: all its unknowns at one coordinate) are
        // split by the other axes, so that each side stays contiguous; an arbitrary split of
        // equal coordinates would put a whole rod on the boundary (a dense separator).
        let key = |i: usize| {
            let p = pts[i];
            [p[axis], p[(axis + 1) % 3], p[(axis + 2) % 3]]
        };
        ids.select_nth_unstable_by(mid, |&a, &b| {
            let (ka, kb) = (key(a), key(b));
            ka[0]
                .total_cmp(&kb[0])
                .then(ka[1].total_cmp(&kb[1]))
                .then(ka[2].total_cmp(&kb[2]))
                .then(a.cmp(&b))
        });
        let call = self.calls.fetch_add(1, Relaxed) + 1;
        for (k, &i) in ids.iter().enumerate() {
            self.stamp[i].store(call, Relaxed);
            self.side[i].store(if k < mid { 1 } else { 2 }, Relaxed);
        }
        // Each side's boundary: its unknowns coupled to the other side.
        let on_boundary = |i: usize| {
            let own = self.side[i].load(Relaxed);
            self.adj[self.start[i]..self.start[i + 1]]
                .iter()
                .any(|&j| self.stamp[j].load(Relaxed) == call && self.side[j].load(Relaxed) != own)
        };
        let (mut left, mut right, mut sep_l, mut sep_r) = (vec![], vec![], vec![], vec![]);
        for (k, &i) in ids.iter().enumerate() {
            match (k < mid, on_boundary(i)) {
                (true, true) => sep_l.push(i),
                (true, false) => left.push(i),
                (false, true) => sep_r.push(i),
                (false, false) => right.push(i),
            }
        }
        let separator = if sep_l.len() <= sep_r.len() {
            right.extend(sep_r);
            sep_l
        } else {
            left.extend(sep_l);
            sep_r
        };
        if left.is_empty() || right.is_empty() {
            // No progress (a clique or coincident points): stop splitting.
            let (a, rest) = out.split_at_mut(left.len());
            let (b, c) = rest.split_at_mut(right.len());
            a.copy_from_slice(&left);
            b.copy_from_slice(&right);
            c.copy_from_slice(&separator);
            return;
        }
        let (l_out, rest) = out.split_at_mut(left.len());
        let (r_out, s_out) = rest.split_at_mut(right.len());
        s_out.copy_from_slice(&separator);
        if left.len() + right.len() >= PARALLEL_PART {
            rayon::join(|| self.dissect(left, l_out), || self.dissect(right, r_out));
        } else {
            self.dissect(left, l_out);
            self.dissect(right, r_out);
        }
    }

    fn longest_axis(&self, ids: &[usize]) -> usize {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for &i in ids {
            for a in 0..3 {
                lo[a] = lo[a].min(self.points[i][a]);
                hi[a] = hi[a].max(self.points[i][a]);
            }
        }
        (0..3)
            .max_by(|&a, &b| (hi[a] - lo[a]).total_cmp(&(hi[b] - lo[b])))
            .unwrap()
    }
}

/// The elimination order of the upper triangle `pattern` that `ordering` asks for: AMD below
/// the size where the dissection is tried (or without `positions`), else the dissection, kept
/// under `Auto` only if its factorization takes under [`AUTO_FLOPS_RATIO`] of AMD's flops.
/// `amd` makes AMD's order; `size` gives an order's factor non-zeros and flops (column counts,
/// no symbolic structure). The dissection is not made at all when AMD's flops are too few for
/// any ordering to go that far below them: a factor with ν non-zeros in n columns takes at
/// least ν²/n flops, and ν is at least the pattern's. Returns the order, the ordering it is,
/// and the factor non-zeros of the one compared and not kept, if any.
pub(super) fn choose(
    pattern: &SymbolicSparseColMat<usize>,
    ordering: Ordering,
    positions: impl FnOnce() -> Option<Vec<[f64; 3]>>,
    amd: impl Fn() -> Option<Vec<usize>>,
    size: impl Fn(&[usize]) -> Option<(usize, f64)>,
) -> Option<(Vec<usize>, Ordering, Option<usize>)> {
    let n = pattern.ncols();
    let try_nd = match ordering {
        Ordering::Amd => false,
        Ordering::NestedDissection => true,
        Ordering::Auto => n >= AUTO_MIN_UNKNOWNS,
    };
    if !try_nd {
        return Some((amd()?, Ordering::Amd, None));
    }
    let amd_order = match ordering {
        Ordering::NestedDissection => None,
        _ => {
            let order = amd()?;
            let s = size(&order)?;
            Some((order, s))
        }
    };
    let least_flops = (pattern.row_idx().len() as f64).powi(2) / n.max(1) as f64;
    let nd_cannot_win = amd_order
        .as_ref()
        .is_some_and(|(_, (_, flops))| AUTO_FLOPS_RATIO * flops <= least_flops);
    let pts = (!nd_cannot_win).then(positions).flatten();
    let Some(pts) = pts else {
        return Some(match amd_order {
            Some((order, _)) => (order, Ordering::Amd, None),
            None => (amd()?, Ordering::Amd, None),
        });
    };
    let nd = dissection_of_pattern(pattern, &pts);
    drop(pts);
    let Some((amd_order, (amd_nnz, amd_flops))) = amd_order else {
        return Some((nd, Ordering::NestedDissection, None));
    };
    let (nd_nnz, nd_flops) = size(&nd)?;
    Some(if nd_flops < AUTO_FLOPS_RATIO * amd_flops {
        (nd, Ordering::NestedDissection, Some(amd_nnz))
    } else {
        (amd_order, Ordering::Amd, Some(nd_nnz))
    })
}

/// The graph of an m × m grid Laplacian (upper-triangle pairs with the diagonal) and its
/// points: the test case of the orderings and of their cost estimate.
#[cfg(test)]
pub(crate) fn grid_graph(m: usize) -> (Vec<(usize, usize)>, Vec<[f64; 3]>) {
    let (mut pairs, mut pts) = (vec![], vec![]);
    for i in 0..m {
        for j in 0..m {
            let k = i * m + j;
            pts.push([i as f64, j as f64, 0.0]);
            pairs.push((k, k));
            if i + 1 < m {
                pairs.push((k, k + m));
            }
            if j + 1 < m {
                pairs.push((k, k + 1));
            }
        }
    }
    (pairs, pts)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Sibling parts are dissected in parallel: the order is the same on one and on two
    /// threads (a grid large enough for parallel parts).
    #[test]
    fn dissection_does_not_depend_on_the_thread_count() {
        let m = 100;
        let (pairs, pts) = grid_graph(m);
        let on = |threads: usize| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| nested_dissection(m * m, &pairs, &pts))
        };
        assert!(m * m >= 2 * PARALLEL_PART);
        assert_eq!(on(1), on(2));
    }

    /// A 2-D grid Laplacian: the order is a permutation, and each separator splits the grid
    /// (no unknown ordered before the separator of its part is coupled across it).
    #[test]
    fn dissection_of_a_grid_is_a_permutation_with_small_fill() {
        let m = 40;
        let n = m * m;
        let (pairs, pts) = grid_graph(m);
        let order = nested_dissection(n, &pairs, &pts);
        let mut seen = vec![false; n];
        for &k in &order {
            assert!(!seen[k]);
            seen[k] = true;
        }
        assert!(seen.iter().all(|&s| s));
        // The last unknowns eliminated form the top separator: a grid line of about m unknowns.
        let top: Vec<usize> = order[n - m..].to_vec();
        let rows: std::collections::HashSet<usize> = top.iter().map(|k| k / m).collect();
        let cols: std::collections::HashSet<usize> = top.iter().map(|k| k % m).collect();
        assert!(rows.len() == 1 || cols.len() == 1, "{rows:?} {cols:?}");
    }
}
