//! The potential of the dead nodal loads, measured from the rest configuration.
//!
//! The solver's `PointLoad` term is −λ f·x, measured from the coordinate origin: its gradient is
//! all Newton needs, and a constant does not matter there. As a reported energy it does: lifting
//! a structure by 100 m would change its total energy by the load times 100 m. Reported here is
//! −λ f·(x − x̄), minus the work the loads have done from the rest positions x̄, so the energy
//! does not depend on where the scene sits. (Torques are already measured from rest: their
//! potential uses the frame's accumulated rotation.)

use crate::network::rest::rod_nodes;
use crate::network::Network;
use crate::scene::Scene;

/// −λ Σ f·(x − x̄) over the point loads of `net`, J.
pub fn from_rest(net: &Network, scene: &Scene) -> f64 {
    let m = &net.model;
    let mut rest: Vec<Option<[f64; 3]>> = vec![None; m.layout.n_nodes()];
    for (info, rod) in net.rods.iter().zip(&scene.rods) {
        for (&node, p) in info.nodes.iter().zip(rod_nodes(rod)) {
            rest[node].get_or_insert(p);
        }
    }
    let lambda = m.state.load_factor;
    let mut e = 0.0;
    for load in &m.terms.loads {
        let Some(node) = m.layout.node_of(load.vars[0]) else {
            continue;
        };
        // Loads act on rod nodes, which all have a rest position.
        debug_assert!(
            rest[node].is_some(),
            "a loaded node without a rest position"
        );
        let x0 = rest[node].unwrap_or([0.0; 3]);
        let x = m.world_position(node);
        for k in 0..3 {
            e -= lambda * load.force[k] * (x[k] - x0[k]);
        }
    }
    e
}
