//! A network of rods: built from a scene ([`build`]), held as a Newton problem ([`Model`]),
//! assembled ([`assembly`]), lent to the solver ([`problem`]), and measured at equilibrium
//! ([`equilibrium`]).

pub mod active_set;
pub mod assembly;
pub mod budget;
pub mod build;
pub mod contact;
pub mod drag;
pub mod equilibrium;
pub mod floor;
pub mod indent;
pub mod info;
pub mod initial;
pub mod joint;
pub mod mechanism;
pub mod model;
pub mod nonconservative;
pub mod path_check;
pub mod positions;
pub mod problem;
pub mod projection;
pub mod rest;
pub mod roller;
pub mod scratch;
pub mod stability;
pub mod stage;
pub mod states;
pub mod support;
pub mod symmetry_break;
pub mod zero_stiffness;

pub use build::build;
pub use info::{Gauge, JointInfo, RodInfo, SupportInfo};
pub use model::Model;
pub use problem::{solve, NetworkProblem};
pub use symmetry_break::solve_toward;

/// A built network: the Newton model plus what the results need to name things.
#[derive(Debug, Clone)]
pub struct Network {
    pub model: Model,
    pub rods: Vec<RodInfo>,
    pub supports: Vec<SupportInfo>,
    pub joints: Vec<JointInfo>,
    /// Unsupported structures only (`build/gauge.rs`).
    pub gauge: Option<Gauge>,
}

impl Network {
    pub fn n_nodes(&self) -> usize {
        self.model.layout.n_nodes()
    }

    /// Unit tangents of rod `r`'s edges, in order, at the current state.
    pub fn rod_tangents(&self, r: &RodInfo) -> Vec<[f64; 3]> {
        let m = &self.model;
        r.edges
            .iter()
            .map(|&e| {
                let [a, b] = m.edge_nodes[e];
                crate::math::vec::normalize(crate::math::vec::sub(m.position(b), m.position(a)))
            })
            .collect()
    }

    /// The rod named `name`.
    pub fn rod(&self, name: &str) -> Option<&RodInfo> {
        self.rods.iter().find(|r| r.name == name)
    }

    /// Current position of input vertex `vertex` of rod `rod`.
    pub fn vertex_position(&self, rod: &str, vertex: usize) -> Option<[f64; 3]> {
        let n = self.rod(rod)?.vertex_node(vertex)?;
        Some(self.model.world_position(n))
    }
}
