//! Elastic energy per rod: every term that knows its edge ([`Term::edge`]) is attributed to that
//! edge's rod, by category.

use serde::{Deserialize, Serialize};

use crate::energy::registry::TermVisitor;
use crate::energy::{Category, Term};
use crate::network::Network;
use crate::variables::State;

/// Stretching, bending and twisting energy stored in one rod, J. Bending and twisting include
/// the terms that couple the rod to a joint or clamp frame at its vertices.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct RodEnergy {
    pub total: f64,
    pub stretch: f64,
    pub bend: f64,
    pub twist: f64,
}

pub fn per_rod(net: &Network) -> Vec<RodEnergy> {
    let m = &net.model;
    let mut rod_of_edge = vec![usize::MAX; m.edge_nodes.len()];
    for (r, info) in net.rods.iter().enumerate() {
        for &e in &info.edges {
            rod_of_edge[e] = r;
        }
    }
    let mut by_rod = ByRod {
        st: &m.state,
        rod_of_edge,
        out: vec![RodEnergy::default(); net.rods.len()],
    };
    m.terms.visit(&mut by_rod);
    let mut out = by_rod.out;
    for r in &mut out {
        r.total = r.stretch + r.bend + r.twist;
    }
    out
}

struct ByRod<'a> {
    st: &'a State,
    rod_of_edge: Vec<usize>,
    out: Vec<RodEnergy>,
}

impl TermVisitor for ByRod<'_> {
    fn visit<const N: usize, E: Term<N>>(&mut self, _: usize, terms: &[E]) {
        for t in terms {
            let Some(e) = t.edge() else { continue };
            let Some(r) = self.out.get_mut(self.rod_of_edge[e]) else {
                continue;
            };
            let mut e = [0.0; 2];
            t.energies_by_category(self.st, &mut e[..E::CATEGORIES.len()]);
            for (c, e) in E::CATEGORIES.iter().zip(e) {
                match c {
                    Category::Stretch => r.stretch += e,
                    Category::Bend => r.bend += e,
                    Category::Twist => r.twist += e,
                    Category::Joints | Category::Supports | Category::External => {}
                }
            }
        }
    }
}
