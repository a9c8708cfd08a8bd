//! Legendre elliptic integrals through Carlson's symmetric integrals `R_F` and `R_D`
//! (duplication algorithm, B. C. Carlson, "Numerical computation of real or complex elliptic
//! integrals", Numer. Algorithms 10, 1995), which stay accurate where the Legendre forms cancel.

use std::f64::consts::PI;

/// Carlson's symmetric elliptic integral of the first kind,
/// `R_F(x, y, z) = ½ ∫₀^∞ dt / √((t+x)(t+y)(t+z))`.
///
/// # Panics
/// If an argument is negative or more than one is zero.
#[must_use]
pub fn carlson_rf(x: f64, y: f64, z: f64) -> f64 {
    assert!(
        x >= 0.0 && y >= 0.0 && z >= 0.0,
        "carlson_rf: negative argument"
    );
    assert!(
        (x == 0.0) as u8 + (y == 0.0) as u8 + (z == 0.0) as u8 <= 1,
        "carlson_rf: more than one zero argument"
    );
    let (mut x, mut y, mut z) = (x, y, z);
    loop {
        let a = (x + y + z) / 3.0;
        let (dx, dy) = (1.0 - x / a, 1.0 - y / a);
        let dz = -(dx + dy);
        // The neglected terms of the Taylor series are O(r^6); r < 1e-3 keeps them < 1e-18.
        if dx.abs().max(dy.abs()).max(dz.abs()) < 1e-3 {
            let e2 = dx * dy - dz * dz;
            let e3 = dx * dy * dz;
            return (1.0 - e2 / 10.0 + e3 / 14.0 + e2 * e2 / 24.0 - 3.0 * e2 * e3 / 44.0)
                / a.sqrt();
        }
        let (sx, sy, sz) = (x.sqrt(), y.sqrt(), z.sqrt());
        let lambda = sx * sy + sy * sz + sz * sx;
        x = 0.25 * (x + lambda);
        y = 0.25 * (y + lambda);
        z = 0.25 * (z + lambda);
    }
}

/// Carlson's symmetric elliptic integral of the second kind,
/// `R_D(x, y, z) = 3/2 ∫₀^∞ dt / ((t+z) √((t+x)(t+y)(t+z)))`.
///
/// # Panics
/// If an argument is negative, `z` is zero, or both `x` and `y` are zero.
#[must_use]
pub fn carlson_rd(x: f64, y: f64, z: f64) -> f64 {
    assert!(
        x >= 0.0 && y >= 0.0 && z > 0.0,
        "carlson_rd: invalid argument"
    );
    assert!(x + y > 0.0, "carlson_rd: x and y both zero");
    let (mut x, mut y, mut z) = (x, y, z);
    let mut sum = 0.0;
    let mut scale = 1.0;
    loop {
        let a = (x + y + 3.0 * z) / 5.0;
        let (dx, dy) = (1.0 - x / a, 1.0 - y / a);
        let dz = -(dx + dy) / 3.0;
        if dx.abs().max(dy.abs()).max(dz.abs()) < 1e-3 {
            let xy = dx * dy;
            let z2 = dz * dz;
            let e2 = xy - 6.0 * z2;
            let e3 = (3.0 * xy - 8.0 * z2) * dz;
            let e4 = 3.0 * (xy - z2) * z2;
            let e5 = xy * z2 * dz;
            let series = 1.0 - 3.0 * e2 / 14.0 + e3 / 6.0 + 9.0 * e2 * e2 / 88.0
                - 3.0 * e4 / 22.0
                - 9.0 * e2 * e3 / 52.0
                + 3.0 * e5 / 26.0;
            return 3.0 * sum + scale * series / (a * a.sqrt());
        }
        let (sx, sy, sz) = (x.sqrt(), y.sqrt(), z.sqrt());
        let lambda = sx * sy + sy * sz + sz * sx;
        sum += scale / (sz * (z + lambda));
        scale *= 0.25;
        x = 0.25 * (x + lambda);
        y = 0.25 * (y + lambda);
        z = 0.25 * (z + lambda);
    }
}

/// Complete elliptic integral of the first kind `K(m)`, parameter `m = k²`.
///
/// # Panics
/// If `m ≥ 1` (`K` diverges at `m = 1`).
#[must_use]
pub fn elliptic_k(m: f64) -> f64 {
    assert!(m < 1.0, "elliptic_k: parameter must be < 1");
    carlson_rf(0.0, 1.0 - m, 1.0)
}

/// Complete elliptic integral of the second kind `E(m)`, parameter `m = k²`.
///
/// # Panics
/// If `m > 1`.
#[must_use]
pub fn elliptic_e(m: f64) -> f64 {
    assert!(m <= 1.0, "elliptic_e: parameter must be <= 1");
    if m == 1.0 {
        return 1.0;
    }
    let y = 1.0 - m;
    carlson_rf(0.0, y, 1.0) - m / 3.0 * carlson_rd(0.0, y, 1.0)
}

/// Splits `phi` into `phi_r + j π` with `|phi_r| ≤ π/2`, because the Carlson forms below are
/// valid on one half-period only and the Legendre integrals grow by `2K` per period.
fn reduce_amplitude(phi: f64) -> (f64, f64) {
    let j = (phi / PI).round();
    (phi - j * PI, j)
}

/// Incomplete elliptic integral of the first kind `F(φ | m) = ∫₀^φ dθ / √(1 − m sin²θ)`.
#[must_use]
pub fn elliptic_f(phi: f64, m: f64) -> f64 {
    let (p, j) = reduce_amplitude(phi);
    let (s, c) = p.sin_cos();
    let part = s * carlson_rf(c * c, 1.0 - m * s * s, 1.0);
    if j == 0.0 {
        part
    } else {
        part + 2.0 * j * elliptic_k(m)
    }
}

/// Incomplete elliptic integral of the second kind `E(φ | m) = ∫₀^φ √(1 − m sin²θ) dθ`.
#[must_use]
pub fn elliptic_e_incomplete(phi: f64, m: f64) -> f64 {
    let (p, j) = reduce_amplitude(phi);
    let (s, c) = p.sin_cos();
    let (x, y) = (c * c, 1.0 - m * s * s);
    let part = s * carlson_rf(x, y, 1.0) - m / 3.0 * s * s * s * carlson_rd(x, y, 1.0);
    if j == 0.0 {
        part
    } else {
        part + 2.0 * j * elliptic_e(m)
    }
}
