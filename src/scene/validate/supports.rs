use std::collections::HashMap;

use super::{finite3, InJoint, RodIndex};
use crate::scene::types::{Scene, SupportKind};
use crate::scene::FieldError;

/// A node of the built network: a joint, or a rod vertex outside any joint.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
enum NodeKey {
    Joint(usize),
    Vertex(String, usize),
}

pub(super) fn supports(s: &Scene, rods: &RodIndex, in_joint: &InJoint) -> Result<(), FieldError> {
    // Joined rod vertices are one node, so supports are compared per node: one support that
    // holds a node at rest and another that moves it cannot both hold.
    let node_of = |rod: &str, v: usize| match in_joint.get(&(rod, v)) {
        Some(&j) => NodeKey::Joint(j),
        None => NodeKey::Vertex(rod.to_string(), v),
    };
    let mut motion: HashMap<NodeKey, (usize, Option<[f64; 3]>)> = HashMap::new();
    for (i, sp) in s.supports.iter().enumerate() {
        let err = |f: &str, msg: String| Err(FieldError::new("supports", i, f, msg));
        if let Err((f, m)) = rods.rod_vertex(&sp.rod, sp.vertex) {
            return err(f, m);
        }
        if let Some(r) = sp.rotate_by {
            if !finite3(&r) {
                return err("rotate_by", format!("must be finite, got {r:?}"));
            }
            if sp.kind != SupportKind::Clamp {
                return err(
                    "rotate_by",
                    "only a Clamp can be rotated (a Pin leaves rotations free)".into(),
                );
            }
        }
        if let Some(t) = sp.move_to {
            if !finite3(&t) {
                return err("move_to", format!("must be finite, got {t:?}"));
            }
        }
        if let SupportKind::Spring { stiffness } = sp.kind {
            let ok = stiffness.iter().all(|k| k.is_finite() && *k >= 0.0)
                && stiffness.iter().any(|k| *k > 0.0)
                && stiffness.iter().all(|k| *k <= super::MAX_MAGNITUDE);
            if !ok {
                return err(
                    "kind",
                    format!(
                        "a Spring's stiffness (N/m along x, y, z) must be finite, non-negative                          and not all zero, got {stiffness:?}"
                    ),
                );
            }
        }
        if let SupportKind::Roller { normal } = sp.kind {
            if !finite3(&normal) || sp.kind.roller_axis().is_none() {
                return err(
                    "kind",
                    format!(
                        "a Roller's normal must lie along x, y or z (one non-zero component), got \
                         {normal:?}: a general normal needs a change of variables that rodnet does \
                         not have yet"
                    ),
                );
            }
        }
        let node = node_of(&sp.rod, sp.vertex);
        let Some(&(k, prev)) = motion.get(&node) else {
            motion.insert(node, (i, sp.move_to));
            continue;
        };
        let where_ = match &node {
            NodeKey::Joint(j) => format!("joint \"{}\"", s.joints[*j].name),
            NodeKey::Vertex(..) => format!("vertex {} of rod \"{}\"", sp.vertex, sp.rod),
        };
        if let Some(m) = contradiction(&where_, k, prev, sp.move_to) {
            let field = if sp.move_to.is_some() {
                "move_to"
            } else {
                "kind"
            };
            return err(field, m);
        }
    }
    Ok(())
}

/// Why a support that moves the node at `where_` to `now` (or holds it at rest) contradicts
/// supports[`k`], which moves it to `prev`, if it does.
fn contradiction(
    where_: &str,
    k: usize,
    prev: Option<[f64; 3]>,
    now: Option<[f64; 3]>,
) -> Option<String> {
    match (prev, now) {
        (Some(a), Some(b)) if a != b => Some(format!(
            "contradicts supports[{k}], which moves {where_} to {a:?}, not {b:?}"
        )),
        (Some(a), None) => Some(format!(
            "holds {where_} at its rest position, but supports[{k}] moves it \
             to {a:?}; give both the same `move_to` or drop one"
        )),
        (None, Some(b)) => Some(format!(
            "moves {where_} to {b:?}, but supports[{k}] holds it at its rest \
             position; give both the same `move_to` or drop one"
        )),
        _ => None,
    }
}
