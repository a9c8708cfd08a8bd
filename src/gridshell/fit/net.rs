//! The Chebyshev net of a gridshell on a target mesh: rods, crossings and rod ends, from two
//! compass constructions (steps a/m and a/2m) combined by Richardson extrapolation.
//!
//! The compass with chord h is second order: its nodes approach the smooth net's as h², so
//! (4 X(h/2) − X(h))/3 removes the leading error and |X(h/2) − X(h)|/3 estimates what is left
//! in X(h/2) (docs/gridshell.md, "Nets on meshes", measures both against the analytic net).
//! On a mesh the smooth net is the one of the piecewise-flat surface; the mesh's own distance
//! from the designer's surface enters on top, at O(edge²) (measured there too).

use std::collections::BTreeMap;

use super::compass::{self, FineNet, Node, Seed};
use crate::math::vec::{add, cross, dot, norm, scalef, sub};
use crate::surface::Surface;

#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Family {
    /// Along the first generator's direction: the net curve v = offset.
    U,
    /// Along the second: u = offset.
    V,
}

impl Family {
    pub fn name(self) -> &'static str {
        match self {
            Family::U => "u",
            Family::V => "v",
        }
    }
}

/// Rods on the generators (offsets k·a) or between them ((k + ½)·a).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Layout {
    On,
    Between,
}

/// Why a rod ends where it does.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum EndKind {
    /// On the surface's boundary: the net left the surface there.
    Boundary,
    /// The net's cells closed below the locking angle.
    Locked,
    /// The compass found no point of the surface (the net cannot go on).
    NoStep,
    /// The net beside the rod stopped first, so it could not be continued.
    Blocked,
}

impl EndKind {
    pub fn describe(self) -> &'static str {
        match self {
            EndKind::Boundary => "boundary",
            EndKind::Locked => "net locks (its cells sheared past --min-angle)",
            EndKind::NoStep => "compass step has no solution on the surface",
            EndKind::Blocked => "the net beside this rod stopped first",
        }
    }
}

#[derive(Debug, Clone, Copy)]
pub struct RodEnd {
    /// Net parameter along the rod (arc length from the other generator), m.
    pub param: f64,
    pub point: [f64; 3],
    pub kind: EndKind,
}

#[derive(Debug, Clone)]
pub struct NetRod {
    pub family: Family,
    /// Coarse index: offset = (k + ½ if between) · a.
    pub k: i64,
    pub offset: f64,
    /// Start (negative parameter side) and end.
    pub ends: [RodEnd; 2],
    /// Crossings on the rod, in order of parameter (indices into `Net::crossings`).
    pub crossings: Vec<usize>,
    /// The rod's curve from the finer construction: (parameter, point), ends included.
    pub curve: Vec<(f64, [f64; 3])>,
}

#[derive(Debug, Clone, Copy)]
pub struct Crossing {
    /// Rod indices of its family-U and family-V rods.
    pub rods: [usize; 2],
    /// (u, v): its parameter along the V rod and along the U rod.
    pub uv: [f64; 2],
    pub point: [f64; 3],
    /// Angle between the two rods' tangents, rad.
    pub angle: f64,
}

#[derive(Debug, Clone)]
pub struct Net {
    pub spacing: f64,
    pub layout: Layout,
    pub seed: Seed,
    pub rods: Vec<NetRod>,
    pub crossings: Vec<Crossing>,
    /// Fine steps per spacing of the coarser and the finer construction.
    pub steps: [usize; 2],
    /// Estimated error of the finer construction's crossings, max |X(h/2) − X(h)|/3, m.
    pub construction_error: f64,
    /// Largest change made by extrapolating a crossing, m.
    pub extrapolation_change: f64,
}

/// Fine steps per spacing of the coarser construction (the finer one takes twice as many).
pub const DEFAULT_STEPS: usize = 4;

