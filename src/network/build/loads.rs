//! Loads as potentials: point forces and gravity lumped onto nodes, torques on vertex frames;
//! and the force scale that makes residuals relative.

use super::geometry::Rest;
use super::nodes::Numbered;
use crate::energy::registry::Terms;
use crate::energy::{point_load::PointLoad, torque::Torque};
use crate::math::vec::{add, norm, scalef};
use crate::network::joint::PortTable;
use crate::scene::types::Load;
use crate::scene::Scene;
use crate::variables::DofLayout;

/// Adds the load terms; returns the force scale (N). `driven`: the scene prescribes motions.
#[allow(clippy::too_many_arguments)]
pub fn apply(
    scene: &Scene,
    rest: &Rest,
    net: &Numbered,
    table: &PortTable,
    layout: &DofLayout,
    length_scale: f64,
    driven: bool,
    terms: &mut Terms,
) -> f64 {
    let mut nodal = vec![[0.0; 3]; net.n_nodes()];
    let mut force_scale: f64 = 0.0;
    for l in &scene.loads {
        match l {
            Load::Force { rod, vertex, force } => {
                let (r, rn) = rest.site(rod, *vertex);
                let node = net.rods[r].nodes[rn];
                nodal[node] = add(nodal[node], *force);
                force_scale = force_scale.max(norm(*force));
            }
            Load::Gravity { g } => {
                let mut weight = 0.0;
                for (e, &[a, b]) in net.edge_nodes.iter().enumerate() {
                    let m = 0.5
                        * net.rods[net.edge_rod[e]].stiffness.mass_per_length
                        * net.rest_lengths[e];
                    nodal[a] = add(nodal[a], scalef(*g, m));
                    nodal[b] = add(nodal[b], scalef(*g, m));
                    weight += 2.0 * m * norm(*g);
                }
                force_scale = force_scale.max(weight);
            }
            Load::Torque {
                rod,
                vertex,
                torque,
            } => {
                let f = table.ports[table.port_of[&rest.site(rod, *vertex)]].frame;
                terms.torques.push(Torque {
                    vars: layout.frame(f),
                    frame: f,
                    torque: *torque,
                });
                force_scale = force_scale.max(norm(*torque) / length_scale);
            }
        }
    }
    for (n, f) in nodal.iter().enumerate() {
        if *f != [0.0; 3] {
            terms.loads.push(PointLoad {
                vars: layout.node(n),
                force: *f,
            });
        }
    }
    // Loads set the force scale when there are any; prescribed motions (and unloaded scenes)
    // are measured against the rods' bending scale EI/L².
    if driven || force_scale == 0.0 {
        for rod in &net.rods {
            let ei = rod.stiffness.ei1.max(rod.stiffness.ei2);
            force_scale = force_scale.max(ei / (length_scale * length_scale));
        }
    }
    force_scale
}
