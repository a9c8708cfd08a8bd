use std::collections::HashSet;

use super::{direction, positive, InJoint, RodIndex, MIN_DIRECTION};
use crate::scene::types::{Joint, Scene};
use crate::scene::FieldError;

/// Checks every joint and returns which joint holds each joined rod vertex.
pub(super) fn joints<'a>(s: &'a Scene, rods: &RodIndex) -> Result<InJoint<'a>, FieldError> {
    let mut joint_names = HashSet::new();
    let mut in_joint = InJoint::new();
    for (i, j) in s.joints.iter().enumerate() {
        let err = |f: &str, msg: String| Err(FieldError::new("joints", i, f, msg));
        if !joint_names.insert(j.name.as_str()) {
            return err("name", format!("duplicate joint name \"{}\"", j.name));
        }
        if j.at.is_empty() {
            return err("at", "must list at least one (rod, vertex) pair".into());
        }
        for (rod, v) in &j.at {
            if let Err(m) = rods.vertex(rod, *v) {
                return err("at", m);
            }
            if let Some(other) = in_joint.insert((rod.as_str(), *v), i) {
                return err(
                    "at",
                    format!(
                        "vertex {v} of rod \"{rod}\" is already in joint \"{}\"",
                        s.joints[other].name
                    ),
                );
            }
        }
        if let Some(n) = j.normal {
            if !direction(&n) {
                return err(
                    "normal",
                    format!("must be a finite direction of length at least {MIN_DIRECTION:e}, got {n:?}"),
                );
            }
        }
        if let Err(m) = elastic(j) {
            return err("kind", m);
        }
    }
    Ok(in_joint)
}

/// The stiffnesses of an `Elastic` joint.
fn elastic(j: &Joint) -> Result<(), String> {
    let Some(e) = &j.kind.elastic() else {
        return Ok(());
    };
    for (f, v) in [
        ("bending", e.bending),
        ("twist", e.twist),
        ("scissor", e.scissor),
    ] {
        if let Some(v) = v {
            if !(v.is_finite() && v >= 0.0) {
                return Err(format!(
                    "Elastic `{f}` must be non-negative and finite, got {v:?}"
                ));
            }
        }
    }
    if let Some(c) = &e.cylinder {
        if !(positive(c.young_modulus) && positive(c.diameter) && positive(c.height)) {
            return Err(
                "Elastic `cylinder` needs positive young_modulus, diameter and height".into(),
            );
        }
    }
    Ok(())
}
