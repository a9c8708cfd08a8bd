//! The outer function of the fused bend + twist kernels, with its derivatives written out.
//!
//! [`super::bend_twist`] and [`super::frame_bend_twist`] differentiate the frames and their
//! products by automatic differentiation and then need the energy as a function of a handful of
//! scalars: κb's projections on the frames, the reference twist and the edges' angles. That
//! function is a sum of weighted squares of quantities whose derivatives are short closed forms
//! (a 2-D rotation of two projections by an angle, a sum of angles), so its gradient and Hessian
//! are assembled here directly, term by term, instead of by hyper-dual arithmetic in all its
//! variables, which cost more than the frames themselves. The separate terms ([`super::bend`],
//! [`super::twist`]) keep the hyper-dual path and serve as the independent check
//! (tests/fused_kernels.rs).

use crate::math::HD;

/// Adds w·f² to `out`, f a function of the variables `idx` with value `f`, gradient `df` and
/// Hessian `ddf` in them: the gradient gains 2w f ∇f and the Hessian 2w (∇f ∇fᵀ + f ∇²f).
/// `idx` holds distinct indices.
#[inline(always)]
fn add_square<const K: usize, const L: usize>(
    out: &mut HD<K>,
    idx: [usize; L],
    f: f64,
    df: [f64; L],
    ddf: [[f64; L]; L],
    w: f64,
) {
    out.v += w * f * f;
    let w2 = 2.0 * w;
    for p in 0..L {
        out.g[idx[p]] += w2 * f * df[p];
        for q in 0..L {
            let (i, j) = (idx[p], idx[q]);
            if i <= j {
                out.h[i][j] += w2 * (df[p] * df[q] + f * ddf[p][q]);
            }
        }
    }
}

/// Adds w [EI1 (κ1 − κ̄1)² + EI2 (κ2 − κ̄2)²] for the material curvature of an edge whose frame
/// is turned by θ' = σθ from its θ = 0 frame: with (a, b) = (κb·u, κb·v) and (s, c) = sin, cos θ',
/// κ1 = c b − s a and κ2 = −(c a + s b). Variables `idx` = (a, b, θ).
#[inline(always)]
pub fn add_rotated_bend<const K: usize>(
    out: &mut HD<K>,
    idx: [usize; 3],
    [a, b, theta]: [f64; 3],
    sign: f64,
    rest: [f64; 2],
    [ei1, ei2]: [f64; 2],
    w: f64,
) {
    let (s, c) = (theta * sign).sin_cos();
    let k1 = c * b - s * a;
    let k2 = -(c * a + s * b);
    // ∂κ1/∂θ = σκ2, ∂κ2/∂θ = −σκ1; second derivatives in θ are −κ (σ² = 1).
    let d1 = [-s, c, sign * k2];
    let dd1 = [
        [0.0, 0.0, -sign * c],
        [0.0, 0.0, -sign * s],
        [-sign * c, -sign * s, -k1],
    ];
    let d2 = [-c, -s, -sign * k1];
    let dd2 = [
        [0.0, 0.0, sign * s],
        [0.0, 0.0, -sign * c],
        [sign * s, -sign * c, -k2],
    ];
    add_square(out, idx, k1 - rest[0], d1, dd1, w * ei1);
    add_square(out, idx, k2 - rest[1], d2, dd2, w * ei2);
}

/// Adds w [EI1 (κ1 − κ̄1)² + EI2 (κ2 − κ̄2)²] for the material curvature (κ1, κ2) = (b, −a) of a
/// frame that does not turn with a variable angle. Variables `idx` = (a, b).
#[inline(always)]
pub fn add_fixed_bend<const K: usize>(
    out: &mut HD<K>,
    idx: [usize; 2],
    [a, b]: [f64; 2],
    rest: [f64; 2],
    [ei1, ei2]: [f64; 2],
    w: f64,
) {
    add_square(out, [idx[1]], b - rest[0], [1.0], [[0.0]], w * ei1);
    add_square(out, [idx[0]], -a - rest[1], [-1.0], [[0.0]], w * ei2);
}

/// Adds w (Σ cᵢ xᵢ − m̄)², the twist energy: the discrete twist is linear in the reference
/// twist and the angles. Variables `idx` with values `x` and coefficients `coef`.
#[inline(always)]
pub fn add_linear_square<const K: usize, const L: usize>(
    out: &mut HD<K>,
    idx: [usize; L],
    x: [f64; L],
    coef: [f64; L],
    rest: f64,
    w: f64,
) {
    let f = (0..L).map(|i| coef[i] * x[i]).sum::<f64>() - rest;
    add_square(out, idx, f, coef, [[0.0; L]; L], w);
}
