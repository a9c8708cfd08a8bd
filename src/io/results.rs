//! Results of a solve, in the shape of the contract's results JSON.

use serde::Serialize;

use crate::io::reference::ReferenceJson;
use crate::io::rod_energy::{self, RodEnergy};
use crate::math::vec::{norm, scalef, sub};
use crate::network::build::Network;
use crate::network::contact::{Contact, Source};
use crate::network::model::{Assembly, EnergyParts, FIXED};
use crate::scene::types::Target;
use crate::solver::{ConstraintReport, NewtonReport};

#[derive(Debug, Clone, Serialize)]
pub struct EnergyJson {
    pub total: f64,
    pub stretch: f64,
    pub bend: f64,
    pub twist: f64,
    pub joints: f64,
    pub external: f64,
}

impl From<EnergyParts> for EnergyJson {
    fn from(p: EnergyParts) -> Self {
        EnergyJson {
            total: p.total(),
            stretch: p.stretch,
            bend: p.bend,
            twist: p.twist,
            joints: p.joints,
            external: p.external,
        }
    }
}

#[derive(Debug, Clone, Serialize)]
pub struct RodJson {
    pub name: String,
    /// Every node after subdivision, m.
    pub points: Vec<[f64; 3]>,
    /// Material-frame angle θ of each edge relative to its time-parallel reference frame, rad.
    pub twist: Vec<f64>,
    /// Largest extreme-fibre bending stress over the rod's vertices, Pa.
    pub max_bending_stress: f64,
    /// Extreme-fibre bending stress at each node (zero at free ends), Pa.
    pub bending_stress: Vec<f64>,
    /// Elastic energy stored in the rod, J.
    pub energy: RodEnergy,
    /// The rod's length after deformation, m.
    pub length: f64,
}

#[derive(Debug, Clone, Serialize)]
pub struct JointJson {
    pub name: String,
    pub position: [f64; 3],
}

#[derive(Debug, Clone, Serialize)]
pub struct ReactionJson {
    pub rod: String,
    pub vertex: usize,
    /// Force the support exerts on the structure, N.
    pub force: [f64; 3],
    /// Moment the support exerts (clamps), N·m.
    pub moment: [f64; 3],
}

#[derive(Debug, Clone, Serialize)]
pub struct TargetJson {
    pub shape: String,
    pub max_abs_radial_deviation: f64,
    pub rms_radial_deviation: f64,
    pub apex_height: f64,
    /// Gridshells only: distance of each joint to its crossing on the Chebyshev net, over R.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_net_distance: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rms_net_distance: Option<f64>,
}

#[derive(Debug, Clone, Serialize)]
pub struct SolverJson {
    pub factorizations: usize,
    pub regularized_iterations: usize,
    pub saddle_escapes: usize,
    pub stable: bool,
    pub factor_seconds: f64,
    pub free_unknowns: usize,
    pub step_iterations: Vec<usize>,
    pub message: Option<String>,
}

/// The force one active constraint (obstacle contact or coordinate bound) exerts on a node.
#[derive(Debug, Clone, Serialize)]
pub struct ContactJson {
    pub rod: String,
    /// Index of the node in the rod's `points`.
    pub node: usize,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub obstacle: Option<usize>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bound: Option<usize>,
    /// N, on the rod (the multiplier times the constraint's unit gradient).
    pub force: [f64; 3],
    /// Distance of the rod's surface from the obstacle (of the node from the bound), m.
    pub gap: f64,
}

/// First-order optimality (KKT) of the constrained equilibrium, with the last step QP's
/// multipliers z and the constraints c(x) ≥ 0 at the final state.
#[derive(Debug, Clone, Serialize)]
pub struct KktJson {
    /// Largest constraint violation max(0, −c), m.
    pub primal_feasibility: f64,
    /// The same over the length scale.
    pub primal_feasibility_relative: f64,
    /// Largest |z·c|, J.
    pub complementarity: f64,
    /// The same over force scale × length scale.
    pub complementarity_relative: f64,
    /// Smallest multiplier, N (non-negative at a KKT point).
    pub min_multiplier: f64,
    /// Largest component of ∇E − Jᵀz relative to the force (moment) scale, as `residual`.
    pub stationarity: f64,
    /// Constraints whose force exceeds tolerance × force scale.
    pub active_set: usize,
    pub constraints: usize,
    pub qp_solves: usize,
    /// QPs that stopped short of full accuracy (their steps still passed the line search).
    pub inexact_qps: usize,
    /// QPs refined to the exact solution on their active set.
    pub polished_qps: usize,
    /// Newton steps that needed no QP (the unconstrained step was feasible).
    pub steps_without_qp: usize,
    pub qp_iterations: usize,
    pub qp_seconds: f64,
}

