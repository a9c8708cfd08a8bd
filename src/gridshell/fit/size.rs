//! How large a net a spacing asks for, checked before anything of the net is built: a spacing
//! far below the mesh's size would otherwise allocate (or step through) a construction grid of
//! (size/spacing)² nodes before any node limit is reached (issue 39).

use super::compass::Node;
use crate::network::budget::{bytes_text, MIN_BYTES_PER_NODE};
use crate::scene::validate::MAX_NODES;
use crate::surface::Surface;

/// Largest construction grid, nodes: the finer construction has (2m)² = 64 grid nodes per net
/// cell where the scene has 2K, and its rectangle covers more than the surface; this bounds it
/// for every `subdivide` (2 GiB of grid at the scene node limit).
pub const MAX_GRID_NODES: usize = 32 * MAX_NODES;

/// Scene nodes of a net with spacing `a` covering the surface, about: each crossing starts one
/// segment of `subdivide` edges on each of its two rods, and a cell (a rhombus of side a)
/// covers at most a² of the surface. Saturates to infinity, never overflows.
pub fn estimated_nodes(s: &Surface, a: f64, subdivide: usize) -> f64 {
    2.0 * subdivide as f64 * s.area() / (a * a)
}

/// The spacing whose estimated net has `nodes` nodes.
fn spacing_for(s: &Surface, subdivide: usize, nodes: f64) -> f64 {
    (2.0 * subdivide as f64 * s.area() / nodes).sqrt()
}

/// Refuses a spacing whose net would pass the node limit or, by its lower bound, the memory
/// limit (`memory_limit` bytes); otherwise the construction grid's node limit for
/// [`super::net::build`].
pub fn check(s: &Surface, a: f64, subdivide: usize, memory_limit: u64) -> Result<usize, String> {
    let nodes = estimated_nodes(s, a, subdivide);
    if nodes.is_nan() || nodes > MAX_NODES as f64 {
        return Err(format!(
            "--spacing {a} would give a net of about {nodes:.3e} nodes (2 K A / a² on the \
             mesh's {:.4} m², K = --subdivide {subdivide}), above the limit of {MAX_NODES}; \
             the smallest spacing within it is about {:.3e} m",
            s.area(),
            spacing_for(s, subdivide, MAX_NODES as f64)
        ));
    }
    let per_node = (MIN_BYTES_PER_NODE / 2) as f64;
    if nodes * per_node > memory_limit as f64 {
        return Err(format!(
            "--spacing {a} would give a net of about {nodes:.3e} nodes, needing at least {}, \
             above --max-memory {}; the smallest spacing within it is about {:.3e} m",
            bytes_text((nodes * per_node) as u64),
            bytes_text(memory_limit),
            spacing_for(s, subdivide, memory_limit as f64 / per_node)
        ));
    }
    // Both constructions' grids (the coarser a quarter of the finer) within the memory limit.
    let node_bytes = 1.25 * std::mem::size_of::<Node>() as f64;
    Ok(((memory_limit as f64 / node_bytes) as usize).min(MAX_GRID_NODES))
}

/// The refusal of a construction grid of at least `grid` nodes above `max` (the mesh's shape
/// made the net's rectangle much larger than the surface).
pub fn grid_refusal(a: f64, grid: usize, max: usize) -> String {
    let node_bytes = 1.25 * std::mem::size_of::<Node>() as f64;
    format!(
        "--spacing {a}: the net's construction grid would have at least {grid} nodes \
         (about {}), above its limit of {max} nodes (from --max-memory and the node limit); \
         the smallest spacing within it is at least {:.3e} m",
        bytes_text((grid as f64 * node_bytes) as u64),
        a * (grid as f64 / max as f64).sqrt()
    )
}
