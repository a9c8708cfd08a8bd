//! What a solve found, computed once from the network at its final state: positions, energies
//! (by category, by term kind, by rod), reactions, internal forces and stresses, contact forces
//! with the KKT measures, and the comparisons the scene asks for (target, reference). Output
//! formats (`io`) only format this value.

mod constraints;
mod internal_forces;
mod load_energy;
mod reference;
mod rod_energy;
mod stress;
mod target;

use serde::{Deserialize, Serialize};

use crate::network::assembly::Assembly;
use crate::network::model::{EnergyParts, KindEnergy};
use crate::network::rest;
use crate::network::support::{Reported, SupportTag};
use crate::network::Network;
use crate::rod::frames::canonical_angles;
use crate::scene::types::Load;
use crate::scene::Scene;
use crate::solver::NewtonReport;

pub use constraints::{ConstraintForces, ContactForce, Kkt};
pub use internal_forces::{von_mises, EdgeForces};
pub use reference::ReferenceCheck;
pub use rod_energy::RodEnergy;
pub use stress::VertexBending;
pub use target::{MeshDistance, NetBlock, SphereDeviation, TargetCheck};

/// One rod at equilibrium.
#[derive(Debug, Clone)]
pub struct RodEquilibrium {
    pub name: String,
    /// Every node after subdivision, m.
    pub points: Vec<[f64; 3]>,
    /// Material-frame angle θ of each edge relative to its time-parallel reference frame, rad.
    pub twist: Vec<f64>,
    /// Length after deformation, m.
    pub length: f64,
    pub energy: RodEnergy,
    /// Curvature, bending strain and stress at each node.
    pub bending: Vec<VertexBending>,
    /// Axial force EA (|e|/|ē| − 1) in each edge, N (tension positive).
    pub axial_force: Vec<f64>,
    /// Internal force and moment of each edge in its material frame (docs/internal-forces.md).
    pub forces: Vec<EdgeForces>,
    /// Largest utilization over the rod's edges, when its material has a yield strength.
    pub utilization: Option<f64>,
    /// Every node in the rest shape, m (pictures draw the undeformed shape from these).
    pub rest_points: Vec<[f64; 3]>,
    /// Scenes with a target: signed distance of each node to it, m (sphere: radial, positive
    /// outside; mesh: along its normals).
    pub target_distance: Option<Vec<f64>>,
}

/// The most utilized edge of the structure.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Utilization {
    /// Largest von Mises stress over yield strength.
    pub max: f64,
    pub rod: String,
    /// Index of the edge in the rod (edge k joins nodes k and k + 1).
    pub edge: usize,
}

/// Force and moment a support exerts on the structure.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Reaction {
    /// N.
    pub force: [f64; 3],
    /// N·m (clamps; zero for pins).
    pub moment: [f64; 3],
}

/// A support and what it exerts on the structure.
#[derive(Debug, Clone, PartialEq)]
pub struct SupportReaction {
    pub rod: String,
    /// Input vertex of the rod (scene numbering).
    pub vertex: usize,
    /// Index of the vertex's node in the rod's nodes (vertex × subdivide).
    pub node: usize,
    /// Its name in the results: [`SupportTag::name`].
    pub kind: SupportTag,
    pub reaction: Reaction,
}

/// A point force or torque of the scene at the final state's load factor.
#[derive(Debug, Clone, PartialEq)]
pub struct AppliedLoad {
    pub rod: String,
    pub vertex: usize,
    /// Index of the vertex's node in the rod's nodes.
    pub node: usize,
    /// N.
    pub force: [f64; 3],
    /// N·m.
    pub moment: [f64; 3],
}

#[derive(Debug, Clone)]
pub struct Equilibrium {
    /// By category; `external` is the loads' potential measured from the rest configuration
    /// (minus the work the loads did from the rest positions).
    pub energy: EnergyParts,
    /// Energy of each term kind, in the order of `Terms::NAMES`.
    pub energy_by_kind: Vec<KindEnergy>,
    pub rods: Vec<RodEquilibrium>,
    /// Joint names and positions, m.
    pub joints: Vec<(String, [f64; 3])>,
    /// Support (rod, vertex) and its reaction. Supports that hold one node (frame) share its
    /// reaction: the first in scene order reports the whole force (moment), the others zero.
    pub reactions: Vec<SupportReaction>,
    /// The scene's point forces and torques (gravity, being distributed, is not listed).
    pub loads: Vec<AppliedLoad>,
    /// Scenes with obstacles or bounds only.
    pub constraints: Option<ConstraintForces>,
    pub target: Option<TargetCheck>,
    pub reference: Option<ReferenceCheck>,
    pub free_unknowns: usize,
    /// Unsupported structures: how their rigid translations were removed.
    pub gauge: Option<String>,
    /// Rods whose material has a yield strength: the most utilized edge among them.
    pub utilization: Option<Utilization>,
}

