//! The scene's rods in their rest shape, and how scene sites (rod name, input vertex) map to rod
//! nodes.

use std::collections::HashMap;

use crate::math::vec::Frame;
use crate::network::rest;
use crate::rod::frames::EdgeRef;
use crate::scene::Scene;

pub struct Rest<'s> {
    pub scene: &'s Scene,
    /// Rest nodes of each rod.
    pub nodes: Vec<Vec<[f64; 3]>>,
    /// Rest reference frames of each rod's edges.
    pub edges: Vec<Vec<EdgeRef>>,
    rod_index: HashMap<&'s str, usize>,
    /// Diagonal of the rest shape's bounding box, m.
    pub length_scale: f64,
}

impl<'s> Rest<'s> {
    pub fn of(scene: &'s Scene) -> Self {
        let nodes: Vec<Vec<[f64; 3]>> = scene.rods.iter().map(rest::rod_nodes).collect();
        let edges = scene
            .rods
            .iter()
            .zip(&nodes)
            .map(|(r, p)| rest::rod_edge_frames(p, r.closed, r.normal))
            .collect();
        let rod_index = scene
            .rods
            .iter()
            .enumerate()
            .map(|(i, r)| (r.name.as_str(), i))
            .collect();
        let length_scale = rest::bbox_diagonal(nodes.iter().flatten());
        Rest {
            scene,
            nodes,
            edges,
            rod_index,
            length_scale,
        }
    }

    /// (rod index, rod node) of input vertex `v` of the rod named `rod`.
    pub fn site(&self, rod: &str, v: usize) -> (usize, usize) {
        let r = self.rod_index[rod];
        (r, v * self.scene.rods[r].subdivide)
    }

    /// Rest frame of rod `r` at its node `j` (from its edges in and out).
    pub fn frame_at(&self, r: usize, j: usize) -> Frame {
        let (np, closed) = (self.nodes[r].len(), self.scene.rods[r].closed);
        let e = &self.edges[r];
        let e_in = (closed || j > 0).then(|| e[(j + np - 1) % np]);
        let e_out = (closed || j + 1 < np).then(|| e[j % e.len()]);
        rest::vertex_frame(e_in, e_out)
    }

    /// Whether node `node` of rod `r` is one of its ends.
    pub fn is_end(&self, r: usize, node: usize) -> bool {
        !self.scene.rods[r].closed && (node == 0 || node + 1 == self.nodes[r].len())
    }
}
