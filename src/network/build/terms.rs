//! The elastic terms of a network: stretching per edge, bending and twisting stencils at rod
//! vertices and across straight splices, half-stencils between rod edges and vertex frames, and
//! the springs of elastic joints. Rest curvature and twist are measured on the rest state.

use super::end_weights::EndWeights;
use super::frames::Joined;
use super::nodes::Numbered;
use crate::energy::registry::Terms;
use crate::energy::{
    bend::Bend, bend_twist::BendTwist, frame_bend::FrameBend, frame_bend_twist::FrameBendTwist,
    frame_twist::FrameTwist, joint_rotation::JointRotation, joint_translation::JointTranslation,
    stretch::Stretch, twist::Twist, Term,
};
use crate::math::vec::cross;
use crate::network::info::RodInfo;
use crate::rod::section::Stiffness;
use crate::variables::{DofLayout, Port, State};

pub fn elastic(
    net: &Numbered,
    joined: &Joined,
    layout: &DofLayout,
    state: &mut State,
    fixed: &mut [bool],
    weights: &EndWeights,
) -> Terms {
    let mut terms = Terms::default();
    for (e, &[a, b]) in net.edge_nodes.iter().enumerate() {
        let [a0, a1, a2] = layout.node(a);
        let [b0, b1, b2] = layout.node(b);
        terms.stretch.push(Stretch {
            vars: [a0, a1, a2, b0, b1, b2],
            edge: e,
            rest_length: net.rest_lengths[e],
            ea: net.rods[net.edge_rod[e]].stiffness.ea,
        });
    }
    rod_stencils(net, joined, layout, &mut terms, state, weights);
    splice_stencils(net, joined, layout, &mut terms, state);
    twist_gauge(net, joined, layout, &terms, fixed);
    port_stencils(net, joined, layout, &mut terms, state, weights);
    joint_springs(net, joined, layout, &mut terms);
    terms
}

/// A bend-and-twist stencil at a vertex between two edges (oriented along the stencil).
struct Stencil {
    vars: [usize; 11],
    edges: [usize; 2],
    signs: [f64; 2],
    lengths: [f64; 2],
    stiffness: [Stiffness; 2],
    /// The bending quadrature's weight over the Voronoi length (the end correction).
    bend_weight: f64,
}

/// Local variables of a vertex stencil: (x_prev, x_vertex, x_next, θ_in, θ_out).
fn stencil_vars(layout: &DofLayout, nodes: [usize; 3], edges: [usize; 2]) -> [usize; 11] {
    let [a, b, c] = nodes.map(|n| layout.node(n));
    [
        a[0],
        a[1],
        a[2],
        b[0],
        b[1],
        b[2],
        c[0],
        c[1],
        c[2],
        layout.theta(edges[0]),
        layout.theta(edges[1]),
    ]
}

impl Stencil {
    /// Adds the bend and twist terms with their rest curvature and twist from the current
    /// (rest) state.
    fn push(&self, terms: &mut Terms, state: &mut State) {
        let voronoi = 0.5 * (self.lengths[0] + self.lengths[1]);
        let [k0, k1] = self.stiffness;
        let mut bend = Bend {
            vars: self.vars,
            edges: self.edges,
            signs: self.signs,
            rest: [[0.0; 2]; 2],
            voronoi: voronoi * self.bend_weight,
            ei: [[k0.ei1, k0.ei2], [k1.ei1, k1.ei2]],
        };
        let y = Twist::reduced(&bend.gather(&state.q));
        bend.rest = bend.curvatures::<f64>(state, &y);
        let slot = state.twist_prev.len();
        state.twist_prev.push(0.0);
        // Twist compliance in series over the two half-edges.
        let gj = voronoi / (0.5 * self.lengths[0] / k0.gj + 0.5 * self.lengths[1] / k1.gj);
        let mut tw = Twist {
            vars: self.vars,
            edges: self.edges,
            signs: self.signs,
            slot,
            rest: 0.0,
            voronoi,
            gj,
        };
        state.twist_prev[slot] = tw.reference_twist::<f64>(state, &y);
        tw.rest = tw.twist::<f64>(state, &y);
        terms.bend_twist.push(BendTwist::new(bend, tw));
    }
}

