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
    /// Every step reached equilibrium (else `message` says where the curve stops).
    pub complete: bool,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub message: Option<String>,
    /// The first solve (the scene as given, form finding included).
    pub solve_iterations: usize,
    pub iterations: usize,
    pub seconds: f64,
}

impl IndentJson {
    pub fn curve_of(c: &Curve) -> (Vec<[f64; 2]>, Vec<[f64; 2]>) {
        (
            c.points.iter().map(|&(d, f)| [d, f]).collect(),
            c.limit_points.iter().map(|&(d, f)| [d, f]).collect(),
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
