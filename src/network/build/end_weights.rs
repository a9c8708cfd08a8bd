//! End-corrected bending weights (Gregory's correction of the trapezoidal rule).
//!
//! The bending energy is a trapezoidal rule over the rod's vertices. A vertex frame (a clamp, a
//! joint's port, a rotational spring, a torque) splits the rod's stencil there into
//! half-stencils of weight h/2, and the moment is not smooth across it (it ends, or has a kink
//! or a jump): Euler–Maclaurin leaves an O(h²) term at each such side, the leading part of DER's
//! error constant on clamped and jointed rods (docs/performance.md, "Where DER's error constant
//! comes from"). Gregory's one-sided correction moves h/12 of each such half-stencil's weight to
//! the neighbouring vertex: 5h/12 and (h₀ + h₁)/2 + h/12. A stencil's weight is both the length
//! over which its turning angle is a curvature and its quadrature weight, so the bending energy
//! φ²/(2w) takes it in the denominator. The weights' sum is kept, so a constant curvature's
//! energy stays exact; only bending is corrected (a uniform twist stays exact with the plain
//! weights).
//!
//! Not corrected: free and pinned ends and vertices without a frame (ball joints, point loads:
//! no half-stencil), rods with `end_correction: false`, sides whose neighbour is itself at a
//! vertex frame or a rod end, closed rods, and two clamped ends that meet smoothly at their
//! targets (a rod closed into a ring by its clamps, Michell's ring): there the plain weights are
//! already the periodic rule.

use std::collections::{HashMap, HashSet};

use super::frames::Joined;
use super::geometry::Rest;
use super::nodes::Numbered;
use crate::math::vec::{dist, dot, rotate, sub};
use crate::scene::types::SupportKind;

/// The bending weights over the Voronoi lengths, where the correction changes them.
#[derive(Debug, Default)]
pub struct EndWeights {
    /// By (port index, edge): that half-stencil's factor (5/6 where corrected).
    port: HashMap<(usize, usize), f64>,
    /// By (rod, rod node): that inner vertex's factor.
    vertex: HashMap<(usize, usize), f64>,
}

impl EndWeights {
    pub fn port(&self, p: usize, edge: usize) -> f64 {
        self.port.get(&(p, edge)).copied().unwrap_or(1.0)
    }

    pub fn vertex(&self, rod: usize, node: usize) -> f64 {
        self.vertex.get(&(rod, node)).copied().unwrap_or(1.0)
    }
}

pub fn end_weights(rest: &Rest, net: &Numbered, joined: &Joined) -> EndWeights {
    let junctions = smooth_junctions(rest);
    let mut out = EndWeights::default();
    for (pi, p) in joined.table.ports.iter().enumerate() {
        let (r, j) = (p.rod, p.node);
        let rod = &net.rods[r];
        let np = rod.nodes.len();
        if !rest.scene.rods[r].end_correction || rod.closed || junctions.contains(&(r, j)) {
            continue;
        }
        // Each side of the frame whose neighbour is a regular inner vertex: the stencil there
        // weighs (h + h₁)/2, h the edge between them and h₁ the edge beyond.
        let before = (j > 0).then(|| (rod.edges[j - 1], j - 1, j.checked_sub(2)));
        let after = (j + 1 < np).then(|| (rod.edges[j], j + 1, Some(j + 1)));
        for (e, nb, beyond) in before.into_iter().chain(after) {
            let Some(e2) = beyond.and_then(|k| rod.edges.get(k).copied()) else {
                continue;
            };
            if nb == 0 || nb + 1 == np || joined.table.port_of.contains_key(&(r, nb)) {
                continue;
            }
            let (h, h1) = (net.rest_lengths[e], net.rest_lengths[e2]);
            out.port.insert((pi, e), 5.0 / 6.0);
            *out.vertex.entry((r, nb)).or_insert(1.0) += h / 12.0 / (0.5 * (h + h1));
        }
    }
    out
}

/// A clamped rod end at its target: (rod, rod node), position, outward unit tangent.
struct ClampedEnd {
    site: (usize, usize),
    at: [f64; 3],
    outward: [f64; 3],
}

/// Clamped rod ends whose targets meet another clamped end's in position with a continuous
/// tangent (the one end's outward tangent opposite the other's).
fn smooth_junctions(rest: &Rest) -> HashSet<(usize, usize)> {
    let ends: Vec<ClampedEnd> = rest
        .scene
        .supports
        .iter()
        .filter(|s| s.kind == SupportKind::Clamp)
        .filter_map(|s| {
            let (r, j) = rest.site(&s.rod, s.vertex);
            if !rest.is_end(r, j) {
                return None;
            }
            let nodes = &rest.nodes[r];
            let inner = if j == 0 { 1 } else { j - 1 };
            let out_dir = sub(nodes[j], nodes[inner]);
            let len = dot(out_dir, out_dir).sqrt();
            let w = s.rotate_by.unwrap_or([0.0; 3]);
            Some(ClampedEnd {
                site: (r, j),
                at: s.move_to.unwrap_or(nodes[j]),
                outward: rotate(w, out_dir.map(|x| x / len)),
            })
        })
        .collect();
    let tol = 1e-9 * rest.length_scale.max(f64::MIN_POSITIVE);
    // Ends within `tol` of each other fall in the same or neighbouring cells of size `tol`: a
    // scene with many clamps is not compared pair by pair.
    let cell = |p: [f64; 3]| p.map(|x| (x / tol).floor() as i64);
    let mut grid: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
    for (k, e) in ends.iter().enumerate() {
        grid.entry(cell(e.at)).or_default().push(k);
    }
    let mut out = HashSet::new();
    for (k, a) in ends.iter().enumerate() {
        let c = cell(a.at);
        for d in 0..27 {
            let key = [c[0] + d % 3 - 1, c[1] + (d / 3) % 3 - 1, c[2] + d / 9 - 1];
            for &m in grid.get(&key).into_iter().flatten().filter(|&&m| m > k) {
                let b = &ends[m];
                let continuous = dist(&a.outward, &b.outward.map(|x| -x)) <= 1e-8;
                if a.site != b.site && dist(&a.at, &b.at) <= tol && continuous {
                    out.extend([a.site, b.site]);
                }
            }
        }
    }
    out
}
