//! Second-order forward-mode automatic differentiation.
//!
//! Every energy term in rodnet is written once, generic over [`Real`], and evaluated either with
//! plain `f64` (line searches) or with [`HD<N>`] (value, gradient and Hessian in the term's `N`
//! local variables). The Hessians are therefore exact to round-off for the closed-form discrete
//! energies, including the parallel-transport and reference-twist terms that hand-derived DER
//! Hessians often drop.

use std::ops::{Add, AddAssign, Div, Mul, Neg, Sub};

/// Scalar arithmetic shared by `f64` and hyper-dual numbers.
pub trait Real:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + Add<f64, Output = Self>
    + Sub<f64, Output = Self>
    + Mul<f64, Output = Self>
    + Div<f64, Output = Self>
    + AddAssign
{
    fn cst(v: f64) -> Self;
    fn val(&self) -> f64;
    fn sqrt(self) -> Self;
    fn sin(self) -> Self;
    fn cos(self) -> Self;
    fn recip(self) -> Self;
    /// `atan2(self, x)`.
    fn atan2(self, x: Self) -> Self;
    fn sqr(self) -> Self {
        self * self
    }
    /// Σₖ sₖ aₖ bₖ: a hyper-dual sum of products in one pass, without temporaries.
    #[inline(always)]
    fn dot3(a: [Self; 3], b: [Self; 3], s: [f64; 3]) -> Self {
        a[0] * b[0] * s[0] + a[1] * b[1] * s[1] + a[2] * b[2] * s[2]
    }
}

impl Real for f64 {
    #[inline]
    fn cst(v: f64) -> Self {
        v
    }
    #[inline]
    fn val(&self) -> f64 {
        *self
    }
    #[inline]
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
    #[inline]
    fn sin(self) -> Self {
        f64::sin(self)
    }
    #[inline]
    fn cos(self) -> Self {
        f64::cos(self)
    }
    #[inline]
    fn recip(self) -> Self {
        1.0 / self
    }
    #[inline]
    fn atan2(self, x: Self) -> Self {
        f64::atan2(self, x)
    }
}

/// Hyper-dual number: value, gradient and Hessian in `N` variables.
/// Only the upper triangle (`j >= i`) of `h` is maintained; [`HD::hessian`] mirrors it.
#[derive(Clone, Copy, Debug)]
pub struct HD<const N: usize> {
    pub v: f64,
    pub g: [f64; N],
    pub h: [[f64; N]; N],
}

impl<const N: usize> HD<N> {
    /// The `i`-th independent variable with value `v`.
    pub fn var(v: f64, i: usize) -> Self {
        let mut r = Self::cst(v);
        r.g[i] = 1.0;
        r
    }

    /// Seeds `N` independent variables from their values.
    pub fn vars(vals: &[f64; N]) -> [Self; N] {
        std::array::from_fn(|i| Self::var(vals[i], i))
    }

    /// Full symmetric Hessian.
    pub fn hessian(&self) -> [[f64; N]; N] {
        let mut h = self.h;
        for i in 0..N {
            for j in 0..i {
                h[i][j] = h[j][i];
            }
        }
        h
    }

    /// Applies a scalar function with derivatives `d1 = f'(v)` and `d2 = f''(v)`.
    #[inline(always)]
    fn chain(&self, f: f64, d1: f64, d2: f64) -> Self {
        let mut r = Self::cst(f);
        for i in 0..N {
            r.g[i] = d1 * self.g[i];
        }
        for i in 0..N {
            let gi = d2 * self.g[i];
            for j in i..N {
                r.h[i][j] = d1 * self.h[i][j] + gi * self.g[j];
            }
        }
        r
    }
}

