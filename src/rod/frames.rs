//! Edge frames, curvature binormals and reference twist (Bergou et al. 2008, 2010).
//!
//! Each edge keeps a reference frame (t_ref, u_ref) from the last accepted iterate. Its current
//! reference director is u = P(t_ref → t) u_ref (time-parallel transport), and its material frame is
//! u and v = t × u rotated by the edge's twist angle θ. All functions are generic over [`Real`], so
//! their exact derivatives come from automatic differentiation.

use crate::math::vec::*;
use crate::math::Real;

/// Reference frame of an edge at the last accepted iterate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EdgeRef {
    pub t: [f64; 3],
    pub u: [f64; 3],
}

/// Material frame of an edge.
pub struct EdgeFrame<T> {
    pub t: V3<T>,
    /// Reference director after time-parallel transport (θ = 0 direction).
    pub u: V3<T>,
    pub m1: V3<T>,
    pub m2: V3<T>,
}

pub fn edge_frame<T: Real>(xa: V3<T>, xb: V3<T>, theta: T, r: &EdgeRef) -> EdgeFrame<T> {
    edge_frame_of(sub(xb, xa), theta, r)
}

/// Material frame of an edge from its vector e = x_b − x_a.
pub fn edge_frame_of<T: Real>(e: V3<T>, theta: T, r: &EdgeRef) -> EdgeFrame<T> {
    let t = normalize(e);
    let u = transport(lift(r.t), t, lift(r.u));
    let v = cross(t, u);
    let (s, c) = (theta.sin(), theta.cos());
    EdgeFrame {
        t,
        u,
        m1: add(scale(u, c), scale(v, s)),
        m2: sub(scale(v, c), scale(u, s)),
    }
}

/// Director `u` (⊥ unit `from`) transported onto unit `to` in one step. Where `to` is opposite
/// `from` the transport is undefined; `u` made perpendicular to `to` (a half turn about `u`)
/// stands in there.
fn transported(from: [f64; 3], u: [f64; 3], to: [f64; 3]) -> [f64; 3] {
    if 1.0 + dot(from, to) > 1e-8 {
        normalize(transport(from, to, u))
    } else {
        normalize(sub(u, scalef(to, dot(u, to))))
    }
}

/// The canonical θ = 0 directors of a rod's edges, from their unit tangents in order: the first
/// edge's rest reference director transported onto its tangent in one step, and each next one
/// the previous one transported onto the next tangent (space-parallel transport along the rod,
/// a Bishop frame). Time-parallel transport along a solve depends on the path (its holonomy turns
/// the reference directors about the tangents); these depend on the state alone, so angles
/// measured from them do too. The reference twist between consecutive canonical frames is zero,
/// so the angles' differences along the rod are the discrete twists (modulo 2π).
pub fn canonical_directors(rest_first: &EdgeRef, tangents: &[[f64; 3]]) -> Vec<[f64; 3]> {
    let mut out: Vec<[f64; 3]> = Vec::with_capacity(tangents.len());
    let (mut from, mut u) = (rest_first.t, rest_first.u);
    for &t in tangents {
        u = transported(from, u, t);
        from = t;
        out.push(u);
    }
    out
}

/// The material angles of a rod's edges measured from their [`canonical_directors`], from their
/// unit tangents, reference frames `refs` (of the last accepted iterate) and angles `thetas`
/// against those: θ plus the signed angle β from the canonical director to the transported
/// reference one. β is unwrapped along the rod (by 2π, against the previous edge's β plus the
/// reference twist between the two reference frames), so that neighbouring angles differ by
/// the discrete twist between them, not by it plus 2π, where the reference frames have turned
/// half a turn from the canonical ones.
pub fn canonical_angles(
    rest_first: &EdgeRef,
    tangents: &[[f64; 3]],
    refs: &[EdgeRef],
    thetas: &[f64],
) -> Vec<f64> {
    let directors = canonical_directors(rest_first, tangents);
    let mut out = Vec::with_capacity(tangents.len());
    let mut prev: Option<([f64; 3], [f64; 3], f64)> = None;
    for k in 0..tangents.len() {
        let t = tangents[k];
        let u = normalize(transport(refs[k].t, t, refs[k].u));
        let mut beta = signed_angle(directors[k], u, t);
        if let Some((pt, pu, pbeta)) = prev {
            let reference_twist = signed_angle(transported(pt, pu, t), u, t);
            beta = unwrap_angle(beta, pbeta + reference_twist);
        }
        prev = Some((t, u, beta));
        out.push(thetas[k] + beta);
    }
    out
}

