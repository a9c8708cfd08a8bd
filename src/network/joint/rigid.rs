//! Rigid joint (Perez 2015, Zehnder 2016, X-shells): one rigid frame at the vertex; every incident
//! rod's material frame there is a fixed rotation of it, so the rods keep their rest relative
//! orientation exactly. The rods' edges attach to it by bending and twisting half-stencils.

use super::{PortBuild, PortTable, Site};

/// Two rod ends joined rigidly, with no clamp or torque there, are spliced instead: the rods'
/// own bend and twist stencil continues across the joint (edges oriented along it), which is
/// exactly the discretization of one continuous rod and needs no frame. The rest angle is
/// kept, so the angle across the stencil cannot approach π unless the rest shape folds back.
pub fn is_splice(sites: &[Site], rod_ends: impl Fn(usize, usize) -> bool, loaded: bool) -> bool {
    sites.len() == 2
        && !loaded
        && sites.iter().all(|s| !s.clamped && rod_ends(s.rod, s.node))
        && sites[0].rod != sites[1].rod
}

pub fn add(table: &mut PortTable, sites: &[Site]) -> Result<usize, String> {
    let frame = table.new_frame(false);
    for s in sites {
        if s.clamped {
            table.frame_fixed[frame] = true;
        }
        table.attach(PortBuild {
            rod: s.rod,
            node: s.node,
            frame,
            rest: s.rest,
            alpha: None,
            hinge_axis: [0.0, 0.0, 1.0],
        })?;
    }
    Ok(frame)
}
