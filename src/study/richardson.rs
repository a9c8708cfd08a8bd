//! Richardson extrapolation and observed orders for a sequence of solutions whose edges halve
//! from one level to the next.
//!
//! With an error that behaves like C·hᵖ, the differences between three successive levels
//! shrink by 2ᵖ, so p = log2(d₀₁/d₁₂), and the finest solution plus d₁₂/(2ᵖ − 1) estimates the
//! limit h → 0. The differences are measured in the max norm over all probe points, the same
//! norm in which the errors are then reported.

use crate::math::vec::{norm, sub};

/// Largest distance between corresponding points of `a` and `b`.
pub fn max_distance(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
    assert_eq!(a.len(), b.len(), "probe sets of different sizes");
    a.iter()
        .zip(b)
        .map(|(p, q)| norm(sub(*p, *q)))
        .fold(0.0, f64::max)
}

/// The limit of three successive levels.
#[derive(Debug, Clone, PartialEq)]
pub struct Extrapolation {
    /// Observed order p from the three levels.
    pub order: f64,
    /// Max-norm difference between the coarsest and the middle level, m.
    pub coarse_difference: f64,
    /// Max-norm difference between the middle and the finest level, m.
    pub fine_difference: f64,
    /// The extrapolated probe points, m.
    pub limit: Vec<[f64; 3]>,
}

/// Extrapolates three levels with halving edges. Fails, saying why, when the differences do not
/// shrink (the levels are not in the asymptotic range, or already agree to round-off), since an
/// order estimated from them would be meaningless.
pub fn extrapolate(
    coarse: &[[f64; 3]],
    mid: &[[f64; 3]],
    fine: &[[f64; 3]],
) -> Result<Extrapolation, String> {
    let d01 = max_distance(coarse, mid);
    let d12 = max_distance(mid, fine);
    if !(d01.is_finite() && d12.is_finite()) {
        return Err("the positions are not finite".into());
    }
    if d12 == 0.0 {
        return Err(format!(
            "the two finest levels give identical positions (the coarser pair differs by \
             {d01:.3e} m): no discretization error left to extrapolate"
        ));
    }
    if d01 <= d12 {
        return Err(format!(
            "the differences between successive levels do not shrink ({d01:.3e} m, then \
             {d12:.3e} m): the levels are not in the asymptotic range (or at round-off)"
        ));
    }
    let order = (d01 / d12).log2();
    let gain = 1.0 / (order.exp2() - 1.0);
    let limit = mid
        .iter()
        .zip(fine)
        .map(|(m, f)| std::array::from_fn(|k| f[k] + gain * (f[k] - m[k])))
        .collect();
    Ok(Extrapolation {
        order,
        coarse_difference: d01,
        fine_difference: d12,
        limit,
    })
}

/// Extrapolates a scalar from its two finest values with a known order.
pub fn extrapolate_scalar(mid: f64, fine: f64, order: f64) -> f64 {
    fine + (fine - mid) / (order.exp2() - 1.0)
}

/// Order between two successive levels: log2 of the ratio of their errors.
pub fn order(coarse_error: f64, fine_error: f64) -> Option<f64> {
    (coarse_error > 0.0 && fine_error > 0.0 && coarse_error.is_finite() && fine_error.is_finite())
        .then(|| (coarse_error / fine_error).log2())
}

/// Least-squares slope of −log2(error) against the level over successive levels (edges halving
/// from each to the next): the observed order fitted over them. Needs two positive errors.
pub fn fitted_order(errors: &[f64]) -> Option<f64> {
    if errors.len() < 2 || errors.iter().any(|e| !(e.is_finite() && *e > 0.0)) {
        return None;
    }
    let n = errors.len() as f64;
    let xm = (n - 1.0) / 2.0;
    let ys: Vec<f64> = errors.iter().map(|e| -e.log2()).collect();
    let ym = ys.iter().sum::<f64>() / n;
    let (mut sxy, mut sxx) = (0.0, 0.0);
    for (i, y) in ys.iter().enumerate() {
        let dx = i as f64 - xm;
        sxy += dx * (y - ym);
        sxx += dx * dx;
    }
    Some(sxy / sxx)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Points x(h) = x* + a h² + b h³ with h = 1/N: a smooth second-order discretization.
    fn level(n: f64) -> Vec<[f64; 3]> {
        let h = 1.0 / n;
        vec![
            [1.0 + 0.3 * h * h + 0.2 * h.powi(3), -2.0 - 0.1 * h * h, 0.5],
            [0.2 - 0.7 * h * h, 0.4 + 0.05 * h.powi(3), 3.0 + 0.4 * h * h],
        ]
    }

    #[test]
    fn recovers_the_order_and_the_limit_of_a_smooth_sequence() {
        let x = extrapolate(&level(40.0), &level(80.0), &level(160.0)).unwrap();
        assert!((x.order - 2.0).abs() < 0.02, "p = {}", x.order);
        let exact = level(f64::INFINITY);
        let before = max_distance(&level(160.0), &exact);
        let after = max_distance(&x.limit, &exact);
        // The h² term is gone; what is left is of order h³, far below the finest error.
        assert!(after < 0.01 * before, "{after:e} vs {before:e}");
    }

    #[test]
    fn refuses_differences_that_do_not_shrink() {
        let a = level(10.0);
        assert!(extrapolate(&a, &a, &a).unwrap_err().contains("identical"));
        let e = extrapolate(&level(80.0), &level(40.0), &level(20.0)).unwrap_err();
        assert!(e.contains("do not shrink"), "{e}");
    }

    #[test]
    fn orders_from_error_ratios() {
        assert_eq!(order(4e-3, 1e-3), Some(2.0));
        assert_eq!(order(0.0, 1e-3), None);
        let e: Vec<f64> = (0..4).map(|k| 3.0 * 8f64.powi(-k)).collect();
        assert!((fitted_order(&e).unwrap() - 3.0).abs() < 1e-12);
        // The fit averages a noisy sequence: orders 2.2 and 1.8 fit to 2.
        assert!(
            (fitted_order(&[1.0, 2f64.powf(-2.2), 2f64.powf(-4.0)]).unwrap() - 2.0).abs() < 1e-12
        );
        assert_eq!(fitted_order(&[1.0]), None);
        assert_eq!(extrapolate_scalar(1.0, 0.25, 2.0), 0.0);
    }
}
