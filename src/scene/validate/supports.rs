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
    // Orthonormal directions each node's Rollers hold, to refuse a third independent one.
    let mut held: HashMap<NodeKey, Vec<[f64; 3]>> = HashMap::new();
    for (i, sp) in s.supports.iter().enumerate() {
        let err = |f: &str, msg: String| Err(FieldError::new("supports", i, f, msg));
        if let Err((f, m)) = rods.rod_vertex(&sp.rod, sp.vertex) {
            return err(f, m);
        }
        if let Some(r) = sp.rotate_by {
            if !finite3(&r) {
                return err("rotate_by", format!("must be finite, got {r:?}"));
            }
            if sp.kind != SupportKind::Clamp && sp.kind.rotational_stiffness().is_none() {
                return err(
                    "rotate_by",
                    "only a Clamp can be rotated, or a Spring's anchor when it has `rotational` \
                     stiffness (a Pin leaves rotations free)"
                        .into(),
                );
            }
        }
        if let Some(t) = sp.move_to {
            if !finite3(&t) {
                return err("move_to", format!("must be finite, got {t:?}"));
            }
        }
        if let SupportKind::Spring {
            stiffness,
            rotational,
            axes,
        } = sp.kind
        {
            if let Err((f, m)) = spring(stiffness, rotational, axes) {
                return err(f, m);
            }
            // A spring holds nothing: its `move_to` moves its anchor, never the node, so it
            // cannot contradict what other supports do with the node.
            continue;
        }
        if let SupportKind::Roller { normal } = sp.kind {
            let len =
                (normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]).sqrt();
            if !finite3(&normal) || len <= 1e-150 || !len.is_finite() {
                return err(
                    "kind",
                    format!(
                        "a Roller's normal must be a finite, non-zero direction, got {normal:?}"
                    ),
                );
            }
            let basis = held.entry(node_of(&sp.rod, sp.vertex)).or_default();
            if adds_direction(basis, normal) && basis.len() > 2 {
                return err(
                    "kind",
                    "this Roller's normal and those of two earlier Rollers on this node are \
                     independent: together they hold the node in place; use a Pin (with its \
                     `move_to`) instead"
                        .into(),
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

/// Adds `n` to the orthonormal `basis` (Gram–Schmidt) unless the basis already spans it, as
/// parallel normals through one node (one plane) do; whether it did.
fn adds_direction(basis: &mut Vec<[f64; 3]>, n: [f64; 3]) -> bool {
    use crate::math::vec::{dot, normalize, scalef, sub};
    let mut u = normalize(n);
    for b in basis.iter() {
        u = sub(u, scalef(*b, dot(u, *b)));
    }
    let new = dot(u, u) > 1e-12;
    if new {
        basis.push(normalize(u));
    }
    new
}

/// Checks a Spring's stiffnesses and axes; the error names the field of `kind` at fault.
fn spring(
    stiffness: [f64; 3],
    rotational: Option<[f64; 3]>,
    axes: Option<[[f64; 3]; 3]>,
) -> Result<(), (&'static str, String)> {
    let valid = |k: &[f64; 3]| {
        k.iter()
            .all(|x| x.is_finite() && *x >= 0.0 && *x <= super::MAX_MAGNITUDE)
    };
    if !valid(&stiffness) {
        return Err((
            "kind",
            format!(
                "a Spring's `stiffness` (N/m) must be finite and non-negative, got {stiffness:?}"
            ),
        ));
    }
    let rot = rotational.unwrap_or([0.0; 3]);
    if !valid(&rot) {
        return Err((
            "kind",
            format!("a Spring's `rotational` stiffness (N·m/rad) must be finite and non-negative, got {rot:?}"),
        ));
    }
    if stiffness.iter().chain(&rot).all(|k| *k == 0.0) {
        return Err((
            "kind",
            "a Spring needs a non-zero `stiffness` (N/m) or `rotational` stiffness (N·m/rad)"
                .into(),
        ));
    }
    let Some(a) = axes else { return Ok(()) };
    let len = |v: &[f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if let Some(i) = (0..3).find(|&i| !finite3(&a[i]) || len(&a[i]) <= 1e-150) {
        return Err((
            "kind",
            format!(
                "a Spring's axes[{i}] must be a finite, non-zero direction, got {:?}",
                a[i]
            ),
        ));
    }
    for (i, j) in [(0, 1), (0, 2), (1, 2)] {
        let c = (0..3).map(|k| a[i][k] * a[j][k]).sum::<f64>() / (len(&a[i]) * len(&a[j]));
        if c.abs() > 1e-6 {
            return Err((
                "kind",
                format!(
                    "a Spring's axes must be mutually perpendicular: axes[{i}] and axes[{j}] \
                     have cos = {c:.3e} (at most 1e-6)"
                ),
            ));
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