/// Σ aᵢ bᵢ of two 3-vectors that depend on disjoint variables: `a` on the first A of the P
/// variables, `b` on the next B (P = A + B). The Hessian of a product of such functions is
/// block-structured (a's block scaled by b, b's by a, the outer product of the gradients off the
/// diagonal), which costs far less than a general product in all P variables. This is the
/// coupling of two edges' frames in the bending and twisting stencils.
#[inline(always)]
pub fn separable_dot<const A: usize, const B: usize, const P: usize>(
    a: &[HD<A>; 3],
    b: &[HD<B>; 3],
) -> HD<P> {
    debug_assert_eq!(A + B, P);
    let mut r = HD::<P>::cst(0.0);
    for k in 0..3 {
        let (x, y) = (&a[k], &b[k]);
        r.v += x.v * y.v;
        for i in 0..A {
            r.g[i] += x.g[i] * y.v;
            for j in i..A {
                r.h[i][j] += x.h[i][j] * y.v;
            }
            for j in 0..B {
                r.h[i][A + j] += x.g[i] * y.g[j];
            }
        }
        for i in 0..B {
            r.g[A + i] += x.v * y.g[i];
            for j in i..B {
                r.h[A + i][A + j] += x.v * y.h[i][j];
            }
        }
    }
    r
}

/// Exact derivatives of a composition f(a(y), z) by the chain rule.
///
/// `inner` holds M intermediates a as functions of the P variables y; `outer` is f as a function
/// of (a, z), a first (K = M + Q − P variables); the result is in the Q variables (y, z). An
/// energy that depends on many variables only through a few intermediates is thereby
/// differentiated in the small spaces (P and K) instead of all Q variables at once, which is
/// what makes the bending and twisting stencils cheap.
pub fn compose<const P: usize, const M: usize, const K: usize, const Q: usize>(
    inner: &[HD<P>; M],
    outer: &HD<K>,
) -> HD<Q> {
    debug_assert!(P <= Q && K + P == M + Q);
    let z = Q - P;
    let f = outer.hessian();
    let mut r = HD::<Q>::cst(outer.v);
    // w[k][j] = Σ_l ∂²f/∂a_k∂a_l ∂a_l/∂y_j
    let mut w = [[0.0; P]; M];
    for k in 0..M {
        for (l, a) in inner.iter().enumerate() {
            let fkl = f[k][l];
            for j in 0..P {
                w[k][j] += fkl * a.g[j];
            }
        }
    }
    for (k, a) in inner.iter().enumerate() {
        let fk = outer.g[k];
        for i in 0..P {
            r.g[i] += fk * a.g[i];
            let gi = a.g[i];
            for j in i..P {
                r.h[i][j] += fk * a.h[i][j] + gi * w[k][j];
            }
        }
    }
    for m in 0..z {
        r.g[P + m] = outer.g[M + m];
        for (k, a) in inner.iter().enumerate() {
            let fkm = f[k][M + m];
            for i in 0..P {
                r.h[i][P + m] += fkm * a.g[i];
            }
        }
        for n in m..z {
            r.h[P + m][P + n] = f[M + m][M + n];
        }
    }
    r
}

impl<const N: usize> Real for HD<N> {
    #[inline(always)]
    fn cst(v: f64) -> Self {
        HD {
            v,
            g: [0.0; N],
            h: [[0.0; N]; N],
        }
    }
    #[inline(always)]
    fn val(&self) -> f64 {
        self.v
    }
    fn sqrt(self) -> Self {
        let s = self.v.sqrt();
        self.chain(s, 0.5 / s, -0.25 / (s * self.v))
    }
    fn sin(self) -> Self {
        let (s, c) = self.v.sin_cos();
        self.chain(s, c, -s)
    }
    fn cos(self) -> Self {
        let (s, c) = self.v.sin_cos();
        self.chain(c, -s, -c)
    }
    fn recip(self) -> Self {
        let r = 1.0 / self.v;
        self.chain(r, -r * r, 2.0 * r * r * r)
    }
    #[inline(always)]
    fn dot3(a: [Self; 3], b: [Self; 3], s: [f64; 3]) -> Self {
        let sa = [0, 1, 2].map(|k| s[k] * a[k].v);
        let sb = [0, 1, 2].map(|k| s[k] * b[k].v);
        let mut r = Self::cst((0..3).map(|k| sa[k] * b[k].v).sum());
        for i in 0..N {
            r.g[i] = (0..3).map(|k| sa[k] * b[k].g[i] + sb[k] * a[k].g[i]).sum();
        }
        for k in 0..3 {
            let (a, b) = (&a[k], &b[k]);
            for i in 0..N {
                let (ag, bg) = (s[k] * a.g[i], s[k] * b.g[i]);
                for j in i..N {
                    r.h[i][j] += sa[k] * b.h[i][j] + sb[k] * a.h[i][j] + ag * b.g[j] + bg * a.g[j];
                }
            }
        }
        r
    }
    fn atan2(self, x: Self) -> Self {
        // With y = self: ∇θ = N/r², N = x∇y − y∇x, and
        // ∇²θ = (x∇²y − y∇²x)/r² − (N⊗w + w⊗N)/r⁴ with w = x∇x + y∇y.
        let y = self;
        // Products with 1/r² and 1/r⁴, not divisions: the compiler may not rewrite them.
        let inv2 = 1.0 / (x.v * x.v + y.v * y.v);
        let inv4 = inv2 * inv2;
        let (xs, ys) = (x.v * inv2, y.v * inv2);
        let mut r = Self::cst(y.v.atan2(x.v));
        let mut n = [0.0; N];
        let mut w = [0.0; N];
        for i in 0..N {
            n[i] = x.v * y.g[i] - y.v * x.g[i];
            w[i] = (x.v * x.g[i] + y.v * y.g[i]) * inv4;
            r.g[i] = n[i] * inv2;
        }
        for i in 0..N {
            for j in i..N {
                r.h[i][j] = xs * y.h[i][j] - ys * x.h[i][j] - (n[i] * w[j] + w[i] * n[j]);
            }
        }
        r
    }
}

