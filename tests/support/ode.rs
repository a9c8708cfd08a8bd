//! The one ODE integrator of the references: Gragg–Bulirsch–Stoer (modified midpoint rule and
//! polynomial extrapolation) with fixed macro steps, whose error is far below 1e-12 for the
//! smooth, non-stiff elastica equations.

use super::vector::axpy;

/// Substep counts of the extrapolation tableau. Eight levels of the even sequence give an
/// order-16 method per macro step, so a few dozen macro steps reach round-off.
const GBS_SUBSTEPS: [usize; 8] = [2, 4, 6, 8, 10, 12, 14, 16];

fn modified_midpoint<const N: usize, F>(
    f: &F,
    t: f64,
    y: &[f64; N],
    h_big: f64,
    n: usize,
) -> [f64; N]
where
    F: Fn(f64, &[f64; N]) -> [f64; N],
{
    let h = h_big / n as f64;
    let mut prev = *y;
    let mut cur = axpy(&prev, h, &f(t, y));
    for step in 1..n {
        let next = axpy(&prev, 2.0 * h, &f(t + step as f64 * h, &cur));
        prev = cur;
        cur = next;
    }
    let d = f(t + h_big, &cur);
    std::array::from_fn(|i| 0.5 * (cur[i] + prev[i] + h * d[i]))
}

/// Integrates `y' = f(t, y)` from `t0` to `t1` with `macro_steps` equal Bulirsch–Stoer steps.
/// A fixed step (rather than adaptive control) keeps every result a smooth function of the
/// shooting parameters, which the Newton iterations and finite differences rely on.
pub fn integrate<const N: usize, F>(
    f: &F,
    y0: [f64; N],
    t0: f64,
    t1: f64,
    macro_steps: usize,
) -> [f64; N]
where
    F: Fn(f64, &[f64; N]) -> [f64; N],
{
    let h_big = (t1 - t0) / macro_steps as f64;
    let mut y = y0;
    let mut row: Vec<[f64; N]> = Vec::with_capacity(GBS_SUBSTEPS.len());
    let mut new_row: Vec<[f64; N]> = Vec::with_capacity(GBS_SUBSTEPS.len());
    for step in 0..macro_steps {
        let t = t0 + step as f64 * h_big;
        row.clear();
        for (j, &n) in GBS_SUBSTEPS.iter().enumerate() {
            new_row.clear();
            new_row.push(modified_midpoint(f, t, &y, h_big, n));
            // Aitken–Neville in the variable (H/n)², the midpoint rule's error expansion.
            for k in 1..=j {
                let ratio = n as f64 / GBS_SUBSTEPS[j - k] as f64;
                let denom = ratio * ratio - 1.0;
                let (fine, coarse) = (new_row[k - 1], row[k - 1]);
                new_row.push(std::array::from_fn(|i| {
                    fine[i] + (fine[i] - coarse[i]) / denom
                }));
            }
            std::mem::swap(&mut row, &mut new_row);
        }
        y = row[row.len() - 1];
    }
    y
}
