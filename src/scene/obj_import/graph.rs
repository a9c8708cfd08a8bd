//! OBJ polylines to a graph: vertices closer than the weld tolerance become one point, 2-vertex
//! lines are chained into rods, and each point knows the rod vertices that meet there.

use std::collections::{BTreeMap, HashMap, HashSet};

use super::{ElementKind, ObjError, ObjFile};
use crate::math::vec::{dist, dot, norm, sub};
use crate::scene::validate::MAX_MAGNITUDE;

/// Segments turning by less than this at a vertex where several edges meet continue one rod.
const CHAIN_MAX_TURN_DEG: f64 = 45.0;

/// A rod before naming: weld ids in order, closed or not, group and source line.
pub(super) struct Chain {
    pub ids: Vec<usize>,
    pub closed: bool,
    pub group: String,
    pub line: usize,
}

/// The welded points of an OBJ file and the rods through them.
pub(super) struct Graph {
    /// Weld id of each OBJ vertex (usize::MAX when unused).
    pub id: Vec<usize>,
    /// Representative OBJ vertex of each weld id.
    pub rep: Vec<usize>,
    /// Position of each weld id (that of its representative).
    pub points: Vec<[f64; 3]>,
    /// Points closer than this are one point, m.
    pub tol: f64,
    pub chains: Vec<Chain>,
    /// The rod vertices at each point that rods use, as (chain, position in it), by weld id.
    pub at_point: BTreeMap<usize, Vec<(usize, usize)>>,
}

/// A 2-vertex line: weld ids of its ends and its source line.
type Segment = (usize, usize, usize);

/// The 2-vertex lines of each group, groups in their order in the file.
type GroupSegments = Vec<(String, Vec<Segment>)>;

