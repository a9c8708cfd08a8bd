//! Rod networks drawn in a 3-D tool and saved as OBJ: `l` polylines become rods, vertices
//! shared by several polylines become joints, and simple selectors choose the supports.
//!
//! rodnet reads `v`, `l`, `p`, `o` and `g` itself instead of using `tobj`: tobj parses `l` in
//! the same branch as `f`, so a polyline comes back as a polygon (`l 1 2 3` is indistinguishable
//! from a triangle, and `triangulate` fans it), 2-vertex lines are dropped by its GPU options,
//! and positions are re-indexed per object, which loses the vertices that rods share
//! (checked when the dependencies were chosen). Polylines need the raw element lists.
//!
//! Tools write networks in two ways, and both are read:
//! - one `l` element per curve (Rhino, most CAD exporters), each curve usually in its own `o`
//!   or `g` with its own copies of shared points;
//! - one 2-vertex `l` per edge (Blender's mesh edges). Within one object these are chained
//!   back into rods: through every vertex where exactly two edges meet, and where more meet,
//!   through the straightest pairs (turning less than 45°); a joint sits wherever chains meet.
//!
//! Points closer than the weld tolerance are one point, so duplicated copies of a shared point
//! (one per object) still make a joint.

use std::collections::{BTreeMap, HashMap};
use std::fmt;

use crate::scene::types::{
    Joint, JointKind, Load, Material, Rod, Scene, Section, Solver, Support, SupportKind,
};

/// A parsed OBJ file: only what networks need.
#[derive(Debug, Clone, Default)]
pub struct ObjFile {
    pub vertices: Vec<[f64; 3]>,
    /// 1-based source line of each vertex.
    pub vertex_lines: Vec<usize>,
    pub elements: Vec<Element>,
    /// Elements that are read but not used for rods (faces, free-form curves), by keyword.
    pub ignored: BTreeMap<String, usize>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ElementKind {
    Line,
    Point,
}

#[derive(Debug, Clone)]
pub struct Element {
    pub kind: ElementKind,
    /// Name of the enclosing `o` or `g` (the later of the two), empty before any.
    pub group: String,
    /// 0-based vertex indices.
    pub vertices: Vec<usize>,
    /// 1-based source line.
    pub line: usize,
}

/// An error in an OBJ file (`line` set) or in the options that turn it into a scene.
#[derive(Debug, Clone, PartialEq)]
pub struct ObjError {
    pub line: Option<usize>,
    pub message: String,
}

impl ObjError {
    fn at(line: usize, message: String) -> Self {
        ObjError {
            line: Some(line),
            message,
        }
    }
    fn global(message: String) -> Self {
        ObjError {
            line: None,
            message,
        }
    }
}

impl fmt::Display for ObjError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line {
            Some(l) => write!(f, "{l}: {}", self.message),
            None => write!(f, "{}", self.message),
        }
    }
}

