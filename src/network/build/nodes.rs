//! Global nodes (rod nodes merged by joints, then elastic joints' centre nodes) and global edges
//! with their rest lengths and reference frames.

use super::frames::{Joined, JointNode};
use super::geometry::Rest;
use crate::math::union_find::UnionFind;
use crate::math::vec::{norm, sub};
use crate::network::info::RodInfo;
use crate::rod::frames::EdgeRef;

pub struct Numbered {
    pub rods: Vec<RodInfo>,
    pub rest_pos: Vec<[f64; 3]>,
    /// First centre node of elastic joints.
    pub first_center: usize,
    pub edge_nodes: Vec<[usize; 2]>,
    pub rest_lengths: Vec<f64>,
    pub edge_refs: Vec<EdgeRef>,
    /// Rod of each global edge.
    pub edge_rod: Vec<usize>,
}

impl Numbered {
    pub fn n_nodes(&self) -> usize {
        self.rest_pos.len()
    }

    pub fn joint_node(&self, n: &JointNode) -> usize {
        match *n {
            JointNode::Site(r, node) => self.rods[r].nodes[node],
            JointNode::Center(c) => self.first_center + c,
        }
    }
}

pub fn number(rest: &Rest, joined: &Joined) -> Numbered {
    let (rods, mut rest_pos) = nodes(rest, joined);
    let first_center = rest_pos.len();
    rest_pos.extend(joined.table.centers.iter().copied());
    let mut n = Numbered {
        rods,
        rest_pos,
        first_center,
        edge_nodes: Vec::new(),
        rest_lengths: Vec::new(),
        edge_refs: Vec::new(),
        edge_rod: Vec::new(),
    };
    edges(rest, &mut n);
    n
}

/// Union-find over the joints' merges; rods with their global nodes, and each node's rest
/// position.
fn nodes(rest: &Rest, joined: &Joined) -> (Vec<RodInfo>, Vec<[f64; 3]>) {
    let scene = rest.scene;
    let mut first_id = Vec::new();
    let mut n_raw = 0;
    for p in &rest.nodes {
        first_id.push(n_raw);
        n_raw += p.len();
    }
    let mut sets = UnionFind::new(n_raw);
    for group in &joined.merges {
        let a = first_id[group[0].0] + group[0].1;
        for &(r, node) in &group[1..] {
            sets.union(a, first_id[r] + node);
        }
    }
    let mut node_of_root = vec![usize::MAX; n_raw];
    let mut rest_pos: Vec<[f64; 3]> = Vec::new();
    let mut rods: Vec<RodInfo> = Vec::new();
    for (ri, rod) in scene.rods.iter().enumerate() {
        let mut nodes = Vec::with_capacity(rest.nodes[ri].len());
        for (k, p) in rest.nodes[ri].iter().enumerate() {
            let root = sets.find(first_id[ri] + k);
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
            yield_strength: mat.yield_strength,
        });
    }
    (rods, rest_pos)
}

fn edges(rest: &Rest, n: &mut Numbered) {
    for (ri, refs) in rest.edges.iter().enumerate() {
        let np = n.rods[ri].nodes.len();
        for (k, r) in refs.iter().enumerate() {
            let (a, b) = (n.rods[ri].nodes[k], n.rods[ri].nodes[(k + 1) % np]);
            n.rods[ri].edges.push(n.edge_nodes.len());
            n.edge_nodes.push([a, b]);
            n.rest_lengths.push(norm(sub(n.rest_pos[b], n.rest_pos[a])));
            n.edge_refs.push(*r);
            n.edge_rod.push(ri);
        }
    }
}