/// Welds the vertices that the elements use, with the given tolerance (default 1e-6 × the
/// diagonal of their bounding box), and chains 2-vertex lines of one group when `chain`.
pub(super) fn graph(obj: &ObjFile, weld_tol: Option<f64>, chain: bool) -> Result<Graph, ObjError> {
    let mut used = vec![false; obj.vertices.len()];
    for e in &obj.elements {
        for &v in &e.vertices {
            used[v] = true;
        }
    }
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for (v, p) in obj.vertices.iter().enumerate() {
        if used[v] {
            // Beyond the scene's limit the default tolerance (a fraction of the bounding box's
            // diagonal) would overflow to infinity and weld everything into one point.
            if let Some(x) = p.iter().find(|x| !x.is_finite() || x.abs() > MAX_MAGNITUDE) {
                return Err(ObjError {
                    line: obj.vertex_lines.get(v).copied(),
                    message: format!(
                        "vertex {}: coordinate {x:e} is not finite or beyond ±{MAX_MAGNITUDE:e} m \
                         (the largest a scene accepts)",
                        v + 1
                    ),
                });
            }
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
    }
    if !obj.elements.iter().any(|e| e.kind == ElementKind::Line) {
        return Err(no_polylines(obj));
    }
    let tol = match weld_tol {
        Some(t) if t.is_finite() && t >= 0.0 => t,
        Some(t) => {
            return Err(ObjError::global(format!(
                "--weld must be a non-negative length, got {t}"
            )))
        }
        None => 1e-6 * dist(&lo, &hi),
    };
    // A zero tolerance still merges exactly repeated coordinates.
    let (id, rep) = weld(obj, &used, tol.max(f64::MIN_POSITIVE));
    let points: Vec<[f64; 3]> = rep.iter().map(|&v| obj.vertices[v]).collect();
    let (mut chains, segments) = polylines(obj, &id, tol, chain)?;
    for (group, segs) in &segments {
        chain_segments(group, segs, &points, &mut chains)?;
    }
    let mut at_point: BTreeMap<usize, Vec<(usize, usize)>> = BTreeMap::new();
    for (r, c) in chains.iter().enumerate() {
        for (k, &id) in c.ids.iter().enumerate() {
            at_point.entry(id).or_default().push((r, k));
        }
    }
    Ok(Graph {
        id,
        rep,
        points,
        tol,
        chains,
        at_point,
    })
}

fn no_polylines(obj: &ObjFile) -> ObjError {
    let ignored: Vec<String> = obj
        .ignored
        .iter()
        .map(|(k, n)| format!("{n} `{k}`"))
        .collect();
    ObjError::global(format!(
        "the file has no `l` polylines, so no rods{}; export the curves as polylines",
        if ignored.is_empty() {
            String::new()
        } else {
            format!(
                " (it has {}, which rodnet does not read)",
                ignored.join(", ")
            )
        }
    ))
}

/// The weld id of each used OBJ vertex and the representative vertex of each weld id: a vertex
/// joins the first earlier representative within `tol`, searched through a grid of cells.
fn weld(obj: &ObjFile, used: &[bool], tol: f64) -> (Vec<usize>, Vec<usize>) {
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
    (id, rep)
}

/// The `l` elements in weld ids: the rods they are by themselves, and when `chain` the
/// 2-vertex lines set aside per group for chaining.
fn polylines(
    obj: &ObjFile,
    id: &[usize],
    tol: f64,
    chain: bool,
) -> Result<(Vec<Chain>, GroupSegments), ObjError> {
    let mut chains: Vec<Chain> = Vec::new();
    let mut segments = GroupSegments::new();
    for e in obj.elements.iter().filter(|e| e.kind == ElementKind::Line) {
        let mut ids: Vec<usize> = e.vertices.iter().map(|&v| id[v]).collect();
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
        if chain && ids.len() == 2 {
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
    Ok((chains, segments))
}

/// Chains one group's 2-vertex segments into rods (see the module comment of
/// [`super`]).
fn chain_segments(
    group: &str,
    segs: &[Segment],
    points: &[[f64; 3]],
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
    let partner = partners(segs, &incident, points);
    let end_of = |s: usize, v: usize| if segs[s].0 == v { 0 } else { 1 };
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
    let mut push = |s: usize, (ids, closed): (Vec<usize>, bool)| {
        out.push(Chain {
            ids,
            closed,
            group: group.to_string(),
            line: segs[s].2,
        })
    };
    // Open chains start at an unpartnered end; what is left are closed loops.
    for s in 0..segs.len() {
        for end in 0..2 {
            if !done[s] && !partner.contains_key(&(s, end)) {
                push(s, walk(s, end, &mut done));
            }
        }
    }
    for s in 0..segs.len() {
        if !done[s] {
            push(s, walk(s, 0, &mut done));
        }
    }
    Ok(())
}

/// `partner[(segment, end)]`: the segment that continues a segment through the vertex at that
/// end. Where two segments meet they continue each other; where more meet, the straightest
/// pairs do, if they turn by less than [`CHAIN_MAX_TURN_DEG`].
fn partners(
    segs: &[Segment],
    incident: &BTreeMap<usize, Vec<usize>>,
    points: &[[f64; 3]],
) -> HashMap<(usize, usize), usize> {
    let cos_limit = -(CHAIN_MAX_TURN_DEG.to_radians().cos());
    let mut partner: HashMap<(usize, usize), usize> = HashMap::new();
    let end_of = |s: usize, v: usize| if segs[s].0 == v { 0 } else { 1 };
    for (&v, list) in incident {
        if list.len() == 2 {
            partner.insert((list[0], end_of(list[0], v)), list[1]);
            partner.insert((list[1], end_of(list[1], v)), list[0]);
            continue;
        }
        let dir = |s: usize| {
            let (a, b, _) = segs[s];
            let other = if a == v { b } else { a };
            let d = sub(points[other], points[v]);
            let n = norm(d);
            [d[0] / n, d[1] / n, d[2] / n]
        };
        let mut pairs: Vec<(f64, usize, usize)> = Vec::new();
        for i in 0..list.len() {
            for j in i + 1..list.len() {
                let c = dot(dir(list[i]), dir(list[j]));
                if c < cos_limit {
                    pairs.push((c, list[i], list[j]));
                }
            }
        }
        pairs.sort_by(|x, y| x.0.total_cmp(&y.0).then((x.1, x.2).cmp(&(y.1, y.2))));
        let mut paired = HashSet::new();
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
    partner
}
