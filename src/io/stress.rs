//! Bending strain and stress at rod vertices from the discrete curvature: the curvature density
//! κ/l̄ (l̄ the Voronoi length) times the extreme-fibre distance along each material axis.

use crate::math::vec::{norm, sub};
use crate::network::build::{Network, RodInfo};

/// Pointwise (κ density, max fibre strain, max fibre stress) at each node of a rod.
pub fn vertex_bending(net: &Network, rod: &RodInfo) -> Vec<(f64, f64, f64)> {
    let q = &net.model.state.q;
    let pos = |n: usize| [q[3 * n], q[3 * n + 1], q[3 * n + 2]];
    let np = rod.nodes.len();
    let (h1, h2) = rod.section.half_extents();
    let c = h1.max(h2);
    (0..np)
        .map(|j| {
            let has_prev = rod.closed || j > 0;
            let has_next = rod.closed || j + 1 < np;
            if !(has_prev && has_next) {
                return (0.0, 0.0, 0.0);
            }
            let a = pos(rod.nodes[(j + np - 1) % np]);
            let b = pos(rod.nodes[j]);
            let d = pos(rod.nodes[(j + 1) % np]);
            let (e0, e1) = (sub(b, a), sub(d, b));
            let (l0, l1) = (norm(e0), norm(e1));
            let cosang = (e0[0] * e1[0] + e0[1] * e1[1] + e0[2] * e1[2]) / (l0 * l1);
            let phi = cosang.clamp(-1.0, 1.0).acos();
            let kappa = 2.0 * (0.5 * phi).sin() / (0.5 * (l0 + l1));
            let strain = kappa * c;
            (kappa, strain, strain * rod.young_modulus)
        })
        .collect()
}

pub fn max_bending_stress(net: &Network, rod: &RodInfo) -> f64 {
    vertex_bending(net, rod)
        .iter()
        .map(|v| v.2)
        .fold(0.0, f64::max)
}
