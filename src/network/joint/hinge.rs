//! Hinge joint: as [`super::rigid`], but each rod may rotate about the joint normal n̄ (the scissor
//! motion of X-shells and Chebyshev nets): site k's frame is F·R(n̄, α_k)·C_k, with α of the
//! reference site fixed at zero (it is the frame's own rotation about n̄). A clamped site is the
//! reference, so a clamp fixes its own rod and leaves the others free to scissor.

use super::{joint_normal, PortBuild, PortTable, Site};

pub fn add(
    table: &mut PortTable,
    sites: &mut [Site],
    normal: Option<[f64; 3]>,
) -> Result<usize, String> {
    if let Some(k) = sites.iter().position(|s| s.clamped) {
        sites.swap(0, k);
    }
    let axis = joint_normal(sites, normal).ok_or_else(|| {
        if sites.len() < 2 && normal.is_none() {
            "a Hinge joining fewer than two rod vertices needs `normal`".to_string()
        } else {
            "hinge axis undefined: the first two rods are parallel; give `normal`".to_string()
        }
    })?;
    let frame = table.new_frame(false);
    for (k, s) in sites.iter().enumerate() {
        let alpha = if k > 0 {
            let a = table.new_alpha();
            if s.clamped {
                table.fixed_alpha.push(a);
            }
            Some(a)
        } else {
            None
        };
        if s.clamped {
            table.frame_fixed[frame] = true;
        }
        table.attach(PortBuild {
            rod: s.rod,
            node: s.node,
            frame,
            rest: s.rest,
            alpha,
            hinge_axis: axis,
        })?;
    }
    Ok(frame)
}