/// Parses the OBJ elements rodnet uses. Positive indices may refer to vertices defined later
/// (some exporters write elements first); negative ones count back from the vertices so far.
pub fn parse(src: &str) -> Result<ObjFile, ObjError> {
    let mut obj = ObjFile::default();
    let mut group = String::new();
    // (element index, position in it, raw index, line) of positive indices, checked at the end.
    let mut forward: Vec<(usize, usize, i64, usize)> = Vec::new();
    let mut pending = String::new();
    let mut pending_line = 0;
    for (i, raw) in src.lines().enumerate() {
        let text = raw.split('#').next().unwrap_or("");
        // A trailing backslash continues the statement on the next line.
        if pending.is_empty() {
            pending_line = i + 1;
        }
        if let Some(head) = text.trim_end().strip_suffix('\\') {
            pending.push_str(head);
            pending.push(' ');
            continue;
        }
        pending.push_str(text);
        let stmt = std::mem::take(&mut pending);
        let line = pending_line;
        let mut toks = stmt.split_whitespace();
        let Some(key) = toks.next() else { continue };
        match key {
            "v" => {
                let nums: Vec<&str> = toks.collect();
                if nums.len() < 3 {
                    return Err(ObjError::at(
                        line,
                        format!("`v` needs x, y and z, got {} number(s)", nums.len()),
                    ));
                }
                let mut p = [0.0; 3];
                for k in 0..3 {
                    p[k] = match nums[k].parse::<f64>() {
                        Ok(x) if x.is_finite() => x,
                        _ => {
                            return Err(ObjError::at(
                                line,
                                format!(
                                    "vertex coordinate {} is `{}`, not a finite number",
                                    ["x", "y", "z"][k],
                                    nums[k]
                                ),
                            ))
                        }
                    };
                }
                obj.vertices.push(p);
                obj.vertex_lines.push(line);
            }
            "o" | "g" => {
                group = toks.collect::<Vec<_>>().join(" ");
            }
            "l" | "p" => {
                let kind = if key == "l" {
                    ElementKind::Line
                } else {
                    ElementKind::Point
                };
                let e = obj.elements.len();
                let mut vertices = Vec::new();
                for (k, tok) in toks.enumerate() {
                    let first = tok.split('/').next().unwrap_or("");
                    let idx: i64 = first.parse().map_err(|_| {
                        ObjError::at(line, format!("`{tok}` is not a vertex index"))
                    })?;
                    let n = obj.vertices.len() as i64;
                    if idx == 0 {
                        return Err(ObjError::at(
                            line,
                            "vertex index 0 is invalid (OBJ indices start at 1)".into(),
                        ));
                    } else if idx < 0 {
                        if -idx > n {
                            return Err(ObjError::at(
                                line,
                                format!(
                                    "relative vertex index {idx} reaches before the first vertex \
                                     ({n} defined so far)"
                                ),
                            ));
                        }
                        vertices.push((n + idx) as usize);
                    } else {
                        forward.push((e, k, idx, line));
                        vertices.push((idx - 1) as usize);
                    }
                }
                if kind == ElementKind::Line && vertices.len() < 2 {
                    return Err(ObjError::at(
                        line,
                        format!(
                            "a line element needs at least 2 vertices, got {}",
                            vertices.len()
                        ),
                    ));
                }
                obj.elements.push(Element {
                    kind,
                    group: group.clone(),
                    vertices,
                    line,
                });
            }
            "f" | "curv" | "curv2" | "surf" => {
                *obj.ignored.entry(key.to_string()).or_default() += 1;
            }
            _ => {}
        }
    }
    let n = obj.vertices.len();
    for (_, _, idx, line) in forward {
        if idx as usize > n {
            return Err(ObjError::at(
                line,
                format!("vertex index {idx} is out of range: the file defines {n} vertices"),
            ));
        }
    }
    Ok(obj)
}

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

/// Segments turning by less than this at a vertex where several edges meet continue one rod.
const CHAIN_MAX_TURN_DEG: f64 = 45.0;

struct Weld {
    /// Weld id of each OBJ vertex (usize::MAX when unused).
    id: Vec<usize>,
    /// Representative OBJ vertex of each weld id.
    rep: Vec<usize>,
}

fn weld(obj: &ObjFile, used: &[bool], tol: f64) -> Weld {
    let mut id = vec![usize::MAX; obj.vertices.len()];
    let mut rep = Vec::new();
    let cell = |x: f64| (x / tol).floor() as i64;
    let mut grid: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
    for (v, p) in obj.vertices.iter().enumerate() {
        if !used[v] {
            continue;
        }
        let c = [cell(p[0]), cell(p[1]), cell(p[2])];
        let mut found = None;
        'search: for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    if let Some(list) = grid.get(&[c[0] + dx, c[1] + dy, c[2] + dz]) {
                        for &w in list {
                            if dist(&obj.vertices[rep[w]], p) <= tol {
                                found = Some(w);
                                break 'search;
                            }
                        }
                    }
                }
            }
        }
        id[v] = match found {
            Some(w) => w,
            None => {
                rep.push(v);
                grid.entry(c).or_default().push(rep.len() - 1);
                rep.len() - 1
            }
        };
    }
    Weld { id, rep }
}

