//! The round-off floor a scene will have, known before the solve: measured on the built network
//! at its start state (one gradient evaluation, before the Hessian is allocated), the way the
//! solver measures it at the end (`NetworkProblem::residual_floor`). A scene whose floor makes a
//! meaningful answer impossible (`verdict::MEANINGFUL_FLOOR`) is refused at the field that
//! causes it, with the largest value of that field that would work, instead of a solve that
//! spends minutes learning it (docs/design.md, "The convergence verdict").

use super::problem::NetworkProblem;
use super::Network;
use crate::scene::types::{Scene, SupportKind};
use crate::scene::FieldError;
use crate::solver::problem::Core;
use crate::solver::verdict::MEANINGFUL_FLOOR;

/// A start floor this many times above `MEANINGFUL_FLOOR` is refused: the floor at the
/// equilibrium differs from the start's by the change of the coordinates' magnitudes (measured
/// within a factor 2 on the cantilever), and below this the solve runs and its verdict decides.
const REFUSE_FACTOR: f64 = 4.0;
/// The floor a refusal's suggested value brings the scene to: well inside the bound, where the
/// verdict is not in doubt.
const SUGGESTED_FLOOR: f64 = 0.1 * MEANINGFUL_FLOOR;

/// The relative residual that rounding the free unknowns to doubles causes at the network's
/// current state, each node's coordinates rounded at the size of its largest one.
pub fn at_start(net: &mut Network) -> f64 {
    let mut g = vec![0.0; net.model.n_free];
    let mut p = NetworkProblem::new(&mut net.model);
    p.assemble(&mut g, None);
    p.rounding_response(&g, true)
}

/// Refuses a network whose start floor is beyond `REFUSE_FACTOR` × `MEANINGFUL_FLOOR`.
pub fn check(scene: &Scene, net: &mut Network) -> Result<f64, FieldError> {
    let floor = at_start(net);
    if floor.is_finite() && floor <= REFUSE_FACTOR * MEANINGFUL_FLOOR {
        return Ok(floor);
    }
    let cause = largest_cause(scene, net);
    let share = SUGGESTED_FLOOR / floor;
    let head = format!(
        "the round-off floor of this scene is {floor:.2e} of its force scale (rounding the \
         unknowns to doubles alone leaves that much out of balance; rodnet calls nothing with \
         a floor above {MEANINGFUL_FLOOR:.0e} converged, docs/design.md, \"The convergence verdict\")"
    );
    Err(match cause {
        Cause::Bending { rod, subdivide } => FieldError::new(
            "rods",
            rod,
            "subdivide",
            format!(
                "{head}: the rod's bending stencils turn a rounding of its coordinates into \
                 forces that grow as the cube of its subdivision; subdivide ≤ {} would work",
                largest_subdivision(subdivide, share.cbrt())
            ),
        ),
        Cause::Stretching {
            material,
            young_modulus,
        } => FieldError::keyed(
            "materials",
            &material,
            "young_modulus",
            format!(
                "{head}: the rods' axial stiffness EA turns a rounding of their coordinates \
                 into forces far above the loads; young_modulus ≤ {:.2e} Pa would work (or larger \
                 loads, or fewer edges)",
                young_modulus * share
            ),
        ),
        Cause::Spring {
            section,
            index,
            stiffness,
            unit,
        } => FieldError::new(
            section,
            index,
            "kind",
            format!(
                "{head}: this spring's stiffness turns a rounding of the coordinates into forces \
                 far above the loads; a stiffness ≤ {:.2e} {unit} would work (or a rigid \
                 support or joint instead)",
                stiffness * share
            ),
        ),
    })
}

fn largest_subdivision(subdivide: usize, factor: f64) -> usize {
    ((subdivide as f64 * factor).floor() as usize).max(1)
}

enum Cause {
    Bending {
        rod: usize,
        subdivide: usize,
    },
    Stretching {
        material: String,
        young_modulus: f64,
    },
    Spring {
        section: &'static str,
        index: usize,
        stiffness: f64,
        unit: &'static str,
    },
}

impl Cause {
    fn spring(section: &'static str, index: usize, stiffness: f64, unit: &'static str) -> Cause {
        Cause::Spring {
            section,
            index,
            stiffness,
            unit,
        }
    }
}

/// The term that makes most of the floor, by the forces a rounding δ = ε·|x| of the coordinates
/// makes: EA·δ/h in stretching, 16·EI·δ/h³ in bending (the discrete curvature is a second
/// difference of positions, and its force another: 4 × 4 on alternating signs), k·δ in a
/// translational spring.
fn largest_cause(scene: &Scene, net: &Network) -> Cause {
    let m = &net.model;
    let reach = |nodes: &mut dyn Iterator<Item = usize>| {
        nodes
            .map(|n| m.position(n).iter().fold(0.0_f64, |a, x| a.max(x.abs())))
            .fold(0.0, f64::max)
            * f64::EPSILON
    };
    let mut best = (0.0, None);
    let mut consider = |force: f64, cause: Cause| {
        if force > best.0 || best.1.is_none() {
            best = (force, Some(cause));
        }
    };
    for (i, (r, sr)) in net.rods.iter().zip(&scene.rods).enumerate() {
        let delta = reach(&mut r.nodes.iter().copied());
        let h = r
            .edges
            .iter()
            .map(|&e| m.rest_lengths[e])
            .fold(f64::INFINITY, f64::min);
        let s = &r.stiffness;
        let young_modulus = r.young_modulus;
        consider(
            s.ea * delta / h,
            Cause::Stretching {
                material: sr.material.clone(),
                young_modulus,
            },
        );
        consider(
            16.0 * s.ei1.max(s.ei2) * delta / (h * h * h),
            Cause::Bending {
                rod: i,
                subdivide: sr.subdivide,
            },
        );
    }
    let delta = reach(&mut (0..m.layout.n_nodes()));
    for (i, s) in scene.supports.iter().enumerate() {
        if let SupportKind::Spring { stiffness, .. } = s.kind {
            let k = stiffness.iter().fold(0.0_f64, |a, k| a.max(*k));
            consider(k * delta, Cause::spring("supports", i, k, "N/m"));
        }
    }
    // A frame's orientation is rounded to ε radians whatever its angle: a rotational spring c
    // makes a moment c·ε, a force c·ε / L on the residual's scale.
    let turn = f64::EPSILON / m.length_scale;
    for (i, s) in scene.supports.iter().enumerate() {
        if let Some(c) = s.kind.rotational_stiffness() {
            let c = c.iter().fold(0.0_f64, |a, k| a.max(*k));
            consider(c * turn, Cause::spring("supports", i, c, "N·m/rad"));
        }
    }
    for (i, j) in scene.joints.iter().enumerate() {
        let Some(e) = j.kind.elastic() else { continue };
        if let Some(k) = e.translation {
            consider(k * delta, Cause::spring("joints", i, k, "N/m"));
        }
        let c = [e.bending, e.twist, e.scissor]
            .iter()
            .flatten()
            .fold(0.0_f64, |a, k| a.max(*k));
        consider(c * turn, Cause::spring("joints", i, c, "N·m/rad"));
    }
    best.1.expect("a network has rods")
}
