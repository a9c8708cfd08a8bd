use std::collections::HashMap;

use super::{
    direction, finite3, segments, InJoint, RodIndex, MAX_MAGNITUDE, MAX_NODES, MIN_DIRECTION,
};
use crate::math::vec::{cross, dist, dot, norm, sub};
use crate::scene::types::{Rod, Scene};
use crate::scene::FieldError;

/// Checks every rod and returns them by name for the sections that refer to them.
pub(super) fn rods(s: &Scene) -> Result<RodIndex<'_>, FieldError> {
    if s.rods.is_empty() {
        return Err(FieldError::global(
            "rods",
            "",
            "the scene has no rods; there is nothing to solve".into(),
        ));
    }
    let mut rods: HashMap<&str, &Rod> = HashMap::new();
    let mut total_nodes = 0usize;
    let origin = crate::scene::translate::origin(s);
    for (i, r) in s.rods.iter().enumerate() {
        let err = |f: &str, msg: String| Err(FieldError::new("rods", i, f, msg));
        if r.name.is_empty() {
            return err("name", "must not be empty".into());
        }
        // Names are written into OBJ, CSV and scripts line by line, where a control character
        // (a newline, a NUL) would end or corrupt a line.
        if let Some((k, c)) = r.name.chars().enumerate().find(|(_, c)| c.is_control()) {
            return err(
                "name",
                format!(
                    "must not hold control characters, got {c:?} at character {k} of {:?}",
                    r.name
                ),
            );
        }
        if rods.insert(r.name.as_str(), r).is_some() {
            return err("name", format!("duplicate rod name \"{}\"", r.name));
        }
        if !s.materials.contains_key(&r.material) {
            let known: Vec<&String> = s.materials.keys().collect();
            return err(
                "material",
                format!("unknown material \"{}\" (defined: {known:?})", r.material),
            );
        }
        if let Err(m) = points(r) {
            return err("points", m);
        }
        if r.subdivide == 0 {
            return err("subdivide", "must be at least 1".into());
        }
        let nodes = segments(r).saturating_mul(r.subdivide).saturating_add(1);
        total_nodes = total_nodes.saturating_add(nodes);
        if total_nodes > MAX_NODES {
            return err("subdivide", format!(
                "the scene would have more than {MAX_NODES} nodes; reduce `subdivide` (limit in docs/scene-format.md)"
            ));
        }
        if let Err(m) = resolution(r, origin) {
            return err("points", m);
        }
        if let Some(n) = r.normal {
            if !normal_ok(r, n) {
                return err(
                    "normal",
                    format!(
                        "must be finite and not parallel to the first edge (a direction of \
                         length at least {MIN_DIRECTION:e}), got {n:?}"
                    ),
                );
            }
        }
    }
    Ok(RodIndex(rods))
}

/// Rest length of a rod through its input points.
pub(super) fn length(r: &Rod) -> f64 {
    let m = r.points.len();
    let mut length = 0.0;
    for k in 0..segments(r) {
        length += dist(&r.points[k], &r.points[(k + 1) % m]);
    }
    length
}

/// The checks of a rod's `points`: enough of them, finite, and a polyline that neither has a
/// zero-length segment nor folds back on itself.
fn points(r: &Rod) -> Result<(), String> {
    let min_points = if r.closed { 3 } else { 2 };
    if r.points.len() < min_points {
        return Err(format!(
            "needs at least {min_points} points, got {}",
            r.points.len()
        ));
    }
    if let Some(k) = r.points.iter().position(|p| !finite3(p)) {
        return Err(format!(
            "point {k} is not finite (or above {MAX_MAGNITUDE:e} m): {:?}",
            r.points[k]
        ));
    }
    let m = r.points.len();
    let length = length(r);
    if r.closed && dist(&r.points[0], &r.points[m - 1]) <= 1e-12 * length {
        return Err(format!(
            "the last point repeats the first; a closed rod connects point {} back to \
             point 0 by itself, so leave the repeated point out",
            m - 1
        ));
    }
    for k in 0..segments(r) {
        let l = dist(&r.points[k], &r.points[(k + 1) % m]);
        if l <= 1e-12 * length {
            return Err(format!(
                "points {k} and {} coincide (zero-length segment)",
                (k + 1) % m
            ));
        }
    }
    let range = if r.closed { 0..m } else { 1..m - 1 };
    for k in range {
        let (a, b, c) = (
            &r.points[(k + m - 1) % m],
            &r.points[k],
            &r.points[(k + 1) % m],
        );
        let cosang = dot(sub(*b, *a), sub(*c, *b)) / (dist(a, b) * dist(b, c));
        if cosang < -0.99985 {
            return Err(format!(
                "the rod folds back on itself at point {k} (turning angle above 179°); split it into two rods joined there"
            ));
        }
    }
    Ok(())
}

