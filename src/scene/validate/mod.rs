//! Semantic checks of a parsed scene. Everything the builder assumes is checked here, so that a
//! bad scene gives one clear message naming its field instead of a panic or a NaN.

use std::collections::{HashMap, HashSet};

use super::types::*;
use super::FieldError;

/// Largest number of nodes a scene may create (about 1 GB of solver memory per million nodes).
pub const MAX_NODES: usize = 2_000_000;
/// Largest number of load steps.
pub const MAX_LOAD_STEPS: usize = 100_000;
/// Largest scene file read, bytes. A scene at the node limit written out point by point is
/// about 100 MB; anything much larger is not a scene and is refused before it is read.
pub const MAX_SCENE_BYTES: u64 = 256 * 1024 * 1024;

/// Largest magnitude of any number in a scene. The solver squares forces and stiffnesses
/// (F², EA·ε²), which overflow above about 1e154; nothing physical comes near 1e100.
pub const MAX_MAGNITUDE: f64 = 1e100;

fn finite3(v: &[f64; 3]) -> bool {
    v.iter().all(|x| x.is_finite() && x.abs() <= MAX_MAGNITUDE)
}

fn positive(x: f64) -> bool {
    x.is_finite() && x > 0.0 && x <= MAX_MAGNITUDE
}

