//! A load stage (`stages`): the stage's network starts in the previous stage's equilibrium,
//! and its load terms are ramped from the previous stage's values to its own (`Model::ramp`),
//! so that the continuation follows the added loads only.

use std::collections::BTreeMap;

use crate::energy::point_load::PointLoad;
use crate::network::initial::{place, RodState};
use crate::network::model::LoadRamp;
use crate::network::Network;

/// Puts `next` (the scene of the next stage: the same rods, more loads) in `prev`'s state and
/// sets its load ramp.
pub fn start_from(prev: &Network, next: &mut Network) -> Result<(), String> {
    if prev.model.layout == next.model.layout {
        next.model.state = prev.model.state.clone();
    } else {
        // A torque on a new vertex adds a frame: carry positions and twists, and let
        // `place` turn the frames.
        place(next, &rod_states(prev))?;
    }
    let m = &mut next.model;
    let node = |l: &PointLoad| {
        prev.model
            .layout
            .node_of(l.vars[0])
            .expect("a point load acts on a node")
    };
    let mut before: BTreeMap<usize, [f64; 3]> = prev
        .model
        .terms
        .loads
        .iter()
        .map(|l| (node(l), l.force))
        .collect();
    let mut ramp = LoadRamp::default();
    for l in &m.terms.loads {
        ramp.loads
            .push([before.remove(&node(l)).unwrap_or([0.0; 3]), l.force]);
    }
    // Loads the stage cancels (its own opposite a node's earlier load) go to zero.
    for (n, f) in before {
        m.terms.loads.push(PointLoad {
            vars: m.layout.node(n),
            force: [0.0; 3],
        });
        ramp.loads.push([f, [0.0; 3]]);
    }
    // Stages only add loads, so the earlier torques are the first ones, in the same order.
    for (i, t) in m.terms.torques.iter().enumerate() {
        let from = prev
            .model
            .terms
            .torques
            .get(i)
            .map_or([0.0; 3], |p| p.torque);
        ramp.torques.push([from, t.torque]);
    }
    m.ramp = Some(ramp);
    m.set_load(0.0);
    Ok(())
}

fn rod_states(net: &Network) -> Vec<RodState> {
    let m = &net.model;
    net.rods
        .iter()
        .map(|r| RodState {
            name: r.name.clone(),
            points: r.nodes.iter().map(|&n| m.world_position(n)).collect(),
            twist: r
                .edges
                .iter()
                .map(|&e| m.state.q[m.layout.theta(e)])
                .collect(),
        })
        .collect()
}
