//! The active contacts and bounds of a solved state held as constraints, for an eigen-analysis
//! (`--modes` with contact): each node in contact is held on the tangent plane of its active
//! constraints (as a slanted roller, `network/roller.rs`), and the curvature of a curved obstacle
//! enters through the multiplier, −μ∇²c, the Hessian of the Lagrangian E − μc along the surface
//! (a node pressed onto a ball of radius d loses μ/d of stiffness along it). Contacts that carry
//! no force are free: the modes are those of the structure with its active set fixed.

use std::collections::BTreeMap;

use crate::energy::spring::Spring;
use crate::math::vec::{any_perpendicular, cross, norm, normalize, scalef};
use crate::network::equilibrium::ConstraintForces;
use crate::network::roller::{
    holding_spring, holding_stiffness, orthonormal, Rollers, SlantedRoller,
};
use crate::network::Network;

/// A copy of `net` without its contact and bounds, its active constraints held. Returns the
/// copy and the number of nodes held by contact.
pub fn hold_active(net: &Network, forces: &ConstraintForces) -> (Network, usize) {
    let mut held = net.clone();
    let Some(contact) = held.model.contact.take() else {
        return (held, 0);
    };
    let m = &mut held.model;
    let q = m.state.q.clone();
    let mut normals: BTreeMap<usize, Vec<[f64; 3]>> = BTreeMap::new();
    for r in &m.rollers.list {
        normals.entry(r.node).or_default().extend(&r.normals);
    }
    let mut in_contact = 0;
    for f in &forces.contacts {
        let Some(node) = net.rod(&f.rod).and_then(|r| r.nodes.get(f.node)).copied() else {
            continue;
        };
        let mu = norm(f.force);
        if mu == 0.0 {
            continue;
        }
        let n = scalef(f.force, 1.0 / mu);
        let list = normals.entry(node).or_default();
        in_contact += usize::from(list.is_empty());
        list.push(n);
        let row = contact
            .rows
            .iter()
            .find(|r| r.node == node && r.source == f.source);
        if let Some((d, axis)) = row.and_then(|r| r.curvature(&contact, &q)) {
            m.terms
                .springs
                .push(surface_curvature(m.layout.node(node), n, axis, mu / d, &q));
        }
    }
    let s = holding_stiffness(&m.terms);
    m.terms.roller_normals.clear();
    let mut list = Vec::new();
    for (node, ns) in normals {
        let vars = m.layout.node(node);
        let x = m.layout.position(&q, node);
        let roller = SlantedRoller::new(node, vars, orthonormal(&ns), [x, x]);
        m.terms.roller_normals.push(holding_spring(&roller, s));
        list.push(roller);
    }
    m.rollers = Rollers::new(list, q.len());
    (held, in_contact)
}

/// −μ/d along the surface's curved tangent directions (both on a ball; the one across the axis
/// on a cylinder), as a spring of negative stiffness anchored where the node is.
fn surface_curvature(
    vars: [usize; 3],
    n: [f64; 3],
    axis: Option<[f64; 3]>,
    k: f64,
    q: &[f64],
) -> Spring {
    let x = std::array::from_fn(|i| q[vars[i]]);
    let (a, stiff_a) = match axis {
        Some(a) => (a, 0.0),
        None => (normalize(any_perpendicular(n)), -k),
    };
    // On a cylinder the second tangent is the one across the axis.
    let b = normalize(cross(n, a));
    let a = normalize(cross(b, n));
    Spring {
        vars,
        stiffness: [0.0, stiff_a, -k],
        axes: [n, a, b],
        anchor: [x, x],
    }
}
