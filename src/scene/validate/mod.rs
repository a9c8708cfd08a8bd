//! Semantic checks of a parsed scene. Everything the builder assumes is checked here, so that a
//! bad scene gives one clear message naming its field instead of a panic or a NaN.
//!
//! One function per section, run in the order of [`validate`]: later sections refer to rods and
//! joints checked before them, and the first error found is the one reported.

mod constraints;
mod joints;
mod loads;
mod materials;
mod rods;
mod stages;
mod supports;
mod targets;

use std::collections::HashMap;

use super::types::*;
use super::FieldError;

/// Largest number of nodes a scene may create (about 1 GB of solver memory per million nodes).
pub const MAX_NODES: usize = 2_000_000;
/// Largest number of load steps.
pub const MAX_LOAD_STEPS: usize = 100_000;
/// Most Newton iterations per load step (`solver.max_iterations`): a hundred times the default
/// and far past any solve that converges (Newton converges in tens of iterations or stalls), so
/// that the count bounds the run (docs/scene-format.md); `time_limit` bounds its seconds.
pub const MAX_ITERATIONS: usize = 100_000;
/// Largest scene file read, bytes. A scene at the node limit written out point by point is
/// about 100 MB; anything much larger is not a scene and is refused before it is read.
pub const MAX_SCENE_BYTES: u64 = 256 * 1024 * 1024;

/// Largest magnitude of any number in a scene. The solver squares forces and stiffnesses
/// (F², EA·ε²), which overflow above about 1e154; nothing physical comes near 1e100.
pub const MAX_MAGNITUDE: f64 = 1e100;

fn finite3(v: &[f64; 3]) -> bool {
    v.iter().all(|x| x.is_finite() && x.abs() <= MAX_MAGNITUDE)
}

/// Shortest direction vector accepted (normals, axes): normalizing squares the components,
/// and below about 1e-154 the squares fall into subnormals or to zero, so the unit vector
/// would be inexact or not finite.
pub const MIN_DIRECTION: f64 = 1e-150;

/// A finite vector that can be normalized.
fn direction(v: &[f64; 3]) -> bool {
    finite3(v) && crate::math::vec::norm(*v) >= MIN_DIRECTION
}

fn positive(x: f64) -> bool {
    x.is_finite() && x > 0.0 && x <= MAX_MAGNITUDE
}

/// Number of segments between a rod's input points.
fn segments(r: &Rod) -> usize {
    let m = r.points.len();
    if r.closed {
        m
    } else {
        m - 1
    }
}

/// The first error of a scene, section by section.
pub fn validate(s: &Scene) -> Result<(), FieldError> {
    materials::materials(s)?;
    let rods = rods::rods(s)?;
    let in_joint = joints::joints(s, &rods)?;
    rods::repeated_points(s, &in_joint)?;
    supports::supports(s, &rods, &in_joint)?;
    loads::loads(s, &rods)?;
    loads::unsupported_loads(s)?;
    stages::stages(s, &rods)?;
    constraints::obstacles(s)?;
    constraints::bounds(s, &rods)?;
    targets::target(s)?;
    targets::reference(s, &rods)?;
    solver(&s.solver)
}

/// What a valid scene probably did not mean, located like errors (`rodnet solve` prints them
/// on stderr, and the results JSON lists them under `warnings`).
pub fn warnings(s: &Scene) -> Vec<FieldError> {
    let mut w = loads::gravity_warnings(s);
    w.extend(stages::warnings(s));
    w
}

/// The field at fault in one item of a section, and why.
type Fault = (&'static str, String);

/// The joint that holds each joined rod vertex, by (rod name, vertex).
type InJoint<'a> = HashMap<(&'a str, usize), usize>;

/// The rods of a scene by name, for the sections that refer to a rod's vertices.
struct RodIndex<'a>(HashMap<&'a str, &'a Rod>);

impl<'a> RodIndex<'a> {
    fn get(&self, rod: &str) -> Option<&'a Rod> {
        self.0.get(rod).copied()
    }

    /// Whether `rod` exists and has an input point `v`.
    fn vertex(&self, rod: &str, v: usize) -> Result<(), String> {
        match self.get(rod) {
            None => Err(format!("unknown rod \"{rod}\"")),
            Some(r) if v >= r.points.len() => Err(format!(
                "vertex {v} is out of range: rod \"{rod}\" has {} input points (vertices 0..{})",
                r.points.len(),
                r.points.len() - 1
            )),
            Some(_) => Ok(()),
        }
    }

    /// [`Self::vertex`] for an item with separate `rod` and `vertex` fields: the error names
    /// the field at fault.
    fn rod_vertex(&self, rod: &str, v: usize) -> Result<(), Fault> {
        self.vertex(rod, v).map_err(|m| {
            let field = if m.starts_with("unknown") {
                "rod"
            } else {
                "vertex"
            };
            (field, m)
        })
    }
}

fn solver(sv: &Solver) -> Result<(), FieldError> {
    if let Some(t) = sv.tolerance.filter(|t| !positive(*t)) {
        return Err(FieldError::global(
            "solver",
            "tolerance",
            format!("must be positive and finite (at most {MAX_MAGNITUDE:e}), got {t:e}"),
        ));
    }
    if let Some(d) = sv.buckle_toward {
        if !direction(&d) {
            return Err(FieldError::global(
                "solver",
                "buckle_toward",
                format!("must be a finite, non-zero direction, got {d:?}"),
            ));
        }
    }
    if let Some(t) = sv.time_limit.filter(|t| !positive(*t)) {
        return Err(FieldError::global(
            "solver",
            "time_limit",
            format!("must be a positive number of seconds, got {t:e}"),
        ));
    }
    if sv.max_iterations == 0 {
        return Err(FieldError::global(
            "solver",
            "max_iterations",
            "must be at least 1".into(),
        ));
    }
    if sv.max_iterations > MAX_ITERATIONS {
        return Err(FieldError::global(
            "solver",
            "max_iterations",
            format!(
                "must be at most {MAX_ITERATIONS} (the largest accepted value), got {}",
                sv.max_iterations
            ),
        ));
    }
    if sv.load_steps == 0 || sv.load_steps > MAX_LOAD_STEPS {
        return Err(FieldError::global(
            "solver",
            "load_steps",
            format!("must be in 1..={MAX_LOAD_STEPS}"),
        ));
    }
    Ok(())
}
