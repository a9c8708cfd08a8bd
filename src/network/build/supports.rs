//! Supports: pinned and clamped nodes leave the unknowns; `move_to` and `rotate_by` become
//! motions prescribed over the continuation; springs become energy terms.

use std::collections::HashMap;

use super::geometry::Rest;
use super::nodes::Numbered;
use crate::energy::rotational_spring::RotationalSpring;
use crate::energy::spring::Spring;
use crate::network::info::SupportInfo;
use crate::network::joint::PortTable;
use crate::network::model::{Prescribed, PrescribedRotation};
use crate::scene::types::SupportKind;
use crate::scene::FieldError;
use crate::variables::DofLayout;

/// The Rollers with a general normal on one node: (node, their normals, a point of their
/// planes at λ = 0 and 1).
pub type Slanted = (usize, Vec<[f64; 3]>, [[f64; 3]; 2]);

pub struct Supported {
    pub prescribed: Vec<Prescribed>,
    /// Elastic supports: their energy terms.
    pub springs: Vec<Spring>,
    pub rotational: Vec<RotationalSpring>,
    /// Rollers with a general normal, by node.
    pub slanted: Vec<Slanted>,
    pub rotations: Vec<PrescribedRotation>,
    pub infos: Vec<SupportInfo>,
}

pub fn apply(
    rest: &Rest,
    net: &Numbered,
    table: &PortTable,
    layout: &DofLayout,
    fixed: &mut [bool],
) -> Result<Supported, FieldError> {
    let mut out = Supported {
        prescribed: Vec::new(),
        springs: Vec::new(),
        rotational: Vec::new(),
        slanted: Vec::new(),
        rotations: Vec::new(),
        infos: Vec::new(),
    };
    let slanted_nodes: std::collections::HashSet<usize> = rest
        .scene
        .supports
        .iter()
        .filter(|s| matches!(s.kind, SupportKind::Roller { .. }) && s.kind.roller_axis().is_none())
        .map(|s| {
            let (r, rnode) = rest.site(&s.rod, s.vertex);
            net.rods[r].nodes[rnode]
        })
        .collect();
    let mut moved: HashMap<usize, [f64; 3]> = HashMap::new();
    let mut turned: HashMap<usize, (usize, Option<[f64; 3]>)> = HashMap::new();
    for (si, s) in rest.scene.supports.iter().enumerate() {
        let (r, rnode) = rest.site(&s.rod, s.vertex);
        let node = net.rods[r].nodes[rnode];
        if let SupportKind::Spring { stiffness, .. } = s.kind {
            // A spring holds nothing: its node (frame) stays free, tied to an anchor that moves
            // with the load factor from rest to `move_to` (turns to `rotate_by`).
            let rest_pos = net.rest_pos[node];
            let axes = s.kind.spring_axes();
            let spring = stiffness.iter().any(|k| *k != 0.0).then(|| {
                out.springs.push(Spring {
                    vars: [0, 1, 2].map(|k| layout.node_coord(node, k)),
                    stiffness,
                    axes,
                    anchor: [rest_pos, s.move_to.unwrap_or(rest_pos)],
                });
                out.springs.len() - 1
            });
            let rotational = s.kind.rotational_stiffness().map(|k| {
                let port = table.port_of[&(r, rnode)];
                let frame = table.ports[port].frame;
                out.rotational.push(RotationalSpring {
                    vars: layout.frame(frame),
                    frame,
                    axes,
                    stiffness: k,
                    rotate_by: s.rotate_by.unwrap_or([0.0; 3]),
                });
                (out.rotational.len() - 1, frame)
            });
            out.infos.push(SupportInfo {
                rod: s.rod.clone(),
                vertex: s.vertex,
                node,
                frame: rotational.map(|(_, f)| f),
                spring,
                rotational: rotational.map(|(k, _)| k),
            });
            continue;
        }
        // A node with a slanted Roller keeps its coordinates: all its Rollers hold it by
        // projection (`network/roller.rs`).
        let slanted = match s.kind {
            SupportKind::Roller { normal } if slanted_nodes.contains(&node) => {
                let rest_pos = net.rest_pos[node];
                match out.slanted.iter_mut().find(|e| e.0 == node) {
                    Some(e) => e.1.push(normal),
                    None => out.slanted.push((
                        node,
                        vec![normal],
                        [rest_pos, s.move_to.unwrap_or(rest_pos)],
                    )),
                }
                true
            }
            _ => false,
        };
        // A Roller holds (and moves) one coordinate; Pins and Clamps all three.
        let held: Vec<usize> = match (s.kind.roller_axis(), slanted) {
            (_, true) => vec![],
            (Some(k), false) => vec![k],
            (None, false) => vec![0, 1, 2],
        };
        for &k in &held {
            fixed[layout.node_coord(node, k)] = true;
        }
        if let Some(target) = s.move_to.filter(|_| !held.is_empty()) {
            match moved.insert(node, target) {
                Some(prev) if prev != target => {
                    return Err(FieldError::new(
                        "supports",
                        si,
                        "move_to",
                        "this node already has a different `move_to` from another support".into(),
                    ))
                }
                Some(_) => {}
                None => out.prescribed.extend(held.iter().map(|&k| Prescribed {
                    var: layout.node_coord(node, k),
                    start: net.rest_pos[node][k],
                    end: target[k],
                })),
            }
        }
        let frame = match s.kind {
            SupportKind::Clamp => table
                .port_of
                .get(&(r, rnode))
                .map(|&p| table.ports[p].frame),
            SupportKind::Pin | SupportKind::Roller { .. } | SupportKind::Spring { .. } => None,
        };
        if let Some(f) = frame {
            // Clamps on one frame (one rod vertex twice, or rods of one Rigid or Hinge joint)
            // must agree on how it turns: held, or rotated by the same rotation vector.
            match turned.insert(f, (si, s.rotate_by)) {
                Some((k, prev)) if prev != s.rotate_by => {
                    let field = if s.rotate_by.is_some() {
                        "rotate_by"
                    } else {
                        "kind"
                    };
                    return Err(FieldError::new(
                        "supports",
                        si,
                        field,
                        frame_contradiction(k, prev, s.rotate_by),
                    ));
                }
                Some(_) => {}
                None => {
                    if let Some(rotation) = s.rotate_by {
                        out.rotations
                            .push(PrescribedRotation { frame: f, rotation });
                    }
                }
            }
        }
        out.infos.push(SupportInfo {
            rod: s.rod.clone(),
            vertex: s.vertex,
            node,
            frame,
            spring: None,
            rotational: None,
        });
    }
    Ok(out)
}

/// Why a clamp that turns its frame by `now` (or holds it) contradicts supports[`k`], which
/// clamps the same frame and turns it by `prev` (or holds it).
fn frame_contradiction(k: usize, prev: Option<[f64; 3]>, now: Option<[f64; 3]>) -> String {
    let what = match (prev, now) {
        (Some(a), Some(b)) => format!("rotates it by {a:?}, not {b:?}"),
        (Some(a), None) => {
            format!("rotates it by {a:?}, but this clamp holds it; give both the same `rotate_by`")
        }
        (None, Some(_)) => {
            "holds it, but this clamp rotates it; give both the same `rotate_by`".into()
        }
        (None, None) => unreachable!("equal motions do not contradict"),
    };
    format!("supports[{k}] clamps the same vertex frame (one joint or vertex) and {what}")
}