/// Builds the net with spacing `a`; `m` even. The finer construction's grid has at most
/// `max_nodes` nodes (the coarser one a quarter): a larger one is refused before it is
/// allocated, with the number of nodes it would have had (at least).
pub fn build(
    s: &Surface,
    seed: &Seed,
    a: f64,
    layout: Layout,
    m: usize,
    max_nodes: usize,
) -> Result<Net, usize> {
    // Saturating: a spacing far below the mesh's size gives a huge bound, held by `max_nodes`.
    let max_steps = (((8.0 * s.size / a).ceil() + 2.0) * 2.0 * m as f64).min(usize::MAX as f64);
    let max_steps = max_steps as usize;
    let fine = compass::build(s, seed, a, 2 * m, max_steps, max_nodes)?;
    let coarse = compass::build(s, seed, a, m, max_steps / 2, max_nodes)?;
    let lo = extract(s, &coarse, seed, layout);
    let hi = extract(s, &fine, seed, layout);
    Ok(combine(s, *seed, a, layout, [m, 2 * m], lo, hi))
}

/// Rods and crossings of one construction, keyed by (family, k) and (k_u, k_v).
struct Extracted {
    rods: BTreeMap<(Family, i64), NetRod>,
    crossings: BTreeMap<(i64, i64), ([f64; 3], f64)>,
}

fn extract(s: &Surface, net: &FineNet, seed: &Seed, layout: Layout) -> Extracted {
    let m = net.m as i64;
    let half = if layout == Layout::Between { m / 2 } else { 0 };
    let fine_of = |k: i64| k * m + half;
    let offset = |k: i64| fine_of(k) as f64 * net.h;
    let mut rods = BTreeMap::new();
    for family in [Family::U, Family::V] {
        let (lo, hi) = match family {
            Family::U => (net.reach[2] as i64, net.reach[3] as i64),
            Family::V => (net.reach[0] as i64, net.reach[1] as i64),
        };
        let dir = if family == Family::U {
            seed.d1
        } else {
            seed.d2
        };
        let kmin = (-lo - half).div_euclid(m) + 1;
        for k in kmin - 1..=(hi - half).div_euclid(m) {
            let jf = fine_of(k);
            if jf < -lo || jf > hi {
                continue;
            }
            let at = |t: i64| match family {
                Family::U => net.node(t, jf),
                Family::V => net.node(jf, t),
            };
            if let Some(rod) = trace(s, &at, net.h, dir, family, k, offset(k)) {
                rods.insert((family, k), rod);
            }
        }
    }
    let mut crossings = BTreeMap::new();
    for ((fu, ku), ru) in &rods {
        if *fu != Family::U {
            continue;
        }
        for ((fv, kv), rv) in &rods {
            if *fv != Family::V {
                continue;
            }
            let (u, v) = (rv.offset, ru.offset);
            // A crossing within a twentieth of a spacing of a rod end would leave a sliver of
            // an end segment (a stiff, tiny edge): the rod ends there without it.
            let margin = 0.05 * net.h * net.m as f64;
            let inside =
                |r: &NetRod, p: f64| r.ends[0].param + margin < p && p < r.ends[1].param - margin;
            if !(inside(ru, u) && inside(rv, v)) {
                continue;
            }
            let (i, j) = (fine_of(*kv), fine_of(*ku));
            if let Some(p) = net.at(i, j) {
                crossings.insert((*ku, *kv), (p, angle(net, i, j)));
            }
        }
    }
    Extracted { rods, crossings }
}

/// The rod through node(0) along `at(t)`, out to its ends in both directions.
fn trace(
    s: &Surface,
    at: &dyn Fn(i64) -> Node,
    h: f64,
    dir: [f64; 3],
    family: Family,
    k: i64,
    offset: f64,
) -> Option<NetRod> {
    at(0).point()?;
    let mut ends = [None, None];
    let mut curve = Vec::new();
    for (side, sign) in [(0usize, -1i64), (1, 1)] {
        let mut t = 0;
        while at(t + sign).point().is_some() {
            t += sign;
        }
        let last = at(t).point().expect("traced");
        let prev = at(t - sign)
            .point()
            .unwrap_or_else(|| sub(last, scalef(dir, sign as f64 * h)));
        // The node before `prev`, for a quadratic continuation (linear when there is none).
        let prev2 = at(t - 2 * sign)
            .point()
            .unwrap_or_else(|| sub(scalef(prev, 2.0), last));
        let kind = match at(t + sign) {
            Node::Locked => EndKind::Locked,
            Node::NoRoot => EndKind::NoStep,
            _ => EndKind::Blocked,
        };
        let end = match boundary_after(s, [prev2, prev, last]) {
            Some((p, partial)) => RodEnd {
                param: (t as f64 * h) + sign as f64 * partial,
                point: p,
                kind: EndKind::Boundary,
            },
            None => RodEnd {
                param: t as f64 * h,
                point: last,
                kind,
            },
        };
        if side == 0 {
            if end.kind == EndKind::Boundary {
                curve.push((end.param, end.point));
            }
            for u in t..=0 {
                curve.push((u as f64 * h, at(u).point().expect("traced")));
            }
        } else {
            for u in 1..=t {
                curve.push((u as f64 * h, at(u).point().expect("traced")));
            }
            if end.kind == EndKind::Boundary {
                curve.push((end.param, end.point));
            }
        }
        ends[side] = Some(end);
    }
    let ends = ends.map(|e| e.expect("both sides traced"));
    (ends[1].param - ends[0].param > 0.0).then_some(NetRod {
        family,
        k,
        offset,
        ends,
        crossings: Vec::new(),
        curve,
    })
}