fn dist(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// A 2-vertex line: weld ids of its ends and its source line.
type Segment = (usize, usize, usize);

/// A rod before naming: weld ids in order, closed or not, group and source line.
struct Chain {
    ids: Vec<usize>,
    closed: bool,
    group: String,
    line: usize,
}

pub fn to_scene(obj: &ObjFile, o: &NetworkOptions) -> Result<Generated, ObjError> {
    let mut used = vec![false; obj.vertices.len()];
    for e in &obj.elements {
        for &v in &e.vertices {
            used[v] = true;
        }
    }
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for (v, p) in obj.vertices.iter().enumerate() {
        if used[v] {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
    }
    let lines = obj
        .elements
        .iter()
        .filter(|e| e.kind == ElementKind::Line)
        .count();
    if lines == 0 {
        let ignored: Vec<String> = obj
            .ignored
            .iter()
            .map(|(k, n)| format!("{n} `{k}`"))
            .collect();
        return Err(ObjError::global(format!(
            "the file has no `l` polylines, so no rods{}; export the curves as polylines",
            if ignored.is_empty() {
                String::new()
            } else {
                format!(
                    " (it has {}, which rodnet does not read)",
                    ignored.join(", ")
                )
            }
        )));
    }
    let diag = dist(&lo, &hi);
    let tol = match o.weld {
        Some(t) if t.is_finite() && t >= 0.0 => t,
        Some(t) => {
            return Err(ObjError::global(format!(
                "--weld must be a non-negative length, got {t}"
            )))
        }
        None => 1e-6 * diag,
    };
    // A zero tolerance still merges exactly repeated coordinates.
    let w = weld(obj, &used, tol.max(f64::MIN_POSITIVE));
    let pos = |id: usize| obj.vertices[w.rep[id]];

    let mut chains: Vec<Chain> = Vec::new();
    // 2-vertex lines per group, for chaining: (a, b, line).
    let mut segments: Vec<(String, Vec<Segment>)> = Vec::new();
    for e in obj.elements.iter().filter(|e| e.kind == ElementKind::Line) {
        let mut ids: Vec<usize> = e.vertices.iter().map(|&v| w.id[v]).collect();
        for k in 0..ids.len() - 1 {
            if ids[k] == ids[k + 1] {
                return Err(ObjError::at(
                    e.line,
                    format!(
                        "points {} and {} of this polyline (vertices {} and {}) are the same \
                         point within the weld tolerance {tol:.3e} m: a zero-length segment",
                        k + 1,
                        k + 2,
                        e.vertices[k] + 1,
                        e.vertices[k + 1] + 1
                    ),
                ));
            }
        }
        if o.chain && ids.len() == 2 {
            match segments.iter_mut().find(|(g, _)| *g == e.group) {
                Some((_, list)) => list.push((ids[0], ids[1], e.line)),
                None => segments.push((e.group.clone(), vec![(ids[0], ids[1], e.line)])),
            }
            continue;
        }
        let closed = ids.len() > 2 && ids[0] == ids[ids.len() - 1];
        if closed {
            ids.pop();
            if ids.len() < 3 {
                return Err(ObjError::at(
                    e.line,
                    "a closed polyline needs at least 3 distinct points".into(),
                ));
            }
        }
        chains.push(Chain {
            ids,
            closed,
            group: e.group.clone(),
            line: e.line,
        });
    }
    for (group, segs) in &segments {
        chain_segments(group, segs, &pos, &mut chains)?;
    }

    // Names: the group's name, numbered when a group holds several rods, unique overall.
    let mut per_group: HashMap<&str, usize> = HashMap::new();
    for c in &chains {
        *per_group.entry(c.group.as_str()).or_default() += 1;
    }
    let mut counter: HashMap<&str, usize> = HashMap::new();
    let mut taken: std::collections::HashSet<String> = Default::default();
    let mut rods = Vec::new();
    let mut rod_lines = Vec::new();
    for c in &chains {
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
        rods.push(Rod {
            name,
            material: MATERIAL.into(),
            points: c.ids.iter().map(|&id| pos(id)).collect(),
            subdivide: o.subdivide,
            closed: c.closed,
            normal: None,
        });
        rod_lines.push(c.line);
    }

    // Joints wherever several rod vertices share a point.
    let mut at_point: BTreeMap<usize, Vec<(usize, usize)>> = BTreeMap::new();
    for (r, c) in chains.iter().enumerate() {
        for (k, &id) in c.ids.iter().enumerate() {
            at_point.entry(id).or_default().push((r, k));
        }
    }
    let mut joints = Vec::new();
    let mut joint_lines = Vec::new();
    for (&id, at) in &at_point {
        if at.len() < 2 {
            continue;
        }
        joints.push(Joint {
            name: format!("v{}", w.rep[id] + 1),
            at: at.iter().map(|&(r, k)| (rods[r].name.clone(), k)).collect(),
            kind: o.joint.clone(),
            normal: None,
        });
        joint_lines.push(obj.vertex_lines[w.rep[id]]);
    }

    // Supports.
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
        let hits: Vec<usize> = at_point
            .keys()
            .copied()
            .filter(|&id| pos(id)[2] <= z + tol)
            .collect();
        if hits.is_empty() {
            let lowest = at_point
                .keys()
                .map(|&id| pos(id)[2])
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
        for g in groups {
            let elems: Vec<&Element> = obj.elements.iter().filter(|e| e.group == *g).collect();
            if elems.is_empty() {
                let mut names: Vec<&str> = obj.elements.iter().map(|e| e.group.as_str()).collect();
                names.sort();
                names.dedup();
                return Err(ObjError::global(format!(
                    "{flag} {g:?}: the file has no `o` or `g` of that name (it has {names:?})"
                )));
            }
            for e in elems {
                for &v in &e.vertices {
                    let id = w.id[v];
                    if !at_point.contains_key(&id) {
                        return Err(ObjError::at(
                            e.line,
                            format!(
                                "{flag} {g:?}: vertex {} at {:?} is not a point of any polyline",
                                v + 1,
                                obj.vertices[v]
                            ),
                        ));
                    }
                    mark(id, kind);
                }
            }
        }
    }
    let mut supports = Vec::new();
    let mut support_lines = Vec::new();
    for (&id, &kind) in &kind_of {
        let at = &at_point[&id];
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
            support_lines.push(obj.vertex_lines[w.rep[id]]);
        }
    }

    let mut materials = BTreeMap::new();
    materials.insert(
        MATERIAL.to_string(),
        Material {
            young_modulus: o.young_modulus,
            poisson_ratio: o.poisson_ratio,
            shear_modulus: o.shear_modulus,
            density: o.density,
            section: Section::Circle { radius: o.radius },
        },
    );
    let loads = match o.gravity {
        Some(g) => vec![Load::Gravity { g: [0.0, 0.0, -g] }],
        None => Vec::new(),
    };
    Ok(Generated {
        scene: Scene {
            materials,
            rods,
            joints,
            supports,
            loads,
            obstacles: Vec::new(),
            bounds: Vec::new(),
            target: None,
            reference: None,
            solver: o.solver.clone(),
        },
        rod_lines,
        joint_lines,
        support_lines,
        weld_tolerance: tol,
    })
}

/// Chains one group's 2-vertex segments into rods (see the module comment).
fn chain_segments(
    group: &str,
    segs: &[Segment],
    pos: &dyn Fn(usize) -> [f64; 3],
    out: &mut Vec<Chain>,
) -> Result<(), ObjError> {
    let mut seen: HashMap<(usize, usize), usize> = HashMap::new();
    let mut incident: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for (s, &(a, b, line)) in segs.iter().enumerate() {
        if let Some(first) = seen.insert((a.min(b), a.max(b)), line) {
            return Err(ObjError::at(
                line,
                format!("this edge repeats the edge on line {first}"),
            ));
        }
        incident.entry(a).or_default().push(s);
        incident.entry(b).or_default().push(s);
    }
    let cos_limit = -(CHAIN_MAX_TURN_DEG.to_radians().cos());
    // partner[(segment, end)] = the segment that continues it through that end's vertex.
    let mut partner: HashMap<(usize, usize), usize> = HashMap::new();
    let end_of = |s: usize, v: usize| if segs[s].0 == v { 0 } else { 1 };
    for (&v, list) in &incident {
        if list.len() == 2 {
            partner.insert((list[0], end_of(list[0], v)), list[1]);
            partner.insert((list[1], end_of(list[1], v)), list[0]);
            continue;
        }
        let dir = |s: usize| {
            let (a, b, _) = segs[s];
            let other = if a == v { b } else { a };
            let (p, q) = (pos(v), pos(other));
            let d = [q[0] - p[0], q[1] - p[1], q[2] - p[2]];
            let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            [d[0] / n, d[1] / n, d[2] / n]
        };
        let mut pairs: Vec<(f64, usize, usize)> = Vec::new();
        for i in 0..list.len() {
            for j in i + 1..list.len() {
                let (di, dj) = (dir(list[i]), dir(list[j]));
                let c = di[0] * dj[0] + di[1] * dj[1] + di[2] * dj[2];
                if c < cos_limit {
                    pairs.push((c, list[i], list[j]));
                }
            }
        }
        pairs.sort_by(|x, y| x.0.total_cmp(&y.0).then((x.1, x.2).cmp(&(y.1, y.2))));
        let mut paired = std::collections::HashSet::new();
        for (_, s, t) in pairs {
            if paired.contains(&s) || paired.contains(&t) {
                continue;
            }
            paired.insert(s);
            paired.insert(t);
            partner.insert((s, end_of(s, v)), t);
            partner.insert((t, end_of(t, v)), s);
        }
    }
    let mut done = vec![false; segs.len()];
    // Walks from segment `s`, entering through end `from`, and returns the vertex ids.
    let walk = |s0: usize, from: usize, done: &mut [bool]| -> (Vec<usize>, bool) {
        let (a, b, _) = segs[s0];
        let mut ids = if from == 0 { vec![a, b] } else { vec![b, a] };
        done[s0] = true;
        let (mut s, mut exit) = (s0, 1 - from);
        while let Some(&t) = partner.get(&(s, exit)) {
            if t == s0 {
                ids.pop();
                return (ids, true);
            }
            if done[t] {
                break;
            }
            done[t] = true;
            let v = *ids.last().unwrap();
            let e = end_of(t, v);
            let (ta, tb, _) = segs[t];
            ids.push(if e == 0 { tb } else { ta });
            s = t;
            exit = 1 - e;
        }
        (ids, false)
    };
    // Open chains start at an unpartnered end; what is left are closed loops.
    for s in 0..segs.len() {
        for end in 0..2 {
            if !done[s] && !partner.contains_key(&(s, end)) {
                let (ids, closed) = walk(s, end, &mut done);
                out.push(Chain {
                    ids,
                    closed,
                    group: group.to_string(),
                    line: segs[s].2,
                });
            }
        }
    }
    for s in 0..segs.len() {
        if !done[s] {
            let (ids, closed) = walk(s, 0, &mut done);
            out.push(Chain {
                ids,
                closed,
                group: group.to_string(),
                line: segs[s].2,
            });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn opts() -> NetworkOptions {
        NetworkOptions {
            young_modulus: 1e9,
            poisson_ratio: Some(0.3),
            shear_modulus: None,
            density: 0.0,
            radius: 0.01,
            joint: JointKind::Rigid,
            subdivide: 1,
            pin_below: None,
            clamp_below: None,
            pin_groups: vec![],
            clamp_groups: vec![],
            weld: None,
            chain: true,
            gravity: None,
            solver: Solver::default(),
        }
    }

    #[test]
    fn polylines_with_duplicated_shared_points_make_joints() {
        // Two objects, each with its own copy of the crossing point (as Rhino writes them).
        let src = "o a\nv 0 0 0\nv 1 0 0\nv 2 0 0\nl 1 2 3\n\
                   o b\nv 1 -1 0\nv 1 0 0\nv 1 1 0\nl 4 5 6\n";
        let g = to_scene(&parse(src).unwrap(), &opts()).unwrap();
        let s = &g.scene;
        assert_eq!(s.rods.len(), 2);
        assert_eq!(
            (s.rods[0].name.as_str(), s.rods[1].name.as_str()),
            ("a", "b")
        );
        assert_eq!(s.joints.len(), 1);
        assert_eq!(
            s.joints[0].at,
            vec![("a".to_string(), 1), ("b".to_string(), 1)]
        );
        assert_eq!(g.rod_lines, vec![5, 10]);
        assert_eq!(g.joint_lines, vec![3]);
    }

    #[test]
    fn edges_are_chained_through_straight_continuations() {
        // A plus sign drawn edge by edge (Blender style) plus a closed triangle of edges.
        let src = "o plus\nv 0 0 0\nv 1 0 0\nv 2 0 0\nv 1 -1 0\nv 1 1 0\n\
                   l 1 2\nl 2 3\nl 4 2\nl 2 5\n\
                   o tri\nv 5 0 0\nv 6 0 0\nv 5 1 0\nl 6 7\nl 8 7\nl 6 8\n";
        let s = to_scene(&parse(src).unwrap(), &opts()).unwrap().scene;
        let by_name: HashMap<&str, &Rod> = s.rods.iter().map(|r| (r.name.as_str(), r)).collect();
        assert_eq!(s.rods.len(), 3, "{:?}", by_name.keys());
        let h = by_name["plus.1"];
        assert_eq!(
            h.points,
            vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]]
        );
        let v = by_name["plus.2"];
        assert_eq!(
            v.points,
            vec![[1.0, -1.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0]]
        );
        let t = by_name["tri"];
        assert!(t.closed);
        assert_eq!(t.points.len(), 3);
        assert_eq!(s.joints.len(), 1);
        // Without chaining every edge is its own rod.
        let mut o = opts();
        o.chain = false;
        let s = to_scene(&parse(src).unwrap(), &o).unwrap().scene;
        assert_eq!(s.rods.len(), 7);
    }

    #[test]
    fn supports_from_height_and_groups() {
        let src = "v 0 0 0\nv 0 0 1\nv 1 0 1\nv 1 0 0\nl 1 2 3 4\n\
                   g anchors\np 3\n";
        let mut o = opts();
        o.pin_below = Some(0.0);
        o.clamp_groups = vec!["anchors".into()];
        let s = to_scene(&parse(src).unwrap(), &o).unwrap().scene;
        let got: Vec<(usize, SupportKind)> =
            s.supports.iter().map(|s| (s.vertex, s.kind)).collect();
        assert_eq!(
            got,
            vec![
                (0, SupportKind::Pin),
                (2, SupportKind::Clamp),
                (3, SupportKind::Pin)
            ]
        );
        o.pin_below = Some(-1.0);
        let e = to_scene(&parse(src).unwrap(), &o).unwrap_err();
        assert!(e.message.contains("the lowest is at z = 0"), "{e}");
    }

    #[test]
    fn located_errors() {
        let cases = [
            ("v 0 0 0\nv 1 0\n", 2, "needs x, y and z"),
            ("v 0 0 0\nv 1 0 nan\n", 2, "not a finite number"),
            ("v 0 0 0\nv 1 0 0\nl 1 3\n", 3, "out of range"),
            ("v 0 0 0\nl 1 0\n", 2, "index 0"),
            ("v 0 0 0\nl -2 1\n", 2, "reaches before the first vertex"),
            ("v 0 0 0\nl 1\n", 2, "at least 2 vertices"),
            ("v 0 0 0\nv 1 0 0\nl 1 x\n", 3, "not a vertex index"),
        ];
        for (src, line, needle) in cases {
            let e = parse(src).unwrap_err();
            assert_eq!(e.line, Some(line), "{src:?}: {e}");
            assert!(e.message.contains(needle), "{src:?}: {e}");
        }
        let gen = |src: &str| to_scene(&parse(src).unwrap(), &opts()).unwrap_err();
        let e = gen("v 0 0 0\nv 0 0 0\nv 1 0 0\nl 1 2 3\n");
        assert_eq!(e.line, Some(4));
        assert!(e.message.contains("zero-length"), "{e}");
        let e = gen("v 0 0 0\nv 1 0 0\nf 1 2 1\n");
        assert!(
            e.message.contains("no `l` polylines") && e.message.contains("1 `f`"),
            "{e}"
        );
        let e = gen("v 0 0 0\nv 1 0 0\nl 1 2\nl 2 1\n");
        assert_eq!(e.line, Some(4));
        assert!(e.message.contains("repeats the edge on line 3"), "{e}");
    }

    #[test]
    fn continuation_lines_and_forward_references() {
        let src = "l 1 2 \\\n  3\nv 0 0 0\nv 1 0 0\nv 2 1 0\n";
        let obj = parse(src).unwrap();
        assert_eq!(obj.elements[0].vertices, vec![0, 1, 2]);
        assert_eq!(obj.elements[0].line, 1);
        assert_eq!(obj.vertex_lines, vec![3, 4, 5]);
    }
}
