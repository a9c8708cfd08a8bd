//! The gauge of an unsupported structure: with no support, obstacle or bound, a rigid
//! translation changes neither the elastic energy nor (loads being balanced, which validation
//! checks) the loads' potential, so the Hessian is singular along it. One node, the one nearest
//! the rest shape's centroid, is held in place: that removes the three translations without
//! changing any equilibrium (its reaction is the loads' net force, zero). Rigid rotations are
//! left free: under dead loads they have a stiffness of their own, which decides stability.

use super::nodes::Numbered;
use crate::network::info::Gauge;
use crate::scene::Scene;
use crate::variables::DofLayout;

pub fn apply(
    scene: &Scene,
    net: &Numbered,
    layout: &DofLayout,
    fixed: &mut [bool],
) -> Option<Gauge> {
    if !(scene.supports.is_empty() && scene.obstacles.is_empty() && scene.bounds.is_empty()) {
        return None;
    }
    let n = net.n_nodes() as f64;
    let c = net.rest_pos.iter().fold([0.0; 3], |a, p| {
        [a[0] + p[0] / n, a[1] + p[1] / n, a[2] + p[2] / n]
    });
    let dist = |p: &[f64; 3]| (0..3).map(|k| (p[k] - c[k]).powi(2)).sum::<f64>();
    let node = (0..net.n_nodes())
        .min_by(|&a, &b| dist(&net.rest_pos[a]).total_cmp(&dist(&net.rest_pos[b])))?;
    let (rod, index) = net.rods.iter().find_map(|r| {
        r.nodes
            .iter()
            .position(|&m| m == node)
            .map(|i| (r.name.clone(), i))
    })?;
    for k in 0..3 {
        fixed[layout.node_coord(node, k)] = true;
    }
    Some(Gauge { node, rod, index })
}