#[derive(Debug, Clone, Serialize)]
pub struct Results {
    pub converged: bool,
    pub iterations: usize,
    pub load_steps: usize,
    pub residual: f64,
    pub seconds: f64,
    pub energy: EnergyJson,
    pub rods: Vec<RodJson>,
    pub joints: Vec<JointJson>,
    pub reactions: Vec<ReactionJson>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub target: Option<TargetJson>,
    /// Scenes with a `reference` only (filled in by [`crate::job::solve_scene`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reference: Option<ReferenceJson>,
    pub solver: SolverJson,
    /// Scenes with obstacles or bounds only.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub contacts: Option<Vec<ContactJson>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub kkt: Option<KktJson>,
}

fn node_pos(q: &[f64], n: usize) -> [f64; 3] {
    [q[3 * n], q[3 * n + 1], q[3 * n + 2]]
}

impl Results {
    pub fn collect(net: &Network, report: &NewtonReport, target: Option<&Target>) -> Results {
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
        let bending = crate::io::stress::all_vertex_bending(net);
        let rods = net
            .rods
            .iter()
            .zip(energies)
            .zip(bending)
            .map(|((r, energy), bend)| {
                let points: Vec<[f64; 3]> = r.nodes.iter().map(|&n| node_pos(q, n)).collect();
                let twist = r.edges.iter().map(|&e| q[3 * net.n_nodes + e]).collect();
                let length = r
                    .edges
                    .iter()
                    .map(|&e| {
                        let [a, b] = m.edge_nodes[e];
                        norm(sub(node_pos(q, b), node_pos(q, a)))
                    })
                    .sum();
                let bending_stress: Vec<f64> = bend.iter().map(|b| b.2).collect();
                RodJson {
                    name: r.name.clone(),
                    points,
                    twist,
                    max_bending_stress: bending_stress.iter().copied().fold(0.0, f64::max),
                    bending_stress,
                    energy,
                    length,
                }
            })
            .collect();
        let joints = net
            .joints
            .iter()
            .map(|j| JointJson {
                name: j.name.clone(),
                position: node_pos(q, j.node),
            })
            .collect();
        let reactions = net
            .supports
            .iter()
            .map(|s| {
                let n = s.node;
                let force = [full[3 * n], full[3 * n + 1], full[3 * n + 2]];
                let moment = match s.frame.and_then(|f| m.frame_var(f)) {
                    Some(v) => [full[v], full[v + 1], full[v + 2]],
                    None => [0.0; 3],
                };
                ReactionJson {
                    rod: s.rod.clone(),
                    vertex: s.vertex,
                    force,
                    moment,
                }
            })
            .collect();
        let target = target.map(|t| sphere_metrics(net, t));
        let (contacts, kkt) = match &m.contact {
            Some(c) => {
                // A scene whose constrained nodes are all supported has no rows and no QP.
                let none = ConstraintReport::default();
                let cr = report.constraints.as_ref().unwrap_or(&none);
                let (contacts, kkt) = constraint_results(net, c, cr, &grad, report.tolerance);
                (Some(contacts), Some(kkt))
            }
            None => (None, None),
        };
        Results {
            converged: report.converged,
            iterations: report.iterations,
            load_steps: report.load_steps,
            residual: report.residual,
            seconds: report.seconds,
            energy: m.energy_parts().into(),
            rods,
            joints,
            reactions,
            target,
            reference: None,
            solver: SolverJson {
                factorizations: report.factorizations,
                regularized_iterations: report.regularized_iterations,
                saddle_escapes: report.saddle_escapes,
                stable: report.stable,
                factor_seconds: report.factor_seconds,
                free_unknowns: m.n_free,
                step_iterations: report.step_iterations.clone(),
                message: report.message.clone(),
            },
            contacts,
            kkt,
        }
    }

