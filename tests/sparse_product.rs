//! The symmetric sparse product H·x (`SparseCholesky::multiply_with`, which keeps a column's
//! own sum in a register) sums every entry of y in the order of adding each upper entry to its
//! row and its column in memory: saddle escapes and eigensolvers iterate on it, and a faster
//! product must not change their results.

use rodnet::solver::linalg::SparseCholesky;

/// A pseudo-random value with magnitudes over 16 decades, so that any change in the order of a
/// sum changes its last bits.
fn value(k: usize) -> f64 {
    let h = (k as u64)
        .wrapping_mul(0x9e37_79b9_7f4a_7c15)
        .rotate_left(17);
    let m = (h >> 11) as f64 / (1u64 << 53) as f64 - 0.5;
    m * 10f64.powi((h % 17) as i32 - 8)
}

/// The product as one thread forms it: column by column, each upper entry added to its row,
/// then to its column.
fn reference(n: usize, pairs: &[(usize, usize)], vals: &[f64], x: &[f64]) -> Vec<f64> {
    let mut cols: Vec<Vec<(usize, f64)>> = vec![Vec::new(); n];
    for (&(r, c), &v) in pairs.iter().zip(vals) {
        cols[c].push((r, v));
    }
    let mut y = vec![0.0; n];
    for (c, col) in cols.iter_mut().enumerate() {
        col.sort_by_key(|e| e.0);
        for &(r, v) in col.iter() {
            y[r] += v * x[c];
            if r != c {
                y[c] += v * x[r];
            }
        }
    }
    y
}

/// Coupling of every unknown to those within `band` of it, and of some to a far one (which
/// comes first in its column).
#[test]
fn product_is_the_sum_in_memory_to_the_last_bit() {
    let (n, band): (usize, usize) = (30_000, 3);
    let mut pairs = Vec::new();
    for c in 0..n {
        for r in c.saturating_sub(band)..=c {
            pairs.push((r, c));
        }
        if c % 7 == 0 && c >= 20_000 {
            pairs.push(((c * 31) % 10_000, c));
        }
    }
    let (mut h, slots) = SparseCholesky::new(n, &pairs);
    let vals: Vec<f64> = (0..pairs.len()).map(value).collect();
    for (k, v) in vals.iter().enumerate() {
        h.values[slots[k]] = *v;
    }
    let x: Vec<f64> = (0..n).map(|i| value(7 * i + 3)).collect();
    let want = reference(n, &pairs, &vals, &x);
    let mut y = vec![0.0; n];
    h.multiply(&x, &mut y);
    let differ = (0..n)
        .filter(|&i| y[i].to_bits() != want[i].to_bits())
        .count();
    assert_eq!(differ, 0, "{differ} of {n} entries differ");
}