impl<const N: usize> Add for HD<N> {
    type Output = Self;
    #[inline(always)]
    fn add(mut self, o: Self) -> Self {
        self.v += o.v;
        for i in 0..N {
            self.g[i] += o.g[i];
            for j in i..N {
                self.h[i][j] += o.h[i][j];
            }
        }
        self
    }
}

impl<const N: usize> AddAssign for HD<N> {
    #[inline(always)]
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}

impl<const N: usize> Sub for HD<N> {
    type Output = Self;
    #[inline(always)]
    fn sub(mut self, o: Self) -> Self {
        self.v -= o.v;
        for i in 0..N {
            self.g[i] -= o.g[i];
            for j in i..N {
                self.h[i][j] -= o.h[i][j];
            }
        }
        self
    }
}

impl<const N: usize> Neg for HD<N> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        self * -1.0
    }
}

impl<const N: usize> Mul for HD<N> {
    type Output = Self;
    #[inline(always)]
    fn mul(self, o: Self) -> Self {
        let mut r = Self::cst(self.v * o.v);
        for i in 0..N {
            r.g[i] = self.v * o.g[i] + o.v * self.g[i];
        }
        for i in 0..N {
            let (a, b) = (self.g[i], o.g[i]);
            for j in i..N {
                r.h[i][j] = self.v * o.h[i][j] + o.v * self.h[i][j] + a * o.g[j] + b * self.g[j];
            }
        }
        r
    }
}

#[allow(clippy::suspicious_arithmetic_impl)] // a / b = a · (1/b)
impl<const N: usize> Div for HD<N> {
    type Output = Self;
    #[inline(always)]
    fn div(self, o: Self) -> Self {
        self * o.recip()
    }
}

impl<const N: usize> Add<f64> for HD<N> {
    type Output = Self;
    #[inline(always)]
    fn add(mut self, o: f64) -> Self {
        self.v += o;
        self
    }
}

impl<const N: usize> Sub<f64> for HD<N> {
    type Output = Self;
    #[inline(always)]
    fn sub(mut self, o: f64) -> Self {
        self.v -= o;
        self
    }
}

impl<const N: usize> Mul<f64> for HD<N> {
    type Output = Self;
    #[inline(always)]
    fn mul(mut self, o: f64) -> Self {
        self.v *= o;
        for i in 0..N {
            self.g[i] *= o;
            for j in i..N {
                self.h[i][j] *= o;
            }
        }
        self
    }
}

impl<const N: usize> Div<f64> for HD<N> {
    type Output = Self;
    #[inline(always)]
    fn div(self, o: f64) -> Self {
        self * (1.0 / o)
    }
}

/// First-order dual number: value and gradient in `N` variables (gradient-only assembly).
#[derive(Clone, Copy, Debug)]
pub struct D1<const N: usize> {
    pub v: f64,
    pub g: [f64; N],
}

