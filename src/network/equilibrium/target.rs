//! The equilibrium against the scene's target shape.

use crate::math::vec::{norm, sub};
use crate::network::Network;
use crate::scene::types::Target;

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TargetCheck {
    pub shape: &'static str,
    /// Over R.
    pub max_abs_radial_deviation: f64,
    pub rms_radial_deviation: f64,
    /// Highest node above the centre, over R.
    pub apex_height: f64,
    /// Gridshells only: distance of each joint to its crossing on the Chebyshev net, over R
    /// (max, rms); set by the gridshell job, which knows the net.
    pub net_distance: Option<(f64, f64)>,
}

/// Sphere deviations over the joint positions (all rod nodes when there are no joints),
/// relative to R.
pub fn check(net: &Network, t: &Target) -> TargetCheck {
    let Target::Sphere { center, radius } = t;
    let m = &net.model;
    let nodes: Vec<usize> = if net.joints.is_empty() {
        (0..net.n_nodes()).collect()
    } else {
        net.joints.iter().map(|j| j.node).collect()
    };
    let mut max: f64 = 0.0;
    let mut sum2 = 0.0;
    for &n in &nodes {
        let d = (norm(sub(m.position(n), *center)) - radius) / radius;
        max = max.max(d.abs());
        sum2 += d * d;
    }
    let apex = (0..net.n_nodes())
        .map(|n| m.position(n)[2] - center[2])
        .fold(f64::NEG_INFINITY, f64::max)
        / radius;
    TargetCheck {
        shape: "sphere",
        max_abs_radial_deviation: max,
        rms_radial_deviation: (sum2 / nodes.len().max(1) as f64).sqrt(),
        apex_height: apex,
        net_distance: None,
    }
}
