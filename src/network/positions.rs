//! Where each free unknown sits in space, for the geometric nested-dissection ordering
//! (`solver::ordering`): a node's coordinates at the node, every other unknown (edge angle,
//! frame rotation, hinge angle) at the centroid of the nodes of the first term that couples it.

use super::model::Model;
use crate::energy::registry::TermVisitor;
use crate::energy::Term;

impl Model {
    pub fn unknown_positions(&self) -> Vec<[f64; 3]> {
        let mut place = Place {
            model: self,
            pos: vec![None; self.n_free],
        };
        self.terms.visit(&mut place);
        // An unknown no term touches has no neighbours; anywhere will do.
        place
            .pos
            .into_iter()
            .map(|p| p.unwrap_or([0.0; 3]))
            .collect()
    }
}

struct Place<'a> {
    model: &'a Model,
    pos: Vec<Option<[f64; 3]>>,
}

impl TermVisitor for Place<'_> {
    fn visit<const N: usize, E: Term<N>>(&mut self, _: usize, terms: &[E]) {
        let m = self.model;
        let unknowns = m.unknowns();
        for term in terms {
            // Centroid of the term's nodes, each counted once per coordinate variable.
            let mut c = [0.0; 3];
            let mut k = 0.0;
            for n in term.vars().iter().filter_map(|&v| m.layout.node_of(v)) {
                let p = m.position(n);
                for a in 0..3 {
                    c[a] += p[a];
                }
                k += 1.0;
            }
            for &v in term.vars() {
                let Some(f) = unknowns.of(v) else { continue };
                if self.pos[f].is_some() {
                    continue;
                }
                self.pos[f] = Some(match m.layout.node_of(v) {
                    Some(n) => m.position(n),
                    None if k > 0.0 => [c[0] / k, c[1] / k, c[2] / k],
                    None => continue,
                });
            }
        }
    }
}
