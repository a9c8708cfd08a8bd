//! The supernodal solve (`supernodal_solve.rs`) reads faer's factor storage by its layout; here
//! it is checked against faer's own solve of the same factor on random positive definite
//! matrices of several sizes and patterns: supernodes of many widths, the solve on one thread,
//! split over two, and split because the factor is large enough.

use faer::sparse::linalg::cholesky::SymbolicCholeskyRaw;

use super::SparseCholesky;

/// xorshift64*: the tests' matrices, the same at every run.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    /// Uniform in [0, 1).
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
}

/// Nodes at random places in the unit square (`dim` 2) or cube (3), each with 1 to `max_dofs`
/// unknowns coupled to each other and to those of every node within `reach`: a rod network's
/// kind of pattern, with node blocks of several sizes. Returns n and the upper-triangle pairs.
fn random_network(
    rng: &mut Rng,
    nodes: usize,
    dim: usize,
    max_dofs: usize,
    reach: f64,
) -> (usize, Vec<(usize, usize)>) {
    let pts: Vec<[f64; 3]> = (0..nodes)
        .map(|_| {
            let mut p = [0.0; 3];
            p[..dim].iter_mut().for_each(|x| *x = rng.unit());
            p
        })
        .collect();
    let mut first = vec![0];
    for _ in 0..nodes {
        let d = 1 + rng.below(max_dofs);
        first.push(first.last().unwrap() + d);
    }
    let mut pairs = vec![];
    for a in 0..nodes {
        for b in a..nodes {
            let d2: f64 = (0..3).map(|k| (pts[a][k] - pts[b][k]).powi(2)).sum();
            if a != b && d2 > reach * reach {
                continue;
            }
            for i in first[a]..first[a + 1] {
                for j in first[b]..first[b + 1] {
                    if i <= j {
                        pairs.push((i, j));
                    }
                }
            }
        }
    }
    (first[nodes], pairs)
}

/// A w × w grid of nodes with three unknowns each, coupled to their neighbours and diagonal
/// neighbours.
fn grid(w: usize) -> (usize, Vec<(usize, usize)>) {
    let node = |i: usize, j: usize| (i * w + j) * 3;
    let mut pairs = vec![];
    for i in 0..w {
        for j in 0..w {
            for (di, dj) in [(0, 0), (0, 1), (1, 0), (1, 1)] {
                if i + di < w && j + dj < w {
                    for a in 0..3 {
                        for b in 0..3 {
                            let (p, q) = (node(i, j) + a, node(i + di, j + dj) + b);
                            if p <= q || (di, dj) != (0, 0) {
                                pairs.push((p.min(q), p.max(q)));
                            }
                        }
                    }
                }
            }
        }
    }
    (w * w * 3, pairs)
}

/// The factorization of `pairs` with random values, positive definite by diagonal dominance
/// and then scaled by a random diagonal D (D A D: entries over several orders of magnitude).
fn factored(rng: &mut Rng, n: usize, pairs: &[(usize, usize)]) -> SparseCholesky {
    let (mut s, slots) = SparseCholesky::new(n, pairs);
    let mut dominance = vec![1.0; n];
    for (k, &(r, c)) in pairs.iter().enumerate() {
        if r != c {
            let v = 2.0 * rng.unit() - 1.0;
            s.values[slots[k]] += v;
            dominance[r] += v.abs();
            dominance[c] += v.abs();
        }
    }
    for (k, &(r, c)) in pairs.iter().enumerate() {
        if r == c {
            s.values[slots[k]] = dominance[r] * (1.0 + rng.unit());
            dominance[r] = 0.0;
        }
    }
    let scale: Vec<f64> = (0..n).map(|_| 10f64.powf(3.0 * rng.unit())).collect();
    let (cp, ri) = (s.col_ptr().to_vec(), s.row_idx().to_vec());
    for c in 0..n {
        for p in cp[c]..cp[c + 1] {
            s.values[p] *= scale[ri[p]] * scale[c];
        }
    }
    s.use_faer_solve(false);
    s.factor(0.0).expect("positive definite by construction");
    s
}