/// Stencils at every inner vertex of every rod that is not at a vertex frame.
fn rod_stencils(
    net: &Numbered,
    joined: &Joined,
    layout: &DofLayout,
    terms: &mut Terms,
    state: &mut State,
    weights: &EndWeights,
) {
    for (ri, rod) in net.rods.iter().enumerate() {
        let (np, k) = (rod.nodes.len(), rod.stiffness);
        let inner = if rod.closed { 0..np } else { 1..np - 1 };
        for j in inner {
            if joined.table.port_of.contains_key(&(ri, j)) {
                continue;
            }
            let (ei, eo) = (rod.edges[(j + np - 1) % np], rod.edges[j % rod.edges.len()]);
            let nodes = [
                rod.nodes[(j + np - 1) % np],
                rod.nodes[j],
                rod.nodes[(j + 1) % np],
            ];
            let stencil = Stencil {
                vars: stencil_vars(layout, nodes, [ei, eo]),
                edges: [ei, eo],
                signs: [1.0, 1.0],
                lengths: [net.rest_lengths[ei], net.rest_lengths[eo]],
                stiffness: [k, k],
                bend_weight: weights.vertex(ri, j),
            };
            stencil.push(terms, state);
        }
    }
}

/// The edge of `rod` at its end node `n`, the node next to it, and the edge's sign when the
/// stencil runs into the joint (`arriving`) or out of it.
fn end_edge(rod: &RodInfo, n: usize, arriving: bool) -> (usize, usize, f64) {
    let (e, other, leaves) = if n == 0 {
        (rod.edges[0], rod.nodes[1], true)
    } else {
        (rod.edges[n - 1], rod.nodes[n - 1], false)
    };
    // The stencil runs a → joint → b: rod a's edge arrives, rod b's leaves.
    let along = if arriving { !leaves } else { leaves };
    (e, other, if along { 1.0 } else { -1.0 })
}

/// One continuous stencil across each straight rigid joint of two rod ends.
fn splice_stencils(
    net: &Numbered,
    joined: &Joined,
    layout: &DofLayout,
    terms: &mut Terms,
    state: &mut State,
) {
    for &[(ra, na), (rb, nb)] in &joined.splices {
        let (rod_a, rod_b) = (&net.rods[ra], &net.rods[rb]);
        let (ea, other_a, sa) = end_edge(rod_a, na, true);
        let (eb, other_b, sb) = end_edge(rod_b, nb, false);
        let stencil = Stencil {
            vars: stencil_vars(layout, [other_a, rod_a.nodes[na], other_b], [ea, eb]),
            edges: [ea, eb],
            signs: [sa, sb],
            lengths: [net.rest_lengths[ea], net.rest_lengths[eb]],
            stiffness: [rod_a.stiffness, rod_b.stiffness],
            bend_weight: 1.0,
        };
        stencil.push(terms, state);
    }
}

/// Twist gauge: an isotropic rod that is straight at rest, touches no vertex frame and is not
/// spliced to another rod has an energy that depends on its edge angles only through their
/// differences (|κb| does not see θ when EI₁ = EI₂ and κ̄ = 0), so turning all of them together
/// is a zero-energy mode. Fixing the first edge's angle removes it without changing any
/// equilibrium, and keeps the Hessian positive definite instead of singular.
fn twist_gauge(
    net: &Numbered,
    joined: &Joined,
    layout: &DofLayout,
    terms: &Terms,
    fixed: &mut [bool],
) {
    let mut no_gauge = vec![false; net.rods.len()];
    for s in &joined.splices {
        no_gauge[s[0].0] = true;
        no_gauge[s[1].0] = true;
    }
    for p in &joined.table.ports {
        no_gauge[p.rod] = true;
    }
    for b in terms.bend_twist.iter().map(|s| &s.bend) {
        if b.rest.iter().flatten().any(|v| v.abs() >= 1e-12) {
            no_gauge[net.edge_rod[b.edges[0]]] = true;
        }
    }
    for (ri, rod) in net.rods.iter().enumerate() {
        if rod.stiffness.ei1 == rod.stiffness.ei2 && !no_gauge[ri] {
            fixed[layout.theta(rod.edges[0])] = true;
        }
    }
}

