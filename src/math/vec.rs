//! Small 3-vector and rotation helpers, generic over [`Real`] so energies can be written once.

use super::dual::Real;

pub type V3<T> = [T; 3];

#[inline(always)]
pub fn lift<T: Real>(a: [f64; 3]) -> V3<T> {
    [T::cst(a[0]), T::cst(a[1]), T::cst(a[2])]
}
#[inline(always)]
pub fn add<T: Real>(a: V3<T>, b: V3<T>) -> V3<T> {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
#[inline(always)]
pub fn sub<T: Real>(a: V3<T>, b: V3<T>) -> V3<T> {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
#[inline(always)]
pub fn scale<T: Real>(a: V3<T>, s: T) -> V3<T> {
    [a[0] * s, a[1] * s, a[2] * s]
}
#[inline(always)]
pub fn scalef<T: Real>(a: V3<T>, s: f64) -> V3<T> {
    [a[0] * s, a[1] * s, a[2] * s]
}
#[inline(always)]
pub fn dot<T: Real>(a: V3<T>, b: V3<T>) -> T {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
#[inline(always)]
pub fn cross<T: Real>(a: V3<T>, b: V3<T>) -> V3<T> {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
#[inline(always)]
pub fn norm<T: Real>(a: V3<T>) -> T {
    dot(a, a).sqrt()
}
/// Distance between two points.
#[inline(always)]
pub fn dist(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    norm(sub(*a, *b))
}
#[inline(always)]
pub fn normalize<T: Real>(a: V3<T>) -> V3<T> {
    scale(a, norm(a).recip())
}
/// Plain-f64 values of a generic vector.
#[inline(always)]
pub fn value<T: Real>(a: V3<T>) -> [f64; 3] {
    [a[0].val(), a[1].val(), a[2].val()]
}

/// Rotates `w` by the minimal rotation taking unit vector `a` to unit vector `b`
/// (discrete parallel transport). Undefined only for `b = -a`, which callers avoid by
/// limiting how far a tangent may turn in one Newton step.
#[inline(always)]
pub fn transport<T: Real>(a: V3<T>, b: V3<T>, w: V3<T>) -> V3<T> {
    let c = dot(a, b);
    let k = cross(a, b);
    let kw = dot(k, w);
    let f = (c + 1.0).recip();
    add(add(scale(w, c), cross(k, w)), scale(k, kw * f))
}

/// [`transport`] of a constant vector `w` from a constant unit vector `a`: the same rotation,
/// with the constant operands kept as plain numbers (cheaper under automatic differentiation).
#[inline(always)]
pub fn transport_from<T: Real>(a: [f64; 3], b: V3<T>, w: [f64; 3]) -> V3<T> {
    let c = b[0] * a[0] + b[1] * a[1] + b[2] * a[2];
    // k = a × b
    let k = [
        b[2] * a[1] - b[1] * a[2],
        b[0] * a[2] - b[2] * a[0],
        b[1] * a[0] - b[0] * a[1],
    ];
    let kw = k[0] * w[0] + k[1] * w[1] + k[2] * w[2];
    let f = kw * (c + 1.0).recip();
    // w c + k × w + k (k·w)/(1 + c)
    [
        c * w[0] + k[1] * w[2] - k[2] * w[1] + k[0] * f,
        c * w[1] + k[2] * w[0] - k[0] * w[2] + k[1] * f,
        c * w[2] + k[0] * w[1] - k[1] * w[0] + k[2] * f,
    ]
}

/// Signed angle from `a` to `b` about the unit axis `n` (both perpendicular to `n`).
#[inline(always)]
pub fn signed_angle<T: Real>(a: V3<T>, b: V3<T>, n: V3<T>) -> T {
    dot(cross(a, b), n).atan2(dot(a, b))
}

/// Rodrigues coefficients A = sin t / t and B = (1 − cos t)/t² as functions of t² = |ω|²,
/// smooth at ω = 0 so that derivatives at zero rotation are exact.
fn rodrigues_coeffs<T: Real>(t2: T) -> (T, T) {
    if t2.val() < 0.1 {
        // Taylor series to t^12: truncation error below 1e-19 for t² < 0.1.
        let a = [
            1.0,
            -1.0 / 6.0,
            1.0 / 120.0,
            -1.0 / 5040.0,
            1.0 / 362880.0,
            -1.0 / 39916800.0,
            1.0 / 6227020800.0,
        ];
        let b = [
            0.5,
            -1.0 / 24.0,
            1.0 / 720.0,
            -1.0 / 40320.0,
            1.0 / 3628800.0,
            -1.0 / 479001600.0,
            1.0 / 87178291200.0,
        ];
        let mut pa = T::cst(a[6]);
        let mut pb = T::cst(b[6]);
        for k in (0..6).rev() {
            pa = pa * t2 + a[k];
            pb = pb * t2 + b[k];
        }
        (pa, pb)
    } else {
        let t = t2.sqrt();
        (t.sin() / t, (-(t.cos()) + 1.0) / t2)
    }
}

/// Rotates `v` by exp(ω̂) (rotation vector ω, spatial).
pub fn rotate<T: Real>(w: V3<T>, v: V3<T>) -> V3<T> {
    let [r] = rotate_each(w, [v]);
    r
}

/// [`rotate`] of several vectors by the same ω (the coefficients are computed once).
pub fn rotate_each<T: Real, const K: usize>(w: V3<T>, vs: [V3<T>; K]) -> [V3<T>; K] {
    let t2 = dot(w, w);
    if t2.val() == 0.0 {
        // At ω = 0 (every committed iterate: increments are folded into the frames) A − 1 and
        // B − ½ are O(|ω|²) and multiply terms of order ≥ 1 in ω, so with A = 1, B = ½ the
        // result differs at third order only: value, gradient and Hessian are exact.
        return vs.map(|v| {
            let wv = cross(w, v);
            add(add(v, wv), scalef(cross(w, wv), 0.5))
        });
    }
    let (a, b) = rodrigues_coeffs(t2);
    vs.map(|v| {
        let wv = cross(w, v);
        let wwv = cross(w, wv);
        add(add(v, scale(wv, a)), scale(wwv, b))
    })
}

/// Rotation about unit axis `n` by angle `alpha` applied to `v`.
pub fn rotate_axis<T: Real>(n: V3<T>, alpha: T, v: V3<T>) -> V3<T> {
    let (s, c) = (alpha.sin(), alpha.cos());
    let nv = cross(n, v);
    let nnv = cross(n, nv);
    add(add(v, scale(nv, s)), scale(nnv, -c + 1.0))
}

/// 3×3 rotation matrices stored as columns (d1, d2, d3).
pub type Frame = [[f64; 3]; 3];

pub fn frame_rotate(w: [f64; 3], f: &Frame) -> Frame {
    [rotate(w, f[0]), rotate(w, f[1]), rotate(w, f[2])]
}

/// Re-orthonormalizes a frame (Gram–Schmidt, keeping d3 first) so that accumulated round-off in
/// repeated rotations cannot drift.
pub fn frame_orthonormalize(f: &Frame) -> Frame {
    let d3 = normalize(f[2]);
    let d1 = normalize(sub(f[0], scalef(d3, dot(f[0], d3))));
    let d2 = cross(d3, d1);
    [d1, d2, d3]
}

/// Some unit vector perpendicular to unit `t`, chosen deterministically.
pub fn any_perpendicular(t: [f64; 3]) -> [f64; 3] {
    let trial = if t[2].abs() < 0.9 {
        [0.0, 0.0, 1.0]
    } else {
        [1.0, 0.0, 0.0]
    };
    normalize(cross(cross(t, trial), t))
}

/// Rotation vector of the smallest rotation taking the unit vector `a` to the unit vector `b`.
pub fn rotation_between(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    let axis = cross(a, b);
    let s = norm(axis);
    if s == 0.0 {
        return [0.0; 3];
    }
    scalef(axis, s.atan2(dot(a, b)) / s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rotation_series_and_closed_form_agree() {
        let v = [0.3, -0.2, 0.9];
        for s in [0.3160, 0.3163] {
            let w = scalef(normalize([1.0, 2.0, -0.5]), s);
            let r = rotate(w, v);
            let r2 = rotate_axis(normalize(w), s, v);
            for k in 0..3 {
                assert!((r[k] - r2[k]).abs() < 1e-15);
            }
        }
    }

    #[test]
    fn transport_maps_a_to_b() {
        let a = normalize([1.0, 0.2, 0.1]);
        let b = normalize([-0.3, 1.0, 0.4]);
        let t = transport(a, b, a);
        for k in 0..3 {
            assert!((t[k] - b[k]).abs() < 1e-14);
        }
        let u = any_perpendicular(a);
        assert!(dot(transport(a, b, u), b).abs() < 1e-14);
    }
}
