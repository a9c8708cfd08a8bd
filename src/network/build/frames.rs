//! Vertex frames and node merges: each joint by its kind (one file per kind in
//! `network::joint`), sharp rest corners as rigid corners, clamps, and vertices that carry a
//! torque or a rotational spring.

use std::collections::HashSet;

use super::geometry::Rest;
use crate::math::vec::{dot, norm, sub};
use crate::network::joint::{self, PortTable, Site};
use crate::scene::types::{Joint, JointKind, Load, SupportKind};
use crate::scene::FieldError;

/// Rest turning angle above which a vertex is a rigid corner rather than a bending stencil
/// (15°: the stencil's stiffness factor cos²(φ/2) is then above 0.983).
pub const KINK_ANGLE: f64 = 15.0 * std::f64::consts::PI / 180.0;

/// Where a joint's position is reported: a shared rod node, or an elastic joint's centre node.
pub enum JointNode {
    Site(usize, usize),
    Center(usize),
}

/// A rod site: (rod index, rod node).
pub type RodSite = (usize, usize);

pub struct Joined {
    pub table: PortTable,
    /// Straight rigid joints of two rod ends, built as one continuous bending stencil.
    pub splices: Vec<[RodSite; 2]>,
    /// Groups of sites that share one node.
    pub merges: Vec<Vec<RodSite>>,
    /// One per scene joint.
    pub joint_nodes: Vec<JointNode>,
}

pub fn join(rest: &Rest) -> Result<Joined, FieldError> {
    let scene = rest.scene;
    let clamped: HashSet<RodSite> = scene
        .supports
        .iter()
        .filter(|s| s.kind == SupportKind::Clamp)
        .map(|s| rest.site(&s.rod, s.vertex))
        .collect();
    let frame_sites: HashSet<RodSite> = frame_sites_in_order(rest).into_iter().collect();
    let mut joined = Joined {
        table: PortTable::default(),
        splices: Vec::new(),
        merges: Vec::new(),
        joint_nodes: Vec::new(),
    };
    for (ji, j) in scene.joints.iter().enumerate() {
        add_joint(rest, &mut joined, ji, j, &clamped, &frame_sites)?;
    }
    let table = &mut joined.table;
    rigid_corners(rest, table);
    // Scene order (not the set's), so that frames are numbered the same in every run.
    let mut seen = HashSet::new();
    let clamps: Vec<RodSite> = scene
        .supports
        .iter()
        .filter(|s| s.kind == SupportKind::Clamp)
        .map(|s| rest.site(&s.rod, s.vertex))
        .filter(|s| seen.insert(*s))
        .collect();
    for &(r, node) in &clamps {
        if let Some(&p) = table.port_of.get(&(r, node)) {
            table.frame_fixed[table.ports[p].frame] = true;
        } else {
            table.single(r, node, true, rest.frame_at(r, node));
        }
    }
    for site in &frame_sites_in_order(rest) {
        if !table.port_of.contains_key(site) {
            table.single(site.0, site.1, false, rest.frame_at(site.0, site.1));
        }
    }
    Ok(joined)
}

/// Vertices whose rotation something acts on, torques (in the order of the scene's loads) and
/// rotational springs (in the order of its supports): each needs a vertex frame. Frames are
/// numbered in this order.
fn frame_sites_in_order(rest: &Rest) -> Vec<RodSite> {
    let torques = rest.scene.loads.iter().filter_map(|l| match l {
        Load::Torque { rod, vertex, .. } => Some(rest.site(rod, *vertex)),
        _ => None,
    });
    let springs = rest
        .scene
        .supports
        .iter()
        .filter(|s| s.kind.rotational_stiffness().is_some())
        .map(|s| rest.site(&s.rod, s.vertex));
    torques.chain(springs).collect()
}

fn add_joint(
    rest: &Rest,
    joined: &mut Joined,
    ji: usize,
    j: &Joint,
    clamped: &HashSet<RodSite>,
    frame_sites: &HashSet<RodSite>,
) -> Result<(), FieldError> {
    let mut sites: Vec<Site> =
        j.at.iter()
            .map(|(rn, v)| {
                let (rod, node) = rest.site(rn, *v);
                Site {
                    rod,
                    node,
                    rest: rest.frame_at(rod, node),
                    clamped: clamped.contains(&(rod, node)),
                }
            })
            .collect();
    let p0 = rest.nodes[sites[0].rod][sites[0].node];
    for (k, s) in sites.iter().enumerate().skip(1) {
        let d = norm(sub(rest.nodes[s.rod][s.node], p0));
        if d > 1e-9 * rest.length_scale {
            return Err(FieldError::new(
                "joints",
                ji,
                "at",
                format!(
                    "entry {k} (rod \"{}\") is {d:.3e} m away from the joint's first vertex; \
                     joined vertices must coincide in the rest shape",
                    j.at[k].0
                ),
            ));
        }
    }
    let at_err = |m: String| FieldError::new("joints", ji, "at", m);
    let table = &mut joined.table;
    let mut shared = true;
    match &j.kind {
        JointKind::Rigid => {
            let loaded = sites.iter().any(|s| frame_sites.contains(&(s.rod, s.node)));
            let turning = {
                let (a, b) = (sites[0].rest[2], sites[sites.len() - 1].rest[2]);
                // Rod-end frames point along their rod; a straight continuation has the two
                // tangents antiparallel when both rods leave the joint, parallel otherwise.
                let c = dot(a, b).abs().min(1.0);
                c.acos()
            };
            let rod_end = |r: usize, node: usize| rest.is_end(r, node);
            if turning < KINK_ANGLE && joint::rigid::is_splice(&sites, rod_end, loaded) {
                joined
                    .splices
                    .push([(sites[0].rod, sites[0].node), (sites[1].rod, sites[1].node)]);
            } else {
                joint::rigid::add(table, &sites).map_err(at_err)?;
            }
        }
        JointKind::Hinge => {
            joint::hinge::add(table, &mut sites, j.normal)
                .map_err(|m| FieldError::new("joints", ji, "normal", m))?;
        }
        JointKind::Ball => joint::ball::add(&sites),
        JointKind::Elastic { .. } => {
            let e = j.kind.elastic().expect("elastic joint");
            joint::elastic::add(table, &sites, &e, j.normal, p0).map_err(at_err)?;
            shared = e.translation.is_none();
        }
    }
    if shared {
        joined
            .merges
            .push(sites.iter().map(|s| (s.rod, s.node)).collect());
        joined
            .joint_nodes
            .push(JointNode::Site(sites[0].rod, sites[0].node));
    } else {
        joined
            .joint_nodes
            .push(JointNode::Center(table.centers.len() - 1));
    }
    Ok(())
}

/// Sharp corners of a rest polyline are rigid corners (a Kirchhoff rod with a corner): a
/// bending stencil with rest turning angle φ resists relative rotation with only cos²(φ/2) of
/// the rod's stiffness, an error that does not vanish with refinement.
fn rigid_corners(rest: &Rest, table: &mut PortTable) {
    for (r, rod) in rest.scene.rods.iter().enumerate() {
        let np = rest.nodes[r].len();
        let inner = if rod.closed { 0..np } else { 1..np - 1 };
        for j in inner {
            let e = &rest.edges[r];
            let (ti, to) = (e[(j + np - 1) % np].t, e[j % e.len()].t);
            if dot(ti, to).clamp(-1.0, 1.0).acos() >= KINK_ANGLE
                && !table.port_of.contains_key(&(r, j))
            {
                table.single(r, j, false, rest.frame_at(r, j));
            }
        }
    }
}