/// Shortest edge accepted, in units of the rounding of the coordinates it is solved in: at
/// 1000 roundings an edge's length, strain and turning angle are known to 0.1 %; below, the
/// doubles no longer resolve the rod and Newton's steps are made of round-off.
const MIN_EDGE_ROUNDINGS: f64 = 1e3;

/// The edges of a rod (its segments cut in `subdivide`) must be long against the rounding of
/// the coordinates the network is solved in (relative to `origin`, `scene::translate`): a rod
/// far from the rest of the scene cannot be moved near the origin with it.
fn resolution(r: &Rod, origin: [f64; 3]) -> Result<(), String> {
    let m = r.points.len();
    let far = |k: usize| (0..3).fold(0.0_f64, |a, i| a.max((r.points[k][i] - origin[i]).abs()));
    for k in 0..segments(r) {
        let j = (k + 1) % m;
        let edge = dist(&r.points[k], &r.points[j]) / r.subdivide as f64;
        let (at, x) = if far(k) >= far(j) {
            (k, far(k))
        } else {
            (j, far(j))
        };
        let rounding = x * f64::EPSILON;
        if edge < MIN_EDGE_ROUNDINGS * rounding {
            return Err(format!(
                "point {at} {:?} is {x:.3e} m from where the scene is solved ({origin:?}), where \
                 doubles round to {rounding:.1e} m: too coarse for this rod's edges of {edge:.3e} m \
                 (at least {MIN_EDGE_ROUNDINGS:e} roundings needed); draw the scene's rods near \
                 each other, or nearer the origin",
                r.points[at]
            ));
        }
    }
    Ok(())
}

/// A rod's `normal` must give a material axis: finite and not along the first edge.
fn normal_ok(r: &Rod, n: [f64; 3]) -> bool {
    let t = sub(r.points[1], r.points[0]);
    let nn = norm(n);
    direction(&n) && norm(cross(t, n)) > 1e-8 * nn * dist(&r.points[1], &r.points[0])
}

/// Two non-adjacent points of one rod at the same place would make two nodes sit on each other
/// with nothing between them; that is only meaningful when a joint ties them together.
pub(super) fn repeated_points(s: &Scene, in_joint: &InJoint) -> Result<(), FieldError> {
    for (i, r) in s.rods.iter().enumerate() {
        let m = r.points.len();
        let tol = 1e-12 * length(r);
        let mut order: Vec<usize> = (0..m).collect();
        order.sort_by(|&a, &b| r.points[a][0].total_cmp(&r.points[b][0]));
        for (oi, &a) in order.iter().enumerate() {
            for &b in &order[oi + 1..] {
                if r.points[b][0] - r.points[a][0] > tol {
                    break;
                }
                if dist(&r.points[a], &r.points[b]) > tol {
                    continue;
                }
                let (lo, hi) = (a.min(b), a.max(b));
                let joined = match (
                    in_joint.get(&(r.name.as_str(), lo)),
                    in_joint.get(&(r.name.as_str(), hi)),
                ) {
                    (Some(x), Some(y)) => x == y,
                    _ => false,
                };
                if !joined {
                    return Err(FieldError::new(
                        "rods",
                        i,
                        "points",
                        format!(
                            "points {lo} and {hi} are at the same place {:?}; if the rod crosses \
                             itself there, join the two vertices with a Joint, otherwise move one",
                            r.points[lo]
                        ),
                    ));
                }
            }
        }
    }
    Ok(())
}
