use std::collections::HashMap;

use super::{finite3, segments, RodIndex, MAX_MAGNITUDE};
use crate::math::vec::{add, cross, dist, norm, scale};
use crate::math::UnionFind;
use crate::scene::types::{Load, Scene};
use crate::scene::FieldError;

pub(super) fn loads(s: &Scene, rods: &RodIndex) -> Result<(), FieldError> {
    for (i, l) in s.loads.iter().enumerate() {
        let err = |f: &str, msg: String| Err(FieldError::new("loads", i, f, msg));
        let (rod, vertex, field, value, unit) = match l {
            Load::Force { rod, vertex, force } => (rod, vertex, "force", force, "N"),
            Load::Torque {
                rod,
                vertex,
                torque,
            } => (rod, vertex, "torque", torque, "N·m"),
            Load::Gravity { g } => {
                if !finite3(g) {
                    return err("g", format!("must be finite, got {g:?}"));
                }
                continue;
            }
        };
        if let Err((f, m)) = rods.rod_vertex(rod, *vertex) {
            return err(f, m);
        }
        if !finite3(value) {
            return err(
                field,
                format!("must be finite (at most {MAX_MAGNITUDE:e} {unit}), got {value:?}"),
            );
        }
    }
    Ok(())
}

/// Gravity loads that act on nothing: every rod's material has density 0 (the default). A
/// warning, not an error: the contract's own example scene has `density: 0.0` beside a
/// commented-out `Gravity`, and such scenes have always solved (as unloaded). Rods of density 0
/// beside heavier ones are weightless on purpose (cables, ties) and get no warning.
pub(super) fn gravity_warnings(s: &Scene) -> Vec<FieldError> {
    let Some(why) = weightless(s) else {
        return Vec::new();
    };
    s.loads
        .iter()
        .enumerate()
        .filter(|(_, l)| matches!(l, Load::Gravity { .. }))
        .map(|(i, _)| FieldError::new("loads", i, "g", why.clone()))
        .collect()
}

/// Why gravity would act on nothing, if it would.
fn weightless(s: &Scene) -> Option<String> {
    let mut names: Vec<&str> = Vec::new();
    for r in &s.rods {
        if s.materials[&r.material].density > 0.0 {
            return None;
        }
        if !names.contains(&r.material.as_str()) {
            names.push(&r.material);
        }
    }
    let quoted: Vec<String> = names.iter().map(|n| format!("\"{n}\"")).collect();
    let (what, verb) = match names.len() {
        1 => ("the density of material", "is"),
        _ => ("the densities of materials", "are"),
    };
    Some(format!(
        "Gravity acts on no mass, so it does nothing: {what} {} {verb} 0 (the default); give \
         a `density` in kg/m³",
        quoted.join(", ")
    ))
}

/// Net force and net moment about the origin on one group of joined rods, with a magnitude
/// for round-off and the first load on the group (load index, rod index).
#[derive(Debug, Clone, Copy, Default)]
struct Net {
    force: [f64; 3],
    moment: [f64; 3],
    scale: f64,
    first: Option<(usize, usize)>,
}

impl Net {
    fn add(&mut self, force: [f64; 3], moment: [f64; 3], scale: f64, first: (usize, usize)) {
        for k in 0..3 {
            self.force[k] += force[k];
            self.moment[k] += moment[k];
        }
        self.scale += scale;
        self.first.get_or_insert(first);
    }

    /// A force `f` at point `p`.
    fn add_force(&mut self, p: [f64; 3], f: [f64; 3], first: (usize, usize)) {
        self.add(f, cross(p, f), norm(f) * (1.0 + norm(p)), first);
    }
}

/// A group of joined rods with a net load and no support has no equilibrium: Newton would
/// chase a rigid-body drift. Self-equilibrated loads (zero net force and moment) are allowed.
pub(super) fn unsupported_loads(s: &Scene) -> Result<(), FieldError> {
    let index: HashMap<&str, usize> = s
        .rods
        .iter()
        .enumerate()
        .map(|(i, r)| (r.name.as_str(), i))
        .collect();
    let mut groups = UnionFind::new(s.rods.len());
    for j in &s.joints {
        let a = index[j.at[0].0.as_str()];
        for (rod, _) in &j.at[1..] {
            groups.union(a, index[rod.as_str()]);
        }
    }
    let n = s.rods.len();
    let mut supported = vec![false; n];
    for sp in &s.supports {
        let c = groups.find(index[sp.rod.as_str()]);
        supported[c] = true;
    }
    let net = net_loads(s, &index, &mut groups);
    for ri in 0..n {
        let c = groups.find(ri);
        if c != ri || supported[c] {
            continue;
        }
        let Net {
            force: f,
            moment: m,
            scale,
            first,
        } = net[c];
        let Some((li, loaded)) = first else { continue };
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

/// The net load on each group, indexed by the group's root; weight acts at segment midpoints.
fn net_loads(s: &Scene, index: &HashMap<&str, usize>, groups: &mut UnionFind) -> Vec<Net> {
    let mut net = vec![Net::default(); s.rods.len()];
    for (li, l) in s.loads.iter().enumerate() {
        match l {
            Load::Force { rod, vertex, force } => {
                let ri = index[rod.as_str()];
                let p = s.rods[ri].points[*vertex];
                net[groups.find(ri)].add_force(p, *force, (li, ri));
            }
            Load::Torque {
                rod,
                vertex: _,
                torque,
            } => {
                let ri = index[rod.as_str()];
                net[groups.find(ri)].add([0.0; 3], *torque, norm(*torque), (li, ri));
            }
            Load::Gravity { g } => {
                for (ri, r) in s.rods.iter().enumerate() {
                    let mat = &s.materials[&r.material];
                    let m = r.points.len();
                    let c = groups.find(ri);
                    for k in 0..segments(r) {
                        let (a, b) = (&r.points[k], &r.points[(k + 1) % m]);
                        let w = mat.density * mat.section.area() * dist(a, b);
                        if w == 0.0 {
                            continue;
                        }
                        net[c].add_force(scale(add(*a, *b), 0.5), scale(*g, w), (li, ri));
                    }
                }
            }
        }
    }
    net
}
