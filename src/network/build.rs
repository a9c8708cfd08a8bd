//! From a validated scene to a [`Model`]: rods subdivided into nodes and edges, joints merged
//! into shared nodes and vertex frames (one file per kind in [`super::joint`]), supports
//! eliminated from the unknowns, rest curvature and twist measured on the rest shape, loads turned
//! into potentials.

use std::collections::{HashMap, HashSet};

use crate::energy::{
    bend::Bend, frame_bend::FrameBend, frame_twist::FrameTwist, joint_rotation::JointRotation,
    joint_translation::JointTranslation, point_load::PointLoad, stretch::Stretch, torque::Torque,
    twist::Twist, Term,
};
use crate::math::vec::*;
use crate::network::joint::{self, PortTable, Site};
use crate::network::model::{Model, Prescribed, PrescribedRotation, Terms, VarKind};
use crate::network::port::Port;
use crate::network::rest;
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
    /// The shared node, or the joint's centre node for translationally elastic joints.
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

/// A bend-and-twist stencil at a vertex between two edges (oriented along the stencil).
struct Stencil {
    vars: [usize; 11],
    edges: [usize; 2],
    signs: [f64; 2],
    lengths: [f64; 2],
    stiffness: [Stiffness; 2],
}

impl Stencil {
    /// Adds the bend and twist terms with their rest curvature and twist from the current
    /// (rest) state.
    fn push(&self, terms: &mut Terms, state: &mut State) {
        let voronoi = 0.5 * (self.lengths[0] + self.lengths[1]);
        let [k0, k1] = self.stiffness;
        let mut bend = Bend {
            vars: self.vars,
            edges: self.edges,
            signs: self.signs,
            rest: [[0.0; 2]; 2],
            voronoi,
            ei: [[k0.ei1, k0.ei2], [k1.ei1, k1.ei2]],
        };
        let y = Twist::reduced(&bend.gather(&state.q));
        bend.rest = bend.curvatures::<f64>(state, &y);
        terms.bend.push(bend);
        let slot = state.twist_prev.len();
        state.twist_prev.push(0.0);
        // Twist compliance in series over the two half-edges.
        let gj = voronoi / (0.5 * self.lengths[0] / k0.gj + 0.5 * self.lengths[1] / k1.gj);
        let mut tw = Twist {
            vars: self.vars,
            edges: self.edges,
            signs: self.signs,
            slot,
            rest: 0.0,
            voronoi,
            gj,
        };
        state.twist_prev[slot] = tw.reference_twist::<f64>(state, &y);
        tw.rest = tw.twist::<f64>(state, &y);
        terms.twist.push(tw);
    }
}

/// Rest turning angle above which a vertex is a rigid corner rather than a bending stencil
/// (15°: the stencil's stiffness factor cos²(φ/2) is then above 0.983).
pub const KINK_ANGLE: f64 = 15.0 * std::f64::consts::PI / 180.0;

enum JointNode {
    Site(usize, usize),
    Center(usize),
}

fn find(p: &mut [usize], mut i: usize) -> usize {
    while p[i] != i {
        p[i] = p[p[i]];
        i = p[i];
    }
    i
}

