//! Steps of fixed chord length on a surface. Each one is a root of the signed distance along a
//! circle of candidate points, found by bracketing outward from a guess and refining by the
//! Illinois method: a one-dimensional search that stays well defined across the kinks of a
//! piecewise-flat mesh, where a Newton step on the projection would not.

use super::Surface;
use crate::math::vec::{add, cross, dot, norm, normalize, scalef, sub};

/// Why a step has no point on the surface.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NoStep {
    /// The two known corners are 2h or more apart: the net's cell has closed (ω → 0 or π).
    Locked,
    /// The candidate circle does not meet the surface near the guess.
    NoRoot,
    /// The point found lies beyond the surface's boundary.
    OffSurface,
}

/// Angular increment of the bracketing scan, rad; the search covers ±`SCAN_LIMIT`.
const SCAN: f64 = 0.04;
const SCAN_LIMIT: f64 = 1.2;

/// The next point of a straightest curve: at chord `h` from `here`, in the plane through
/// `here` spanned by the incoming direction `dir` and the surface normal. A discrete geodesic:
/// its curvature vector is normal to the surface.
pub fn geodesic_step(
    s: &Surface,
    here: [f64; 3],
    dir: [f64; 3],
    h: f64,
) -> Result<[f64; 3], NoStep> {
    let n = s.closest(here).normal;
    let t = normalize(sub(dir, scalef(n, dot(dir, n))));
    on_circle(s, here, t, n, h)
}

/// The compass step: the point at chord `h` from both `a` and `b`, on the side away from the
/// cell's known corner `opposite` (the rhombus a, opposite, b, new).
pub fn compass_step(
    s: &Surface,
    a: [f64; 3],
    b: [f64; 3],
    opposite: [f64; 3],
    h: f64,
) -> Result<[f64; 3], NoStep> {
    let w = sub(b, a);
    let d = norm(w);
    if d >= 2.0 * h * (1.0 - 1e-12) {
        return Err(NoStep::Locked);
    }
    let axis = scalef(w, 1.0 / d);
    let mid = scalef(add(a, b), 0.5);
    let away = sub(mid, opposite);
    let e1 = sub(away, scalef(axis, dot(away, axis)));
    if norm(e1) <= 1e-12 * h {
        return Err(NoStep::Locked);
    }
    let e1 = normalize(e1);
    let e2 = cross(axis, e1);
    let rho = (h * h - 0.25 * d * d).sqrt();
    on_circle(s, mid, e1, e2, rho)
}

/// The root of the signed distance on the circle `center + r (cos ψ e1 + sin ψ e2)` nearest
/// to ψ = 0.
fn on_circle(
    s: &Surface,
    center: [f64; 3],
    e1: [f64; 3],
    e2: [f64; 3],
    r: f64,
) -> Result<[f64; 3], NoStep> {
    let at = |psi: f64| {
        add(
            center,
            scalef(add(scalef(e1, psi.cos()), scalef(e2, psi.sin())), r),
        )
    };
    let f = |psi: f64| s.signed_distance(at(psi));
    let f0 = f(0.0);
    if f0 == 0.0 {
        return finish(s, at(0.0));
    }
    let mut bracket = None;
    let mut k = 1;
    while bracket.is_none() && (k as f64) * SCAN <= SCAN_LIMIT {
        for sign in [1.0, -1.0] {
            let (p0, p1) = (sign * (k - 1) as f64 * SCAN, sign * k as f64 * SCAN);
            let (g0, g1) = (f(p0), f(p1));
            if g0 * g1 <= 0.0 {
                bracket = Some((p0, g0, p1, g1));
                break;
            }
        }
        k += 1;
    }
    let (mut x0, mut g0, mut x1, mut g1) = bracket.ok_or(NoStep::NoRoot)?;
    // Illinois: regula falsi with the stale end's value halved.
    let mut stale = 0i8;
    for _ in 0..100 {
        if (x1 - x0).abs() * r <= 1e-14 * (r + s.size) {
            break;
        }
        let x = if g1 != g0 {
            x1 - g1 * (x1 - x0) / (g1 - g0)
        } else {
            0.5 * (x0 + x1)
        };
        let g = f(x);
        if g == 0.0 {
            return finish(s, at(x));
        }
        if g * g1 < 0.0 {
            (x0, g0) = (x1, g1);
            stale = 0;
        } else {
            if stale == 1 {
                g0 *= 0.5;
            }
            stale = 1;
        }
        (x1, g1) = (x, g);
    }
    finish(s, at(if g0.abs() < g1.abs() { x0 } else { x1 }))
}

fn finish(s: &Surface, p: [f64; 3]) -> Result<[f64; 3], NoStep> {
    let c = s.closest(p);
    if c.beyond_boundary {
        return Err(NoStep::OffSurface);
    }
    Ok(p)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A flat square [-2, 2]² at z = 0, two triangles.
    fn plane() -> Surface {
        Surface::from_obj(
            "p.obj",
            "v -2 -2 0\nv 2 -2 0\nv 2 2 0\nv -2 2 0\nf 1 2 3\nf 1 3 4\n",
        )
        .unwrap()
    }

    #[test]
    fn on_a_plane_the_compass_closes_the_rhombus_and_geodesics_are_straight() {
        let s = plane();
        let (o, a, b) = ([0.0; 3], [0.1, 0.0, 0.0], [0.06, 0.08, 0.0]);
        let c = compass_step(&s, a, b, o, 0.1).unwrap();
        let want = [0.16, 0.08, 0.0];
        assert!(norm(sub(c, want)) < 1e-14, "{c:?}");
        let g = geodesic_step(&s, [0.5, 0.5, 0.0], [1.0, 1.0, 0.3], 0.2).unwrap();
        let want = add([0.5, 0.5, 0.0], scalef(normalize([1.0, 1.0, 0.0]), 0.2));
        assert!(norm(sub(g, want)) < 1e-14, "{g:?}");
        assert_eq!(
            compass_step(&s, [0.0; 3], [0.2, 0.0, 0.0], [0.1, -0.01, 0.0], 0.1),
            Err(NoStep::Locked)
        );
        assert_eq!(
            geodesic_step(&s, [1.95, 0.0, 0.0], [1.0, 0.0, 0.0], 0.1),
            Err(NoStep::OffSurface)
        );
    }
}