/// The boundary point where the curve through the last three nodes `p` leaves the surface
/// within 1.5 steps of the last, and its chord from the last node; None if it does not leave
/// the surface there. The curve is continued by the parabola through the three nodes, so that
/// its turning within the step (geodesic curvature) does not shift the end by O(h²).
fn boundary_after(s: &Surface, p: [[f64; 3]; 3]) -> Option<([f64; 3], f64)> {
    let [p2, p1, p0] = p;
    let d1 = sub(p0, p1);
    let d2 = add(sub(p0, scalef(p1, 2.0)), p2);
    let curve = |t: f64| add(p0, add(scalef(d1, t), scalef(d2, 0.5 * t * (t + 1.0))));
    let beyond = |t: f64| s.closest(curve(t)).beyond_boundary;
    if s.closest(p0).beyond_boundary || !beyond(1.5) {
        return None;
    }
    let (mut lo, mut hi) = (0.0, 1.5);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if beyond(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let e = s.closest(curve(lo)).point;
    Some((e, norm(sub(e, p0))))
}

/// The angle between the net's two curves at fine node (i, j), rad, from central differences
/// where both neighbours exist.
fn angle(net: &FineNet, i: i64, j: i64) -> f64 {
    let diff = |a: Option<[f64; 3]>, b: Option<[f64; 3]>, c: [f64; 3]| match (a, b) {
        (Some(a), Some(b)) => sub(a, b),
        (Some(a), None) => sub(a, c),
        (None, Some(b)) => sub(c, b),
        (None, None) => [0.0; 3],
    };
    let c = net.at(i, j).expect("a crossing node");
    let tu = diff(net.at(i + 1, j), net.at(i - 1, j), c);
    let tv = diff(net.at(i, j + 1), net.at(i, j - 1), c);
    norm(cross(tu, tv)).atan2(dot(tu, tv))
}

fn combine(
    s: &Surface,
    seed: Seed,
    a: f64,
    layout: Layout,
    steps: [usize; 2],
    lo: Extracted,
    hi: Extracted,
) -> Net {
    let extrapolate = |x: [f64; 3], y: [f64; 3]| {
        let p = scalef(sub(scalef(y, 4.0), x), 1.0 / 3.0);
        s.closest(p).point
    };
    let mut rods: Vec<NetRod> = Vec::new();
    let mut index = BTreeMap::new();
    for (key, mut rod) in hi.rods {
        if let Some(coarse) = lo.rods.get(&key) {
            for (e, c) in rod.ends.iter_mut().zip(&coarse.ends) {
                if e.kind == EndKind::Boundary && c.kind == EndKind::Boundary {
                    e.param = (4.0 * e.param - c.param) / 3.0;
                    e.point = extrapolate(c.point, e.point);
                }
            }
            let n = rod.curve.len();
            rod.curve[0] = (rod.ends[0].param, rod.curve[0].1);
            rod.curve[n - 1] = (rod.ends[1].param, rod.curve[n - 1].1);
        }
        index.insert(key, rods.len());
        rods.push(rod);
    }
    let (mut error, mut change) = (0.0f64, 0.0f64);
    let mut crossings = Vec::new();
    for ((ku, kv), (p, angle)) in hi.crossings {
        let (Some(&ru), Some(&rv)) = (index.get(&(Family::U, ku)), index.get(&(Family::V, kv)))
        else {
            continue;
        };
        let point = match lo.crossings.get(&(ku, kv)) {
            Some((q, _)) => {
                error = error.max(norm(sub(p, *q)) / 3.0);
                let x = extrapolate(*q, p);
                change = change.max(norm(sub(x, p)));
                x
            }
            None => p,
        };
        let uv = [rods[rv].offset, rods[ru].offset];
        rods[ru].crossings.push(crossings.len());
        rods[rv].crossings.push(crossings.len());
        crossings.push(Crossing {
            rods: [ru, rv],
            uv,
            point,
            angle,
        });
    }
    for r in &mut rods {
        let along = |c: &usize| crossings[*c].uv[if r.family == Family::U { 0 } else { 1 }];
        r.crossings.sort_by(|x, y| along(x).total_cmp(&along(y)));
    }
    Net {
        spacing: a,
        layout,
        seed,
        rods,
        crossings,
        steps,
        construction_error: error,
        extrapolation_change: change,
    }
}

impl NetRod {
    /// The rod's point at net parameter `t`, interpolated along its finer curve.
    pub fn point_at(&self, t: f64) -> [f64; 3] {
        let c = &self.curve;
        let k = c.partition_point(|(p, _)| *p < t).clamp(1, c.len() - 1);
        let ((t0, p0), (t1, p1)) = (c[k - 1], c[k]);
        let f = if t1 > t0 { (t - t0) / (t1 - t0) } else { 0.0 };
        add(p0, scalef(sub(p1, p0), f))
    }

    pub fn length(&self) -> f64 {
        self.ends[1].param - self.ends[0].param
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gridshell::chebyshev::HemisphereNet;
    use crate::surface::shapes;

    /// The net of a hemisphere mesh against the analytic net (n rods per family, R = 1): the
    /// largest crossing distance and the largest rod-length error.
    pub(crate) fn hemisphere_error(n: usize, rings: usize, m: usize) -> (f64, f64, Net) {
        let s =
            Surface::from_obj("h.obj", &shapes::to_obj(&shapes::hemisphere(1.0, rings))).unwrap();
        let exact = HemisphereNet::new(1.0, n);
        let seed = Seed {
            origin: [0.0, 0.0, 1.0],
            d1: [1.0, 0.0, 0.0],
            d2: [0.0, 1.0, 0.0],
            min_angle: 10f64.to_radians(),
        };
        let layout = if n.is_multiple_of(2) {
            Layout::Between
        } else {
            Layout::On
        };
        let net = build(&s, &seed, exact.spacing, layout, m, usize::MAX).unwrap();
        let shift = (n / 2) as i64;
        let (mut dx, mut dl) = (0.0f64, 0.0f64);
        for c in &net.crossings {
            let (ru, rv) = (&net.rods[c.rods[0]], &net.rods[c.rods[1]]);
            let (i, j) = ((rv.k + shift) as usize, (ru.k + shift) as usize);
            dx = dx.max(norm(sub(c.point, exact.crossing(i, j))));
        }
        for r in &net.rods {
            let k = (r.k + shift) as usize;
            dl = dl.max((r.length() - 2.0 * exact.half_lengths[k]).abs());
        }
        (dx, dl, net)
    }

    #[test]
    fn a_hemisphere_mesh_gives_the_analytic_net_at_second_order_in_the_mesh() {
        // n = 12: every crossing and rod of the analytic net, at distances that fall about
        // fourfold per halving of the mesh's edges (docs/gridshell.md has the table).
        let mut last: Option<(f64, f64)> = None;
        for rings in [32, 64, 128] {
            let (dx, dl, net) = hemisphere_error(12, rings, DEFAULT_STEPS);
            assert_eq!((net.crossings.len(), net.rods.len()), (112, 24));
            if let Some((px, pl)) = last {
                assert!(
                    px / dx > 2.8 && pl / dl > 2.8,
                    "{rings}: {px} {dx} {pl} {dl}"
                );
            }
            if rings == 64 {
                // The extrapolated construction is converged well below the mesh's error:
                // doubling its steps moves no crossing by a fifth of it.
                let (_, _, finer) = hemisphere_error(12, rings, 2 * DEFAULT_STEPS);
                let moved = net
                    .crossings
                    .iter()
                    .zip(&finer.crossings)
                    .map(|(a, b)| norm(sub(a.point, b.point)))
                    .fold(0.0, f64::max);
                assert!(moved < 0.2 * dx, "{moved} against {dx}");
            }
            last = Some((dx, dl));
        }
        let (dx, dl) = last.unwrap();
        assert!(dx < 1.2e-4 && dl < 1.2e-4, "{dx} {dl}");
    }

    /// Hazzidakis on every full cell of spacing a of a compass net: the Gaussian curvature
    /// integrated over the cell (K at each fine cell's centre times its area) equals 2π minus
    /// its corner angles, ω10 + ω01 − ω00 − ω11. Returns the cells checked and the worst
    /// residual relative to the cell's total curvature.
    fn hazzidakis(
        mesh: shapes::Mesh,
        origin: [f64; 3],
        a: f64,
        gauss: &dyn Fn([f64; 3]) -> f64,
    ) -> (usize, f64) {
        let s = Surface::from_obj("s.obj", &shapes::to_obj(&mesh)).unwrap();
        let seed = Seed {
            origin,
            d1: [1.0, 0.0, 0.0],
            d2: [0.0, 1.0, 0.0],
            min_angle: 10f64.to_radians(),
        };
        let m = 16i64;
        let net = compass::build(&s, &seed, a, m as usize, 1000, usize::MAX).unwrap();
        let (mut worst, mut cells) = (0.0f64, 0);
        let reach = (2.0 / a).ceil() as i64;
        for cj in -reach..reach {
            for ci in -reach..reach {
                let corner = |di: i64, dj: i64| ((ci + di) * m, (cj + dj) * m);
                let full = (-1..=m + 1)
                    .all(|x| (-1..=m + 1).all(|y| net.at(ci * m + x, cj * m + y).is_some()));
                if !full {
                    continue;
                }
                let mut curvature = 0.0;
                for y in 0..m {
                    for x in 0..m {
                        let p =
                            |dx: i64, dy: i64| net.at(ci * m + x + dx, cj * m + y + dy).unwrap();
                        let d1 = sub(p(1, 1), p(0, 0));
                        let d2 = sub(p(0, 1), p(1, 0));
                        let centre =
                            scalef(add(add(p(0, 0), p(1, 1)), add(p(0, 1), p(1, 0))), 0.25);
                        curvature += gauss(centre) * 0.5 * norm(cross(d1, d2));
                    }
                }
                let w = |di: i64, dj: i64| {
                    let (i, j) = corner(di, dj);
                    angle(&net, i, j)
                };
                let angles = w(1, 0) + w(0, 1) - w(0, 0) - w(1, 1);
                worst = worst.max((angles - curvature).abs() / curvature.abs());
                cells += 1;
            }
        }
        (cells, worst)
    }

    #[test]
    fn net_cells_obey_hazzidakis() {
        let sphere = hazzidakis(
            shapes::hemisphere(1.0, 128),
            [0.0, 0.0, 1.0],
            std::f64::consts::PI / 13.0,
            &|_| 1.0,
        );
        // z = h (1 − r²): K = 4h² / (1 + 4h²r²)².
        let h = 0.6;
        let paraboloid = hazzidakis(shapes::paraboloid(1.0, h, 128), [0.0, 0.0, h], 0.2, &|p| {
            4.0 * h * h / (1.0 + 4.0 * h * h * (p[0] * p[0] + p[1] * p[1])).powi(2)
        });
        // z = (x² − y²)/(2R): K = −1 / (R² (1 + (x² + y²)/R²)²).
        let r = 1.5;
        let saddle = hazzidakis(shapes::saddle(1.0, r, 256), [0.0; 3], 0.2, &|p| {
            -1.0 / (r * r * (1.0 + (p[0] * p[0] + p[1] * p[1]) / (r * r)).powi(2))
        });
        for (name, (cells, worst)) in [
            ("sphere", sphere),
            ("paraboloid", paraboloid),
            ("saddle", saddle),
        ] {
            println!("{name}: {cells} cells, worst relative Hazzidakis residual {worst:.3e}");
            assert!(cells >= 50, "{name}: {cells}");
            assert!(worst < 5e-3, "{name}: {worst}");
        }
    }
}