    /// Whether every number is finite. JSON has no NaN (serde_json would write `null`), so
    /// results with a non-finite number are never written.
    pub fn all_finite(&self) -> bool {
        let e = &self.energy;
        let fin = |v: &f64| v.is_finite();
        [
            self.residual,
            self.seconds,
            e.total,
            e.stretch,
            e.bend,
            e.twist,
            e.joints,
            e.external,
        ]
        .iter()
        .all(fin)
            && self.rods.iter().all(|r| {
                let re = &r.energy;
                r.points.iter().flatten().all(fin)
                    && r.twist.iter().all(fin)
                    && r.bending_stress.iter().all(fin)
                    && [r.max_bending_stress, r.length, re.total, re.stretch]
                        .iter()
                        .chain(&[re.bend, re.twist])
                        .all(fin)
            })
            && self.joints.iter().all(|j| j.position.iter().all(fin))
            && self
                .reactions
                .iter()
                .all(|r| r.force.iter().chain(&r.moment).all(fin))
            && self.target.as_ref().is_none_or(|t| {
                [
                    t.max_abs_radial_deviation,
                    t.rms_radial_deviation,
                    t.apex_height,
                ]
                .iter()
                .all(fin)
            })
            && self.reference.as_ref().is_none_or(|r| r.error.is_finite())
            && self
                .contacts
                .iter()
                .flatten()
                .all(|c| c.force.iter().all(fin) && c.gap.is_finite())
    }
}

/// Active constraint forces and the KKT measures at the final state.
fn constraint_results(
    net: &Network,
    contact: &Contact,
    cr: &ConstraintReport,
    grad: &[f64],
    tolerance: f64,
) -> (Vec<ContactJson>, KktJson) {
    let m = &net.model;
    let q = &m.state.q;
    let z = &cr.multipliers;
    let mut owner = vec![None; net.n_nodes];
    for (r, rod) in net.rods.iter().enumerate() {
        for (k, &n) in rod.nodes.iter().enumerate() {
            owner[n].get_or_insert((r, k));
        }
    }
    let (f, l) = (m.force_scale, m.length_scale);
    let mut stationarity = grad.to_vec();
    let mut contacts = Vec::new();
    let (mut violation, mut compl, mut zmin): (f64, f64, f64) = (0.0, 0.0, f64::INFINITY);
    for (j, row) in contact.rows.iter().enumerate() {
        let (c, g) = row.at(contact, q);
        for k in 0..3 {
            let v = m.free[3 * row.node + k];
            if v != FIXED {
                stationarity[v as usize] -= z[j] * g[k];
            }
        }
        violation = violation.max(-c);
        compl = compl.max((z[j] * c).abs());
        zmin = zmin.min(z[j]);
        if z[j] > tolerance * f {
            let (r, k) = owner[row.node].expect("constraint on a rod node");
            let (obstacle, bound) = match row.source {
                Source::Obstacle(i) => (Some(i), None),
                Source::Bound(i) => (None, Some(i)),
            };
            contacts.push(ContactJson {
                rod: net.rods[r].name.clone(),
                node: k,
                obstacle,
                bound,
                force: scalef(g, z[j]),
                gap: c,
            });
        }
    }
    let kkt = KktJson {
        primal_feasibility: violation,
        primal_feasibility_relative: violation / l,
        complementarity: compl,
        complementarity_relative: compl / (f * l),
        min_multiplier: if z.is_empty() { 0.0 } else { zmin },
        stationarity: m.relative_residual(&stationarity),
        active_set: contacts.len(),
        constraints: contact.len(),
        qp_solves: cr.qp_solves,
        steps_without_qp: cr.steps_without_qp,
        polished_qps: cr.polished_qps,
        inexact_qps: cr.inexact_qps,
        qp_iterations: cr.qp_iterations,
        qp_seconds: cr.qp_seconds,
    };
    (contacts, kkt)
}

/// Sphere deviations over the joint positions (all rod nodes when there are no joints),
/// relative to R; apex height = highest node above the centre over R.
fn sphere_metrics(net: &Network, t: &Target) -> TargetJson {
    let Target::Sphere { center, radius } = t;
    let q = &net.model.state.q;
    let nodes: Vec<usize> = if net.joints.is_empty() {
        (0..net.n_nodes).collect()
    } else {
        net.joints.iter().map(|j| j.node).collect()
    };
    let mut max: f64 = 0.0;
    let mut sum2 = 0.0;
    for &n in &nodes {
        let d = (norm(sub(node_pos(q, n), *center)) - radius) / radius;
        max = max.max(d.abs());
        sum2 += d * d;
    }
    let apex = (0..net.n_nodes)
        .map(|n| node_pos(q, n)[2] - center[2])
        .fold(f64::NEG_INFINITY, f64::max)
        / radius;
    TargetJson {
        shape: "sphere".into(),
        max_abs_radial_deviation: max,
        rms_radial_deviation: (sum2 / nodes.len().max(1) as f64).sqrt(),
        apex_height: apex,
        max_net_distance: None,
        rms_net_distance: None,
    }
}
