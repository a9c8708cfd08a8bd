//! A stencil's two θ = 0 frames at a committed state, to second order in the edge vectors, in
//! closed form.
//!
//! After `Model::commit` each edge's reference tangent is its tangent, and Newton assembles its
//! Hessians there. With (T, U, V) an edge's frame oriented along the stencil, ℓ its length and
//! (τ, μ, ν) = (T, U, V)·δe/ℓ the local coordinates of a change δe of its vector, the normalized
//! tangent and the time-parallel transport of the reference director give, up to third order,
//!
//! - T(δe) = T + μU + νV − τ(μU + νV) − ½(μ² + ν²) T,
//! - U(δe) = U − μT + τμT − ½μ(μU + νV),
//! - V(δe) = V − νT + τνT − ½ν(μU + νV).
//!
//! A product of a vector of one frame with one of the other is then bilinear in these
//! coefficients and the nine products D of the two frames' vectors, so its gradient and Hessian
//! in the six local coordinates are read off D: neither the normalization nor the transport is
//! differentiated. Elsewhere (trial points, tests at arbitrary reference frames) the frames are
//! differentiated by hyper-dual arithmetic (`BendTwist::derivatives`), which is the reference
//! this is tested against (tests/fused_kernels.rs).

use crate::math::vec::{cross, dot, norm, normalize, scalef};
use crate::math::{Real, HD};
use crate::rod::frames::{EdgeRef, FrameDots};

const T: usize = 0;
const U: usize = 1;
const V: usize = 2;

/// First derivative of each frame vector (T, U, V) in each local coordinate (τ, μ, ν): the
/// frame vector it points along, with its sign (None: zero).
const FIRST: [[Option<(usize, f64)>; 3]; 3] = [
    [None, Some((U, 1.0)), Some((V, 1.0))],
    [None, Some((T, -1.0)), None],
    [None, None, Some((T, -1.0))],
];

/// Second derivatives of each frame vector: (coordinate i, coordinate j ≥ i, frame vector,
/// coefficient) of its non-zero entries.
const SECOND: [&[(usize, usize, usize, f64)]; 3] = [
    &[
        (0, 1, U, -1.0),
        (0, 2, V, -1.0),
        (1, 1, T, -1.0),
        (2, 2, T, -1.0),
    ],
    &[(0, 1, T, 1.0), (1, 1, U, -1.0), (1, 2, V, -0.5)],
    &[(0, 2, T, 1.0), (1, 2, U, -0.5), (2, 2, V, -1.0)],
];

/// Largest difference between an edge's tangent and its reference tangent at which the edge
/// counts as committed. Both are the same floating-point computation after a commit (equal to
/// the bit); the derivatives' error is of this order relative to their size.
const COMMITTED: f64 = 1e-14;

/// The two oriented frames of a stencil whose edges are both committed.
pub struct CommittedPair {
    /// Each edge's (T, U, V), oriented along the stencil.
    frames: [[[f64; 3]; 3]; 2],
    lengths: [f64; 2],
    /// d[a][b] = (frame 0's vector a)·(frame 1's vector b).
    d: [[f64; 3]; 3],
}

impl CommittedPair {
    /// The frames of two edges with reference frames `refs`, vectors `along` the stencil and
    /// orientation `signs` (as in `oriented_reference_frame`), if both edges are committed.
    #[inline(always)]
    pub fn new(refs: [&EdgeRef; 2], signs: [f64; 2], along: [[f64; 3]; 2]) -> Option<Self> {
        let mut frames = [[[0.0; 3]; 3]; 2];
        let mut lengths = [0.0; 2];
        for j in 0..2 {
            let e = scalef(along[j], signs[j]);
            let t = normalize(e);
            let r = refs[j];
            if (0..3).any(|k| (t[k] - r.t[k]).abs() > COMMITTED) {
                return None;
            }
            lengths[j] = norm(e);
            let v = cross(t, r.u);
            frames[j] = [scalef(t, signs[j]), r.u, scalef(v, signs[j])];
        }
        let d = std::array::from_fn(|a| std::array::from_fn(|b| dot(frames[0][a], frames[1][b])));
        Some(CommittedPair { frames, lengths, d })
    }

    /// The products of the two frames on which bending and twisting depend, with their
    /// derivatives in the local coordinates (τ⁰, μ⁰, ν⁰, τ¹, μ¹, ν¹).
    #[inline(always)]
    pub fn dots(&self) -> FrameDots<HD<6>> {
        FrameDots {
            tt: self.product(T, T),
            t1u0: self.product(U, T),
            t1v0: self.product(V, T),
            t0u1: self.product(T, U),
            t0v1: self.product(T, V),
            u0u1: self.product(U, U),
            u0v1: self.product(U, V),
        }
    }

