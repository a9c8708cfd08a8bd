//! Elastic energy per rod. The model stores its terms by kind, not by rod, so each term is
//! attributed to a rod through the edge it acts on: this keeps `network/` and `energy/` unaware
//! of the report and costs one pass over the terms.

use std::collections::{HashMap, VecDeque};

use serde::Serialize;

use crate::energy::Term;
use crate::network::build::Network;

/// Stretching, bending and twisting energy stored in one rod, J. Bending and twisting include
/// the terms that couple the rod to a joint or clamp frame at its vertices.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct RodEnergy {
    pub total: f64,
    pub stretch: f64,
    pub bend: f64,
    pub twist: f64,
}

pub fn per_rod(net: &Network) -> Vec<RodEnergy> {
    let m = &net.model;
    let st = &m.state;
    let mut rod_of_edge = vec![usize::MAX; m.edge_nodes.len()];
    for (r, info) in net.rods.iter().enumerate() {
        for &e in &info.edges {
            rod_of_edge[e] = r;
        }
    }
    // A stretch term only knows its two nodes. Two edges can share both nodes (two straight
    // one-edge rods joined at both ends), so each pair keeps a queue of its edges in edge order,
    // which is also the order in which the terms were built.
    let mut edges_of_pair: HashMap<(usize, usize), VecDeque<usize>> = HashMap::new();
    for (e, &[a, b]) in m.edge_nodes.iter().enumerate() {
        edges_of_pair.entry((a, b)).or_default().push_back(e);
    }
    let mut out = vec![RodEnergy::default(); net.rods.len()];
    let mut add = |edge: usize, f: &dyn Fn(&mut RodEnergy)| {
        if let Some(r) = out.get_mut(rod_of_edge[edge]) {
            f(r);
        }
    };
    for t in &m.terms.stretch {
        let v = t.vars();
        let pair = (v[0] / 3, v[3] / 3);
        let e = edges_of_pair.get_mut(&pair).and_then(|q| q.pop_front());
        if let Some(e) = e {
            let x = t.energy(st);
            add(e, &|r| r.stretch += x);
        }
    }
    for t in &m.terms.bend {
        let x = t.energy(st);
        add(t.edges[0], &|r| r.bend += x);
    }
    for t in &m.terms.frame_bend {
        let x = t.energy(st);
        add(t.edge, &|r| r.bend += x);
    }
    for t in &m.terms.twist {
        let x = t.energy(st);
        add(t.edges[0], &|r| r.twist += x);
    }
    for t in &m.terms.frame_twist {
        let x = t.energy(st);
        add(t.edge, &|r| r.twist += x);
    }
    for r in &mut out {
        r.total = r.stretch + r.bend + r.twist;
    }
    out
}
