//! `target` and `reference`: the shapes a solution is compared with.

use super::{finite3, positive, RodIndex};
use crate::math::vec::dist;
use crate::scene::types::{Scene, Target};
use crate::scene::FieldError;

pub(super) fn target(s: &Scene) -> Result<(), FieldError> {
    if let Some(Target::Mesh { path, .. }) = &s.target {
        if path.trim().is_empty() {
            return Err(FieldError::global(
                "target",
                "path",
                "Mesh needs the path of an OBJ file".into(),
            ));
        }
    }
    if let Some(Target::Sphere { center, radius }) = &s.target {
        if !finite3(center) || !positive(*radius) {
            return Err(FieldError::global(
                "target",
                "",
                "Sphere needs a finite center and a positive radius".into(),
            ));
        }
    }
    Ok(())
}

pub(super) fn reference(s: &Scene, rods: &RodIndex) -> Result<(), FieldError> {
    let Some(r) = &s.reference else {
        return Ok(());
    };
    let err = |f: &str, msg: String| Err(FieldError::global("reference", f, msg));
    if let Err((f, m)) = rods.rod_vertex(&r.rod, r.vertex) {
        return err(f, m);
    }
    if !finite3(&r.position) {
        return err("position", format!("must be finite, got {:?}", r.position));
    }
    // The error is relative to the vertex's displacement, so a reference at rest would
    // divide by zero.
    let rod = rods.get(&r.rod).expect("checked above");
    let rest = rod.points[r.vertex];
    let scale = rod.points.iter().fold(0.0f64, |m, p| m.max(dist(p, &rest)));
    if dist(&r.position, &rest) <= 1e-12 * scale {
        return err(
            "position",
            format!(
                "is the rest position {rest:?} of vertex {} of rod \"{}\"; the error is \
                 measured relative to the reference displacement, which must not be zero",
                r.vertex, r.rod
            ),
        );
    }
    Ok(())
}
