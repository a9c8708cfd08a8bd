//! Where each free unknown sits in space, for the geometric nested-dissection ordering
//! (`solver::ordering`): a node's coordinates at the node, every other unknown (edge angle,
//! frame rotation, hinge angle) at the centroid of the nodes of the first term that couples it.

use super::model::{Model, VarKind, FIXED};
use crate::energy::Term;

impl Model {
    pub fn unknown_positions(&self) -> Vec<[f64; 3]> {
        let mut pos: Vec<Option<[f64; 3]>> = vec![None; self.n_free];
        let t = &self.terms;
        self.place(&t.stretch, &mut pos);
        self.place(&t.bend, &mut pos);
        self.place(&t.twist, &mut pos);
        self.place(&t.frame_bend, &mut pos);
        self.place(&t.frame_twist, &mut pos);
        self.place(&t.joint_rotation, &mut pos);
        self.place(&t.joint_translation, &mut pos);
        self.place(&t.loads, &mut pos);
        self.place(&t.torques, &mut pos);
        // An unknown no term touches has no neighbours; anywhere will do.
        pos.into_iter().map(|p| p.unwrap_or([0.0; 3])).collect()
    }

    fn place<const N: usize, E: Term<N>>(&self, terms: &[E], pos: &mut [Option<[f64; 3]>]) {
        let q = &self.state.q;
        for term in terms {
            let mut c = [0.0; 3];
            let mut k = 0.0;
            for &v in term.vars() {
                if self.kinds[v] == VarKind::Position {
                    let node = v / 3;
                    for a in 0..3 {
                        c[a] += q[3 * node + a];
                    }
                    k += 1.0;
                }
            }
            for &v in term.vars() {
                let f = self.free[v];
                if f == FIXED || pos[f as usize].is_some() {
                    continue;
                }
                pos[f as usize] = Some(if self.kinds[v] == VarKind::Position {
                    let node = v / 3;
                    [q[3 * node], q[3 * node + 1], q[3 * node + 2]]
                } else if k > 0.0 {
                    [c[0] / k, c[1] / k, c[2] / k]
                } else {
                    continue;
                });
            }
        }
    }
}