pub fn build(scene: &Scene) -> Result<Network, FieldError> {
    let rods_rest: Vec<Vec<[f64; 3]>> = scene.rods.iter().map(rest::rod_nodes).collect();
    let rod_index: HashMap<&str, usize> = scene
        .rods
        .iter()
        .enumerate()
        .map(|(i, r)| (r.name.as_str(), i))
        .collect();
    let site = |rod: &str, v: usize| {
        let r = rod_index[rod];
        (r, v * scene.rods[r].subdivide)
    };
    let rods_edges: Vec<Vec<EdgeRef>> = scene
        .rods
        .iter()
        .zip(&rods_rest)
        .map(|(r, p)| rest::rod_edge_frames(p, r.closed, r.normal))
        .collect();
    let rest_frame_at = |r: usize, j: usize| {
        let (np, closed) = (rods_rest[r].len(), scene.rods[r].closed);
        let e = &rods_edges[r];
        let e_in = (closed || j > 0).then(|| e[(j + np - 1) % np]);
        let e_out = (closed || j + 1 < np).then(|| e[j % e.len()]);
        rest::vertex_frame(e_in, e_out)
    };
    let mut length_scale = rest::bbox_diagonal(rods_rest.iter().flatten());

    // --- joints: vertex frames and node merges ---------------------------------------------------
    let clamped: HashSet<(usize, usize)> = scene
        .supports
        .iter()
        .filter(|s| s.kind == SupportKind::Clamp)
        .map(|s| site(&s.rod, s.vertex))
        .collect();
    let torque_sites: HashSet<(usize, usize)> = scene
        .loads
        .iter()
        .filter_map(|l| match l {
            Load::Torque { rod, vertex, .. } => Some(site(rod, *vertex)),
            _ => None,
        })
        .collect();
    let rod_end = |r: usize, node: usize| {
        !scene.rods[r].closed && (node == 0 || node + 1 == rods_rest[r].len())
    };
    let mut splices: Vec<[(usize, usize); 2]> = Vec::new();
    let mut table = PortTable::default();
    let mut merges: Vec<Vec<(usize, usize)>> = Vec::new();
    let mut joint_nodes = Vec::new();
    for (ji, j) in scene.joints.iter().enumerate() {
        let mut sites: Vec<Site> =
            j.at.iter()
                .map(|(rn, v)| {
                    let (rod, node) = site(rn, *v);
                    Site {
                        rod,
                        node,
                        rest: rest_frame_at(rod, node),
                        clamped: clamped.contains(&(rod, node)),
                    }
                })
                .collect();
        let p0 = rods_rest[sites[0].rod][sites[0].node];
        for (k, s) in sites.iter().enumerate().skip(1) {
            let d = norm(sub(rods_rest[s.rod][s.node], p0));
            if d > 1e-9 * length_scale {
                return Err(FieldError::new(
                    "joints",
                    ji,
                    "at",
                    format!(
                        "entry {k} (rod \"{}\") is {d:.3e} m away from the joint's first vertex; \
                         joined vertices must coincide in the rest shape",
                        j.at[k].0
                    ),
                ));
            }
        }
        let at_err = |m: String| FieldError::new("joints", ji, "at", m);
        let mut shared = true;
        match &j.kind {
            JointKind::Rigid => {
                let loaded = sites
                    .iter()
                    .any(|s| torque_sites.contains(&(s.rod, s.node)));
                let turning = {
                    let (a, b) = (sites[0].rest[2], sites[sites.len() - 1].rest[2]);
                    // Rod-end frames point along their rod; a straight continuation has the two
                    // tangents antiparallel when both rods leave the joint, parallel otherwise.
                    let c = dot(a, b).abs().min(1.0);
                    c.acos()
                };
                if turning < KINK_ANGLE && joint::rigid::is_splice(&sites, rod_end, loaded) {
                    splices.push([(sites[0].rod, sites[0].node), (sites[1].rod, sites[1].node)]);
                } else {
                    joint::rigid::add(&mut table, &sites).map_err(at_err)?;
                }
            }
            JointKind::Hinge => {
                joint::hinge::add(&mut table, &mut sites, j.normal)
                    .map_err(|m| FieldError::new("joints", ji, "normal", m))?;
            }
            JointKind::Ball => joint::ball::add(&sites),
            JointKind::Elastic { .. } => {
                let e = j.kind.elastic().expect("elastic joint");
                joint::elastic::add(&mut table, &sites, &e, j.normal, p0).map_err(at_err)?;
                shared = e.translation.is_none();
            }
        }
        if shared {
            merges.push(sites.iter().map(|s| (s.rod, s.node)).collect());
            joint_nodes.push(JointNode::Site(sites[0].rod, sites[0].node));
        } else {
            joint_nodes.push(JointNode::Center(table.centers.len() - 1));
        }
    }
    // Sharp corners of a rest polyline are rigid corners (a Kirchhoff rod with a corner): a
    // bending stencil with rest turning angle φ resists relative rotation with only cos²(φ/2)
    // of the rod's stiffness, an error that does not vanish with refinement.
    for (r, rod) in scene.rods.iter().enumerate() {
        let np = rods_rest[r].len();
        let inner = if rod.closed { 0..np } else { 1..np - 1 };
        for j in inner {
            let e = &rods_edges[r];
            let (ti, to) = (e[(j + np - 1) % np].t, e[j % e.len()].t);
            if dot(ti, to).clamp(-1.0, 1.0).acos() >= KINK_ANGLE
                && !table.port_of.contains_key(&(r, j))
            {
                table.single(r, j, false, rest_frame_at(r, j));
            }
        }
    }
    for &(r, node) in &clamped {
        if let Some(&p) = table.port_of.get(&(r, node)) {
            table.frame_fixed[table.ports[p].frame] = true;
        } else {
            table.single(r, node, true, rest_frame_at(r, node));
        }
    }
    for l in &scene.loads {
        if let Load::Torque { rod, vertex, .. } = l {
            let (r, node) = site(rod, *vertex);
            if !table.port_of.contains_key(&(r, node)) {
                table.single(r, node, false, rest_frame_at(r, node));
            }
        }
    }

    // --- global nodes (union-find over the merges) ---------------------------------------------
    let mut first_id = Vec::new();
    let mut n_raw = 0;
    for p in &rods_rest {
        first_id.push(n_raw);
        n_raw += p.len();
    }
    let mut parent: Vec<usize> = (0..n_raw).collect();
    for group in &merges {
        let a = find(&mut parent, first_id[group[0].0] + group[0].1);
        for &(r, node) in &group[1..] {
            let b = find(&mut parent, first_id[r] + node);
            parent[b] = a;
        }
    }
    let mut node_of_root = vec![usize::MAX; n_raw];
    let mut rest_pos: Vec<[f64; 3]> = Vec::new();
    let mut rods: Vec<RodInfo> = Vec::new();
    for (ri, rod) in scene.rods.iter().enumerate() {
        let mut nodes = Vec::with_capacity(rods_rest[ri].len());
        for (k, p) in rods_rest[ri].iter().enumerate() {
            let root = find(&mut parent, first_id[ri] + k);
            if node_of_root[root] == usize::MAX {
                node_of_root[root] = rest_pos.len();
                rest_pos.push(*p);
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
    let first_center = rest_pos.len();
    rest_pos.extend(table.centers.iter().copied());
    let n_nodes = rest_pos.len();

    // --- global edges -----------------------------------------------------------------------------
    let mut edge_nodes = Vec::new();
    let mut rest_lengths = Vec::new();
    let mut edge_refs = Vec::new();
    let mut edge_rod = Vec::new();
    for (ri, refs) in rods_edges.iter().enumerate() {
        let np = rods[ri].nodes.len();
        for (k, r) in refs.iter().enumerate() {
            let (a, b) = (rods[ri].nodes[k], rods[ri].nodes[(k + 1) % np]);
            rods[ri].edges.push(edge_nodes.len());
            edge_nodes.push([a, b]);
            rest_lengths.push(norm(sub(rest_pos[b], rest_pos[a])));
            edge_refs.push(*r);
            edge_rod.push(ri);
        }
    }
    let n_edges = edge_nodes.len();
    length_scale = length_scale.max(rest_lengths.iter().cloned().fold(0.0, f64::max));

    // --- variables ------------------------------------------------------------------------------
    let n_frames = table.frame_fixed.len();
    let theta_var = |e: usize| 3 * n_nodes + e;
    let frame_base = 3 * n_nodes + n_edges;
    let alpha_base = frame_base + 3 * n_frames;
    let zero = alpha_base + table.n_alpha;
    let n_vars = zero + 1;
    let node_vars = |n: usize| [3 * n, 3 * n + 1, 3 * n + 2];
    // Local variables of a vertex stencil: (x_prev, x_vertex, x_next, θ_in, θ_out).
    let stencil_vars = |a: usize, b: usize, c: usize, e0: usize, e1: usize| -> [usize; 11] {
        let (a, b, c) = (node_vars(a), node_vars(b), node_vars(c));
        [
            a[0],
            a[1],
            a[2],
            b[0],
            b[1],
            b[2],
            c[0],
            c[1],
            c[2],
            theta_var(e0),
            theta_var(e1),
        ]
    };
    let mut kinds = vec![VarKind::Angle; n_vars];
    kinds[..3 * n_nodes].fill(VarKind::Position);
    let mut fixed = vec![false; n_vars];
    fixed[zero] = true;
    for (f, &fx) in table.frame_fixed.iter().enumerate() {
        if fx {
            fixed[frame_base + 3 * f..frame_base + 3 * f + 3].fill(true);
        }
    }
    for &a in &table.fixed_alpha {
        fixed[alpha_base + a] = true;
    }
    let mut q = vec![0.0; n_vars];
    for (k, p) in rest_pos.iter().enumerate() {
        q[3 * k..3 * k + 3].copy_from_slice(p);
    }

    // --- supports ---------------------------------------------------------------------------------
    let mut prescribed = Vec::new();
    let mut prescribed_rotations: Vec<PrescribedRotation> = Vec::new();
    let mut supports = Vec::new();
    let mut moved: HashMap<usize, [f64; 3]> = HashMap::new();
    for (si, s) in scene.supports.iter().enumerate() {
        let (r, rnode) = site(&s.rod, s.vertex);
        let node = rods[r].nodes[rnode];
        fixed[3 * node..3 * node + 3].fill(true);
        if let Some(target) = s.move_to {
            match moved.insert(node, target) {
                Some(prev) if prev != target => {
                    return Err(FieldError::new(
                        "supports",
                        si,
                        "move_to",
                        "this node already has a different `move_to` from another support".into(),
                    ))
                }
                Some(_) => {}
                None => prescribed.extend((0..3).map(|k| Prescribed {
                    var: 3 * node + k,
                    start: rest_pos[node][k],
                    end: target[k],
                })),
            }
        }
        let frame = match s.kind {
            SupportKind::Clamp => table
                .port_of
                .get(&(r, rnode))
                .map(|&p| table.ports[p].frame),
            SupportKind::Pin => None,
        };
        if let (Some(f), Some(rotation)) = (frame, s.rotate_by) {
            if prescribed_rotations.iter().any(|p| p.frame == f) {
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

    // --- state at rest and terms ----------------------------------------------------------------
    let mut state = State {
        q,
        edges: edge_refs,
        frames: vec![FrameRef::identity(); n_frames],
        twist_prev: Vec::new(),
        load_factor: 0.0,
    };
    let mut terms = Terms::default();
    for (e, &[a, b]) in edge_nodes.iter().enumerate() {
        let [a0, a1, a2] = node_vars(a);
        let [b0, b1, b2] = node_vars(b);
        terms.stretch.push(Stretch {
            vars: [a0, a1, a2, b0, b1, b2],
            rest_length: rest_lengths[e],
            ea: rods[edge_rod[e]].stiffness.ea,
        });
    }
    for (ri, rod) in rods.iter().enumerate() {
        let (np, k) = (rod.nodes.len(), rod.stiffness);
        let inner = if rod.closed { 0..np } else { 1..np - 1 };
        for j in inner {
            if table.port_of.contains_key(&(ri, j)) {
                continue;
            }
            let (ei, eo) = (rod.edges[(j + np - 1) % np], rod.edges[j % rod.edges.len()]);
            let stencil = Stencil {
                vars: stencil_vars(
                    rod.nodes[(j + np - 1) % np],
                    rod.nodes[j],
                    rod.nodes[(j + 1) % np],
                    ei,
                    eo,
                ),
                edges: [ei, eo],
                signs: [1.0, 1.0],
                lengths: [rest_lengths[ei], rest_lengths[eo]],
                stiffness: [k, k],
            };
            stencil.push(&mut terms, &mut state);
        }
    }
    let splice_rods: Vec<usize> = splices.iter().flat_map(|s| [s[0].0, s[1].0]).collect();
    for [(ra, na), (rb, nb)] in splices {
        // Edge of rod a arriving at the joint, edge of rod b leaving it.
        let (rod_a, rod_b) = (&rods[ra], &rods[rb]);
        let (ea, other_a, sa) = if na == 0 {
            (rod_a.edges[0], rod_a.nodes[1], -1.0)
        } else {
            (rod_a.edges[na - 1], rod_a.nodes[na - 1], 1.0)
        };
        let (eb, other_b, sb) = if nb == 0 {
            (rod_b.edges[0], rod_b.nodes[1], 1.0)
        } else {
            (rod_b.edges[nb - 1], rod_b.nodes[nb - 1], -1.0)
        };
        let stencil = Stencil {
            vars: stencil_vars(other_a, rod_a.nodes[na], other_b, ea, eb),
            edges: [ea, eb],
            signs: [sa, sb],
            lengths: [rest_lengths[ea], rest_lengths[eb]],
            stiffness: [rod_a.stiffness, rod_b.stiffness],
        };
        stencil.push(&mut terms, &mut state);
    }
    // Twist gauge: an isotropic rod that is straight at rest, touches no vertex frame and is not
    // spliced to another rod has an energy that depends on its edge angles only through their
    // differences (|κb| does not see θ when EI₁ = EI₂ and κ̄ = 0), so turning all of them together
    // is a zero-energy mode. Fixing the first edge's angle removes it without changing any
    // equilibrium, and keeps the Hessian positive definite instead of singular.
    let mut no_gauge = vec![false; rods.len()];
    for &r in &splice_rods {
        no_gauge[r] = true;
    }
    for p in &table.ports {
        no_gauge[p.rod] = true;
    }
    for b in &terms.bend {
        if b.rest.iter().flatten().any(|v| v.abs() >= 1e-12) {
            no_gauge[edge_rod[b.edges[0]]] = true;
        }
    }
    for (ri, rod) in rods.iter().enumerate() {
        if rod.stiffness.ei1 == rod.stiffness.ei2 && !no_gauge[ri] {
            fixed[theta_var(rod.edges[0])] = true;
        }
    }
    let frame_vars: Vec<usize> = (0..n_frames).map(|f| frame_base + 3 * f).collect();
    for p in &table.ports {
        let rod = &rods[p.rod];
        let (np, k, j) = (rod.nodes.len(), rod.stiffness, p.node);
        let mut incident = Vec::new();
        if rod.closed || j > 0 {
            incident.push((rod.edges[(j + np - 1) % np], (j + np - 1) % np, -1.0));
        }
        if rod.closed || j + 1 < np {
            incident.push((rod.edges[j % rod.edges.len()], (j + 1) % np, 1.0));
        }
        let fb = frame_vars[p.frame];
        let alpha = p.alpha.map_or(zero, |a| alpha_base + a);
        for (e, other, sign) in incident {
            // Each half-stencil is attached along its own edge (the edge's rest frame, in the
            // rod's direction), so its rest curvature and twist vanish and the frame transmits
            // the full rod stiffness; the port's vertex frame only orients hinge axes and
            // elastic springs.
            let r = state.edges[e];
            let port = Port {
                frame: p.frame,
                rest: [r.u, cross(r.t, r.u), r.t],
                hinge_axis: p.hinge_axis,
            };
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
            let y = FrameTwist::reduced(&bend.gather(&state.q));
            bend.rest = bend.curvatures::<f64>(&state, &y);
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
            state.twist_prev[slot] = tw.reference_twist::<f64>(&state, &y);
            tw.rest = tw.twist::<f64>(&state, &y);
            terms.frame_twist.push(tw);
        }
    }
    for c in &table.couplings {
        let p = &table.ports[c.port];
        let (fp, fj) = (frame_vars[p.frame], frame_vars[c.joint_frame]);
        terms.joint_rotation.push(JointRotation {
            vars: [fp, fp + 1, fp + 2, fj, fj + 1, fj + 2],
            port_frame: p.frame,
            joint_frame: c.joint_frame,
            rest: p.rest,
            axes: c.axes,
            stiffness: c.stiffness,
        });
    }
    for a in &table.anchors {
        let [a0, a1, a2] = node_vars(rods[a.rod].nodes[a.node]);
        let [b0, b1, b2] = node_vars(first_center + a.center);
        terms.joint_translation.push(JointTranslation {
            vars: [a0, a1, a2, b0, b1, b2],
            stiffness: a.stiffness,
        });
    }

    // --- loads ----------------------------------------------------------------------------------
    let mut nodal = vec![[0.0; 3]; n_nodes];
    let mut force_scale: f64 = 0.0;
    for l in &scene.loads {
        match l {
            Load::Force { rod, vertex, force } => {
                let (r, rn) = site(rod, *vertex);
                let node = rods[r].nodes[rn];
                nodal[node] = add(nodal[node], *force);
                force_scale = force_scale.max(norm(*force));
            }
            Load::Gravity { g } => {
                let mut weight = 0.0;
                for (e, &[a, b]) in edge_nodes.iter().enumerate() {
                    let m = 0.5 * rods[edge_rod[e]].stiffness.mass_per_length * rest_lengths[e];
                    nodal[a] = add(nodal[a], scalef(*g, m));
                    nodal[b] = add(nodal[b], scalef(*g, m));
                    weight += 2.0 * m * norm(*g);
                }
                force_scale = force_scale.max(weight);
            }
            Load::Torque {
                rod,
                vertex,
                torque,
            } => {
                let f = table.ports[table.port_of[&site(rod, *vertex)]].frame;
                terms.torques.push(Torque {
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
    // Loads set the force scale when there are any; prescribed motions (and unloaded scenes)
    // are measured against the rods' bending scale EI/L².
    let driven = !prescribed.is_empty() || !prescribed_rotations.is_empty();
    if driven || force_scale == 0.0 {
        for rod in &rods {
            let ei = rod.stiffness.ei1.max(rod.stiffness.ei2);
            force_scale = force_scale.max(ei / (length_scale * length_scale));
        }
    }

    let joints = scene
        .joints
        .iter()
        .zip(&joint_nodes)
        .map(|(j, n)| JointInfo {
            name: j.name.clone(),
            node: match *n {
                JointNode::Site(r, node) => rods[r].nodes[node],
                JointNode::Center(c) => first_center + c,
            },
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
    model.contact = crate::network::contact::Contact::build(scene, &rods, &model)?;
    Ok(Network {
        model,
        rods,
        supports,
        joints,
        n_nodes,
    })
}