fn dist(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

pub fn validate(s: &Scene) -> Result<(), FieldError> {
    for (name, m) in &s.materials {
        let err = |f: &str, msg: String| Err(FieldError::keyed("materials", name, f, msg));
        if !positive(m.young_modulus) {
            return err(
                "young_modulus",
                format!(
                    "must be positive and finite (at most {MAX_MAGNITUDE:e}), got {}",
                    m.young_modulus
                ),
            );
        }
        match (m.poisson_ratio, m.shear_modulus) {
            (Some(_), Some(_)) => {
                return err(
                    "shear_modulus",
                    "give exactly one of `poisson_ratio` and `shear_modulus`, not both".into(),
                )
            }
            (None, None) => {
                return err(
                    "young_modulus",
                    "give exactly one of `poisson_ratio` and `shear_modulus`".into(),
                )
            }
            (Some(nu), None) => {
                if !(nu.is_finite() && nu > -1.0 && nu <= 0.5) {
                    return err("poisson_ratio", format!("must lie in (-1, 0.5], got {nu}"));
                }
            }
            (None, Some(g)) => {
                if !positive(g) {
                    return err(
                        "shear_modulus",
                        format!("must be positive and finite (at most {MAX_MAGNITUDE:e}), got {g}"),
                    );
                }
            }
        }
        if !(m.density.is_finite() && (0.0..=MAX_MAGNITUDE).contains(&m.density)) {
            return err(
                "density",
                format!("must be non-negative and finite, got {}", m.density),
            );
        }
        let ok = match m.section {
            Section::Circle { radius } => positive(radius),
            Section::Ellipse { a, b } => positive(a) && positive(b),
            Section::Rectangle { width, height } => positive(width) && positive(height),
        };
        if !ok {
            return err(
                "section",
                format!(
                    "dimensions must be positive and finite (at most {MAX_MAGNITUDE:e}), got {:?}",
                    m.section
                ),
            );
        }
        // Rigidities go as E·r⁴: a tiny section or modulus underflows to zero stiffness.
        let k = m.section.stiffness(m.young_modulus, m.shear(), m.density);
        for (what, v) in [("EA", k.ea), ("EI1", k.ei1), ("EI2", k.ei2), ("GJ", k.gj)] {
            if !(v.is_normal() && v > 0.0 && v <= MAX_MAGNITUDE) {
                return err(
                    "section",
                    format!(
                        "with this section and modulus the rigidity {what} = {v:e} is not a \
                         usable number (it must lie between {:e} and {MAX_MAGNITUDE:e})",
                        f64::MIN_POSITIVE
                    ),
                );
            }
        }
    }

    if s.rods.is_empty() {
        return Err(FieldError::global(
            "rods",
            "",
            "the scene has no rods; there is nothing to solve".into(),
        ));
    }
    let mut rods: HashMap<&str, &Rod> = HashMap::new();
    let mut total_nodes = 0usize;
    for (i, r) in s.rods.iter().enumerate() {
        let err = |f: &str, msg: String| Err(FieldError::new("rods", i, f, msg));
        if r.name.is_empty() {
            return err("name", "must not be empty".into());
        }
        if rods.insert(r.name.as_str(), r).is_some() {
            return err("name", format!("duplicate rod name \"{}\"", r.name));
        }
        if !s.materials.contains_key(&r.material) {
            let known: Vec<&String> = s.materials.keys().collect();
            return err(
                "material",
                format!("unknown material \"{}\" (defined: {known:?})", r.material),
            );
        }
        let min_points = if r.closed { 3 } else { 2 };
        if r.points.len() < min_points {
            return err(
                "points",
                format!("needs at least {min_points} points, got {}", r.points.len()),
            );
        }
        if let Some(k) = r.points.iter().position(|p| !finite3(p)) {
            return err(
                "points",
                format!(
                    "point {k} is not finite (or above {MAX_MAGNITUDE:e} m): {:?}",
                    r.points[k]
                ),
            );
        }
        let m = r.points.len();
        let segs = if r.closed { m } else { m - 1 };
        let mut length = 0.0;
        for k in 0..segs {
            length += dist(&r.points[k], &r.points[(k + 1) % m]);
        }
        if r.closed && dist(&r.points[0], &r.points[m - 1]) <= 1e-12 * length {
            return err(
                "points",
                format!(
                    "the last point repeats the first; a closed rod connects point {} back to \
                     point 0 by itself, so leave the repeated point out",
                    m - 1
                ),
            );
        }
        for k in 0..segs {
            let l = dist(&r.points[k], &r.points[(k + 1) % m]);
            if l <= 1e-12 * length {
                return err(
                    "points",
                    format!(
                        "points {k} and {} coincide (zero-length segment)",
                        (k + 1) % m
                    ),
                );
            }
        }
        let range = if r.closed { 0..m } else { 1..m - 1 };
        for k in range {
            let (a, b, c) = (
                &r.points[(k + m - 1) % m],
                &r.points[k],
                &r.points[(k + 1) % m],
            );
            let e0 = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
            let e1 = [c[0] - b[0], c[1] - b[1], c[2] - b[2]];
            let cosang =
                (e0[0] * e1[0] + e0[1] * e1[1] + e0[2] * e1[2]) / (dist(a, b) * dist(b, c));
            if cosang < -0.99985 {
                return err("points", format!(
                    "the rod folds back on itself at point {k} (turning angle above 179°); split it into two rods joined there"
                ));
            }
        }
        if r.subdivide == 0 {
            return err("subdivide", "must be at least 1".into());
        }
        let nodes = segs.saturating_mul(r.subdivide).saturating_add(1);
        total_nodes = total_nodes.saturating_add(nodes);
        if total_nodes > MAX_NODES {
            return err("subdivide", format!(
                "the scene would have more than {MAX_NODES} nodes; reduce `subdivide` (limit in docs/scene-format.md)"
            ));
        }
        if let Some(n) = r.normal {
            let t = [
                r.points[1][0] - r.points[0][0],
                r.points[1][1] - r.points[0][1],
                r.points[1][2] - r.points[0][2],
            ];
            let cr = [
                t[1] * n[2] - t[2] * n[1],
                t[2] * n[0] - t[0] * n[2],
                t[0] * n[1] - t[1] * n[0],
            ];
            let nn = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            if !finite3(&n)
                || nn == 0.0
                || dist(&cr, &[0.0; 3]) <= 1e-8 * nn * dist(&r.points[1], &r.points[0])
            {
                return err(
                    "normal",
                    "must be finite and not parallel to the first edge".into(),
                );
            }
        }
    }

    let vertex_ok = |rod: &str, v: usize| -> Result<(), String> {
        match rods.get(rod) {
            None => Err(format!("unknown rod \"{rod}\"")),
            Some(r) if v >= r.points.len() => Err(format!(
                "vertex {v} is out of range: rod \"{rod}\" has {} input points (vertices 0..{})",
                r.points.len(),
                r.points.len() - 1
            )),
            Some(_) => Ok(()),
        }
    };

    let mut joint_names = HashSet::new();
    let mut in_joint: HashMap<(&str, usize), usize> = HashMap::new();
    for (i, j) in s.joints.iter().enumerate() {
        let err = |f: &str, msg: String| Err(FieldError::new("joints", i, f, msg));
        if !joint_names.insert(j.name.as_str()) {
            return err("name", format!("duplicate joint name \"{}\"", j.name));
        }
        if j.at.is_empty() {
            return err("at", "must list at least one (rod, vertex) pair".into());
        }
        for (rod, v) in &j.at {
            if let Err(m) = vertex_ok(rod, *v) {
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
            if !finite3(&n) || n == [0.0; 3] {
                return err("normal", "must be finite and non-zero".into());
            }
        }
        if let Some(e) = &j.kind.elastic() {
            for (f, v) in [
                ("bending", e.bending),
                ("twist", e.twist),
                ("scissor", e.scissor),
            ] {
                if let Some(v) = v {
                    if !(v.is_finite() && v >= 0.0) {
                        return err(
                            "kind",
                            format!("Elastic `{f}` must be non-negative and finite, got {v}"),
                        );
                    }
                }
            }
            if let Some(c) = &e.cylinder {
                if !(positive(c.young_modulus) && positive(c.diameter) && positive(c.height)) {
                    return err(
                        "kind",
                        "Elastic `cylinder` needs positive young_modulus, diameter and height"
                            .into(),
                    );
                }
            }
        }
    }

    repeated_points(s, &in_joint)?;

    // Joined rod vertices are one node, so supports are compared per node: one support that
    // holds a node at rest and another that moves it cannot both hold.
    let node_of = |rod: &str, v: usize| match in_joint.get(&(rod, v)) {
        Some(&j) => NodeKey::Joint(j),
        None => NodeKey::Vertex(rod.to_string(), v),
    };
    let mut motion: HashMap<NodeKey, (usize, Option<[f64; 3]>)> = HashMap::new();
    for (i, sp) in s.supports.iter().enumerate() {
        let err = |f: &str, msg: String| Err(FieldError::new("supports", i, f, msg));
        if let Err(m) = vertex_ok(&sp.rod, sp.vertex) {
            return err(
                if m.starts_with("unknown") {
                    "rod"
                } else {
                    "vertex"
                },
                m,
            );
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
        let node = node_of(&sp.rod, sp.vertex);
        let where_ = match &node {
            NodeKey::Joint(j) => format!("joint \"{}\"", s.joints[*j].name),
            NodeKey::Vertex(..) => format!("vertex {} of rod \"{}\"", sp.vertex, sp.rod),
        };
        if let Some(&(k, prev)) = motion.get(&node) {
            let field = if sp.move_to.is_some() {
                "move_to"
            } else {
                "kind"
            };
            match (prev, sp.move_to) {
                (Some(a), Some(b)) if a != b => {
                    return err(
                        field,
                        format!(
                            "contradicts supports[{k}], which moves {where_} to {a:?}, not {b:?}"
                        ),
                    )
                }
                (Some(a), None) => {
                    return err(
                        field,
                        format!(
                            "holds {where_} at its rest position, but supports[{k}] moves it \
                             to {a:?}; give both the same `move_to` or drop one"
                        ),
                    )
                }
                (None, Some(b)) => {
                    return err(
                        field,
                        format!(
                            "moves {where_} to {b:?}, but supports[{k}] holds it at its rest \
                             position; give both the same `move_to` or drop one"
                        ),
                    )
                }
                _ => {}
            }
        } else {
            motion.insert(node, (i, sp.move_to));
        }
    }

    for (i, l) in s.loads.iter().enumerate() {
        let err = |f: &str, msg: String| Err(FieldError::new("loads", i, f, msg));
        match l {
            Load::Force { rod, vertex, force } => {
                if let Err(m) = vertex_ok(rod, *vertex) {
                    return err(
                        if m.starts_with("unknown") {
                            "rod"
                        } else {
                            "vertex"
                        },
                        m,
                    );
                }
                if !finite3(force) {
                    return err(
                        "force",
                        format!("must be finite (at most {MAX_MAGNITUDE:e} N), got {force:?}"),
                    );
                }
            }
            Load::Torque {
                rod,
                vertex,
                torque,
            } => {
                if let Err(m) = vertex_ok(rod, *vertex) {
                    return err(
                        if m.starts_with("unknown") {
                            "rod"
                        } else {
                            "vertex"
                        },
                        m,
                    );
                }
                if !finite3(torque) {
                    return err(
                        "torque",
                        format!("must be finite (at most {MAX_MAGNITUDE:e} N·m), got {torque:?}"),
                    );
                }
            }
            Load::Gravity { g } => {
                if !finite3(g) {
                    return err("g", format!("must be finite, got {g:?}"));
                }
            }
        }
    }

    unsupported_loads(s)?;

    for (i, o) in s.obstacles.iter().enumerate() {
        let err = |f: &str, msg: String| Err(FieldError::new("obstacles", i, f, msg));
        let nonzero = |v: &[f64; 3]| finite3(v) && v.iter().any(|x| *x != 0.0);
        match o {
            Obstacle::Plane { point, normal } => {
                if !finite3(point) {
                    return err("point", format!("must be finite, got {point:?}"));
                }
                if !nonzero(normal) {
                    return err(
                        "normal",
                        format!("must be finite and non-zero, got {normal:?}"),
                    );
                }
            }
            Obstacle::Sphere { center, radius } => {
                if !finite3(center) {
                    return err("center", format!("must be finite, got {center:?}"));
                }
                if !positive(*radius) {
                    return err(
                        "radius",
                        format!("must be positive and finite, got {radius}"),
                    );
                }
            }
            Obstacle::Cylinder {
                point,
                axis,
                radius,
            } => {
                if !finite3(point) {
                    return err("point", format!("must be finite, got {point:?}"));
                }
                if !nonzero(axis) {
                    return err("axis", format!("must be finite and non-zero, got {axis:?}"));
                }
                if !positive(*radius) {
                    return err(
                        "radius",
                        format!("must be positive and finite, got {radius}"),
                    );
                }
            }
        }
    }

    for (i, b) in s.bounds.iter().enumerate() {
        let err = |f: &str, msg: String| Err(FieldError::new("bounds", i, f, msg));
        match (&b.rod, &b.vertices) {
            (Some(rod), vertices) => {
                if !rods.contains_key(rod.as_str()) {
                    return err("rod", format!("unknown rod \"{rod}\""));
                }
                for &v in vertices.iter().flatten() {
                    if let Err(m) = vertex_ok(rod, v) {
                        return err("vertices", m);
                    }
                }
                if vertices.as_ref().is_some_and(|v| v.is_empty()) {
                    return err(
                        "vertices",
                        "must not be empty (omit it to bound every node)".into(),
                    );
                }
            }
            (None, Some(_)) => {
                return err(
                    "vertices",
                    "needs `rod` (vertices index a rod's input points)".into(),
                )
            }
            (None, None) => {}
        }
        for k in 0..3 {
            for (f, v) in [("min", b.min[k]), ("max", b.max[k])] {
                if v.is_some_and(|x| !x.is_finite()) {
                    return err(f, format!("component {k} must be finite, got {v:?}"));
                }
            }
            if let (Some(lo), Some(hi)) = (b.min[k], b.max[k]) {
                // An equal pair would be an equality with no interior, which the interior-point
                // QP handles badly; a fixed coordinate is a support's job.
                if lo >= hi {
                    return err(
                        "max",
                        format!("component {k}: max {hi} must be above min {lo}"),
                    );
                }
            }
        }
        if b.min.iter().chain(&b.max).all(|v| v.is_none()) {
            return err(
                "min",
                "give at least one component of `min` or `max`".into(),
            );
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

    if let Some(r) = &s.reference {
        let err = |f: &str, msg: String| Err(FieldError::global("reference", f, msg));
        if let Err(m) = vertex_ok(&r.rod, r.vertex) {
            return err(
                if m.starts_with("unknown") {
                    "rod"
                } else {
                    "vertex"
                },
                m,
            );
        }
        if !finite3(&r.position) {
            return err("position", format!("must be finite, got {:?}", r.position));
        }
        // The error is relative to the vertex's displacement, so a reference at rest would
        // divide by zero.
        let rod = rods[r.rod.as_str()];
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
    }

    let sv = &s.solver;
    if !positive(sv.tolerance) {
        return Err(FieldError::global(
            "solver",
            "tolerance",
            format!("must be positive, got {:e}", sv.tolerance),
        ));
    }
    if sv.max_iterations == 0 {
        return Err(FieldError::global(
            "solver",
            "max_iterations",
            "must be at least 1".into(),
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

/// A node of the built network: a joint, or a rod vertex outside any joint.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
enum NodeKey {
    Joint(usize),
    Vertex(String, usize),
}

/// Two non-adjacent points of one rod at the same place would make two nodes sit on each other
/// with nothing between them; that is only meaningful when a joint ties them together.
fn repeated_points(s: &Scene, in_joint: &HashMap<(&str, usize), usize>) -> Result<(), FieldError> {
    for (i, r) in s.rods.iter().enumerate() {
        let m = r.points.len();
        let segs = if r.closed { m } else { m - 1 };
        let length: f64 = (0..segs)
            .map(|k| dist(&r.points[k], &r.points[(k + 1) % m]))
            .sum();
        let tol = 1e-12 * length;
        let mut order: Vec<usize> = (0..m).collect();
        order.sort_by(|&a, &b| r.points[a][0].total_cmp(&r.points[b][0]));
        for (oi, &a) in order.iter().enumerate() {
            for &b in &order[oi + 1..] {
                if r.points[b][0] - r.points[a][0] > tol {
                    break;
                }
                if dist(&r.points[a], &r.points[b]) > tol {
                    continue;
                }
                let (lo, hi) = (a.min(b), a.max(b));
                let joined = match (
                    in_joint.get(&(r.name.as_str(), lo)),
                    in_joint.get(&(r.name.as_str(), hi)),
                ) {
                    (Some(x), Some(y)) => x == y,
                    _ => false,
                };
                if !joined {
                    return Err(FieldError::new(
                        "rods",
                        i,
                        "points",
                        format!(
                            "points {lo} and {hi} are at the same place {:?}; if the rod crosses \
                             itself there, join the two vertices with a Joint, otherwise move one",
                            r.points[lo]
                        ),
                    ));
                }
            }
        }
    }
    Ok(())
}

/// A group of joined rods with a net load and no support has no equilibrium: Newton would
/// chase a rigid-body drift. Self-equilibrated loads (zero net force and moment) are allowed.
fn unsupported_loads(s: &Scene) -> Result<(), FieldError> {
    let index: HashMap<&str, usize> = s
        .rods
        .iter()
        .enumerate()
        .map(|(i, r)| (r.name.as_str(), i))
        .collect();
    let mut parent: Vec<usize> = (0..s.rods.len()).collect();
    fn find(p: &mut [usize], mut i: usize) -> usize {
        while p[i] != i {
            p[i] = p[p[i]];
            i = p[i];
        }
        i
    }
    for j in &s.joints {
        let a = index[j.at[0].0.as_str()];
        for (rod, _) in &j.at[1..] {
            let (ra, rb) = (find(&mut parent, a), find(&mut parent, index[rod.as_str()]));
            parent[rb] = ra;
        }
    }
    let n = s.rods.len();
    let mut supported = vec![false; n];
    for sp in &s.supports {
        let c = find(&mut parent, index[sp.rod.as_str()]);
        supported[c] = true;
    }
    // Net force and net moment about the origin per group, with a magnitude for round-off.
    type Net = ([f64; 3], [f64; 3], f64, Option<(usize, usize)>);
    let mut net: Vec<Net> = vec![([0.0; 3], [0.0; 3], 0.0, None); n];
    let point = |rod: &str, v: usize| s.rods[index[rod]].points[v];
    for (li, l) in s.loads.iter().enumerate() {
        match l {
            Load::Force { rod, vertex, force } => {
                let c = find(&mut parent, index[rod.as_str()]);
                let p = point(rod, *vertex);
                let e = &mut net[c];
                let mo = cross(p, *force);
                for k in 0..3 {
                    e.0[k] += force[k];
                    e.1[k] += mo[k];
                }
                e.2 += norm(force) * (1.0 + norm(&p));
                e.3.get_or_insert((li, index[rod.as_str()]));
            }
            Load::Torque {
                rod,
                vertex: _,
                torque,
            } => {
                let c = find(&mut parent, index[rod.as_str()]);
                let e = &mut net[c];
                for k in 0..3 {
                    e.1[k] += torque[k];
                }
                e.2 += norm(torque);
                e.3.get_or_insert((li, index[rod.as_str()]));
            }
            Load::Gravity { g } => {
                for (ri, r) in s.rods.iter().enumerate() {
                    let mat = &s.materials[&r.material];
                    let m = r.points.len();
                    let segs = if r.closed { m } else { m - 1 };
                    let c = find(&mut parent, ri);
                    for k in 0..segs {
                        let (a, b) = (&r.points[k], &r.points[(k + 1) % m]);
                        let w = mat.density * mat.section.area() * dist(a, b);
                        if w == 0.0 {
                            continue;
                        }
                        let mid = [
                            0.5 * (a[0] + b[0]),
                            0.5 * (a[1] + b[1]),
                            0.5 * (a[2] + b[2]),
                        ];
                        let f = [w * g[0], w * g[1], w * g[2]];
                        let mo = cross(mid, f);
                        let e = &mut net[c];
                        for k in 0..3 {
                            e.0[k] += f[k];
                            e.1[k] += mo[k];
                        }
                        e.2 += norm(&f) * (1.0 + norm(&mid));
                        e.3.get_or_insert((li, ri));
                    }
                }
            }
        }
    }
    for ri in 0..n {
        let c = find(&mut parent, ri);
        if c != ri || supported[c] {
            continue;
        }
        let (f, m, scale, first) = &net[c];
        let Some((li, loaded)) = *first else { continue };
        if norm(f) + norm(m) > 1e-9 * scale {
            return Err(FieldError::new(
                "loads",
                li,
                "",
                format!(
                    "rod \"{}\" is loaded but neither it nor any rod joined to it has a \
                     support, so it has no equilibrium (net force {f:?} N); add a Support",
                    s.rods[loaded].name
                ),
            ));
        }
    }
    Ok(())
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn norm(a: &[f64; 3]) -> f64 {
    (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt()
}
