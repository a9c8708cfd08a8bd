//! The `stability` block of the results JSON (`rodnet solve --modes K`), the results of
//! `rodnet buckle`, and mode shapes as OBJ (one object per mode).

use std::fmt::Write;

use serde::{Deserialize, Serialize};

use crate::network::path_check::PathCritical;
pub use crate::network::stability::Shape;
use crate::network::stability::{LinearBuckling, Stability};

#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct ZeroModesJson {
    pub count: usize,
    /// "gauge" (rigid turns of an unsupported structure) or "neutral" (a mechanism the loads
    /// leave alone), with a description; absent when there are none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kind: Option<String>,
}

#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct StabilityJson {
    /// The Hessian restricted to the free unknowns has no negative eigenvalue and no zero one
    /// but gauge turns.
    pub stable: bool,
    /// The lowest eigenvalues, ascending, in `unit`.
    pub eigenvalues: Vec<f64>,
    /// "N/m": stiffness against a unit motion, an edge's turn θ counted as the motion ē·θ of
    /// its end (ē the mean rest edge length).
    pub unit: String,
    /// Negative eigenvalues among those computed.
    pub negative: usize,
    /// All computed eigenvalues are negative: `negative` is a lower bound (ask more modes).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub negative_at_least: bool,
    pub zero_modes: ZeroModesJson,
    /// Largest relative residual of the eigenpairs, subspace rounds, seconds.
    pub residual: f64,
    pub rounds: usize,
    /// The eigenvalues settled within the iteration limit (else they are the last round's).
    pub converged: bool,
    pub seconds: f64,
}

impl From<&Stability> for StabilityJson {
    fn from(s: &Stability) -> Self {
        StabilityJson {
            stable: s.stable,
            eigenvalues: s.eigenvalues.clone(),
            unit: "N/m".into(),
            negative: s.negative,
            negative_at_least: s.negative_at_least,
            zero_modes: ZeroModesJson {
                count: s.zero_modes,
                kind: s.zero_kind.clone(),
            },
            residual: s.residual,
            rounds: s.rounds,
            converged: s.converged,
            seconds: s.seconds,
        }
    }
}

#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct ModeRodJson {
    pub name: String,
    /// Node displacements of the mode, m, scaled so that the largest is 1.
    pub displacement: Vec<[f64; 3]>,
}

#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct BucklingModeJson {
    pub factor: f64,
    pub rods: Vec<ModeRodJson>,
}

/// The check of the first factor along the nonlinear path (`network::path_check::critical_on_path`).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct PathJson {
    /// Where the lowest eigenvalue of the tangent stiffness crosses zero along the load path
    /// (null: it does not, within the search; see `note`).
    pub critical_load_factor: Option<f64>,
    /// What the path showed: "bifurcation" (the path's state turned unstable and left it: a
    /// clean bifurcation, located), "crossing" (the lowest eigenvalue extrapolated to zero),
    /// "imperfect_bifurcation" (a positive minimum: no critical factor), "no_buckling" (the
    /// eigenvalue does not fall toward zero: the linear factors are no buckling loads of these
    /// loads) or "unresolved" (see `note`).
    #[serde(default)]
    pub kind: String,
    /// [load factor, lowest eigenvalue (N/m)] at each equilibrium solved.
    pub samples: Vec<[f64; 2]>,
    pub iterations: usize,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
}

impl From<&PathCritical> for PathJson {
    fn from(p: &PathCritical) -> Self {
        PathJson {
            critical_load_factor: p.factor,
            kind: p.kind.name().into(),
            samples: p.samples.iter().map(|&(l, f)| [l, f]).collect(),
            iterations: p.iterations,
            note: p.note.clone(),
        }
    }
}

/// The results of `rodnet buckle`.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct BucklingJson {
    /// How the factors were found.
    pub method: String,
    /// Factors by which the scene's loads and prescribed motions can be multiplied before the
    /// structure buckles, ascending (positive only).
    pub critical_load_factors: Vec<f64>,
    pub modes: Vec<BucklingModeJson>,
    /// The factors settled within the iteration limit.
    pub converged: bool,
    /// The first factor checked along the nonlinear path (absent with `--linear-only`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub path: Option<PathJson>,
    pub rounds: usize,
    pub seconds: f64,
    /// A staged scene: the stage whose equilibrium the factors are about ("rest" when they
    /// scale the scene's own loads); null without stages.
    pub about_stage: Option<String>,
}

impl BucklingJson {
    /// `rest` and `shapes`: the rods at rest and displaced along each mode (same order).
    pub fn new(b: &LinearBuckling, rest: &Shape, shapes: &[Shape]) -> BucklingJson {
        let modes = b
            .factors
            .iter()
            .zip(shapes)
            .map(|(&factor, shape)| {
                let d: Vec<Vec<[f64; 3]>> = shape
                    .iter()
                    .zip(rest)
                    .map(|((_, p, _), (_, q, _))| {
                        p.iter()
                            .zip(q)
                            .map(|(a, b)| std::array::from_fn(|k| a[k] - b[k]))
                            .collect()
                    })
                    .collect();
                let big = d
                    .iter()
                    .flatten()
                    .map(|v: &[f64; 3]| v.iter().map(|x| x * x).sum::<f64>().sqrt())
                    .fold(0.0, f64::max)
                    .max(f64::MIN_POSITIVE);
                BucklingModeJson {
                    factor,
                    rods: shape
                        .iter()
                        .zip(d)
                        .map(|((name, _, _), d)| ModeRodJson {
                            name: name.clone(),
                            displacement: d
                                .into_iter()
                                .map(|v| std::array::from_fn(|k| v[k] / big))
                                .collect(),
                        })
                        .collect(),
                }
            })
            .collect();
        BucklingJson {
            method: "linear: (K0 + lambda K1) u = 0 about the start (the rest state, or a \
                     staged scene's equilibrium before the scaled stage), K1 the Hessian's \
                     derivative along the linear response to the loads"
                .into(),
            critical_load_factors: b.factors.clone(),
            modes,
            converged: b.converged,
            path: None,
            rounds: b.rounds,
            seconds: b.seconds,
            about_stage: None,
        }
    }
}

/// One OBJ object per mode (`o mode_1`, …, its label as a comment), each holding every rod as
/// an `l` polyline.
pub fn modes_obj(title: &str, modes: &[(String, Shape)]) -> String {
    let mut s = format!("# rodnet {title}\n");
    let mut base = 1;
    for (i, (label, rods)) in modes.iter().enumerate() {
        let _ = writeln!(s, "# {label}");
        let _ = writeln!(s, "o mode_{}", i + 1);
        for (name, points, closed) in rods {
            let _ = writeln!(s, "# rod {name}");
            base = crate::io::obj::polyline(&mut s, points, *closed, base);
        }
    }
    s
}
