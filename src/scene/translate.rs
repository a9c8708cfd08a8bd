//! Scenes far from the origin: the origin of the coordinates a network is solved in.
//!
//! Architects model at survey coordinates (10⁵–10⁶ m from the origin). A coordinate X stored in
//! a double is rounded to ε·|X|, and a finely subdivided rod's bending turns that rounding into
//! forces EI·ε|X|/h³: the round-off floor of a structure would grow with its distance from the
//! origin, and a scene and its translated copy would not converge alike. A scene whose rods
//! stand far from the origin is therefore built in coordinates relative to the centre of their
//! bounding box (`origin`), and positions are turned back into the scene's own coordinates where
//! they leave the network (results, modes, restarts: `Model::world_position`).

use super::types::{Obstacle, Scene};

/// A scene is solved about its own centre once the distance of that centre from the origin is
/// more than this many times the rods' extent (the rounding of the coordinates then costs more
/// than four bits of the structure's own size). Nearer, it is solved where it is drawn: its
/// floor is then at most this many times the centred one's, and scenes drawn about the origin
/// keep their results bit for bit.
const FAR: f64 = 16.0;

/// The origin of the coordinates the scene's network is solved in: zero, or for a scene far from
/// the origin (`FAR`) the centre of its rods' bounding box. Every coordinate is then within the
/// extent of that centre and far less than it, so its difference from it is exact (Sterbenz),
/// and a scene and its copy translated by an exactly representable vector are the same problem.
pub fn origin(scene: &Scene) -> [f64; 3] {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in scene.rods.iter().flat_map(|r| &r.points) {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let extent = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
    let centre = [0, 1, 2].map(|k| 0.5 * (lo[k] + hi[k]));
    let distance = centre.iter().fold(0.0_f64, |a, c| a.max(c.abs()));
    if distance.is_finite() && distance > FAR * extent {
        centre
    } else {
        [0.0; 3]
    }
}

impl Scene {
    /// The scene moved by `d`: every position a network is built from (rod points, support
    /// targets, obstacles, bounds). Targets and references are compared with positions turned
    /// back into the scene's coordinates, and stay as they are.
    pub fn translated(&self, d: [f64; 3]) -> Scene {
        let mv = |p: &mut [f64; 3]| (0..3).for_each(|k| p[k] += d[k]);
        let mut s = self.clone();
        s.rods.iter_mut().flat_map(|r| &mut r.points).for_each(mv);
        s.supports
            .iter_mut()
            .filter_map(|x| x.move_to.as_mut())
            .for_each(mv);
        for o in &mut s.obstacles {
            match o {
                Obstacle::Plane { point, .. } | Obstacle::Cylinder { point, .. } => mv(point),
                Obstacle::Sphere { center, .. } => mv(center),
            }
        }
        for b in &mut s.bounds {
            for k in 0..3 {
                b.min[k] = b.min[k].map(|x| x + d[k]);
                b.max[k] = b.max[k].map(|x| x + d[k]);
            }
        }
        s
    }
}
