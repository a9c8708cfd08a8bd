//! How close a form-found gridshell is to its analytic shapes: the sphere and the Chebyshev net.

use serde::Serialize;

use crate::gridshell::chebyshev::HemisphereNet;
use crate::gridshell::footprint::CrossingJoint;
use crate::math::vec::{norm, sub};
use crate::network::Network;

/// Shape errors of an equilibrium, every length relative to R.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ShapeMetrics {
    /// Largest |(|x − c| − R)/R| over the joints.
    pub max_abs_radial_deviation: f64,
    pub rms_radial_deviation: f64,
    /// Mean of (|x − c| − R)/R over the joints: negative when the grid sits inside the sphere.
    pub mean_radial_deviation: f64,
    /// Highest node above the sphere centre, over R.
    pub apex_height: f64,
    /// Lowest joint above the equator plane, over R: positive when every crossing went up.
    pub lowest_joint_height: f64,
    /// Largest |x − r(c_i, c_j)|/R over the joints, r the Chebyshev net.
    pub max_net_distance: f64,
    pub rms_net_distance: f64,
}

/// Metrics of the network's current state; `crossings[k]` is the crossing of joint k.
pub fn shape_metrics(
    network: &Network,
    net: &HemisphereNet,
    crossings: &[CrossingJoint],
) -> ShapeMetrics {
    let m = &network.model;
    let r = net.radius;
    let count = network.joints.len().max(1) as f64;
    let (mut max_rad, mut sum2_rad, mut sum_rad) = (0.0f64, 0.0, 0.0);
    let (mut max_net, mut sum2_net) = (0.0f64, 0.0);
    let mut lowest = f64::INFINITY;
    for (j, c) in network.joints.iter().zip(crossings) {
        let x = m.world_position(j.node);
        lowest = lowest.min(x[2] / r);
        let d = (norm(x) - r) / r;
        max_rad = max_rad.max(d.abs());
        sum2_rad += d * d;
        sum_rad += d;
        let e = norm(sub(x, net.crossing(c.i, c.j))) / r;
        max_net = max_net.max(e);
        sum2_net += e * e;
    }
    let apex = (0..network.n_nodes())
        .map(|n| m.world_position(n)[2])
        .fold(f64::NEG_INFINITY, f64::max)
        / r;
    ShapeMetrics {
        max_abs_radial_deviation: max_rad,
        rms_radial_deviation: (sum2_rad / count).sqrt(),
        mean_radial_deviation: sum_rad / count,
        apex_height: apex,
        lowest_joint_height: lowest,
        max_net_distance: max_net,
        rms_net_distance: (sum2_net / count).sqrt(),
    }
}
