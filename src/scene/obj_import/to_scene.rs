//! The welded graph of an OBJ network to a scene: rods named after their groups, joints where
//! rods meet, supports chosen by height or group, one material.

use std::collections::{BTreeMap, HashMap, HashSet};

use super::graph::{graph, Chain, Graph};
use super::{Element, ObjError, ObjFile};
use crate::scene::types::{
    Joint, JointKind, Load, Material, Rod, Scene, Section, Solver, Support, SupportKind,
};

/// How an OBJ network becomes a scene.
#[derive(Debug, Clone)]
pub struct NetworkOptions {
    pub young_modulus: f64,
    pub poisson_ratio: Option<f64>,
    pub shear_modulus: Option<f64>,
    pub density: f64,
    pub radius: f64,
    pub joint: JointKind,
    pub subdivide: usize,
    /// Pin (clamp) every rod vertex with z at or below this height.
    pub pin_below: Option<f64>,
    pub clamp_below: Option<f64>,
    /// Pin (clamp) every vertex used by the elements of these `o`/`g` names.
    pub pin_groups: Vec<String>,
    pub clamp_groups: Vec<String>,
    /// Points closer than this are one point, m; default 1e-6 × the bounding-box diagonal.
    pub weld: Option<f64>,
    /// Chain 2-vertex lines of one object into rods.
    pub chain: bool,
    /// Gravitational acceleration along −z, m/s².
    pub gravity: Option<f64>,
    pub solver: Solver,
}

/// The scene generated from an OBJ network, with where each rod, joint and support came from
/// so that errors found later point into the OBJ file.
#[derive(Debug, Clone)]
pub struct Generated {
    pub scene: Scene,
    pub rod_lines: Vec<usize>,
    pub joint_lines: Vec<usize>,
    pub support_lines: Vec<usize>,
    pub weld_tolerance: f64,
}

/// Name of the single material of a generated scene.
pub const MATERIAL: &str = "obj";

/// The scene of an OBJ network: a rod per polyline or chain of 2-vertex lines, a joint wherever
/// several rod vertices share a point, supports chosen by the options.
pub fn to_scene(obj: &ObjFile, o: &NetworkOptions) -> Result<Generated, ObjError> {
    let g = graph(obj, o.weld, o.chain)?;
    let rods: Vec<Rod> = rod_names(&g.chains)
        .into_iter()
        .zip(&g.chains)
        .map(|(name, c)| Rod {
            name,
            material: MATERIAL.into(),
            points: c.ids.iter().map(|&id| g.points[id]).collect(),
            subdivide: o.subdivide,
            closed: c.closed,
            normal: None,
            end_correction: true,
        })
        .collect();
    let rod_lines = g.chains.iter().map(|c| c.line).collect();

    let mut joints = Vec::new();
    let mut joint_lines = Vec::new();
    for (&id, at) in &g.at_point {
        if at.len() < 2 {
            continue;
        }
        joints.push(Joint {
            name: format!("v{}", g.rep[id] + 1),
            at: at.iter().map(|&(r, k)| (rods[r].name.clone(), k)).collect(),
            kind: o.joint.clone(),
            normal: None,
        });
        joint_lines.push(obj.vertex_lines[g.rep[id]]);
    }

    let mut supports = Vec::new();
    let mut support_lines = Vec::new();
    for (id, kind) in support_kinds(obj, &g, o)? {
        let at = &g.at_point[&id];
        // A pin holds the shared node; a clamp holds the frame of every rod that meets there.
        let n = if kind == SupportKind::Clamp {
            at.len()
        } else {
            1
        };
        for &(r, k) in &at[..n] {
            supports.push(Support {
                rod: rods[r].name.clone(),
                vertex: k,
                kind,
                move_to: None,
                rotate_by: None,
            });
            support_lines.push(obj.vertex_lines[g.rep[id]]);
        }
    }

    Ok(Generated {
        scene: Scene {
            materials: material(o),
            rods,
            joints,
            supports,
            loads: match o.gravity {
                Some(g) => vec![Load::Gravity { g: [0.0, 0.0, -g] }],
                None => Vec::new(),
            },
            obstacles: Vec::new(),
            bounds: Vec::new(),
            target: None,
            reference: None,
            stages: Vec::new(),
            solver: o.solver.clone(),
        },
        rod_lines,
        joint_lines,
        support_lines,
        weld_tolerance: g.tol,
    })
}

