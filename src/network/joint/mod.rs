//! Joint kinds, one per file. A joint joins (rod, vertex) *sites*. All kinds but a translationally
//! elastic joint share one node; the kinds differ in how the rods' frames at the vertex relate:
//!
//! - [`rigid`]: one vertex frame for all sites (rest relative orientation kept exactly);
//! - [`hinge`]: one frame plus a free scissor angle per site about the joint normal;
//! - [`ball`]: no frame; each rod keeps its own stencils through the vertex;
//! - [`elastic`]: one frame per site plus a joint frame, coupled by rotational springs (and
//!   optionally a translational spring instead of a shared node).
//!
//! Clamps and torques also create vertex frames through the same [`PortTable`].

pub mod ball;
pub mod elastic;
pub mod hinge;
pub mod rigid;

use std::collections::HashMap;

use crate::math::vec::Frame;
use crate::scene::types::{JointChoice, JointKind};

impl JointChoice {
    /// Joint kind for rods of modulus `young` and outer radius `radius`.
    pub fn kind(self, young: f64, radius: f64) -> JointKind {
        match self {
            JointChoice::Ball => JointKind::Ball,
            JointChoice::Hinge => JointKind::Hinge,
            JointChoice::Rigid => JointKind::Rigid,
            JointChoice::Elastic => JointKind::from_elastic(elastic::vps_joint(young, radius)),
        }
    }
}

/// A rod's attachment to a vertex frame (before variables are laid out).
#[derive(Debug, Clone)]
pub struct PortBuild {
    pub rod: usize,
    /// Rod-local node index.
    pub node: usize,
    pub frame: usize,
    /// Rest orientation relative to the frame (the frame's rest rotation is the identity).
    pub rest: Frame,
    /// Hinge scissor angle (index among hinge angles), if any.
    pub alpha: Option<usize>,
    pub hinge_axis: [f64; 3],
}

/// Rotational spring of an elastic joint between a port's frame and the joint frame.
#[derive(Debug, Clone)]
pub struct Coupling {
    pub port: usize,
    pub joint_frame: usize,
    pub axes: [[f64; 3]; 3],
    pub stiffness: [f64; 3],
}

/// Translational spring of an elastic joint between a rod node and the joint's centre node.
#[derive(Debug, Clone)]
pub struct Anchor {
    pub rod: usize,
    pub node: usize,
    /// Index among joint centre nodes.
    pub center: usize,
    pub stiffness: f64,
}

/// Vertex frames and the ports attached to them.
#[derive(Debug, Default)]
pub struct PortTable {
    pub ports: Vec<PortBuild>,
    pub port_of: HashMap<(usize, usize), usize>,
    pub frame_fixed: Vec<bool>,
    pub n_alpha: usize,
    pub fixed_alpha: Vec<usize>,
    pub couplings: Vec<Coupling>,
    pub anchors: Vec<Anchor>,
    /// Rest positions of joint centre nodes (translationally elastic joints).
    pub centers: Vec<[f64; 3]>,
}

impl PortTable {
    pub fn new_frame(&mut self, fixed: bool) -> usize {
        self.frame_fixed.push(fixed);
        self.frame_fixed.len() - 1
    }

    pub fn new_alpha(&mut self) -> usize {
        self.n_alpha += 1;
        self.n_alpha - 1
    }

    /// Attaches site (rod, node) to `frame`; a site belongs to at most one frame.
    pub fn attach(&mut self, port: PortBuild) -> Result<usize, String> {
        let key = (port.rod, port.node);
        if self.port_of.contains_key(&key) {
            return Err("this rod vertex already has a frame from another joint".into());
        }
        self.port_of.insert(key, self.ports.len());
        self.ports.push(port);
        Ok(self.ports.len() - 1)
    }

    /// A new frame with one port at (rod, node): clamps and torques at vertices without joints.
    pub fn single(&mut self, rod: usize, node: usize, fixed: bool, rest: Frame) -> usize {
        let frame = self.new_frame(fixed);
        self.port_of.insert((rod, node), self.ports.len());
        self.ports.push(PortBuild {
            rod,
            node,
            frame,
            rest,
            alpha: None,
            hinge_axis: [0.0, 0.0, 1.0],
        });
        self.ports.len() - 1
    }
}

/// What a joint needs from the rods: its sites with their rest frames and clamp status.
pub struct Site {
    pub rod: usize,
    pub node: usize,
    pub rest: Frame,
    pub clamped: bool,
}

/// The joint normal: given, or the cross product of the first two sites' tangents.
pub fn joint_normal(sites: &[Site], given: Option<[f64; 3]>) -> Option<[f64; 3]> {
    use crate::math::vec::{cross, norm, normalize};
    let n = match given {
        Some(n) => n,
        None if sites.len() >= 2 => cross(sites[0].rest[2], sites[1].rest[2]),
        None => return None,
    };
    (norm(n) > 1e-8).then(|| normalize(n))
}