    /// The reference twist (not unwrapped) with its derivatives in the local coordinates, in
    /// closed form. With χ = 1 + t⁰·t¹, κb = 2 t⁰×t¹/χ and t̃ = (t⁰ + t¹)/χ, time-parallel
    /// reference frames give ∇ₑr = κb/(2|e|) for each edge e and
    /// ∇²ₑ₀ₑ₀ r = −(κb⊗(t⁰ + t̃) + (t⁰ + t̃)⊗κb)/(4|e⁰|²) (the same for e¹ with t¹),
    /// ∇²ₑ₀ₑ₁ r = (2[t⁰]ₓ/χ − κb⊗t̃)/(2|e⁰||e¹|) (Bergou et al. 2010; checked against the
    /// hyper-dual frames, tests/fused_kernels.rs). In the local coordinates z = F e/ℓ every
    /// product with a frame vector is one of `d`.
    #[inline(always)]
    pub fn reference_twist(&self) -> HD<6> {
        let d = &self.d;
        let (tt, t1u0, t1v0, t0u1, t0v1) = (d[T][T], d[U][T], d[V][T], d[T][U], d[T][V]);
        let raw = FrameDots {
            tt,
            t1u0,
            t1v0,
            t0u1,
            t0v1,
            u0u1: d[U][U],
            u0v1: d[U][V],
        }
        .reference_twist();
        let chi = 1.0 + tt;
        let ic = chi.recip();
        // F κb / 2 for each frame (the gradient), F (t + t̃) and F t̃ of frame 1.
        let g0 = [0.0, -t1v0 * ic, t1u0 * ic];
        let g1 = [0.0, t0v1 * ic, -t0u1 * ic];
        let b0 = [2.0, t1u0 * ic, t1v0 * ic];
        let b1 = [2.0, t0u1 * ic, t0v1 * ic];
        let c1 = [1.0, t0u1 * ic, t0v1 * ic];
        let mut r = HD::<6>::cst(raw);
        r.g[..3].copy_from_slice(&g0);
        r.g[3..].copy_from_slice(&g1);
        for i in 0..3 {
            for j in i..3 {
                r.h[i][j] = -0.5 * (g0[i] * b0[j] + b0[i] * g0[j]);
                r.h[3 + i][3 + j] = -0.5 * (g1[i] * b1[j] + b1[i] * g1[j]);
            }
            // F⁰[t⁰]ₓF¹ᵀ: rows (t⁰, u⁰, v⁰) are (0, −v⁰·, u⁰·) of frame 1's vectors.
            for j in 0..3 {
                let m = match i {
                    T => 0.0,
                    U => -d[V][j],
                    _ => d[U][j],
                };
                r.h[i][3 + j] = m * ic - g0[i] * c1[j];
            }
        }
        r
    }

    /// Frame 0's vector `a` times frame 1's vector `b`.
    #[inline(always)]
    fn product(&self, a: usize, b: usize) -> HD<6> {
        let d = &self.d;
        let mut r = HD::<6>::cst(d[a][b]);
        for i in 0..3 {
            if let Some((k, s)) = FIRST[a][i] {
                r.g[i] = s * d[k][b];
            }
            if let Some((k, s)) = FIRST[b][i] {
                r.g[3 + i] = s * d[a][k];
            }
        }
        for &(i, j, k, c) in SECOND[a] {
            r.h[i][j] = c * d[k][b];
        }
        for &(i, j, k, c) in SECOND[b] {
            r.h[3 + i][3 + j] = c * d[a][k];
        }
        for i in 0..3 {
            for j in 0..3 {
                if let (Some((k, s)), Some((l, z))) = (FIRST[a][i], FIRST[b][j]) {
                    r.h[i][3 + j] = s * z * d[k][l];
                }
            }
        }
        r
    }

    /// Derivatives in (local coordinates of edge 0, of edge 1, others) turned into derivatives
    /// in (edge vector 0, edge vector 1, others): the coordinates are z = B e with B = F/ℓ for
    /// each edge (F its frame's rows), so ∇ₑ = Bᵀ∇_z and Hₑ = BᵀH_zB.
    #[inline(always)]
    pub fn to_edges<const K: usize>(&self, r: &HD<K>) -> HD<K> {
        let b: [[[f64; 3]; 3]; 2] = std::array::from_fn(|j| {
            let s = self.lengths[j].recip();
            self.frames[j].map(|row| row.map(|x| x * s))
        });
        // The map of the edge that coordinate i (< 6) belongs to.
        let block = |i: usize| &b[i / 3];
        let h = r.hessian();
        let mut out = HD::<K>::cst(r.v);
        // First H·B on the columns of the edge coordinates, then Bᵀ on the rows.
        let mut hb = h;
        for row in hb.iter_mut() {
            let old = *row;
            for j in 0..6 {
                let (bj, base) = (block(j), 3 * (j / 3));
                row[j] = (0..3).map(|a| old[base + a] * bj[a][j % 3]).sum();
            }
        }
        for j in 0..K {
            for i in 0..6 {
                let (bi, base) = (block(i), 3 * (i / 3));
                let v: f64 = (0..3).map(|a| bi[a][i % 3] * hb[base + a][j]).sum();
                if i <= j {
                    out.h[i][j] = v;
                }
            }
            if j >= 6 {
                for i in 6..=j {
                    out.h[i][j] = hb[i][j];
                }
            }
        }
        for i in 0..6 {
            let (bi, base) = (block(i), 3 * (i / 3));
            out.g[i] = (0..3).map(|a| bi[a][i % 3] * r.g[base + a]).sum();
        }
        out.g[6..].copy_from_slice(&r.g[6..]);
        out
    }
}
