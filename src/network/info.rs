//! What a built network knows by name: its rods (nodes and edges of each, section, material),
//! supports and joints. Results, exports and studies name things through these.

use crate::network::model::Model;
use crate::rod::section::{Section, Stiffness};

/// One rod of the built network.
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

impl RodInfo {
    /// Global node of the rod's input vertex `vertex` (before subdivision).
    pub fn vertex_node(&self, vertex: usize) -> Option<usize> {
        self.nodes.get(vertex * self.subdivide).copied()
    }
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
}

impl Network {
    pub fn n_nodes(&self) -> usize {
        self.model.layout.n_nodes()
    }

    /// The rod named `name`.
    pub fn rod(&self, name: &str) -> Option<&RodInfo> {
        self.rods.iter().find(|r| r.name == name)
    }

    /// Current position of input vertex `vertex` of rod `rod`.
    pub fn vertex_position(&self, rod: &str, vertex: usize) -> Option<[f64; 3]> {
        let n = self.rod(rod)?.vertex_node(vertex)?;
        Some(self.model.position(n))
    }
}