impl<const N: usize> D1<N> {
    pub fn vars(vals: &[f64; N]) -> [Self; N] {
        std::array::from_fn(|i| {
            let mut g = [0.0; N];
            g[i] = 1.0;
            D1 { v: vals[i], g }
        })
    }
    #[inline]
    fn chain(&self, f: f64, d1: f64) -> Self {
        let mut r = D1 { v: f, g: self.g };
        r.g.iter_mut().for_each(|x| *x *= d1);
        r
    }
}

impl<const N: usize> Real for D1<N> {
    #[inline]
    fn cst(v: f64) -> Self {
        D1 { v, g: [0.0; N] }
    }
    #[inline]
    fn val(&self) -> f64 {
        self.v
    }
    fn sqrt(self) -> Self {
        let s = self.v.sqrt();
        self.chain(s, 0.5 / s)
    }
    fn sin(self) -> Self {
        let (s, c) = self.v.sin_cos();
        self.chain(s, c)
    }
    fn cos(self) -> Self {
        let (s, c) = self.v.sin_cos();
        self.chain(c, -s)
    }
    fn recip(self) -> Self {
        let r = 1.0 / self.v;
        self.chain(r, -r * r)
    }
    fn atan2(self, x: Self) -> Self {
        let r2 = x.v * x.v + self.v * self.v;
        let mut r = Self::cst(self.v.atan2(x.v));
        for i in 0..N {
            r.g[i] = (x.v * self.g[i] - self.v * x.g[i]) / r2;
        }
        r
    }
}

macro_rules! d1_ops {
    ($($tr:ident $f:ident $op:tt),*) => {$(
        impl<const N: usize> std::ops::$tr<f64> for D1<N> {
            type Output = Self;
            #[inline]
            #[allow(clippy::assign_op_pattern)]
            fn $f(mut self, o: f64) -> Self {
                self.v = self.v $op o;
                d1_scale_grad!(self, $op, o);
                self
            }
        }
    )*};
}
macro_rules! d1_scale_grad {
    ($s:ident, +, $o:ident) => {};
    ($s:ident, -, $o:ident) => {};
    ($s:ident, *, $o:ident) => {
        $s.g.iter_mut().for_each(|x| *x *= $o);
    };
    ($s:ident, /, $o:ident) => {
        $s.g.iter_mut().for_each(|x| *x /= $o);
    };
}
d1_ops!(Add add +, Sub sub -, Mul mul *, Div div /);

