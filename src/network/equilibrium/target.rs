//! The equilibrium against the scene's target shape: a sphere (radial deviations over R) or a
//! mesh (distances in metres, signed along the mesh's normals).

use serde::{Deserialize, Serialize};

use crate::math::vec::{norm, sub};
use crate::network::Network;
use crate::scene::types::Target;

#[derive(Debug, Clone, PartialEq)]
pub struct TargetCheck {
    pub shape: &'static str,
    pub sphere: Option<SphereDeviation>,
    pub mesh: Option<MeshDistance>,
    /// Hemisphere gridshells only: distance of each joint to its crossing on the Chebyshev
    /// net, over R (max, rms); set by the gridshell job, which knows the net.
    pub net_distance: Option<(f64, f64)>,
    /// Fitted gridshells only: the net and the joints' distances to it, set by the fit job.
    pub net: Option<NetBlock>,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SphereDeviation {
    /// Over R.
    pub max_abs_radial_deviation: f64,
    pub rms_radial_deviation: f64,
    /// Highest node above the centre, over R.
    pub apex_height: f64,
}

/// Joints (all nodes when there are none) to the mesh, m.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct MeshDistance {
    pub max_abs_distance: f64,
    pub rms_distance: f64,
    /// Along the mesh's normals: positive on the side they point to.
    pub mean_signed_distance: f64,
}

/// The `net` block of a fitted gridshell: its Chebyshev net and the joints' distances to their
/// crossings on it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NetBlock {
    /// m.
    pub spacing: f64,
    pub rods: usize,
    pub joints: usize,
    /// Angles between the rods at the net's crossings, degrees.
    pub min_angle_deg: f64,
    pub max_angle_deg: f64,
    /// Joint to its net crossing, m.
    pub max_net_distance: f64,
    pub rms_net_distance: f64,
}

/// The joints, or every node of a network without joints.
fn measured_nodes(net: &Network) -> Vec<usize> {
    if net.joints.is_empty() {
        (0..net.n_nodes()).collect()
    } else {
        net.joints.iter().map(|j| j.node).collect()
    }
}

/// Signed distance of every node of `net` to the target, m: radial for a sphere (positive
/// outside), along the normals for a mesh. `None` when a mesh cannot be read.
pub fn node_distances(net: &Network, t: &Target) -> Option<Vec<f64>> {
    let m = &net.model;
    let nodes = 0..net.n_nodes();
    match t {
        Target::Sphere { center, radius } => Some(
            nodes
                .map(|n| norm(sub(m.world_position(n), *center)) - radius)
                .collect(),
        ),
        Target::Mesh { surface, path } => {
            let loaded;
            let s = match surface.0.as_ref() {
                Some(s) => s,
                None => {
                    loaded = reload(path)?;
                    &loaded
                }
            };
            Some(
                nodes
                    .map(|n| s.signed_distance(m.world_position(n)))
                    .collect(),
            )
        }
    }
}

/// A target mesh read again from its path (a scene copy that lost its mesh).
fn reload(path: &str) -> Option<crate::surface::Surface> {
    crate::surface::Surface::load(std::path::Path::new(path), crate::scene::MAX_MESH_BYTES).ok()
}

pub fn check(net: &Network, t: &Target) -> Option<TargetCheck> {
    let nodes = measured_nodes(net);
    let m = &net.model;
    match t {
        Target::Sphere { center, radius } => {
            let mut max: f64 = 0.0;
            let mut sum2 = 0.0;
            for &n in &nodes {
                let d = (norm(sub(m.world_position(n), *center)) - radius) / radius;
                max = max.max(d.abs());
                sum2 += d * d;
            }
            let apex = (0..net.n_nodes())
                .map(|n| m.world_position(n)[2] - center[2])
                .fold(f64::NEG_INFINITY, f64::max)
                / radius;
            Some(TargetCheck {
                shape: "sphere",
                sphere: Some(SphereDeviation {
                    max_abs_radial_deviation: max,
                    rms_radial_deviation: (sum2 / nodes.len().max(1) as f64).sqrt(),
                    apex_height: apex,
                }),
                mesh: None,
                net_distance: None,
                net: None,
            })
        }
        Target::Mesh { surface, path } => {
            // Scenes read from files carry their mesh; a copy that lost it (serialized and read
            // back) reads it again from its path, which parsing made absolute or relative to
            // the working directory.
            let loaded;
            let s = match surface.0.as_ref() {
                Some(s) => s,
                None => {
                    loaded = reload(path)?;
                    &loaded
                }
            };
            let (mut max, mut sum2, mut sum) = (0.0f64, 0.0, 0.0);
            for &n in &nodes {
                let d = s.signed_distance(m.world_position(n));
                max = max.max(d.abs());
                sum2 += d * d;
                sum += d;
            }
            let count = nodes.len().max(1) as f64;
            Some(TargetCheck {
                shape: "mesh",
                sphere: None,
                mesh: Some(MeshDistance {
                    max_abs_distance: max,
                    rms_distance: (sum2 / count).sqrt(),
                    mean_signed_distance: sum / count,
                }),
                net_distance: None,
                net: None,
            })
        }
    }
}