/// Rod names: the group's name, numbered when a group holds several rods, unique overall.
fn rod_names(chains: &[Chain]) -> Vec<String> {
    let mut per_group: HashMap<&str, usize> = HashMap::new();
    for c in chains {
        *per_group.entry(c.group.as_str()).or_default() += 1;
    }
    let mut counter: HashMap<&str, usize> = HashMap::new();
    let mut taken: HashSet<String> = HashSet::new();
    let mut names = Vec::new();
    for c in chains {
        let base = if c.group.trim().is_empty() {
            "rod".to_string()
        } else {
            c.group.trim().to_string()
        };
        let k = counter.entry(c.group.as_str()).or_default();
        *k += 1;
        let mut name = if per_group[c.group.as_str()] > 1 || base == "rod" {
            format!("{base}.{k}")
        } else {
            base.clone()
        };
        let mut extra = 1;
        while !taken.insert(name.clone()) {
            extra += 1;
            name = format!("{base}.{k}.{extra}");
        }
        names.push(name);
    }
    names
}

/// The supported points (weld ids) and their kinds from the height and group options; a
/// point selected both ways is clamped.
fn support_kinds(
    obj: &ObjFile,
    g: &Graph,
    o: &NetworkOptions,
) -> Result<BTreeMap<usize, SupportKind>, ObjError> {
    let mut kind_of: BTreeMap<usize, SupportKind> = BTreeMap::new();
    let mut mark = |id: usize, k: SupportKind| {
        let e = kind_of.entry(id).or_insert(k);
        if k == SupportKind::Clamp {
            *e = k;
        }
    };
    for (below, kind, flag) in [
        (o.pin_below, SupportKind::Pin, "--pin-below"),
        (o.clamp_below, SupportKind::Clamp, "--clamp-below"),
    ] {
        let Some(z) = below else { continue };
        if !z.is_finite() {
            return Err(ObjError::global(format!("{flag} must be finite, got {z}")));
        }
        let hits: Vec<usize> = g
            .at_point
            .keys()
            .copied()
            .filter(|&id| g.points[id][2] <= z + g.tol)
            .collect();
        if hits.is_empty() {
            let lowest = g
                .at_point
                .keys()
                .map(|&id| g.points[id][2])
                .fold(f64::INFINITY, f64::min);
            return Err(ObjError::global(format!(
                "{flag} {z}: no polyline vertex lies at or below z = {z} (the lowest is at z = {lowest})"
            )));
        }
        for id in hits {
            mark(id, kind);
        }
    }
    for (groups, kind, flag) in [
        (&o.pin_groups, SupportKind::Pin, "--pin-group"),
        (&o.clamp_groups, SupportKind::Clamp, "--clamp-group"),
    ] {
        for name in groups {
            for id in group_points(obj, g, name, flag)? {
                mark(id, kind);
            }
        }
    }
    Ok(kind_of)
}

/// The points (weld ids) of the elements of `o`/`g` group `name`, which must all lie on
/// polylines; `flag` names the option in errors.
fn group_points(obj: &ObjFile, g: &Graph, name: &str, flag: &str) -> Result<Vec<usize>, ObjError> {
    let elems: Vec<&Element> = obj.elements.iter().filter(|e| e.group == name).collect();
    if elems.is_empty() {
        let mut names: Vec<&str> = obj.elements.iter().map(|e| e.group.as_str()).collect();
        names.sort();
        names.dedup();
        return Err(ObjError::global(format!(
            "{flag} {name:?}: the file has no `o` or `g` of that name (it has {names:?})"
        )));
    }
    let mut ids = Vec::new();
    for e in elems {
        for &v in &e.vertices {
            let id = g.id[v];
            if !g.at_point.contains_key(&id) {
                return Err(ObjError::at(
                    e.line,
                    format!(
                        "{flag} {name:?}: vertex {} at {:?} is not a point of any polyline",
                        v + 1,
                        obj.vertices[v]
                    ),
                ));
            }
            ids.push(id);
        }
    }
    Ok(ids)
}

/// The one material of a generated scene.
fn material(o: &NetworkOptions) -> BTreeMap<String, Material> {
    let mut materials = BTreeMap::new();
    materials.insert(
        MATERIAL.to_string(),
        Material {
            young_modulus: o.young_modulus,
            poisson_ratio: o.poisson_ratio,
            shear_modulus: o.shear_modulus,
            density: o.density,
            section: Section::Circle { radius: o.radius },
            yield_strength: None,
        },
    );
    materials
}