impl<const N: usize> Add for D1<N> {
    type Output = Self;
    #[inline]
    fn add(mut self, o: Self) -> Self {
        self.v += o.v;
        for i in 0..N {
            self.g[i] += o.g[i];
        }
        self
    }
}
impl<const N: usize> AddAssign for D1<N> {
    #[inline]
    fn add_assign(&mut self, o: Self) {
        *self = *self + o;
    }
}
impl<const N: usize> Sub for D1<N> {
    type Output = Self;
    #[inline]
    fn sub(mut self, o: Self) -> Self {
        self.v -= o.v;
        for i in 0..N {
            self.g[i] -= o.g[i];
        }
        self
    }
}
impl<const N: usize> Neg for D1<N> {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        self * -1.0
    }
}
impl<const N: usize> Mul for D1<N> {
    type Output = Self;
    #[inline]
    fn mul(self, o: Self) -> Self {
        let mut r = Self::cst(self.v * o.v);
        for i in 0..N {
            r.g[i] = self.v * o.g[i] + o.v * self.g[i];
        }
        r
    }
}
#[allow(clippy::suspicious_arithmetic_impl)] // a / b = a · (1/b)
impl<const N: usize> Div for D1<N> {
    type Output = Self;
    #[inline]
    fn div(self, o: Self) -> Self {
        self * o.recip()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Value, gradient and Hessian of `a` within `tol` = (value, gradient, Hessian) of `b`'s.
    fn assert_close<const N: usize>(a: &HD<N>, b: &HD<N>, tol: [f64; 3]) {
        assert!((a.v - b.v).abs() < tol[0], "value {} vs {}", a.v, b.v);
        let (ha, hb) = (a.hessian(), b.hessian());
        for i in 0..N {
            assert!((a.g[i] - b.g[i]).abs() < tol[1], "g{i}");
            for j in 0..N {
                assert!((ha[i][j] - hb[i][j]).abs() < tol[2], "h{i}{j}");
            }
        }
    }

    fn f<T: Real>(x: T, y: T) -> T {
        (x * y).sin() + (x * x + y * y + 1.0).sqrt() / (y + 3.0) + y.atan2(x) * x.cos()
    }

    #[test]
    fn matches_hand_derivatives() {
        // Hand derivatives of the pieces, evaluated at one point; checks every rule used above.
        let (x0, y0) = (0.7, -0.4);
        let [x, y] = HD::<2>::vars(&[x0, y0]);
        let r = f(x, y);
        assert!((r.v - f(x0, y0)).abs() < 1e-15);
        let h = 1e-5;
        let fd = |dx: f64, dy: f64| f(x0 + dx, y0 + dy);
        let gx = (fd(h, 0.0) - fd(-h, 0.0)) / (2.0 * h);
        let gy = (fd(0.0, h) - fd(0.0, -h)) / (2.0 * h);
        assert!((r.g[0] - gx).abs() < 1e-9, "{} {}", r.g[0], gx);
        assert!((r.g[1] - gy).abs() < 1e-9);
        let hxx = (fd(h, 0.0) - 2.0 * fd(0.0, 0.0) + fd(-h, 0.0)) / (h * h);
        let hxy = (fd(h, h) - fd(h, -h) - fd(-h, h) + fd(-h, -h)) / (4.0 * h * h);
        let hyy = (fd(0.0, h) - 2.0 * fd(0.0, 0.0) + fd(0.0, -h)) / (h * h);
        let hh = r.hessian();
        assert!((hh[0][0] - hxx).abs() < 1e-5, "{} {}", hh[0][0], hxx);
        assert!((hh[0][1] - hxy).abs() < 1e-5);
        assert!((hh[1][0] - hxy).abs() < 1e-5);
        assert!((hh[1][1] - hyy).abs() < 1e-5);
        let [a, b] = D1::<2>::vars(&[x0, y0]);
        let d = f(a, b);
        assert!((d.v - r.v).abs() < 1e-15);
        assert!((d.g[0] - r.g[0]).abs() < 1e-14 && (d.g[1] - r.g[1]).abs() < 1e-14);
    }

    /// f(a(y), z) through `compose` equals the direct hyper-dual evaluation.
    #[test]
    fn composition_matches_direct_differentiation() {
        let inner_f = |y: [HD<3>; 3]| -> [HD<3>; 2] {
            [y[0] * y[1].sin() + y[2], (y[0] * y[2]).sqrt() * y[1]]
        };
        let outer_f = |a: [HD<5>; 2], z: [HD<5>; 2]| a[0] * a[1] * z[0] + (a[1] * z[1]).cos();
        // The same outer function, in (a, z) as its own 4 variables.
        let vals = [0.7, -0.4, 1.3, 0.25, -1.1];
        let x = HD::<5>::vars(&vals);
        let direct = {
            let y3 = [x[0], x[1], x[2]];
            let a = [y3[0] * y3[1].sin() + y3[2], (y3[0] * y3[2]).sqrt() * y3[1]];
            outer_f(a, [x[3], x[4]])
        };
        let a = inner_f(HD::<3>::vars(&[vals[0], vals[1], vals[2]]));
        let o = HD::<4>::vars(&[a[0].v, a[1].v, vals[3], vals[4]]);
        let outer4 = o[0] * o[1] * o[2] + (o[1] * o[3]).cos();
        let r: HD<5> = compose::<3, 2, 4, 5>(&a, &outer4);
        assert_close(&r, &direct, [1e-14, 1e-13, 1e-12]);
    }

    #[test]
    fn dot3_is_the_sum_of_products() {
        let x = HD::<4>::vars(&[0.7, -0.4, 1.3, 0.25]);
        let a = [x[0].sin() * x[1], x[2] * x[3] + x[0], x[1].cos()];
        let b = [x[3].sqrt() * x[2], x[0] * x[0] - x[1], x[2] * x[1] * x[3]];
        let s = [1.0, -1.0, 0.5];
        let fused = HD::dot3(a, b, s);
        let plain = a[0] * b[0] * s[0] + a[1] * b[1] * s[1] + a[2] * b[2] * s[2];
        assert_close(&fused, &plain, [1e-15, 1e-14, 1e-14]);
    }
}