impl Equilibrium {
    /// Measures `net` (built from `scene`) at its current state; `report` is the solve that
    /// brought it there (its constraint multipliers and tolerance).
    pub fn compute(net: &Network, scene: &Scene, report: &NewtonReport) -> Equilibrium {
        let m = &net.model;
        let q = &m.state.q;
        let mut grad = vec![0.0; m.n_free];
        let mut full = vec![0.0; q.len()];
        m.assemble(&mut Assembly {
            grad: &mut grad,
            full_grad: Some(&mut full),
            hess: None,
        });
        let energies = rod_energy::per_rod(net);
        let bending = stress::all_vertex_bending(net);
        let forces = internal_forces::all_edge_forces(net);
        let distance = scene
            .target
            .as_ref()
            .and_then(|t| target::node_distances(net, t));
        let rods: Vec<RodEquilibrium> = net
            .rods
            .iter()
            .zip(energies)
            .zip(bending)
            .zip(forces)
            .enumerate()
            .map(|(i, (((r, energy), bending), forces))| RodEquilibrium {
                name: r.name.clone(),
                points: r.nodes.iter().map(|&n| m.world_position(n)).collect(),
                twist: reported_angles(net, r),
                length: r.edges.iter().map(|&e| edge_length(net, e)).sum(),
                energy,
                bending,
                axial_force: r.edges.iter().map(|&e| axial_force(net, e)).collect(),
                utilization: most_utilized(&forces).map(|(_, u)| u),
                forces,
                rest_points: scene.rods.get(i).map(rest::rod_nodes).unwrap_or_default(),
                target_distance: distance
                    .as_ref()
                    .map(|d| r.nodes.iter().map(|&n| d[n]).collect()),
            })
            .collect();
        let utilization = rods
            .iter()
            .filter_map(|r| most_utilized(&r.forces).map(|(edge, max)| (r, edge, max)))
            .max_by(|a, b| a.2.total_cmp(&b.2))
            .map(|(r, edge, max)| Utilization {
                max,
                rod: r.name.clone(),
                edge,
            });
        // The gradient at a fixed node (frame) is the whole reaction there, however many
        // supports hold it; how it divides among them is statically indeterminate. The first
        // support on a node carries its force, the first clamp on a frame its moment, and later
        // ones report zero, so that the reactions sum to minus the loads.
        let constraints = m.contact.as_ref().map(|c| {
            // A scene whose constrained nodes are all supported has no rows and no QP.
            let none = Default::default();
            let cr = report.constraints.as_ref().unwrap_or(&none);
            constraints::forces(net, c, cr, &grad, report.tolerance)
        });
        // A roller's node may also touch an obstacle: the contact takes its share of the node's
        // gradient, the roller the rest.
        let pressed = match (&m.contact, &report.constraints) {
            (Some(c), Some(cr)) => constraints::node_forces(c, cr, &m.state.q),
            _ => Default::default(),
        };
        let mut node_taken = std::collections::HashSet::new();
        let mut frame_taken = std::collections::HashSet::new();
        let reactions = net
            .supports
            .iter()
            .map(|s| {
                let at = |reaction| SupportReaction {
                    rod: s.rod.clone(),
                    vertex: s.vertex,
                    node: node_index(net, &s.rod, s.vertex),
                    kind: s.kind,
                    reaction,
                };
                if s.kind.reported() == Reported::Elastic {
                    // A spring's reaction is its own force (moment); the node and frame are
                    // free, so it takes no share of a fixed node's gradient.
                    let force = s.spring.map_or([0.0; 3], |k| {
                        m.terms.springs[k].force(m.position(s.node), m.state.load_factor)
                    });
                    let moment = s
                        .rotational
                        .map_or([0.0; 3], |k| m.terms.rotational_springs[k].moment(&m.state));
                    return at(Reaction { force, moment });
                }
                let mut at_node = m.layout.node(s.node).map(|v| full[v]);
                if let Some(f) = pressed.get(&s.node) {
                    at_node = std::array::from_fn(|k| at_node[k] - f[k]);
                }
                let slanted = m.rollers.list.iter().find(|r| r.node == s.node);
                let force = match (node_taken.insert(s.node), slanted) {
                    (false, _) => [0.0; 3],
                    // A slanted roller's node is free: its reaction is what the planes take.
                    (true, Some(r)) => r.normal_part(at_node),
                    (true, None) => at_node,
                };
                let moment = match s.frame.filter(|f| frame_taken.insert(*f)) {
                    Some(f) => m.layout.frame(f).map(|v| full[v]),
                    None => [0.0; 3],
                };
                at(Reaction { force, moment })
            })
            .collect();
        let mut energy_by_kind = m.energy_by_kind();
        for k in energy_by_kind.iter_mut().filter(|k| k.name == "loads") {
            k.energy = load_energy::from_rest(net, scene);
        }
        Equilibrium {
            energy: EnergyParts::of(&energy_by_kind),
            energy_by_kind,
            rods,
            joints: net
                .joints
                .iter()
                .map(|j| (j.name.clone(), m.world_position(j.node)))
                .collect(),
            reactions,
            loads: applied_loads(net, scene),
            constraints,
            target: scene.target.as_ref().and_then(|t| target::check(net, t)),
            reference: reference::check(net, scene),
            gauge: net.gauge.as_ref().map(|g| g.describe()),
            free_unknowns: m.n_free,
            utilization,
        }
    }
}

