//! Obstacles and bounds: the sections that turn Newton steps into QPs.

use super::{direction, finite3, positive, Fault, RodIndex, MIN_DIRECTION};
use crate::scene::types::{Bound, Obstacle, Scene};
use crate::scene::FieldError;

pub(super) fn obstacles(s: &Scene) -> Result<(), FieldError> {
    for (i, o) in s.obstacles.iter().enumerate() {
        obstacle(o).map_err(|(f, msg)| FieldError::new("obstacles", i, f, msg))?;
    }
    Ok(())
}

fn obstacle(o: &Obstacle) -> Result<(), Fault> {
    let check = |ok: bool, f: &'static str, what: &str, got: String| {
        if ok {
            Ok(())
        } else {
            Err((f, format!("must be {what}, got {got}")))
        }
    };
    let point = |f, v: &[f64; 3]| check(finite3(v), f, "finite", format!("{v:?}"));
    let direction = |f, v: &[f64; 3]| {
        let what = format!("a finite direction of length at least {MIN_DIRECTION:e}");
        check(direction(v), f, &what, format!("{v:?}"))
    };
    let radius = |r: f64| check(positive(r), "radius", "positive and finite", format!("{r}"));
    match o {
        Obstacle::Plane { point: p, normal } => {
            point("point", p)?;
            direction("normal", normal)
        }
        Obstacle::Sphere { center, radius: r } => {
            point("center", center)?;
            radius(*r)
        }
        Obstacle::Cylinder {
            point: p,
            axis,
            radius: r,
        } => {
            point("point", p)?;
            direction("axis", axis)?;
            radius(*r)
        }
    }
}

pub(super) fn bounds(s: &Scene, rods: &RodIndex) -> Result<(), FieldError> {
    for (i, b) in s.bounds.iter().enumerate() {
        bound(b, rods).map_err(|(f, msg)| FieldError::new("bounds", i, f, msg))?;
    }
    Ok(())
}

fn bound(b: &Bound, rods: &RodIndex) -> Result<(), Fault> {
    match (&b.rod, &b.vertices) {
        (Some(rod), vertices) => {
            if rods.get(rod).is_none() {
                return Err(("rod", format!("unknown rod \"{rod}\"")));
            }
            for &v in vertices.iter().flatten() {
                rods.vertex(rod, v).map_err(|m| ("vertices", m))?;
            }
            if vertices.as_ref().is_some_and(|v| v.is_empty()) {
                return Err((
                    "vertices",
                    "must not be empty (omit it to bound every node)".into(),
                ));
            }
        }
        (None, Some(_)) => {
            return Err((
                "vertices",
                "needs `rod` (vertices index a rod's input points)".into(),
            ))
        }
        (None, None) => {}
    }
    for k in 0..3 {
        for (f, v) in [("min", b.min[k]), ("max", b.max[k])] {
            if v.is_some_and(|x| !x.is_finite()) {
                return Err((f, format!("component {k} must be finite, got {v:?}")));
            }
        }
        if let (Some(lo), Some(hi)) = (b.min[k], b.max[k]) {
            // An equal pair would be an equality with no interior, which the interior-point
            // QP handles badly; a fixed coordinate is a support's job.
            if lo >= hi {
                return Err((
                    "max",
                    format!("component {k}: max {hi} must be above min {lo}"),
                ));
            }
        }
    }
    if b.min.iter().chain(&b.max).all(|v| v.is_none()) {
        return Err((
            "min",
            "give at least one component of `min` or `max`".into(),
        ));
    }
    Ok(())
}
