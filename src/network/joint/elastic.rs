//! Elastic joint: finite rotational (and optionally translational) stiffness between the rods.
//!
//! Each site gets its own vertex frame (its edges attach to it by half-stencils, so a rod
//! through the joint stays continuous), and a joint frame J is added; a rotational spring per site
//! couples the site frame to J·C (its rest orientation) about three axes in the site's rest frame:
//! bending (t × n), twist (t) and scissor (n), n the joint normal. The limits are the other kinds:
//! k → ∞ gives [`super::rigid`], k → 0 gives [`super::ball`].
//!
//! Stiffnesses are given (N·m/rad) or derived from a joint cylinder of modulus E, diameter d and
//! height h whose axis is the joint normal (the VPS joints of Baek et al.: E = 1.3 MPa, d = 3 mm,
//! h = 5 mm): relative rotation about the normal twists the cylinder, k_scissor = G·(πd⁴/32)/h;
//! rotations about in-plane axes (rod bending and rod twist) bend it, k = E·(πd⁴/64)/h; with
//! G = E/(2(1+ν)), ν = 0.5 for elastomers unless given.
//!
//! Without `translation` the sites share one node; with it, each site keeps its own node, tied
//! to a joint centre node by a spring of that stiffness (N/m).

use super::{joint_normal, Anchor, Coupling, PortBuild, PortTable, Site};
use crate::math::vec::{cross, dot, normalize, scalef, sub};
use crate::scene::types::ElasticJoint;

/// The VPS joint of Baek et al. 2018 (cylinder E = 1.3 MPa, d = 3 mm, h = 5 mm, on Nitinol
/// rods E = 83 GPa, d = 254 µm) scaled to rods of modulus `young` and radius `radius`, keeping
/// the experiment's ratios E_joint/E_rod, d/r and h/r: the joint used by `--joint elastic`.
pub fn vps_joint(young: f64, radius: f64) -> ElasticJoint {
    let rod_radius = 127e-6;
    ElasticJoint {
        cylinder: Some(crate::scene::types::JointCylinder {
            young_modulus: young * 1.3e6 / 83e9,
            poisson_ratio: Some(0.5),
            diameter: radius * 3e-3 / rod_radius,
            height: radius * 5e-3 / rod_radius,
        }),
        ..Default::default()
    }
}

/// (bending, twist, scissor) stiffnesses, N·m/rad.
pub fn stiffnesses(e: &ElasticJoint) -> Result<[f64; 3], String> {
    let derived = e.cylinder.as_ref().map(|c| {
        use std::f64::consts::PI;
        let nu = c.poisson_ratio.unwrap_or(0.5);
        let g = c.young_modulus / (2.0 * (1.0 + nu));
        let i = PI * c.diameter.powi(4) / 64.0;
        let bend = c.young_modulus * i / c.height;
        [bend, bend, g * 2.0 * i / c.height]
    });
    let pick = |given: Option<f64>, k: usize, name: &str| -> Result<f64, String> {
        given.or(derived.map(|d| d[k])).ok_or_else(|| {
            format!("Elastic joint needs `{name}` (N·m/rad) or a `cylinder` to derive it from")
        })
    };
    Ok([
        pick(e.bending, 0, "bending")?,
        pick(e.twist, 1, "twist")?,
        pick(e.scissor, 2, "scissor")?,
    ])
}

/// Adds the joint; `center` is the rest position of the joint (for a translational spring).
pub fn add(
    table: &mut PortTable,
    sites: &[Site],
    spec: &ElasticJoint,
    normal: Option<[f64; 3]>,
    center: [f64; 3],
) -> Result<usize, String> {
    let k = stiffnesses(spec)?;
    let n = joint_normal(sites, normal);
    let joint_frame = table.new_frame(false);
    let center_index = spec.translation.map(|_| {
        table.centers.push(center);
        table.centers.len() - 1
    });
    for s in sites {
        let frame = table.new_frame(s.clamped);
        let port = table.attach(PortBuild {
            rod: s.rod,
            node: s.node,
            frame,
            rest: s.rest,
            alpha: None,
            hinge_axis: [0.0, 0.0, 1.0],
        })?;
        // Axes in the site's rest body coordinates (columns of `rest` are its world axes).
        let c = s.rest;
        let twist = [0.0, 0.0, 1.0];
        let n_body = n.map(|n| [dot(c[0], n), dot(c[1], n), dot(c[2], n)]);
        let scissor = match n_body {
            Some(nb) if (1.0 - nb[2] * nb[2]) > 1e-12 => normalize(sub(nb, scalef(twist, nb[2]))),
            _ => [1.0, 0.0, 0.0],
        };
        let bend = cross(twist, scissor);
        table.couplings.push(Coupling {
            port,
            joint_frame,
            axes: [bend, twist, scissor],
            stiffness: k,
        });
        if let (Some(kt), Some(ci)) = (spec.translation, center_index) {
            table.anchors.push(Anchor {
                rod: s.rod,
                node: s.node,
                center: ci,
                stiffness: kt,
            });
        }
    }
    Ok(joint_frame)
}
