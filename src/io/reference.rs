//! The scene's `reference` (a known equilibrium position of one input vertex) against the
//! computed equilibrium.

use serde::Serialize;

use crate::math::vec::{norm, sub};
use crate::network::build::Network;
use crate::scene::types::Reference;
use crate::scene::Scene;

/// The `reference` block of the results JSON.
#[derive(Debug, Clone, Serialize)]
pub struct ReferenceJson {
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

/// Position of input vertex `vertex` of rod `rod` in the current state of `net`.
pub fn vertex_position(net: &Network, rod: &str, vertex: usize) -> Option<[f64; 3]> {
    let r = net.rods.iter().find(|r| r.name == rod)?;
    let n = *r.nodes.get(vertex * r.subdivide)?;
    let q = &net.model.state.q;
    Some([q[3 * n], q[3 * n + 1], q[3 * n + 2]])
}

/// The reference's rest position in `scene`.
fn rest_position(scene: &Scene, r: &Reference) -> Option<[f64; 3]> {
    let rod = scene.rods.iter().find(|x| x.name == r.rod)?;
    rod.points.get(r.vertex).copied()
}

/// Compares the equilibrium in `net` (built from `scene`) with the scene's reference. `None`
/// when the scene has none (validation guarantees that the vertex exists).
pub fn measure(net: &Network, scene: &Scene) -> Option<ReferenceJson> {
    let r = scene.reference.as_ref()?;
    let computed = vertex_position(net, &r.rod, r.vertex)?;
    let rest = rest_position(scene, r)?;
    let error = norm(sub(computed, r.position)) / norm(sub(r.position, rest));
    Some(ReferenceJson {
        rod: r.rod.clone(),
        vertex: r.vertex,
        position: r.position,
        computed,
        error,
    })
}