/// Unit tangent and the material directors at θ = 0 of an edge whose vector *along a stencil*
/// is `along` (orientation as in [`oriented_frame_of`]): with θ' = sign·θ the material frame is
/// m1 = cos θ' u + sin θ' v, m2 = cos θ' v − sin θ' u.
pub struct RefFrame<T> {
    pub t: V3<T>,
    pub u: V3<T>,
    pub v: V3<T>,
}

#[inline(always)]
pub fn oriented_reference_frame<T: Real>(r: &EdgeRef, sign: f64, along: V3<T>) -> RefFrame<T> {
    let t = normalize(scalef(along, sign));
    let u = transport_from(r.t, t, r.u);
    let v = cross(t, u);
    RefFrame {
        t: scalef(t, sign),
        u,
        v: scalef(v, sign),
    }
}

/// Products of two edges' θ = 0 frames on which bending and twisting at their shared vertex
/// depend (with v = t × u in each frame).
pub struct FrameDots<T> {
    /// t⁰·t¹
    pub tt: T,
    pub t1u0: T,
    pub t1v0: T,
    pub t0u1: T,
    pub t0v1: T,
    pub u0u1: T,
    pub u0v1: T,
}

impl<T: Real> FrameDots<T> {
    /// With `dot` the scalar product of a frame-0 and a frame-1 vector (the two frames may
    /// depend on different variables).
    #[inline(always)]
    pub fn new<F0: Real, F1: Real>(
        f0: &RefFrame<F0>,
        f1: &RefFrame<F1>,
        dot: impl Fn(&V3<F0>, &V3<F1>) -> T,
    ) -> Self {
        FrameDots {
            tt: dot(&f0.t, &f1.t),
            t1u0: dot(&f0.u, &f1.t),
            t1v0: dot(&f0.v, &f1.t),
            t0u1: dot(&f0.t, &f1.u),
            t0v1: dot(&f0.t, &f1.v),
            u0u1: dot(&f0.u, &f1.u),
            u0v1: dot(&f0.u, &f1.v),
        }
    }

    /// The curvature binormal κb = 2 t⁰×t¹/|t⁰ + t¹| (|κb| = 2 sin(φ/2)) projected on both
    /// frames' directors, (κb·u⁰, κb·v⁰, κb·u¹, κb·v¹): by the triple-product identities
    /// (t⁰×t¹)·u⁰ = −t¹·v⁰, (t⁰×t¹)·v⁰ = t¹·u⁰, (t⁰×t¹)·u¹ = t⁰·v¹, (t⁰×t¹)·v¹ = −t⁰·u¹.
    #[inline(always)]
    pub fn binormal_projections(&self) -> [T; 4] {
        let f = ((self.tt + 1.0) * 0.5).sqrt().recip();
        [
            -(self.t1v0 * f),
            self.t1u0 * f,
            self.t0v1 * f,
            -(self.t0u1 * f),
        ]
    }

    /// Reference twist (not unwrapped): the signed angle about t¹ from the parallel transport
    /// of u⁰ along t⁰ → t¹ to u¹. With P u⁰ = c u⁰ + k×u⁰ + k (k·u⁰)/(1 + c), k = t⁰×t¹ and
    /// c = t⁰·t¹, its cosine and sine reduce to products of the two frames:
    /// cos ∝ c u⁰·u¹ − (t¹·u⁰)(t⁰·u¹) − (t¹·v⁰)(t⁰·v¹)/(1 + c),
    /// sin ∝ −c u⁰·v¹ + (t¹·u⁰)(t⁰·v¹) − (t¹·v⁰)(t⁰·u¹)/(1 + c).
    #[inline(always)]
    pub fn reference_twist(&self) -> T {
        let w = (self.tt + 1.0).recip();
        let p = self.t1v0 * w;
        let cos = T::dot3(
            [self.tt, self.t1u0, p],
            [self.u0u1, self.t0u1, self.t0v1],
            [1.0, -1.0, -1.0],
        );
        let sin = T::dot3(
            [self.t1u0, self.tt, p],
            [self.t0v1, self.u0v1, self.t0u1],
            [1.0, -1.0, -1.0],
        );
        sin.atan2(cos)
    }
}

