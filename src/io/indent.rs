//! The results of `rodnet indent`: JSON and the force–depth CSV.

use std::fmt::Write;

use serde::{Deserialize, Serialize};

use crate::network::indent::Curve;

#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct IndentJson {
    /// The pushed point: rod, input vertex, joint name if it is a joint, position (m).
    pub rod: String,
    pub vertex: usize,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub joint: Option<String>,
    pub position: [f64; 3],
    /// Unit direction of the push and its full depth, m.
    pub direction: [f64; 3],
    pub depth: f64,
    /// Force per unit displacement of the point along the push with everything else free, from
    /// the Hessian at the solved state, N/m (null when that state is not stable).
    pub linear_stiffness: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub linear_stiffness_note: Option<String>,
    /// True: the point is held along the push only (frictionless); false: on the line of the
    /// push (sticking), with `max_lateral_force` the largest force across it.
    pub frictionless: bool,
    pub max_lateral_force: f64,
    /// [depth m, force N] from [0, 0]: the force the indenter applies along the push.
    pub curve: Vec<[f64; 2]>,
    /// Local maxima of the force: [depth m, force N].
    pub limit_points: Vec<[f64; 2]>,
    /// The stability of each point of `curve` with the pushed point held (extension).
    #[serde(default)]
    pub curve_stability: Vec<PointStabilityJson>,
    /// Where the path lost stability: a bifurcation (or a fold in depth that displacement
    /// control jumps across) (extension).
    #[serde(default)]
    pub bifurcations: Vec<BifurcationJson>,
    /// The push's bifurcations and snaps (contract: kind "snap" where the force drops), with
    /// `load_factor` the depth's share of the full push and `stage` null.
    #[serde(default)]
    pub path_events: Vec<crate::io::results::PathEventJson>,
    /// Every step reached equilibrium (else `message` says where the curve stops).
    pub complete: bool,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub message: Option<String>,
    /// The first solve (the scene as given, form finding included).
    pub solve_iterations: usize,
    pub iterations: usize,
    pub seconds: f64,
}

/// One point of the curve: the Hessian with the pushed point held.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct PointStabilityJson {
    /// Positive definite: a minimum under displacement control.
    pub stable: bool,
    /// The step's solve reached a state that was not stable and left it (the path it
    /// continued lost stability within the step).
    pub left_unstable: bool,
}

#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct BifurcationJson {
    /// Index in `curve` of the step whose solve left the unstable state.
    pub step: usize,
    /// Where the lowest eigenvalue of the path before it reaches zero (linear extrapolation
    /// from the two points before, within the step), m, and the force there on that path, N.
    pub depth: f64,
    pub force: f64,
    /// [depth m, lowest eigenvalue N/m] at the two points before the step (null where there
    /// is none or the eigen-solve failed).
    pub eigenvalues: Vec<[Option<f64>; 2]>,
}

impl IndentJson {
    pub fn events_of(c: &Curve) -> Vec<crate::io::results::PathEventJson> {
        c.events
            .iter()
            .map(|e| crate::io::results::PathEventJson {
                kind: e.kind,
                load_factor: e.load_factor,
                stage: None,
                detail: e.detail.clone(),
            })
            .collect()
    }

    pub fn curve_of(c: &Curve) -> (Vec<[f64; 2]>, Vec<[f64; 2]>) {
        (
            c.points.iter().map(|&(d, f)| [d, f]).collect(),
            c.limit_points.iter().map(|&(d, f)| [d, f]).collect(),
        )
    }

    /// The curve's stability and bifurcations as written.
    pub fn stability_of(c: &Curve) -> (Vec<PointStabilityJson>, Vec<BifurcationJson>) {
        (
            c.stability
                .iter()
                .map(|s| PointStabilityJson {
                    stable: s.stable,
                    left_unstable: s.left_unstable,
                })
                .collect(),
            c.bifurcations
                .iter()
                .map(|b| BifurcationJson {
                    step: b.step,
                    depth: b.depth,
                    force: b.force,
                    eigenvalues: b
                        .eigenvalues
                        .iter()
                        .map(|&(d, l)| [d, l].map(|v| v.is_finite().then_some(v)))
                        .collect(),
                })
                .collect(),
        )
    }
}

/// The curve as CSV: a header with units, one row per depth.
pub fn curve_csv(points: &[(f64, f64)]) -> String {
    let mut s = String::from("depth_m,force_N\n");
    for (d, f) in points {
        let _ = writeln!(s, "{d:.12e},{f:.12e}");
    }
    s
}
