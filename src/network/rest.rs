//! Rods in their rest shape: subdivided nodes, edges with their rest reference frames (space-
//! parallel transport along the rod from the first edge), and the rest frame of a vertex.

use crate::math::vec::*;
use crate::rod::frames::EdgeRef;
use crate::scene::types::Rod;

/// Rest nodes of a rod: every input segment split into `subdivide` equal edges.
pub fn rod_nodes(rod: &Rod) -> Vec<[f64; 3]> {
    let s = rod.subdivide;
    let m = rod.points.len();
    let segs = if rod.closed { m } else { m - 1 };
    let mut pts = Vec::with_capacity(segs * s + 1);
    for k in 0..segs {
        let (a, b) = (rod.points[k], rod.points[(k + 1) % m]);
        for j in 0..s {
            pts.push(add(a, scalef(sub(b, a), j as f64 / s as f64)));
        }
    }
    if !rod.closed {
        pts.push(rod.points[m - 1]);
    }
    pts
}

/// Rest reference frames of a rod's edges: the first edge's director is `normal` projected
/// normal to it (or a deterministic perpendicular), then space-parallel transported.
pub fn rod_edge_frames(pts: &[[f64; 3]], closed: bool, normal: Option<[f64; 3]>) -> Vec<EdgeRef> {
    let np = pts.len();
    let ne = if closed { np } else { np - 1 };
    let mut out: Vec<EdgeRef> = Vec::with_capacity(ne);
    for k in 0..ne {
        let t = normalize(sub(pts[(k + 1) % np], pts[k]));
        let u = match out.last() {
            None => match normal {
                Some(n) => normalize(sub(n, scalef(t, dot(n, t)))),
                None => any_perpendicular(t),
            },
            Some(p) => normalize(transport(p.t, t, p.u)),
        };
        out.push(EdgeRef { t, u });
    }
    out
}

/// Rest frame (d1, d2, d3 = tangent) of a rod at its node `j`, given the rest frames of its
/// incoming and outgoing edges: at an end, the edge's own frame; inside, the incoming frame
/// transported to the bisecting tangent, so that both half-stencils see half the turning.
pub fn vertex_frame(e_in: Option<EdgeRef>, e_out: Option<EdgeRef>) -> Frame {
    match (e_in, e_out) {
        (Some(i), Some(o)) => {
            let tv = normalize(add(i.t, o.t));
            let d1 = normalize(transport(i.t, tv, i.u));
            [d1, cross(tv, d1), tv]
        }
        (Some(r), None) | (None, Some(r)) => [r.u, cross(r.t, r.u), r.t],
        (None, None) => unreachable!("a rod has at least one edge"),
    }
}

pub fn bbox_diagonal<'a>(points: impl Iterator<Item = &'a [f64; 3]>) -> f64 {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in points {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    norm(sub(hi, lo))
}