/// Curvature binormal between unit tangents with |κb| = 2 sin(φ/2), φ the turning angle.
///
/// DER's original 2 tan(φ/2) grows without bound as φ → π; the sine measure agrees with it to
/// O(φ³), stays bounded by 2, and keeps the bending energy monotonic in φ up to a full fold, so
/// energy, gradient and Hessian are finite at 175°.
#[inline(always)]
pub fn curvature_binormal<T: Real>(t0: V3<T>, t1: V3<T>) -> V3<T> {
    let c = dot(t0, t1);
    let f = ((c + 1.0) * 0.5).sqrt().recip();
    scale(cross(t0, t1), f)
}

/// Material curvatures (κ1, κ2) = (κb·m2, −κb·m1) of a binormal in one edge's frame.
#[inline]
pub fn material_curvature<T: Real>(kb: V3<T>, m1: V3<T>, m2: V3<T>) -> [T; 2] {
    [dot(kb, m2), -dot(kb, m1)]
}

/// Adds 2πk to `raw` so that the result is closest to `previous`: reference twist is continuous
/// along a solve even when it exceeds π in magnitude.
#[inline(always)]
pub fn unwrap_angle<T: Real>(raw: T, previous: f64) -> T {
    let two_pi = std::f64::consts::TAU;
    let k = ((previous - raw.val()) / two_pi).round();
    raw + k * two_pi
}

/// Quadratic bending energy density of one edge's material curvature relative to its rest value.
#[inline]
pub fn bend_quadratic<T: Real>(k: [T; 2], rest: [f64; 2], ei1: f64, ei2: f64) -> T {
    let d1 = k[0] - rest[0];
    let d2 = k[1] - rest[1];
    d1 * d1 * ei1 + d2 * d2 * ei2
}

