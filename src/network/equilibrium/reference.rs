//! The scene's `reference` (a known equilibrium position of one input vertex) against the
//! computed equilibrium.

use serde::{Deserialize, Serialize};

use crate::math::vec::{norm, sub};
use crate::network::Network;
use crate::scene::Scene;

/// Also the `reference` block of the results JSON, as it is.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ReferenceCheck {
    pub rod: String,
    pub vertex: usize,
    /// The scene's reference position, m.
    pub position: [f64; 3],
    /// The vertex's computed position, m.
    pub computed: [f64; 3],
    /// |computed − position| / |position − rest|: the error of the vertex's displacement
    /// relative to the reference displacement.
    pub error: f64,
}

/// `None` when the scene has no reference (validation guarantees that its vertex exists).
pub fn check(net: &Network, scene: &Scene) -> Option<ReferenceCheck> {
    let r = scene.reference.as_ref()?;
    let computed = net.vertex_position(&r.rod, r.vertex)?;
    let rod = scene.rods.iter().find(|x| x.name == r.rod)?;
    let rest = *rod.points.get(r.vertex)?;
    let error = norm(sub(computed, r.position)) / norm(sub(r.position, rest));
    Some(ReferenceCheck {
        rod: r.rod.clone(),
        vertex: r.vertex,
        position: r.position,
        computed,
        error,
    })
}
