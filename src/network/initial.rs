//! Starting a solve from an earlier equilibrium of the same scene (`rodnet solve --initial`):
//! node positions and twist angles, checked rod by rod against the built network.

use crate::math::vec::{add, normalize, rotation_between, scalef, sub};
use crate::network::Network;
use crate::rod::frames::{canonical_directors, EdgeRef};

/// One rod of an earlier result: its nodes (after subdivision) and edge twist angles.
#[derive(Debug, Clone, PartialEq)]
pub struct RodState {
    pub name: String,
    pub points: Vec<[f64; 3]>,
    /// Empty: keep the network's own (zero) angles.
    pub twist: Vec<f64>,
}

/// Puts the network in the state `rods` describe. Every rod of the network must be there with
/// as many nodes (and edges, when twist is given), and the nodes that rods share (joints) must
/// agree; nothing is changed otherwise.
pub fn place(net: &mut Network, rods: &[RodState]) -> Result<(), String> {
    let layout = net.model.layout;
    let mut q = net.model.state.q.clone();
    let mut seen: Vec<Option<(usize, [f64; 3])>> = vec![None; layout.n_nodes()];
    let scale = (0..layout.n_nodes())
        .map(|n| {
            let p = net.model.world_position(n);
            p[0].abs().max(p[1].abs()).max(p[2].abs())
        })
        .fold(1e-300, f64::max);
    for (ri, info) in net.rods.iter().enumerate() {
        let Some(r) = rods.iter().find(|r| r.name == info.name) else {
            return Err(format!(
                "rod \"{}\" is not in the initial results",
                info.name
            ));
        };
        if r.points.len() != info.nodes.len() {
            return Err(format!(
                "rod \"{}\" has {} points in the initial results, the scene gives it {} nodes \
                 (the same scene, with the same subdivision, is needed)",
                info.name,
                r.points.len(),
                info.nodes.len()
            ));
        }
        if !r.twist.is_empty() && r.twist.len() != info.edges.len() {
            return Err(format!(
                "rod \"{}\" has {} twist angles in the initial results, the scene gives it {} \
                 edges",
                info.name,
                r.twist.len(),
                info.edges.len()
            ));
        }
        for (&n, p) in info.nodes.iter().zip(&r.points) {
            if !p.iter().all(|x| x.is_finite()) {
                return Err(format!("rod \"{}\": a point is not finite", info.name));
            }
            if let Some((other, at)) = seen[n] {
                let gap = (0..3).map(|k| (at[k] - p[k]).abs()).fold(0.0, f64::max);
                if gap > 1e-9 * scale {
                    return Err(format!(
                        "rods \"{}\" and \"{}\" share a node (a joint) that the initial results \
                         put {gap:.3e} m apart: they are not a state of this scene",
                        net.rods[other].name, info.name
                    ));
                }
            }
            seen[n] = Some((ri, *p));
            let o = net.model.origin;
            layout.set_position(&mut q, n, [0, 1, 2].map(|k| p[k] - o[k]));
        }
        for (&e, &t) in info.edges.iter().zip(&r.twist) {
            if !t.is_finite() {
                return Err(format!(
                    "rod \"{}\": a twist angle is not finite",
                    info.name
                ));
            }
            q[layout.theta(e)] = t;
        }
    }
    net.model.state.q = q;
    turn_frames(net);
    // The results' angles are measured from each rod's canonical directors (its first edge's
    // rest frame carried along the rod): the reference frames start there.
    for r in &net.rods {
        let tangents = net.rod_tangents(r);
        let Some(&first) = r.edges.first() else {
            continue;
        };
        let directors = canonical_directors(&net.model.rest_edges[first], &tangents);
        for ((&e, t), u) in r.edges.iter().zip(tangents).zip(directors) {
            net.model.state.edges[e] = EdgeRef { t, u };
        }
    }
    net.model.commit();
    net.model.nearest_turns();
    Ok(())
}

/// Turns each vertex frame (clamps, Rigid and Hinge joints) by the smallest rotation that takes
/// its first port's tangent onto that edge's new direction: the results do not hold the frames,
/// and a frame left at rest would bend every rod at a turned joint.
fn turn_frames(net: &mut Network) {
    net.model.turn_frames(|m, fb| {
        let at = |k: usize| [0, 1, 2].map(|c| m.state.q[fb.vars[3 * k + c]]);
        // The frame's d3 is the tangent into the edge times the stencil's sign (−1 where the
        // rod arrives at the vertex, as at a rod's last node).
        let t = scalef(normalize(sub(at(1), at(0))), fb.sign);
        let q = m.state.frames[fb.port.frame].rotation;
        let rest = fb.port.rest[2];
        let d3 = add(
            add(scalef(q[0], rest[0]), scalef(q[1], rest[1])),
            scalef(q[2], rest[2]),
        );
        rotation_between(normalize(d3), t)
    });
}
