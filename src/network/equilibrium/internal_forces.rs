//! Internal forces per edge (docs/internal-forces.md): the force and moment that the part of a
//! rod beyond a cut through an edge (higher node indices) exerts on the part before it, in the
//! edge's material frame (m1, m2, t), and the utilization of the section when the material has a
//! yield strength.
//!
//! They are read off the energy terms, not from constitutive formulas, so that they satisfy the
//! discrete statics exactly (to the solve's tolerance):
//! - the force in edge e is the gradient of the energy with respect to the edge vector,
//!   F = ∂E/∂e. Moving every node after the cut by δ changes e alone among the terms' edge
//!   vectors, so equilibrium of that part gives F = Σ (loads and reactions beyond the cut). The
//!   bending and twisting terms see e only through its unit tangent, so F·t is the stretch term's
//!   EA (|e|/|ē| − 1) and the bending terms give the shear;
//! - the moment about an end vertex is the energy's derivative with respect to a rigid turn δφ
//!   of one side about it: the edge vector turns by δφ × e and its angle by δφ·t, which only the
//!   stencils at that vertex feel, so M = e × ∂E/∂e + (∂E/∂θ) t summed over them. At the start
//!   vertex the side turned is the one after the cut (M_a = +that sum); at the end vertex it is
//!   the one before (M_b = −that sum).
//!
//! Turning an edge at fixed θ turns its material frame by the perpendicular part of δφ only
//! when its reference tangent is the current one, so the terms are evaluated on a copy of the
//! state whose edge references are transported to the current tangents (as `Model::commit`
//! does; the angles keep their meaning).

use crate::energy::Term;
use crate::math::dual::D1;
use crate::math::vec::{add, cross, dot, norm, normalize, scalef, sub, transport};
use crate::network::Network;
use crate::rod::frames::edge_frame_of;
use crate::rod::section::Section;
use crate::variables::State;

/// Internal force and moment of one edge, in its material frame.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct EdgeForces {
    /// F·t, N, tension positive (= EA (|e|/|ē| − 1)).
    pub axial: f64,
    /// (F·m1, F·m2), N.
    pub shear: [f64; 2],
    /// (M·m1, M·m2) at the edge's midpoint, N·m: the mean of the two end-vertex moments.
    pub moment: [f64; 2],
    /// M·t, N·m (the same at both ends and the midpoint).
    pub torsion: f64,
    /// (M·m1, M·m2) about the start and the end vertex, N·m.
    pub end_moments: [[f64; 2]; 2],
    /// Largest von Mises stress over the two end sections (docs/internal-forces.md), Pa.
    pub von_mises: f64,
    /// `von_mises` over the material's yield strength, when it has one.
    pub utilization: Option<f64>,
}

/// Cut-force sums of one global edge.
#[derive(Clone, Copy, Default)]
struct Cut {
    /// ∂E/∂e over every term, N.
    force: [f64; 3],
    /// Σ e × ∂E/∂e + (∂E/∂θ) t over the stencils at the start vertex, and at the end vertex.
    turn: [[f64; 3]; 2],
}

impl Cut {
    /// Adds one term's gradient with respect to the edge vector `e` (in the rod's direction)
    /// and the edge's angle, the term sitting at the edge's start (`end` 0) or end (1) vertex.
    fn add(&mut self, e: [f64; 3], grad_e: [f64; 3], grad_theta: f64, end: usize) {
        self.force = add(self.force, grad_e);
        let t = normalize(e);
        let turn = add(cross(e, grad_e), scalef(t, grad_theta));
        self.turn[end] = add(self.turn[end], turn);
    }
}

/// A term's gradient at the state `st` (first derivatives only: the Hessian is not needed).
fn gradient<const N: usize, E: Term<N>>(t: &E, st: &State) -> [f64; N] {
    t.eval(st, &D1::<N>::vars(&t.gather(&st.q))).g
}

fn slice3(g: &[f64], i: usize) -> [f64; 3] {
    [g[i], g[i + 1], g[i + 2]]
}

/// The state with every edge's reference tangent moved to its current tangent.
fn with_current_references(net: &Network) -> State {
    let m = &net.model;
    let mut st = m.state.clone();
    for (e, &[a, b]) in m.edge_nodes.iter().enumerate() {
        let t = normalize(sub(m.position(b), m.position(a)));
        let r = &mut st.edges[e];
        r.u = normalize(transport(r.t, t, r.u));
        r.t = t;
    }
    st
}

