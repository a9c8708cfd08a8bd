//! Bending strain and stress at rod vertices. The strain comes from the change of the material
//! curvatures (κ1, κ2) from the rest shape, so a rod drawn curved is unstressed at rest; the
//! curvature density is the integrated curvature over the stencil's weight (the rest Voronoi
//! length, end-corrected beside vertex frames), as in the bending energy. Vertices at a clamp or
//! joint take their curvature from the half-stencils between the vertex frame and each incident
//! edge (the largest side), so clamped ends are not reported as unstressed; only free ends are.

use crate::energy::{frame_twist::FrameTwist, twist::Twist, Term};
use crate::math::vec::{cross, dot, norm, sub};
use crate::network::info::RodInfo;
use crate::network::Network;
use crate::rod::section::Section;

/// Bending at one rod node.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VertexBending {
    /// Curvature of the deformed centreline 2 sin(φ/2)/l̄, 1/m.
    pub curvature: f64,
    /// Extreme-fibre bending strain from the curvature change.
    pub strain: f64,
    /// Bending stress, Pa.
    pub stress: f64,
}

/// Extreme-fibre strain of a curvature change (Δκ1, Δκ2) in 1/m: the largest of
/// Δκ1·y1 + Δκ2·y2 over the section, with y1 along m1.
fn extreme_strain(section: &Section, dk: [f64; 2]) -> f64 {
    match *section {
        Section::Circle { radius } => radius * (dk[0] * dk[0] + dk[1] * dk[1]).sqrt(),
        Section::Ellipse { a, b } => ((a * dk[0]).powi(2) + (b * dk[1]).powi(2)).sqrt(),
        Section::Rectangle { width, height } => 0.5 * (width * dk[0].abs() + height * dk[1].abs()),
    }
}

/// Strain of one bending stencil: the two material frames (edges, or frame and edge) enter
/// the energy with equal weight, so their strains are combined in the root mean square.
fn stencil_strain(section: &Section, k: [[f64; 2]; 2], rest: [[f64; 2]; 2], voronoi: f64) -> f64 {
    let e = |j: usize| {
        extreme_strain(
            section,
            [
                (k[j][0] - rest[j][0]) / voronoi,
                (k[j][1] - rest[j][1]) / voronoi,
            ],
        )
    };
    (0.5 * (e(0).powi(2) + e(1).powi(2))).sqrt()
}

/// Bending strain at every node of every rod, and the factor on its Voronoi length that its
/// bending stencil weighs (1 but beside a vertex frame, `build/end_weights.rs`),
/// indexed like `net.rods`.
fn strains(net: &Network) -> (Vec<Vec<f64>>, Vec<Vec<f64>>) {
    let m = &net.model;
    let st = &m.state;
    // Rod and position along it of each global edge.
    let mut at_edge = vec![(usize::MAX, 0usize); m.edge_nodes.len()];
    for (r, info) in net.rods.iter().enumerate() {
        for (k, &e) in info.edges.iter().enumerate() {
            at_edge[e] = (r, k);
        }
    }
    let mut out: Vec<Vec<f64>> = net.rods.iter().map(|r| vec![0.0; r.nodes.len()]).collect();
    let mut weights: Vec<Vec<f64>> = net.rods.iter().map(|r| vec![1.0; r.nodes.len()]).collect();
    for b in m.terms.bend_twist.iter().map(|s| &s.bend) {
        let (r, k) = at_edge[b.edges[1]];
        let voronoi = 0.5 * (m.rest_lengths[b.edges[0]] + m.rest_lengths[b.edges[1]]);
        if let Some(w) = weights.get_mut(r).and_then(|n| n.get_mut(k)) {
            *w = b.voronoi / voronoi;
        }
    }
    let mut put = |r: usize, j: usize, v: f64| {
        if let Some(x) = out.get_mut(r).and_then(|n| n.get_mut(j)) {
            *x = x.max(v);
        }
    };
    for b in m.terms.bend_twist.iter().map(|s| &s.bend) {
        // The stencil's vertex is where its outgoing edge starts.
        let (r, k) = at_edge[b.edges[1]];
        let Some(info) = net.rods.get(r) else {
            continue;
        };
        let k_now = b.curvatures::<f64>(st, &Twist::reduced(&b.gather(&st.q)));
        put(
            r,
            k,
            stencil_strain(&info.section, k_now, b.rest, b.voronoi),
        );
    }
    for f in m.terms.frame_bend_twist.iter().map(|f| &f.bend) {
        let (r, k) = at_edge[f.edge];
        let Some(info) = net.rods.get(r) else {
            continue;
        };
        // An incoming edge (sign −1) ends at the vertex, an outgoing one starts there.
        let j = if f.sign < 0.0 {
            (k + 1) % info.nodes.len()
        } else {
            k
        };
        let k_now = f.curvatures::<f64>(st, &FrameTwist::reduced(&f.gather(&st.q)));
        put(
            r,
            j,
            stencil_strain(&info.section, k_now, f.rest, f.voronoi),
        );
    }
    (out, weights)
}

/// Bending at every node of every rod, indexed like `net.rods` (one pass over the terms).
pub fn all_vertex_bending(net: &Network) -> Vec<Vec<VertexBending>> {
    let (s, w) = strains(net);
    net.rods
        .iter()
        .zip(s.iter().zip(&w))
        .map(|(rod, (st, w))| bending_with(net, rod, st, w))
        .collect()
}

fn bending_with(
    net: &Network,
    rod: &RodInfo,
    strain: &[f64],
    weight: &[f64],
) -> Vec<VertexBending> {
    let pos = |n: usize| net.model.position(n);
    let np = rod.nodes.len();
    (0..np)
        .map(|j| {
            let eps = strain.get(j).copied().unwrap_or(0.0);
            let has_prev = rod.closed || j > 0;
            let has_next = rod.closed || j + 1 < np;
            let kappa = if has_prev && has_next {
                let a = pos(rod.nodes[(j + np - 1) % np]);
                let b = pos(rod.nodes[j]);
                let d = pos(rod.nodes[(j + 1) % np]);
                let (e0, e1) = (sub(b, a), sub(d, b));
                let (l0, l1) = (norm(e0), norm(e1));
                // atan2 keeps small angles accurate; acos of the cosine lost them to
                // round-off as ε/φ² (1e-7 relative at φ = 5e-5).
                let phi = norm(cross(e0, e1)).atan2(dot(e0, e1));
                let w = weight.get(j).copied().unwrap_or(1.0);
                2.0 * (0.5 * phi).sin() / (0.5 * (l0 + l1) * w)
            } else {
                0.0
            };
            VertexBending {
                curvature: kappa,
                strain: eps,
                stress: eps * rod.young_modulus,
            }
        })
        .collect()
}
