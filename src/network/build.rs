//! From a validated scene to a [`Model`]: rods subdivided into nodes and edges, joints merged
//! into shared nodes and vertex frames, supports eliminated from the unknowns, rest curvature and
//! twist measured on the rest shape, loads turned into potentials.

use std::collections::HashMap;

use crate::energy::{
    bend::Bend, frame_bend::FrameBend, frame_twist::FrameTwist, point_load::PointLoad,
    stretch::Stretch, torque::Torque, twist::Twist, Term,
};
use crate::math::vec::*;
use crate::network::model::{Model, Prescribed, PrescribedRotation, Terms, VarKind};
use crate::network::port::Port;
use crate::network::state::{FrameRef, State};
use crate::rod::frames::EdgeRef;
use crate::rod::section::{Section, Stiffness};
use crate::scene::types::{JointKind, Load, Scene, SupportKind};
use crate::scene::FieldError;

/// One rod of the built network, for results and exports.
#[derive(Debug, Clone)]
pub struct RodInfo {
    pub name: String,
    /// Global node of each rod node, in order.
    pub nodes: Vec<usize>,
    /// Global edge of each rod edge, in order.
    pub edges: Vec<usize>,
    pub closed: bool,
    pub subdivide: usize,
    pub stiffness: Stiffness,
    pub section: Section,
    pub young_modulus: f64,
}

#[derive(Debug, Clone)]
pub struct SupportInfo {
    pub rod: String,
    pub vertex: usize,
    pub node: usize,
    /// The vertex frame a clamp fixes (its reaction moment).
    pub frame: Option<usize>,
}

#[derive(Debug, Clone)]
pub struct JointInfo {
    pub name: String,
    pub node: usize,
}

/// A built network: the Newton model plus what the results need to name things.
#[derive(Debug, Clone)]
pub struct Network {
    pub model: Model,
    pub rods: Vec<RodInfo>,
    pub supports: Vec<SupportInfo>,
    pub joints: Vec<JointInfo>,
    pub n_nodes: usize,
}

struct PortBuild {
    rod: usize,
    node: usize,
    frame: usize,
    rest: Frame,
    alpha: Option<usize>,
    hinge_axis: [f64; 3],
}

