//! Operations on the fixed-size state arrays of the shooting methods (`rodnet::math::vec` is
//! for 3-vectors generic over dual numbers; these states have 1 to 6 plain components).

/// `y + a x`, componentwise.
pub fn axpy<const N: usize>(y: &[f64; N], a: f64, x: &[f64; N]) -> [f64; N] {
    std::array::from_fn(|i| y[i] + a * x[i])
}
