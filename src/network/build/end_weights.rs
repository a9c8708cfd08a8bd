//! End-corrected bending weights (Gregory's correction of the trapezoidal rule).
//!
//! The bending energy is a trapezoidal rule over the rod's vertices: a rod that ends at a vertex
//! frame (a clamp, a joint, a rotational spring or a torque) has a half-stencil of weight h/2
//! there, and Euler–Maclaurin leaves an O(h²) term at that end, the leading part of DER's error
//! constant on clamped and jointed rods (docs/performance.md, "Where DER's error constant comes
//! from"). Gregory's one-sided correction moves h/12 of the end half-stencil's weight to the next
//! vertex: 5h/12 and (h₀ + h₁)/2 + h/12. A stencil's weight is both the length over which its
//! turning angle is a curvature and its quadrature weight, so the bending energy φ²/(2w) takes
//! it in the denominator. The weights' sum is kept, so a constant curvature stays exact; only
//! bending is corrected (a uniform twist stays exact with the plain weights).
//!
//! Not corrected: free and pinned ends (no half-stencil: the moment and its virtual work vanish
//! there), rods with `end_correction: false`, ends whose next vertex is itself at a vertex frame,
//! rods of one edge, and two clamped ends that meet smoothly at their targets (a rod closed into
//! a ring by its clamps, Michell's ring): there the plain weights are already the periodic rule.

use std::collections::HashMap;

use super::frames::Joined;
use super::geometry::Rest;
use super::nodes::Numbered;
use crate::math::vec::{dist, dot, rotate, sub};
use crate::scene::types::SupportKind;

/// The bending weights over the Voronoi lengths, where the correction changes them.
#[derive(Debug, Default)]
pub struct EndWeights {
    /// By port index: its half-stencil's factor (5/6 where corrected).
    port: HashMap<usize, f64>,
    /// By (rod, rod node): that inner vertex's factor.
    vertex: HashMap<(usize, usize), f64>,
}

impl EndWeights {
    pub fn port(&self, p: usize) -> f64 {
        self.port.get(&p).copied().unwrap_or(1.0)
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
        if !rest.scene.rods[r].end_correction || rod.closed || np < 3 || junctions.contains(&(r, j))
        {
            continue;
        }
        let (end_edge, next_edge, next) = match j {
            0 => (rod.edges[0], rod.edges[1], 1),
            _ if j + 1 == np => (rod.edges[np - 2], rod.edges[np - 3], np - 2),
            _ => continue,
        };
        if joined.table.port_of.contains_key(&(r, next)) {
            continue;
        }
        let (h, h1) = (net.rest_lengths[end_edge], net.rest_lengths[next_edge]);
        out.port.insert(pi, 5.0 / 6.0);
        let voronoi = 0.5 * (h + h1);
        *out.vertex.entry((r, next)).or_insert(1.0) += h / 12.0 / voronoi;
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
fn smooth_junctions(rest: &Rest) -> Vec<(usize, usize)> {
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
    let mut out = Vec::new();
    for (k, a) in ends.iter().enumerate() {
        for b in &ends[k + 1..] {
            let continuous = dist(&a.outward, &b.outward.map(|x| -x)) <= 1e-8;
            if a.site != b.site && dist(&a.at, &b.at) <= tol && continuous {
                out.extend([a.site, b.site]);
            }
        }
    }
    out
}