/// The widths of the factor's supernodes, which must be supernodal.
fn widths(s: &SparseCholesky) -> Vec<usize> {
    let SymbolicCholeskyRaw::Supernodal(sym) = s.symbolic.cholesky().raw() else {
        panic!("a simplicial factor: the supernodal solve is not used");
    };
    let (b, e) = (sym.supernode_begin(), sym.supernode_end());
    (0..sym.n_supernodes()).map(|k| e[k] - b[k]).collect()
}

/// Largest difference between the hand-written solve and faer's, relative to the largest
/// unknown, over three right-hand sides, solved on `threads` threads; the residual of each
/// solution is also checked, against the matrix itself.
fn disagreement(rng: &mut Rng, s: &mut SparseCholesky, threads: usize) -> f64 {
    let n = s.dim();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    let mut worst = 0.0_f64;
    for _ in 0..3 {
        let b: Vec<f64> = (0..n).map(|_| 2.0 * rng.unit() - 1.0).collect();
        let (mut own, mut reference) = (b.clone(), b.clone());
        s.use_faer_solve(false);
        pool.install(|| s.solve(&mut own));
        s.use_faer_solve(true);
        s.solve(&mut reference);
        s.use_faer_solve(false);
        let scale = reference.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
        for (x, y) in own.iter().zip(&reference) {
            worst = worst.max((x - y).abs() / scale);
        }
        let mut ax = vec![0.0; n];
        s.multiply(&own, &mut ax);
        let residual = ax
            .iter()
            .zip(&b)
            .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(residual < 1e-9, "residual {residual:e}");
    }
    worst
}

/// The hand-written solve is faer's to 1e-12 of the solution's size on networks of several
/// sizes, in the plane and in space, with node blocks of one to six unknowns (supernodes of
/// many widths, 1 to over 100 columns), on one thread and split over two.
#[test]
fn supernodal_solve_agrees_with_faers_on_random_networks() {
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let mut splits = 0;
    for (nodes, dim, max_dofs, reach) in [
        (80, 3, 6, 0.5),
        (700, 2, 3, 0.12),
        (300, 3, 6, 0.22),
        (1500, 3, 4, 0.12),
        (2500, 2, 6, 0.04),
    ] {
        let (n, pairs) = random_network(&mut rng, nodes, dim, max_dofs, reach);
        let mut s = factored(&mut rng, n, &pairs);
        let w = widths(&s);
        let mut distinct = w.clone();
        distinct.sort_unstable();
        distinct.dedup();
        assert!(
            distinct.len() >= 4,
            "{nodes} nodes: supernode widths {distinct:?}"
        );
        for split in [false, true] {
            if split && !s.force_split(true) {
                // No two sibling subtrees balanced enough (`supernodal_solve::Split`).
                continue;
            }
            splits += split as usize;
            let d = disagreement(&mut rng, &mut s, 1 + split as usize);
            assert!(d <= 1e-12, "{nodes} nodes, split {split}: {d:e}");
        }
        s.force_split(false);
    }
    assert!(splits >= 2, "{splits} factors split");
}

/// On a factor large enough that a solve splits over two threads on its own
/// (`supernodal_solve::Split::new`), both halves and their joining agree with faer's solve.
#[test]
fn a_factor_split_for_two_threads_agrees_with_faers() {
    let mut rng = Rng(0x2545_f491_4f6c_dd1d);
    let (n, pairs) = grid(100);
    let mut s = factored(&mut rng, n, &pairs);
    assert!(
        s.solves_in_parallel(),
        "{} factor values: too few to split",
        s.factor_nnz()
    );
    let d = disagreement(&mut rng, &mut s, 2);
    assert!(d <= 1e-12, "{d:e}");
}