pub fn build(scene: &Scene) -> Result<Network, FieldError> {
    // --- rods: nodes and rest frames -----------------------------------------------------------
    let mut rod_nodes_rest: Vec<Vec<[f64; 3]>> = Vec::new();
    let mut rod_index: HashMap<&str, usize> = HashMap::new();
    let mut first_id = Vec::new();
    let mut n_raw = 0;
    for (ri, rod) in scene.rods.iter().enumerate() {
        rod_index.insert(rod.name.as_str(), ri);
        let s = rod.subdivide;
        let m = rod.points.len();
        let segs = if rod.closed { m } else { m - 1 };
        let mut pts = Vec::with_capacity(segs * s + 1);
        for k in 0..segs {
            let (a, b) = (rod.points[k], rod.points[(k + 1) % m]);
            for j in 0..s {
                let f = j as f64 / s as f64;
                pts.push(add(a, scalef(sub(b, a), f)));
            }
        }
        if !rod.closed {
            pts.push(rod.points[m - 1]);
        }
        first_id.push(n_raw);
        n_raw += pts.len();
        rod_nodes_rest.push(pts);
    }
    let raw_id = |rod: usize, node: usize| first_id[rod] + node;

    // --- joints merge nodes (union-find) ----------------------------------------------------------
    let mut parent: Vec<usize> = (0..n_raw).collect();
    fn find(p: &mut [usize], mut i: usize) -> usize {
        while p[i] != i {
            p[i] = p[p[i]];
            i = p[i];
        }
        i
    }
    let mut length_scale = bbox_diagonal(&rod_nodes_rest);
    for (ji, j) in scene.joints.iter().enumerate() {
        let (r0, v0) = (rod_index[j.at[0].0.as_str()], j.at[0].1);
        let s0 = scene.rods[r0].subdivide;
        let p0 = rod_nodes_rest[r0][v0 * s0];
        for (k, (rn, v)) in j.at.iter().enumerate().skip(1) {
            let r = rod_index[rn.as_str()];
            let node = v * scene.rods[r].subdivide;
            let p = rod_nodes_rest[r][node];
            if norm(sub(p, p0)) > 1e-9 * length_scale {
                return Err(FieldError::new(
                    "joints",
                    ji,
                    "at",
                    format!(
                        "vertex {v} of rod \"{rn}\" (entry {k}) is {:.3e} m away from the joint's \
                         first vertex; joined vertices must coincide in the rest shape",
                        norm(sub(p, p0))
                    ),
                ));
            }
            let (a, b) = (
                find(&mut parent, raw_id(r0, v0 * s0)),
                find(&mut parent, raw_id(r, node)),
            );
            parent[b] = a;
        }
    }
    let mut node_of_root = vec![usize::MAX; n_raw];
    let mut n_nodes = 0;
    let mut rest_pos: Vec<[f64; 3]> = Vec::new();
    let mut rods: Vec<RodInfo> = Vec::new();
    for (ri, rod) in scene.rods.iter().enumerate() {
        let mut nodes = Vec::new();
        for (k, p) in rod_nodes_rest[ri].iter().enumerate() {
            let root = find(&mut parent, raw_id(ri, k));
            if node_of_root[root] == usize::MAX {
                node_of_root[root] = n_nodes;
                rest_pos.push(*p);
                n_nodes += 1;
            }
            nodes.push(node_of_root[root]);
        }
        let mat = &scene.materials[&rod.material];
        rods.push(RodInfo {
            name: rod.name.clone(),
            nodes,
            edges: Vec::new(),
            closed: rod.closed,
            subdivide: rod.subdivide,
            stiffness: mat
                .section
                .stiffness(mat.young_modulus, mat.shear(), mat.density),
            section: mat.section,
            young_modulus: mat.young_modulus,
        });
    }

    // --- edges and their rest reference frames ----------------------------------------------------
    let mut edge_nodes = Vec::new();
    let mut rest_lengths = Vec::new();
    let mut edge_refs = Vec::new();
    let mut edge_rod = Vec::new();
    for (ri, rod) in scene.rods.iter().enumerate() {
        let pts = &rod_nodes_rest[ri];
        let np = pts.len();
        let ne = if rod.closed { np } else { np - 1 };
        let mut prev: Option<EdgeRef> = None;
        for k in 0..ne {
            let (a, b) = (k, (k + 1) % np);
            let e = sub(pts[b], pts[a]);
            let t = normalize(e);
            let u = match prev {
                None => match rod.normal {
                    Some(n) => normalize(sub(n, scalef(t, dot(n, t)))),
                    None => any_perpendicular(t),
                },
                Some(p) => normalize(transport(p.t, t, p.u)),
            };
            let r = EdgeRef { t, u };
            prev = Some(r);
            rods[ri].edges.push(edge_nodes.len());
            edge_rod.push(ri);
            edge_nodes.push([rods[ri].nodes[a], rods[ri].nodes[b]]);
            rest_lengths.push(norm(e));
            edge_refs.push(r);
        }
    }
    let n_edges = edge_nodes.len();
    length_scale = length_scale.max(rest_lengths.iter().cloned().fold(0.0, f64::max));

    // --- vertex frames and ports ------------------------------------------------------------------
    let clamped: Vec<(usize, usize)> = scene
        .supports
        .iter()
        .filter(|s| s.kind == SupportKind::Clamp)
        .map(|s| {
            let r = rod_index[s.rod.as_str()];
            (r, s.vertex * scene.rods[r].subdivide)
        })
        .collect();
    let mut ports: Vec<PortBuild> = Vec::new();
    let mut port_of: HashMap<(usize, usize), usize> = HashMap::new();
    let mut frame_fixed: Vec<bool> = Vec::new();
    let mut n_alpha = 0;
    let rest_frame_at = |ri: usize, node: usize| -> Frame {
        let rod = &rods[ri];
        let np = rod.nodes.len();
        let e_out = if rod.closed || node + 1 < np {
            Some(rod.edges[node % rod.edges.len()])
        } else {
            None
        };
        let e_in = if rod.closed {
            Some(rod.edges[(node + np - 1) % np])
        } else if node > 0 {
            Some(rod.edges[node - 1])
        } else {
            None
        };
        match (e_in, e_out) {
            (Some(i), Some(o)) => {
                let (ri_, ro) = (edge_refs[i], edge_refs[o]);
                let tv = normalize(add(ri_.t, ro.t));
                let d1 = normalize(transport(ri_.t, tv, ri_.u));
                [d1, cross(tv, d1), tv]
            }
            (Some(e), None) | (None, Some(e)) => {
                let r = edge_refs[e];
                [r.u, cross(r.t, r.u), r.t]
            }
            (None, None) => unreachable!("rods have at least one edge"),
        }
    };
    for (ji, j) in scene.joints.iter().enumerate() {
        let (rigid, hinge) = match j.kind {
            JointKind::Rigid => (true, false),
            JointKind::Hinge => (true, true),
            JointKind::Ball => (false, false),
            JointKind::Elastic(_) => {
                return Err(FieldError::new(
                    "joints",
                    ji,
                    "kind",
                    "Elastic joints are not supported yet (use Rigid, Hinge or Ball)".into(),
                ))
            }
        };
        if !rigid {
            continue;
        }
        let frame = frame_fixed.len();
        frame_fixed.push(false);
        let mut at: Vec<(usize, usize)> =
            j.at.iter()
                .map(|(rn, v)| {
                    let r = rod_index[rn.as_str()];
                    (r, v * scene.rods[r].subdivide)
                })
                .collect();
        // The hinge's reference port (no scissor angle) is a clamped one if any, so that a clamp
        // fixes its own rod and leaves the others free to scissor.
        if let Some(k) = at.iter().position(|p| clamped.contains(p)) {
            at.swap(0, k);
        }
        let axis = if hinge {
            let n = match j.normal {
                Some(n) => n,
                None => {
                    if at.len() < 2 {
                        return Err(FieldError::new(
                            "joints",
                            ji,
                            "normal",
                            "a Hinge joining fewer than two rod vertices needs `normal`".into(),
                        ));
                    }
                    cross(
                        rest_frame_at(at[0].0, at[0].1)[2],
                        rest_frame_at(at[1].0, at[1].1)[2],
                    )
                }
            };
            if norm(n) < 1e-8 {
                return Err(FieldError::new(
                    "joints",
                    ji,
                    "normal",
                    "hinge axis undefined: the first two rods are parallel; give `normal`".into(),
                ));
            }
            normalize(n)
        } else {
            [0.0, 0.0, 1.0]
        };
        for (k, &(r, node)) in at.iter().enumerate() {
            if port_of.contains_key(&(r, node)) {
                return Err(FieldError::new(
                    "joints",
                    ji,
                    "at",
                    format!(
                        "vertex {} of rod \"{}\" is already in another Rigid or Hinge joint",
                        node / scene.rods[r].subdivide,
                        scene.rods[r].name
                    ),
                ));
            }
            let alpha = if hinge && k > 0 {
                n_alpha += 1;
                Some(n_alpha - 1)
            } else {
                None
            };
            port_of.insert((r, node), ports.len());
            ports.push(PortBuild {
                rod: r,
                node,
                frame,
                rest: rest_frame_at(r, node),
                alpha,
                hinge_axis: axis,
            });
        }
    }
    let new_port = |r: usize,
                    node: usize,
                    fixed: bool,
                    ports: &mut Vec<PortBuild>,
                    port_of: &mut HashMap<(usize, usize), usize>,
                    frame_fixed: &mut Vec<bool>| {
        let frame = frame_fixed.len();
        frame_fixed.push(fixed);
        port_of.insert((r, node), ports.len());
        ports.push(PortBuild {
            rod: r,
            node,
            frame,
            rest: rest_frame_at(r, node),
            alpha: None,
            hinge_axis: [0.0, 0.0, 1.0],
        });
    };
    let mut fixed_alpha = Vec::new();
    for &(r, node) in &clamped {
        match port_of.get(&(r, node)) {
            Some(&p) => {
                frame_fixed[ports[p].frame] = true;
                if let Some(a) = ports[p].alpha {
                    fixed_alpha.push(a);
                }
            }
            None => new_port(r, node, true, &mut ports, &mut port_of, &mut frame_fixed),
        }
    }
    for l in &scene.loads {
        if let Load::Torque { rod, vertex, .. } = l {
            let r = rod_index[rod.as_str()];
            let node = vertex * scene.rods[r].subdivide;
            if !port_of.contains_key(&(r, node)) {
                new_port(r, node, false, &mut ports, &mut port_of, &mut frame_fixed);
            }
        }
    }
    let port_of = port_of;
    let n_frames = frame_fixed.len();

    // --- variables ----------------------------------------------------------------------------------
    let theta_var = |e: usize| 3 * n_nodes + e;
    let frame_base = 3 * n_nodes + n_edges;
    let alpha_base = frame_base + 3 * n_frames;
    let zero = alpha_base + n_alpha;
    let n_vars = zero + 1;
    let mut kinds = vec![VarKind::Angle; n_vars];
    kinds[..3 * n_nodes].fill(VarKind::Position);
    let mut fixed = vec![false; n_vars];
    fixed[zero] = true;
    for (f, &fx) in frame_fixed.iter().enumerate() {
        if fx {
            fixed[frame_base + 3 * f..frame_base + 3 * f + 3].fill(true);
        }
    }
    for a in fixed_alpha {
        fixed[alpha_base + a] = true;
    }
    let mut q = vec![0.0; n_vars];
    for (k, p) in rest_pos.iter().enumerate() {
        q[3 * k..3 * k + 3].copy_from_slice(p);
    }
    let mut prescribed = Vec::new();
    let mut prescribed_rotations = Vec::new();
    let mut supports = Vec::new();
    let mut moved: HashMap<usize, [f64; 3]> = HashMap::new();
    for (si, s) in scene.supports.iter().enumerate() {
        let r = rod_index[s.rod.as_str()];
        let rnode = s.vertex * scene.rods[r].subdivide;
        let node = rods[r].nodes[rnode];
        fixed[3 * node..3 * node + 3].fill(true);
        if let Some(target) = s.move_to {
            if let Some(prev) = moved.insert(node, target) {
                if prev != target {
                    return Err(FieldError::new(
                        "supports",
                        si,
                        "move_to",
                        "this node already has a different `move_to` from another support".into(),
                    ));
                }
            } else {
                for k in 0..3 {
                    prescribed.push(Prescribed {
                        var: 3 * node + k,
                        start: rest_pos[node][k],
                        end: target[k],
                    });
                }
            }
        }
        let frame = match s.kind {
            SupportKind::Clamp => port_of.get(&(r, rnode)).map(|&p| ports[p].frame),
            SupportKind::Pin => None,
        };
        if let (Some(f), Some(rotation)) = (frame, s.rotate_by) {
            if prescribed_rotations
                .iter()
                .any(|p: &PrescribedRotation| p.frame == f)
            {
                return Err(FieldError::new(
                    "supports",
                    si,
                    "rotate_by",
                    "this clamp's frame is already rotated by another support".into(),
                ));
            }
            prescribed_rotations.push(PrescribedRotation { frame: f, rotation });
        }
        supports.push(SupportInfo {
            rod: s.rod.clone(),
            vertex: s.vertex,
            node,
            frame,
        });
    }

    // --- state at rest ------------------------------------------------------------------------------
    let mut state = State {
        q,
        edges: edge_refs,
        frames: vec![FrameRef::identity(); n_frames],
        twist_prev: Vec::new(),
        load_factor: 0.0,
    };
    let node_vars = |n: usize| [3 * n, 3 * n + 1, 3 * n + 2];

    // --- terms ----------------------------------------------------------------------------------------
    let mut terms = Terms::default();
    for (e, &[a, b]) in edge_nodes.iter().enumerate() {
        let rod = &rods[edge_rod[e]];
        let [a0, a1, a2] = node_vars(a);
        let [b0, b1, b2] = node_vars(b);
        terms.stretch.push(Stretch {
            vars: [a0, a1, a2, b0, b1, b2],
            rest_length: rest_lengths[e],
            ea: rod.stiffness.ea,
        });
    }
    for (ri, rod) in rods.iter().enumerate() {
        let np = rod.nodes.len();
        let k = rod.stiffness;
        let range: Vec<usize> = if rod.closed {
            (0..np).collect()
        } else {
            (1..np - 1).collect()
        };
        for j in range {
            if port_of.contains_key(&(ri, j)) {
                continue;
            }
            let (jp, jn) = ((j + np - 1) % np, (j + 1) % np);
            let (ei, eo) = (rod.edges[(j + np - 1) % np], rod.edges[j % rod.edges.len()]);
            let [a0, a1, a2] = node_vars(rod.nodes[jp]);
            let [b0, b1, b2] = node_vars(rod.nodes[j]);
            let [c0, c1, c2] = node_vars(rod.nodes[jn]);
            let vars = [
                a0,
                a1,
                a2,
                b0,
                b1,
                b2,
                c0,
                c1,
                c2,
                theta_var(ei),
                theta_var(eo),
            ];
            let voronoi = 0.5 * (rest_lengths[ei] + rest_lengths[eo]);
            let mut bend = Bend {
                vars,
                edges: [ei, eo],
                rest: [[0.0; 2]; 2],
                voronoi,
                ei: [k.ei1, k.ei2],
            };
            let x = bend.gather(&state.q);
            bend.rest = bend.curvatures::<f64>(&state, &x);
            terms.bend.push(bend);
            let slot = state.twist_prev.len();
            state.twist_prev.push(0.0);
            let mut tw = Twist {
                vars,
                edges: [ei, eo],
                slot,
                rest: 0.0,
                voronoi,
                gj: k.gj,
            };
            let r = tw.reference_twist::<f64>(&state, &x);
            state.twist_prev[slot] = r;
            tw.rest = tw.twist::<f64>(&state, &x);
            terms.twist.push(tw);
        }
    }
    let mut frame_vars = Vec::with_capacity(n_frames);
    for f in 0..n_frames {
        frame_vars.push(frame_base + 3 * f);
    }
    for p in &ports {
        let rod = &rods[p.rod];
        let np = rod.nodes.len();
        let k = rod.stiffness;
        let j = p.node;
        let mut incident = Vec::new();
        if rod.closed || j > 0 {
            incident.push((rod.edges[(j + np - 1) % np], (j + np - 1) % np, -1.0));
        }
        if rod.closed || j + 1 < np {
            incident.push((rod.edges[j % rod.edges.len()], (j + 1) % np, 1.0));
        }
        let port = Port {
            frame: p.frame,
            rest: p.rest,
            hinge_axis: p.hinge_axis,
        };
        let fb = frame_base + 3 * p.frame;
        let alpha = p.alpha.map(|a| alpha_base + a).unwrap_or(zero);
        for (e, other, sign) in incident {
            let [a0, a1, a2] = node_vars(rod.nodes[j]);
            let [b0, b1, b2] = node_vars(rod.nodes[other]);
            let vars = [
                a0,
                a1,
                a2,
                b0,
                b1,
                b2,
                theta_var(e),
                fb,
                fb + 1,
                fb + 2,
                alpha,
            ];
            let voronoi = 0.5 * rest_lengths[e];
            let mut bend = FrameBend {
                vars,
                port,
                edge: e,
                sign,
                rest: [[0.0; 2]; 2],
                voronoi,
                ei: [k.ei1, k.ei2],
            };
            let x = bend.gather(&state.q);
            bend.rest = bend.curvatures::<f64>(&state, &x);
            terms.frame_bend.push(bend);
            let slot = state.twist_prev.len();
            state.twist_prev.push(0.0);
            let mut tw = FrameTwist {
                vars,
                port,
                edge: e,
                sign,
                slot,
                rest: 0.0,
                voronoi,
                gj: k.gj,
            };
            let r = tw.reference_twist::<f64>(&state, &x);
            state.twist_prev[slot] = r;
            tw.rest = tw.twist::<f64>(&state, &x);
            terms.frame_twist.push(tw);
        }
    }

    // --- loads ----------------------------------------------------------------------------------------
    let mut nodal = vec![[0.0; 3]; n_nodes];
    let mut force_scale: f64 = 0.0;
    let mut torques = Vec::new();
    for l in &scene.loads {
        match l {
            Load::Force { rod, vertex, force } => {
                let r = rod_index[rod.as_str()];
                let node = rods[r].nodes[vertex * scene.rods[r].subdivide];
                nodal[node] = add(nodal[node], *force);
                force_scale = force_scale.max(norm(*force));
            }
            Load::Gravity { g } => {
                let mut weight = 0.0;
                for rod in &rods {
                    for &e in &rod.edges {
                        let m = 0.5 * rod.stiffness.mass_per_length * rest_lengths[e];
                        for n in edge_nodes[e] {
                            nodal[n] = add(nodal[n], scalef(*g, m));
                        }
                        weight += 2.0 * m * norm(*g);
                    }
                }
                force_scale = force_scale.max(weight);
            }
            Load::Torque {
                rod,
                vertex,
                torque,
            } => {
                let r = rod_index[rod.as_str()];
                let p = port_of[&(r, vertex * scene.rods[r].subdivide)];
                let f = ports[p].frame;
                torques.push(Torque {
                    vars: [frame_vars[f], frame_vars[f] + 1, frame_vars[f] + 2],
                    frame: f,
                    torque: *torque,
                });
                force_scale = force_scale.max(norm(*torque) / length_scale);
            }
        }
    }
    for (n, f) in nodal.iter().enumerate() {
        if *f != [0.0; 3] {
            terms.loads.push(PointLoad {
                vars: node_vars(n),
                force: *f,
            });
        }
    }
    terms.torques = torques;
    for rod in &rods {
        let ei = rod.stiffness.ei1.max(rod.stiffness.ei2);
        force_scale = force_scale.max(ei / (length_scale * length_scale));
    }

    let joints = scene
        .joints
        .iter()
        .map(|j| {
            let r = rod_index[j.at[0].0.as_str()];
            JointInfo {
                name: j.name.clone(),
                node: rods[r].nodes[j.at[0].1 * scene.rods[r].subdivide],
            }
        })
        .collect();

    let mut model = Model::new(
        state,
        terms,
        kinds,
        &fixed,
        prescribed,
        edge_nodes,
        rest_lengths,
        length_scale,
        force_scale,
        frame_vars,
    );
    model.prescribed_rotations = prescribed_rotations;
    Ok(Network {
        model,
        rods,
        supports,
        joints,
        n_nodes,
    })
}

fn bbox_diagonal(rods: &[Vec<[f64; 3]>]) -> f64 {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in rods.iter().flatten() {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    norm(sub(hi, lo))
}
