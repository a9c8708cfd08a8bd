//! Form finding from the flat footprint: the rod ends move in continuation steps from the
//! footprint to their equator points.
//!
//! The footprint and its pinned ends are symmetric under z → −z. Once the ends move inward, the
//! flat grid is a saddle between the dome, its mirror image and mixed states, and rodnet's
//! Newton solver starts badly there: the first continuation sub-step crushes the end edges
//! (only the prescribed ends move), the increments shrink to ~1e-4 of the path, and near the
//! flat saddle the line search finds no energy decrease and the solve stops (the saddle escape
//! only runs once the residual is below tolerance). Measured with `rodnet solve` on footprint
//! scenes (docs/gridshell.md): from the flat footprint 12 of 20 cases with n = 2–6, subdivide
//! 1–8 stop at the saddle; the others leave it through the solver's negative-curvature escape,
//! whose sign is not tied to "up". With an upward lift of 0.1 EI/R² on every joint, n = 8
//! converges at subdivide 4 (221 iterations in the first of 8 load steps) but stops at the
//! saddle at subdivide 8, and so does n = 16 at subdivide 4.
//!
//! So the symmetry is broken by the starting state instead. Before the solve, the footprint is
//! bent onto a shallow spherical cap: the node with footprint coordinates (u, v) goes to the
//! point r(u, v) of the Chebyshev net of a sphere of radius `start_cap · R`, rested on z = 0 at
//! its lowest rod end. That net is isometric along its curves, so every rod keeps its length
//! (up to chord versus arc, ~(l/R_cap)²/24 per edge) and every crossing stays a crossing: the
//! start is an upward, unstretched bend of the footprint, not the answer. The ends then move on
//! straight lines from the cap's rim to their equator points over the load steps. The last step
//! is the pure problem (ends pinned on the equator, no load), so the cap only selects the
//! branch: the equilibrium does not depend on it (docs/gridshell.md compares cap radii).

use std::time::Instant;

use crate::gridshell::chebyshev::HemisphereNet;
use crate::math::vec::{cross, norm, normalize, scalef};
use crate::network::build::Network;
use crate::solver::{self, NewtonReport, NewtonSettings};

/// Radius of the starting cap over R. Larger radii start flatter and need more iterations
/// (see docs/gridshell.md); the equilibrium is the same.
pub const DEFAULT_START_CAP: f64 = 5.0;

pub struct FormFinding {
    pub report: NewtonReport,
    /// Wall time, s.
    pub seconds: f64,
}

/// Form-finds `network` in place. It must be built from a footprint scene of radius `radius`
/// (rods flat in z = 0 with their net parameters as (x, y), ends with `move_to`).
/// `start_cap` is the starting cap's radius over R; 0 starts from the flat footprint itself
/// (no symmetry breaking: for studies of the solver). `settings.load_steps` steps move the
/// ends from the cap's rim to the equator.
pub fn form_find(
    network: &mut Network,
    settings: &NewtonSettings,
    radius: f64,
    start_cap: f64,
) -> FormFinding {
    let t0 = Instant::now();
    let model = &mut network.model;
    if start_cap > 0.0 {
        let cap = HemisphereNet::new(start_cap * radius, 1);
        let q = &mut model.state.q;
        let nodes = network.n_nodes;
        let flat = q[..3 * nodes].to_vec();
        let mut lowest = f64::INFINITY;
        for n in 0..nodes {
            let p = cap.point(flat[3 * n], flat[3 * n + 1]);
            q[3 * n..3 * n + 3].copy_from_slice(&p);
            lowest = lowest.min(p[2]);
        }
        // Joint frames (Rigid, Hinge) turn with the surface, from the plane's normal z to the
        // cap's normal at their node, so that the guess does not twist the rods against them.
        let mut turned = vec![false; model.state.frames.len()];
        for fb in &model.terms.frame_bend {
            let f = fb.port.frame;
            if !std::mem::replace(&mut turned[f], true) {
                let node = fb.vars[0] / 3;
                let normal = normalize([q[3 * node], q[3 * node + 1], q[3 * node + 2]]);
                model.state.frames[f].commit(rotation_from_z(normal));
            }
        }
        // Rest the cap on z = 0 at its lowest node, a rod end.
        for n in 0..nodes {
            q[3 * n + 2] -= lowest;
        }
        for p in &mut model.prescribed {
            p.start = q[p.var];
        }
        // Edge reference frames follow the new tangents before the first assembly.
        model.commit();
    }
    let report = solver::solve(model, settings);
    FormFinding {
        report,
        seconds: t0.elapsed().as_secs_f64(),
    }
}

/// Rotation vector of the smallest rotation taking the z axis to the unit vector `n`.
fn rotation_from_z(n: [f64; 3]) -> [f64; 3] {
    let axis = cross([0.0, 0.0, 1.0], n);
    let s = norm(axis);
    if s == 0.0 {
        return [0.0; 3];
    }
    scalef(axis, s.atan2(n[2]) / s)
}