/// Cut sums of every global edge.
fn cuts(net: &Network) -> Vec<Cut> {
    let m = &net.model;
    let st = with_current_references(net);
    let mut cuts = vec![Cut::default(); m.edge_nodes.len()];
    for s in &m.terms.stretch {
        let g = gradient(s, &st);
        // ∂E/∂x_b = ∂E/∂e; a stretch term turns nothing.
        let f = slice3(&g, 3);
        cuts[s.edge].force = add(cuts[s.edge].force, f);
    }
    // Vertex stencils (x_prev, x_vertex, x_next, θ_in, θ_out): edge 0 arrives at the vertex
    // along the stencil, edge 1 leaves it; a rod edge against the stencil has sign −1.
    let mut stencil = |vars: &[usize; 11], edges: [usize; 2], signs: [f64; 2], g: [f64; 11]| {
        let x = |i: usize| slice3(&st.q, vars[i]);
        let along = [sub(x(3), x(0)), sub(x(6), x(3))];
        let grad_along = [scalef(slice3(&g, 0), -1.0), slice3(&g, 6)];
        for j in 0..2 {
            let s = signs[j];
            // The vertex is the rod edge's start when the edge leaves it in the rod's direction.
            let at_start = (j == 1) == (s > 0.0);
            cuts[edges[j]].add(
                scalef(along[j], s),
                scalef(grad_along[j], s),
                g[9 + j],
                usize::from(!at_start),
            );
        }
    };
    for s in &m.terms.bend_twist {
        let b = &s.bend;
        stencil(&b.vars, b.edges, b.signs, gradient(s, &st));
    }
    // Half-stencils (x_vertex, x_other, θ, ω, α): sign +1 when the rod edge leaves the vertex.
    let mut half = |vars: &[usize; 11], edge: usize, sign: f64, g: [f64; 11]| {
        let along = sub(slice3(&st.q, vars[3]), slice3(&st.q, vars[0]));
        let end = usize::from(sign < 0.0);
        cuts[edge].add(scalef(along, sign), scalef(slice3(&g, 3), sign), g[6], end);
    };
    for f in &m.terms.frame_bend_twist {
        let b = &f.bend;
        half(&b.vars, b.edge, b.sign, gradient(f, &st));
    }
    cuts
}

/// Largest von Mises stress over a section carrying axial force `n`, bending moment
/// (M·m1, M·m2) = `moment` and torsion `torsion`: √(σ² + 3τ²) with σ the largest normal stress
/// and τ the largest torsional shear stress over the section (exact for a circle, where both
/// peak on the whole rim; an upper bound for the other sections).
pub fn von_mises(section: &Section, n: f64, moment: [f64; 2], torsion: f64) -> f64 {
    let sigma = section.max_normal_stress(n, moment);
    let tau = section.max_torsion_stress(torsion);
    (sigma * sigma + 3.0 * tau * tau).sqrt()
}

/// Internal forces of every edge of every rod, indexed like `net.rods`.
pub fn all_edge_forces(net: &Network) -> Vec<Vec<EdgeForces>> {
    let m = &net.model;
    let cuts = cuts(net);
    net.rods
        .iter()
        .map(|rod| {
            rod.edges
                .iter()
                .map(|&e| {
                    let [a, b] = m.edge_nodes[e];
                    let vec = sub(m.position(b), m.position(a));
                    let f = edge_frame_of(vec, m.state.q[m.layout.theta(e)], &m.state.edges[e]);
                    let c = &cuts[e];
                    let ends = [c.turn[0], scalef(c.turn[1], -1.0)];
                    let mid = scalef(add(ends[0], ends[1]), 0.5);
                    // `+ 0.0` turns −0 into 0 so that exact zeros print as such.
                    let comps = |v: [f64; 3]| [dot(v, f.m1) + 0.0, dot(v, f.m2) + 0.0];
                    let s = &net.model.terms.stretch[e];
                    let axial = s.ea * (norm(vec) / s.rest_length - 1.0);
                    let torsion = dot(mid, f.t) + 0.0;
                    let end_moments = ends.map(comps);
                    let von_mises = end_moments
                        .iter()
                        .map(|&mo| von_mises(&rod.section, axial, mo, torsion))
                        .fold(0.0, f64::max);
                    EdgeForces {
                        axial,
                        shear: comps(c.force),
                        moment: comps(mid),
                        torsion,
                        end_moments,
                        von_mises,
                        utilization: rod.yield_strength.map(|y| von_mises / y),
                    }
                })
                .collect()
        })
        .collect()
}
