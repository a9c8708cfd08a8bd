//! What a built network knows by name: its rods (nodes and edges of each, section, material),
//! supports and joints. Results, exports and studies name things through these.

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
    /// The material's yield strength, Pa, when given (utilization).
    pub yield_strength: Option<f64>,
}

impl RodInfo {
    /// Global node of the rod's input vertex `vertex` (before subdivision).
    pub fn vertex_node(&self, vertex: usize) -> Option<usize> {
        self.nodes.get(vertex * self.subdivide).copied()
    }
}

/// A support's kind without its parameters. What each kind is called in the results, how its
/// reaction is reported and how a picture marks it are in `network/support/`, one file per kind.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SupportTag {
    Pin,
    Clamp,
    Roller,
    Spring,
}

#[derive(Debug, Clone)]
pub struct SupportInfo {
    pub rod: String,
    pub vertex: usize,
    pub node: usize,
    pub kind: SupportTag,
    /// The vertex frame a clamp fixes (its reaction moment).
    pub frame: Option<usize>,
    /// An elastic support: its index in `Terms::springs` (its reaction is its spring force).
    pub spring: Option<usize>,
    /// A rotational elastic support: its index in `Terms::rotational_springs` (its reaction
    /// moment is the spring's moment); `frame` is then the frame it turns with.
    pub rotational: Option<usize>,
}

/// The node held in place to remove the rigid translations of an unsupported structure.
#[derive(Debug, Clone)]
pub struct Gauge {
    pub node: usize,
    pub rod: String,
    /// Index of the node in the rod's nodes.
    pub index: usize,
}

impl Gauge {
    pub fn describe(&self) -> String {
        format!(
            "the scene has no supports: rigid translations are removed by holding node {} of rod \"{}\" in place (its reaction is the loads' net force, zero)",
            self.index, self.rod
        )
    }
}

#[derive(Debug, Clone)]
pub struct JointInfo {
    pub name: String,
    /// The shared node, or the joint's centre node for translationally elastic joints.
    pub node: usize,
}
