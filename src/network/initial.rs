//! Starting a solve from an earlier equilibrium of the same scene (`rodnet solve --initial`):
//! node positions and twist angles, checked rod by rod against the built network.

use crate::math::vec::{add, normalize, rotation_between, scalef, sub};
use crate::network::Network;
use crate::rod::frames::{canonical_directors, EdgeRef};
use crate::variables::layout::FIXED;

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
    let (centre, reach) = reach(net);
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
        for (i, (&n, p)) in info.nodes.iter().zip(&r.points).enumerate() {
            let far = p
                .iter()
                .zip(&centre)
                .map(|(x, c)| (x - c).abs())
                .fold(0.0, f64::max);
            if !p.iter().all(|x| x.is_finite()) || far > reach {
                return Err(format!(
                    "rods[\"{}\"].points[{i}] = ({}, {}, {}) is not finite or lies {far:.3e} m \
                     from the scene's centre, beyond the {reach:.3e} m (1000 times the scene's \
                     size) a state of this scene can reach",
                    info.name, p[0], p[1], p[2]
                ));
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
        for (i, (&e, &t)) in info.edges.iter().zip(&r.twist).enumerate() {
            if !t.is_finite() || t.abs() > MAX_TWIST {
                return Err(format!(
                    "rods[\"{}\"].twist[{i}] = {t} rad is not finite or beyond ±{MAX_TWIST:e} \
                     rad (about 1600 turns; past it an angle's rounding exceeds 1e-12 rad)",
                    info.name
                ));
            }
            q[layout.theta(e)] = t;
        }
    }
    // Every scene rod was found above: a count that differs means rods the scene does not have.
    if rods.len() != net.rods.len() {
        let extra = rods
            .iter()
            .find(|r| !net.rods.iter().any(|i| i.name == r.name))
            .map_or(String::new(), |r| {
                format!("; rod \"{}\" is not in the scene", r.name)
            });
        return Err(format!(
            "the initial results hold {} rods, the scene {}{extra}: they are not a state of this \
             scene",
            rods.len(),
            net.rods.len()
        ));
    }
    // The scene, not the file, says where the supports are and how far they have moved: a result
    // of a version whose clamp was elsewhere would otherwise start (and "converge") with the
    // clamp where that version had it. Fixed variables keep the built value; prescribed ones are
    // set to their full motion when the solve sets λ = 1.
    for (v, &f) in net.model.free.iter().enumerate() {
        if f == FIXED {
            q[v] = net.model.state.q[v];
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

/// Checks that a results file's joints (`names`) are the scene's: as many, with the same names.
pub fn check_joints(net: &Network, names: &[String]) -> Result<(), String> {
    let mut ours: Vec<&str> = net.joints.iter().map(|j| j.name.as_str()).collect();
    let mut theirs: Vec<&str> = names.iter().map(String::as_str).collect();
    ours.sort_unstable();
    theirs.sort_unstable();
    if ours == theirs {
        return Ok(());
    }
    let missing = ours.iter().find(|n| theirs.binary_search(n).is_err());
    let extra = theirs.iter().find(|n| ours.binary_search(n).is_err());
    Err(format!(
        "the initial results list {} joints, the scene {}{}{}: they are not a state of this scene",
        theirs.len(),
        ours.len(),
        missing.map_or(String::new(), |n| format!(
            "; joint \"{n}\" is not in the results"
        )),
        extra.map_or(String::new(), |n| format!(
            "; joint \"{n}\" is not in the scene"
        )),
    ))
}

/// Largest |θ| (rad) an edge's angle may have in a restart file: past 1e4 rad a double's spacing
/// exceeds 1.8e-12 rad, so the angle no longer holds a twist to the solver's precision; ten
/// thousand radians are about 1600 turns, far beyond any rod that stays elastic.
pub const MAX_TWIST: f64 = 1e4;

/// The centre of the scene's rest nodes and how far from it (per coordinate) a node of one of its
/// states may lie: 1000 times the scene's size, taken as the larger of its bounding box's
/// largest side and the sum of its rest edge lengths (a rod can stretch, not by a thousandfold).
fn reach(net: &Network) -> ([f64; 3], f64) {
    let m = &net.model;
    let n = m.layout.n_nodes();
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for i in 0..n {
        let p = m.world_position(i);
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    if n == 0 {
        return ([0.0; 3], 0.0);
    }
    let side = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
    let length: f64 = m.rest_lengths.iter().sum();
    let centre = [0, 1, 2].map(|k| 0.5 * (lo[k] + hi[k]));
    (centre, 1e3 * side.max(length))
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