/// Half-stencils of bending and twisting between each port's frame and the rod edges at its
/// vertex.
fn port_stencils(
    net: &Numbered,
    joined: &Joined,
    layout: &DofLayout,
    terms: &mut Terms,
    state: &mut State,
    weights: &EndWeights,
) {
    for (pi, p) in joined.table.ports.iter().enumerate() {
        let rod = &net.rods[p.rod];
        let (np, k, j) = (rod.nodes.len(), rod.stiffness, p.node);
        let mut incident = Vec::new();
        if rod.closed || j > 0 {
            incident.push((rod.edges[(j + np - 1) % np], (j + np - 1) % np, -1.0));
        }
        if rod.closed || j + 1 < np {
            incident.push((rod.edges[j % rod.edges.len()], (j + 1) % np, 1.0));
        }
        let [f0, f1, f2] = layout.frame(p.frame);
        let alpha = p.alpha.map_or(layout.zero(), |a| layout.alpha(a));
        for (e, other, sign) in incident {
            // Each half-stencil is attached along its own edge (the edge's rest frame, in the
            // rod's direction), so its rest curvature and twist vanish and the frame transmits
            // the full rod stiffness; the port's vertex frame only orients hinge axes and
            // elastic springs.
            let r = state.edges[e];
            let port = Port {
                frame: p.frame,
                rest: [r.u, cross(r.t, r.u), r.t],
                hinge_axis: p.hinge_axis,
            };
            let [a0, a1, a2] = layout.node(rod.nodes[j]);
            let [b0, b1, b2] = layout.node(rod.nodes[other]);
            let vars = [a0, a1, a2, b0, b1, b2, layout.theta(e), f0, f1, f2, alpha];
            let voronoi = 0.5 * net.rest_lengths[e];
            let mut bend = FrameBend {
                vars,
                port,
                edge: e,
                sign,
                rest: [[0.0; 2]; 2],
                voronoi: voronoi * weights.port(pi, e),
                ei: [k.ei1, k.ei2],
            };
            let y = FrameTwist::reduced(&bend.gather(&state.q));
            bend.rest = bend.curvatures::<f64>(state, &y);
            let slot = state.twist_prev.len();
            state.twist_prev.push(0.0);
            let mut tw = FrameTwist {
                vars,
                port,
                edge: e,
                sign,
                slot,
                rest: 0.0,
                voronoi,
                gj: k.gj,
            };
            state.twist_prev[slot] = tw.reference_twist::<f64>(state, &y);
            tw.rest = tw.twist::<f64>(state, &y);
            terms.frame_bend_twist.push(FrameBendTwist::new(bend, tw));
        }
    }
}

/// Rotational springs between port frames and joint frames, translational springs between rod
/// nodes and joint centres (elastic joints).
fn joint_springs(net: &Numbered, joined: &Joined, layout: &DofLayout, terms: &mut Terms) {
    let table = &joined.table;
    for c in &table.couplings {
        let p = &table.ports[c.port];
        let [p0, p1, p2] = layout.frame(p.frame);
        let [j0, j1, j2] = layout.frame(c.joint_frame);
        terms.joint_rotation.push(JointRotation {
            vars: [p0, p1, p2, j0, j1, j2],
            port_frame: p.frame,
            joint_frame: c.joint_frame,
            rest: p.rest,
            axes: c.axes,
            stiffness: c.stiffness,
        });
    }
    for a in &table.anchors {
        let [a0, a1, a2] = layout.node(net.rods[a.rod].nodes[a.node]);
        let [b0, b1, b2] = layout.node(net.first_center + a.center);
        terms.joint_translation.push(JointTranslation {
            vars: [a0, a1, a2, b0, b1, b2],
            stiffness: a.stiffness,
        });
    }
}