/// Index in the rod's nodes of input vertex `vertex` of the rod named `rod`.
fn node_index(net: &Network, rod: &str, vertex: usize) -> usize {
    net.rod(rod).map_or(vertex, |r| vertex * r.subdivide)
}

/// The scene's point forces and torques, scaled by the load factor reached.
fn applied_loads(net: &Network, scene: &Scene) -> Vec<AppliedLoad> {
    let lambda = net.model.state.load_factor;
    let at = |rod: &String, vertex: usize, force: [f64; 3], moment: [f64; 3]| AppliedLoad {
        rod: rod.clone(),
        vertex,
        node: node_index(net, rod, vertex),
        force: force.map(|f| lambda * f),
        moment: moment.map(|m| lambda * m),
    };
    scene
        .loads
        .iter()
        .filter_map(|l| match l {
            Load::Force { rod, vertex, force } => Some(at(rod, *vertex, *force, [0.0; 3])),
            Load::Torque {
                rod,
                vertex,
                torque,
            } => Some(at(rod, *vertex, [0.0; 3], *torque)),
            Load::Gravity { .. } => None,
        })
        .collect()
}

/// The edge with the largest utilization and its value (the first of equal ones).
fn most_utilized(forces: &[EdgeForces]) -> Option<(usize, f64)> {
    forces
        .iter()
        .enumerate()
        .filter_map(|(k, f)| f.utilization.map(|u| (k, u)))
        .fold(None, |best, (k, u)| match best {
            Some((_, b)) if b >= u => best,
            _ => Some((k, u)),
        })
}

fn edge_length(net: &Network, e: usize) -> f64 {
    let m = &net.model;
    let [a, b] = m.edge_nodes[e];
    crate::math::vec::norm(crate::math::vec::sub(m.position(b), m.position(a)))
}

fn axial_force(net: &Network, e: usize) -> f64 {
    let s = &net.model.terms.stretch[e];
    debug_assert_eq!(s.edge, e, "one stretch term per edge, in edge order");
    s.ea * (edge_length(net, e) / s.rest_length - 1.0)
}

/// The material angles of rod `r`'s edges as reported: against its canonical directors (the
/// rest frame of its first edge carried along the rod by space-parallel transport,
/// `rod::frames::canonical_directors`), so that they depend on the state alone, not on the
/// solve's path, and a restart from the results (`network/initial.rs`) rebuilds the same
/// material frames.
fn reported_angles(net: &Network, r: &crate::network::RodInfo) -> Vec<f64> {
    let m = &net.model;
    let tangents = net.rod_tangents(r);
    let Some(&first) = r.edges.first() else {
        return Vec::new();
    };
    let refs: Vec<_> = r.edges.iter().map(|&e| m.state.edges[e]).collect();
    let thetas: Vec<f64> = r
        .edges
        .iter()
        .map(|&e| m.state.q[m.layout.theta(e)])
        .collect();
    canonical_angles(&m.rest_edges[first], &tangents, &refs, &thetas)
}