/// Frame of edge `e` whose vector *along the stencil* is `along`: with sign −1 the rod's edge
/// runs against the stencil, so its tangent is −t, its frame (m1, −m2) and its angle −θ.
pub fn oriented_frame_of<T: Real>(r: &EdgeRef, sign: f64, along: V3<T>, theta: T) -> EdgeFrame<T> {
    if sign > 0.0 {
        edge_frame_of(along, theta, r)
    } else {
        let f = edge_frame_of(scalef(along, -1.0), theta, r);
        EdgeFrame {
            t: scalef(f.t, -1.0),
            u: f.u,
            m1: f.m1,
            m2: scalef(f.m2, -1.0),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Deterministic uniform numbers in [−1, 1) (a linear congruential generator).
    fn uniform(mut seed: u64) -> impl FnMut() -> f64 {
        move || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
        }
    }

    /// The frame-product forms of κb's projections and of the reference twist agree with their
    /// definitions (cross product; transport then signed angle) at generic and nearly folded
    /// tangents, in both stencil orientations.
    #[test]
    fn frame_products_match_the_definitions() {
        let mut rnd = uniform(7);
        for case in 0..200 {
            let mut v = || normalize([rnd(), rnd(), rnd()]);
            let (t0r, t1r) = (v(), v());
            let r0 = EdgeRef {
                t: t0r,
                u: normalize(cross(t0r, v())),
            };
            let r1 = EdgeRef {
                t: t1r,
                u: normalize(cross(t1r, v())),
            };
            let e0 = scalef(add(t0r, scalef(v(), 0.3)), 1.7);
            // Every fourth case folds edge 1 back to within ~10° of edge 0.
            let e1 = if case % 4 == 0 {
                add(scalef(e0, -0.9), scalef(v(), 0.15))
            } else {
                add(t1r, scalef(v(), 0.3))
            };
            for (s0, s1) in [(1.0, 1.0), (-1.0, 1.0), (1.0, -1.0)] {
                let f0 = oriented_reference_frame::<f64>(&r0, s0, e0);
                let f1 = oriented_reference_frame::<f64>(&r1, s1, e1);
                let d = FrameDots::new(&f0, &f1, |a, b| dot(*a, *b));
                let kb = curvature_binormal(f0.t, f1.t);
                let want = [dot(kb, f0.u), dot(kb, f0.v), dot(kb, f1.u), dot(kb, f1.v)];
                for (a, b) in d.binormal_projections().iter().zip(want) {
                    assert!((a - b).abs() < 1e-12, "case {case}: {a} vs {b}");
                }
                let twist = signed_angle(transport(f0.t, f1.t, f0.u), f1.u, f1.t);
                assert!(
                    (d.reference_twist() - twist).abs() < 1e-11,
                    "case {case}: {} vs {twist}",
                    d.reference_twist()
                );
            }
        }
    }

    /// The canonical angles describe the same material directors as the angles against the
    /// path-transported reference frames (m1 = cos θ u + sin θ t × u either way), and
    /// neighbouring ones differ by θ's difference plus the reference twist, also where the
    /// reference frames have turned about half a turn from the canonical ones; the canonical
    /// directors are the rest one where the tangents have not moved, have zero reference twist
    /// between neighbours, and stay finite unit vectors perpendicular to their tangents even
    /// where a tangent is opposite the one before it.
    #[test]
    fn canonical_angles_describe_the_same_material_frame() {
        let mut rnd = uniform(11);
        let director = |u: [f64; 3], t: [f64; 3], th: f64| {
            add(scalef(u, th.cos()), scalef(cross(t, u), th.sin()))
        };
        let pi = std::f64::consts::PI;
        for case in 0..60 {
            let mut v = || normalize([rnd(), rnd(), rnd()]);
            let rest_t = v();
            let rest = EdgeRef {
                t: rest_t,
                u: normalize(cross(rest_t, v())),
            };
            // A rod of six edges turning away from the rest tangent.
            let mut t = rest_t;
            let tangents: Vec<[f64; 3]> = (0..6)
                .map(|_| {
                    t = normalize(add(t, scalef(v(), 0.6)));
                    t
                })
                .collect();
            let c = canonical_directors(&rest, &tangents);
            // Reference frames: the canonical ones turned about the tangent by angles near ±π
            // in every third case (held there by a long solve's holonomy), and tilted a little
            // (a frame of the last accepted iterate, before this tangent).
            let turn0 = if case % 3 == 0 {
                pi - 0.05
            } else {
                3.0 * v()[0]
            };
            let refs: Vec<EdgeRef> = (0..6)
                .map(|k| {
                    let turn = turn0 + 0.04 * k as f64 * if case % 2 == 0 { 1.0 } else { -1.0 };
                    let u = director(c[k], tangents[k], turn);
                    let rt = normalize(add(tangents[k], scalef(v(), 0.2)));
                    EdgeRef {
                        t: rt,
                        u: normalize(transport(tangents[k], rt, u)),
                    }
                })
                .collect();
            let thetas: Vec<f64> = (0..6).map(|_| 7.0 * v()[0]).collect();
            let a = canonical_angles(&rest, &tangents, &refs, &thetas);
            for k in 0..6 {
                let t = tangents[k];
                let u = normalize(transport(refs[k].t, t, refs[k].u));
                let (want, got) = (director(u, t, thetas[k]), director(c[k], t, a[k]));
                assert!(norm(sub(got, want)) < 1e-12, "{case} {k}");
                if k > 0 {
                    let twist = signed_angle(transport(tangents[k - 1], t, c[k - 1]), c[k], t);
                    assert!(twist.abs() < 1e-12, "{twist}");
                    let up = normalize(transport(refs[k - 1].t, tangents[k - 1], refs[k - 1].u));
                    let r = signed_angle(transport(tangents[k - 1], t, up), u, t);
                    let d = a[k] - a[k - 1] - (thetas[k] - thetas[k - 1]);
                    assert!((d - r).abs() < 1e-9, "{case} {k}: {d} vs {r}");
                }
            }
        }
        let rest = EdgeRef {
            t: [1.0, 0.0, 0.0],
            u: [0.0, 1.0, 0.0],
        };
        assert_eq!(canonical_directors(&rest, &[rest.t]), vec![rest.u]);
        let folded = canonical_directors(&rest, &[[0.0, 0.0, 1.0], [0.0, 0.0, -1.0]]);
        let u = folded[1];
        assert!((norm(u) - 1.0).abs() < 1e-15 && dot(u, [0.0, 0.0, -1.0]).abs() < 1e-15);
    }
}
