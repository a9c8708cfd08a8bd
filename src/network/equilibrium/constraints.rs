//! Forces of the active constraints (obstacle contacts, coordinate bounds) and the first-order
//! optimality (KKT) of the constrained equilibrium, from the last step QP's multipliers z and
//! the constraints c(x) ≥ 0 at the final state.

use crate::math::vec::scalef;
use crate::network::contact::{Contact, Source};
use crate::network::Network;
use crate::solver::ConstraintReport;

/// The force one active constraint exerts on a node.
#[derive(Debug, Clone)]
pub struct ContactForce {
    pub rod: String,
    /// Index of the node along its rod.
    pub node: usize,
    pub source: Source,
    /// N, on the rod (the multiplier times the constraint's unit gradient).
    pub force: [f64; 3],
    /// Distance of the rod's surface from the obstacle (of the node from the bound), m.
    pub gap: f64,
}

#[derive(Debug, Clone)]
pub struct Kkt {
    /// Largest constraint violation max(0, −c), m.
    pub primal_feasibility: f64,
    pub primal_feasibility_relative: f64,
    /// Largest |z·c|, J.
    pub complementarity: f64,
    pub complementarity_relative: f64,
    /// Smallest multiplier, N (non-negative at a KKT point).
    pub min_multiplier: f64,
    /// Largest component of ∇E − Jᵀz relative to the force (moment) scale.
    pub stationarity: f64,
    pub active_set: usize,
    pub constraints: usize,
    pub report: ConstraintReport,
}

#[derive(Debug, Clone)]
pub struct ConstraintForces {
    pub contacts: Vec<ContactForce>,
    pub kkt: Kkt,
}

/// `grad`: the energy gradient over free unknowns at the final state.
pub fn forces(
    net: &Network,
    contact: &Contact,
    cr: &ConstraintReport,
    grad: &[f64],
    tolerance: f64,
) -> ConstraintForces {
    let m = &net.model;
    let q = &m.state.q;
    let z = &cr.multipliers;
    let mut owner = vec![None; net.n_nodes()];
    for (r, rod) in net.rods.iter().enumerate() {
        for (k, &n) in rod.nodes.iter().enumerate() {
            owner[n].get_or_insert((r, k));
        }
    }
    let (f, l) = (m.force_scale, m.length_scale);
    let unknowns = m.unknowns();
    let mut stationarity = grad.to_vec();
    let mut contacts = Vec::new();
    let (mut violation, mut compl, mut zmin): (f64, f64, f64) = (0.0, 0.0, f64::INFINITY);
    for (j, row) in contact.rows.iter().enumerate() {
        let (c, g) = row.at(contact, q);
        // The gradient is projected where supports hold (slanted rollers), and so is the
        // constraint's pull on the unknowns: the rest is the roller's reaction.
        let jac = row.linearized(contact, q).1;
        for k in 0..3 {
            if let Some(v) = unknowns.of_node(row.node, k) {
                stationarity[v] -= z[j] * jac[k];
            }
        }
        violation = violation.max(-c);
        compl = compl.max((z[j] * c).abs());
        zmin = zmin.min(z[j]);
        if z[j] > tolerance * f {
            let (r, k) = owner[row.node].expect("constraint on a rod node");
            contacts.push(ContactForce {
                rod: net.rods[r].name.clone(),
                node: k,
                source: row.source,
                force: scalef(g, z[j]),
                gap: c,
            });
        }
    }
    let kkt = Kkt {
        primal_feasibility: violation,
        primal_feasibility_relative: violation / l,
        complementarity: compl,
        complementarity_relative: compl / (f * l),
        min_multiplier: if z.is_empty() { 0.0 } else { zmin },
        stationarity: m.relative_residual(&stationarity),
        active_set: contacts.len(),
        constraints: contact.len(),
        report: cr.clone(),
    };
    ConstraintForces { contacts, kkt }
}

/// The constraints' total force on each node they press (the multipliers times the gradients).
pub fn node_forces(
    contact: &Contact,
    cr: &ConstraintReport,
    q: &[f64],
) -> std::collections::HashMap<usize, [f64; 3]> {
    let mut out = std::collections::HashMap::new();
    for (row, &z) in contact.rows.iter().zip(&cr.multipliers) {
        if z != 0.0 {
            let g = row.at(contact, q).1;
            let f: &mut [f64; 3] = out.entry(row.node).or_insert([0.0; 3]);
            (0..3).for_each(|k| f[k] += z * g[k]);
        }
    }
    out
}
