//! From a validated scene to a [`Network`]: rods subdivided into nodes and edges, joints merged
//! into shared nodes and vertex frames (one file per kind in [`super::joint`]), supports
//! eliminated from the unknowns, rest curvature and twist measured on the rest shape, loads turned
//! into potentials. One file per stage, run in this order:
//!
//! [`geometry`] (rest shape) → [`frames`] (joints, kinks, clamps, torques: vertex frames and
//! node merges) → [`nodes`] (global nodes and edges) → [`supports`] (fixed and prescribed
//! variables) → [`end_weights`] (the bending quadrature's end correction beside vertex frames)
//! → [`terms`] (stretch, bend and twist stencils, ports, joint springs) → [`loads`] (point
//! loads, gravity, torques, and the force scale); [`gauge`] holds a node of an
//! unsupported structure.

mod end_weights;
mod frames;
mod gauge;
mod geometry;
mod loads;
mod nodes;
mod supports;
mod terms;

use crate::network::contact::Contact;
use crate::network::info::JointInfo;
use crate::network::model::{Model, ModelParts, Scales};
use crate::network::Network;
use crate::scene::{FieldError, Scene};
use crate::variables::{DofLayout, FrameRef, State};

pub use frames::KINK_ANGLE;

/// Builds the network of a validated scene, about its own centre when it stands far from the
/// origin (`scene::translate`).
pub fn build(scene: &Scene) -> Result<Network, FieldError> {
    let origin = crate::scene::translate::origin(scene);
    if origin == [0.0; 3] {
        return build_here(scene);
    }
    let mut net = build_here(&scene.translated(origin.map(|x| -x)))?;
    net.model.origin = origin;
    Ok(net)
}

fn build_here(scene: &Scene) -> Result<Network, FieldError> {
    let rest = geometry::Rest::of(scene);
    let joined = frames::join(&rest)?;
    let net = nodes::number(&rest, &joined);
    let layout = DofLayout::new(
        net.n_nodes(),
        net.edge_nodes.len(),
        joined.table.frame_fixed.len(),
        joined.table.n_alpha,
    );
    let length_scale = rest
        .length_scale
        .max(net.rest_lengths.iter().cloned().fold(0.0, f64::max));
    let mut fixed = initially_fixed(&layout, &joined.table);
    let supported = supports::apply(&rest, &net, &joined.table, &layout, &mut fixed)?;
    let gauge = gauge::apply(scene, &net, &layout, &mut fixed);
    let mut q = vec![0.0; layout.len()];
    for (n, p) in net.rest_pos.iter().enumerate() {
        layout.set_position(&mut q, n, *p);
    }
    let mut state = State {
        q,
        edges: net.edge_refs.clone(),
        frames: vec![FrameRef::identity(); layout.n_frames()],
        twist_prev: Vec::new(),
        load_factor: 0.0,
    };
    let weights = end_weights::end_weights(&rest, &net, &joined);
    let mut terms = terms::elastic(&net, &joined, &layout, &mut state, &mut fixed, &weights);
    let driven = !supported.prescribed.is_empty()
        || !supported.rotations.is_empty()
        || supported.springs.iter().any(|s| s.anchor[0] != s.anchor[1])
        || supported.rotational.iter().any(|s| s.rotate_by != [0.0; 3]);
    terms.springs = supported.springs;
    terms.rotational_springs = supported.rotational;
    let rollers = slanted_rollers(&supported.slanted, &layout, &fixed, &mut terms);
    let force_scale = loads::apply(
        scene,
        &rest,
        &net,
        &joined.table,
        &layout,
        length_scale,
        driven,
        &mut terms,
    );
    let joints = scene
        .joints
        .iter()
        .zip(&joined.joint_nodes)
        .map(|(j, n)| JointInfo {
            name: j.name.clone(),
            node: net.joint_node(n),
        })
        .collect();
    let mut model = Model::new(ModelParts {
        layout,
        state,
        terms,
        fixed,
        prescribed: supported.prescribed,
        prescribed_rotations: supported.rotations,
        edge_nodes: net.edge_nodes,
        rest_lengths: net.rest_lengths,
        scales: Scales {
            length: length_scale,
            force: force_scale,
        },
        contact: None,
        rollers,
    });
    model.contact = Contact::build(
        scene,
        &net.rods,
        (model.unknowns(), &model.rollers.list),
        &model.state.q,
        length_scale,
    )?;
    Ok(Network {
        model,
        rods: net.rods,
        supports: supported.infos,
        joints,
        gauge,
    })
}

/// Variables fixed by the layout itself: the zero variable, the rotations of fixed frames
/// (clamps) and fixed hinge angles.
fn initially_fixed(layout: &DofLayout, table: &crate::network::joint::PortTable) -> Vec<bool> {
    let mut fixed = vec![false; layout.len()];
    fixed[layout.zero()] = true;
    for (f, &fx) in table.frame_fixed.iter().enumerate() {
        if fx {
            for v in layout.frame(f) {
                fixed[v] = true;
            }
        }
    }
    for &a in &table.fixed_alpha {
        fixed[layout.alpha(a)] = true;
    }
    fixed
}

/// The slanted rollers of nodes that nothing else holds (a Pin or Clamp there holds the node
/// already), with their planes' normals made orthonormal, and the spring that holds each.
fn slanted_rollers(
    slanted: &[crate::network::support::Slanted],
    layout: &DofLayout,
    fixed: &[bool],
    terms: &mut crate::energy::registry::Terms,
) -> Vec<crate::network::roller::SlantedRoller> {
    use crate::network::roller::{holding_spring, holding_stiffness, orthonormal, SlantedRoller};
    let stiffest = holding_stiffness(terms);
    let mut out = Vec::new();
    for (node, normals, through) in slanted {
        let vars = layout.node(*node);
        if vars.iter().any(|&v| fixed[v]) {
            continue;
        }
        let basis = orthonormal(normals);
        // `scene::validate` refuses a third independent normal on one node.
        debug_assert!(basis.len() <= 2);
        let roller = SlantedRoller::new(*node, vars, basis, *through);
        terms.roller_normals.push(holding_spring(&roller, stiffest));
        out.push(roller);
    }
    out
}
