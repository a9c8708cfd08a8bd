//! The results JSON of the contract: one schema, written and read back through serde, filled
//! from an [`Equilibrium`] and the solve's report (formatting only).

use serde::{Deserialize, Serialize};

use crate::network::contact::Source;
use crate::network::equilibrium::{
    ConstraintForces, EdgeForces, Equilibrium, NetBlock, ReferenceCheck, RodEnergy, TargetCheck,
    Utilization,
};
use crate::network::model::EnergyParts;
use crate::solver::NewtonReport;

#[derive(Debug, Clone, Default, Serialize, Deserialize)]
pub struct EnergyJson {
    pub total: f64,
    pub stretch: f64,
    pub bend: f64,
    pub twist: f64,
    pub joints: f64,
    /// Elastic supports (`Spring`), J (extension).
    #[serde(default)]
    pub supports: f64,
    pub external: f64,
}

impl From<EnergyParts> for EnergyJson {
    fn from(p: EnergyParts) -> Self {
        EnergyJson {
            total: p.total(),
            stretch: p.stretch,
            bend: p.bend,
            twist: p.twist,
            joints: p.joints,
            supports: p.supports,
            external: p.external,
        }
    }
}

/// The Richardson extrapolate of two solves, the scene's subdivision and twice it, or of three
/// with four times it too (`study::extrapolate`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ExtrapolationJson {
    /// The highest order of the error removed: 2 with two levels, 3 with three (the h² and h³
    /// terms).
    pub order: f64,
    /// Each rod's (coarse, finest) subdivision, in scene order.
    pub subdivide: Vec<[usize; 2]>,
    /// Each rod's extrapolated nodes at the coarse subdivision, m.
    pub rods: Vec<ExtrapolatedRod>,
    /// Largest distance between the finest solution and the extrapolate, m: the estimated error
    /// of the finest solution (the extrapolate's own error is of higher order).
    pub error_estimate: f64,
    /// `error_estimate` over the diagonal of the deformed structure's bounding box.
    pub relative_error_estimate: f64,
    /// The extrapolated total energy, J.
    pub energy: f64,
    pub coarse_iterations: usize,
    pub fine_iterations: usize,
    /// All solves, s.
    pub seconds: f64,
    /// Solves extrapolated from: 2 (subdivision ×1, ×2) or 3 (×1, ×2, ×4; `--levels 3`).
    #[serde(default = "two_levels")]
    pub levels: usize,
    /// Three levels: Newton iterations of the ×2 solve.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub middle_iterations: Option<usize>,
    /// Three levels: log₂ of the ratio of the largest node changes ×1 → ×2 and ×2 → ×4.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub observed_order: Option<f64>,
    /// Three levels: largest distance between the extrapolate and the two-level extrapolate of
    /// the finer pair, m (an upper estimate of the extrapolate's own error).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub extrapolate_error_estimate: Option<f64>,
}

fn two_levels() -> usize {
    2
}

/// One rod of an [`ExtrapolationJson`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ExtrapolatedRod {
    pub name: String,
    pub points: Vec<[f64; 3]>,
}

/// Fields beyond the contract's (`name`, `points`, `twist`) default when read back, so that any
/// results JSON that keeps the contract can be read.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
#[serde(default)]
pub struct RodJson {
    pub name: String,
    /// Every node after subdivision, m.
    pub points: Vec<[f64; 3]>,
    /// Material-frame angle θ of each edge relative to its time-parallel reference frame, rad.
    pub twist: Vec<f64>,
    /// Largest extreme-fibre bending stress over the rod's vertices, Pa.
    pub max_bending_stress: f64,
    /// Extreme-fibre bending stress at each node (zero at free ends), Pa.
    pub bending_stress: Vec<f64>,
    /// Elastic energy stored in the rod, J.
    pub energy: RodEnergy,
    /// The rod's length after deformation, m.
    pub length: f64,
    /// Internal force and moment of each edge in its material frame (contract name; sign
    /// conventions in docs/internal-forces.md).
    pub forces: Vec<EdgeForceJson>,
    /// Largest von Mises stress over yield strength among the rod's edges (materials with a
    /// `yield_strength` only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub utilization: Option<f64>,
    /// Every node in the rest shape, m (extension).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub rest_points: Vec<[f64; 3]>,
    /// Scenes with a target: signed distance of each node to it, m (extension).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub target_distance: Vec<f64>,
}

/// One edge's entry of `forces`: what the part of the rod after the edge's midpoint exerts on
/// the part before it, in the edge's material frame (m1, m2, t).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct EdgeForceJson {
    /// N, tension positive.
    pub axial: f64,
    /// (along m1, along m2), N.
    pub shear: [f64; 2],
    /// (about m1, about m2) at the edge's midpoint, N·m.
    pub moment: [f64; 2],
    /// About t, N·m.
    pub torsion: f64,
    /// Von Mises stress over yield strength (materials with a `yield_strength` only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub utilization: Option<f64>,
}

impl From<&EdgeForces> for EdgeForceJson {
    fn from(f: &EdgeForces) -> Self {
        EdgeForceJson {
            axial: f.axial,
            shear: f.shear,
            moment: f.moment,
            torsion: f.torsion,
            utilization: f.utilization,
        }
    }
}

impl EdgeForceJson {
    fn all_finite(&self) -> bool {
        [self.axial, self.torsion]
            .iter()
            .chain(&self.shear)
            .chain(&self.moment)
            .chain(&self.utilization)
            .all(|v| v.is_finite())
    }
}

#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct JointJson {
    pub name: String,
    pub position: [f64; 3],
}

#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct ReactionJson {
    pub rod: String,
    pub vertex: usize,
    /// Index of the vertex's node in the rod's `points` (extension).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub node: Option<usize>,
    /// "pin", "clamp", "roller" or "spring" (extension).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub kind: Option<String>,
    /// Force the support exerts on the structure, N.
    pub force: [f64; 3],
    /// Moment the support exerts (clamps), N·m.
    pub moment: [f64; 3],
}

/// A point force or torque of the scene at the final load factor (extension).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct LoadJson {
    pub rod: String,
    pub vertex: usize,
    /// Index of the vertex's node in the rod's `points`.
    pub node: usize,
    /// N.
    pub force: [f64; 3],
    /// N·m.
    pub moment: [f64; 3],
}

#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct TargetJson {
    pub shape: String,
    /// Sphere targets: over R.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_abs_radial_deviation: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rms_radial_deviation: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub apex_height: Option<f64>,
    /// Mesh targets: joints to the surface, m.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_abs_distance: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rms_distance: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mean_signed_distance: Option<f64>,
    /// Fitted gridshells: the net (also at the top level of the results).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub net: Option<NetBlock>,
    /// Gridshells only: distance of each joint to its crossing on the Chebyshev net, over R.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_net_distance: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rms_net_distance: Option<f64>,
}

/// The `continuation` block of the results JSON (arc-length paths).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct ContinuationJson {
    pub kind: String,
    pub steps: usize,
    /// Where the load factor stopped rising (or falling) along the path.
    pub limit_points: Vec<crate::solver::LimitPoint>,
}

/// The `mechanism` block of the results JSON.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct MechanismJson {
    /// Which rods move and how (a rotation names its axis), m.
    pub description: String,
}

#[derive(Debug, Clone, Default, Serialize, Deserialize)]
pub struct SolverJson {
    pub factorizations: usize,
    pub regularized_iterations: usize,
    pub saddle_escapes: usize,
    pub stable: bool,
    pub factor_seconds: f64,
    pub free_unknowns: usize,
    pub step_iterations: Vec<usize>,
    pub message: Option<String>,
    /// Zero-stiffness modes of the final state other than gauge modes (then `stable` is false:
    /// neutral equilibrium).
    #[serde(default)]
    pub zero_modes: usize,
    /// Why `stable` is false when the energy could not judge the state (dead moments).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stability_note: Option<String>,
    /// Iterations of the path under the `buckle_toward` bias (included in `iterations`).
    #[serde(default)]
    pub biased_iterations: usize,
}

/// The force one active constraint (obstacle contact or coordinate bound) exerts on a node.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct ContactJson {
    pub rod: String,
    /// Index of the node in the rod's `points`.
    pub node: usize,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub obstacle: Option<usize>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bound: Option<usize>,
    /// N, on the rod (the multiplier times the constraint's unit gradient).
    pub force: [f64; 3],
    /// Distance of the rod's surface from the obstacle (of the node from the bound), m.
    pub gap: f64,
}

/// First-order optimality (KKT) of the constrained equilibrium, with the last step QP's
/// multipliers z and the constraints c(x) ≥ 0 at the final state.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct KktJson {
    /// Largest constraint violation max(0, −c), m.
    pub primal_feasibility: f64,
    /// The same over the length scale.
    pub primal_feasibility_relative: f64,
    /// Largest |z·c|, J.
    pub complementarity: f64,
    /// The same over force scale × length scale.
    pub complementarity_relative: f64,
    /// Smallest multiplier, N (non-negative at a KKT point).
    pub min_multiplier: f64,
    /// Largest component of ∇E − Jᵀz relative to the force (moment) scale, as `residual`.
    pub stationarity: f64,
    /// Constraints whose force exceeds tolerance × force scale.
    pub active_set: usize,
    pub constraints: usize,
    pub qp_solves: usize,
    /// QPs that stopped short of full accuracy (their steps still passed the line search).
    pub inexact_qps: usize,
    /// QPs refined to the exact solution on their active set.
    pub polished_qps: usize,
    /// Newton steps that needed no QP (the unconstrained step was feasible).
    pub steps_without_qp: usize,
    pub qp_iterations: usize,
    pub qp_seconds: f64,
}

/// Read back (`rodnet plot`), only `rods` is required: the other fields default, so that any JSON
/// that keeps the contract's rod keys can be read.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Results {
    #[serde(default)]
    pub converged: bool,
    #[serde(default)]
    pub iterations: usize,
    #[serde(default)]
    pub load_steps: usize,
    #[serde(default)]
    pub residual: f64,
    #[serde(default)]
    pub seconds: f64,
    /// Relative residual that rounding the unknowns to doubles causes at the final state.
    #[serde(default)]
    pub residual_floor: f64,
    /// The tolerance the solve used.
    #[serde(default)]
    pub tolerance: f64,
    /// The solve stopped below the round-off floor, above the tolerance.
    #[serde(default)]
    pub stopped_at_floor: bool,
    /// What stopped an unconverged solve early ("time limit").
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stopped: Option<String>,
    /// A zero-stiffness mode that the loads excite: the solve stopped at its start.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mechanism: Option<MechanismJson>,
    /// Arc-length continuation only: its steps and the limit points met on the path.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub continuation: Option<ContinuationJson>,
    /// How the rigid translations of an unsupported structure were removed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gauge: Option<String>,
    #[serde(default)]
    pub energy: EnergyJson,
    pub rods: Vec<RodJson>,
    #[serde(default)]
    pub joints: Vec<JointJson>,
    #[serde(default)]
    pub reactions: Vec<ReactionJson>,
    /// The scene's point forces and torques, where they act (extension; gravity not listed).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub loads: Vec<LoadJson>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub target: Option<TargetJson>,
    /// Fitted gridshells: their Chebyshev net (the same block as `target.net`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub net: Option<NetBlock>,
    /// Scenes with a `reference` only.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reference: Option<ReferenceJson>,
    #[serde(default)]
    pub solver: SolverJson,
    /// Scenes with obstacles or bounds only.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub contacts: Option<Vec<ContactJson>>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub kkt: Option<KktJson>,
    /// `rodnet solve --modes K` only: the lowest eigenvalues at the equilibrium.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stability: Option<crate::io::stability::StabilityJson>,
    /// What the scene probably did not mean (`scene::validate::warnings`), as `field: message`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub warnings: Vec<String>,
    /// Scenes with a material's `yield_strength`: the most utilized edge.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub utilization: Option<Utilization>,
    /// `rodnet solve --extrapolate` only: the Richardson extrapolate of this solve and the one
    /// at half its subdivision (extension).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub extrapolation: Option<ExtrapolationJson>,
    /// Scenes with `stages`: the stage these results are of.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stage: Option<StageJson>,
    /// Scenes with `stages`, in the last stage's results: every stage solved, in order.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub stages: Vec<StageJson>,
    /// Limit points, bifurcations and snaps the load path passed (every stage's, in a staged
    /// scene's last results); empty when the path passed none.
    #[serde(default)]
    pub path_events: Vec<PathEventJson>,
}

/// One event of the load path (contract: `kind`, `load_factor`, `stage`; `detail` extends).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PathEventJson {
    pub kind: crate::solver::path_events::EventKind,
    pub load_factor: f64,
    /// The stage whose loads the load factor scales; null for the scene's own loads.
    pub stage: Option<String>,
    pub detail: String,
}

impl PathEventJson {
    /// The events of one solve: its load-controlled path's and its arc-length limit points.
    pub fn of(report: &NewtonReport) -> Vec<PathEventJson> {
        let events = report.path_events.iter().map(|e| PathEventJson {
            kind: e.kind,
            load_factor: e.load_factor,
            stage: None,
            detail: e.detail.clone(),
        });
        let limits = report.limit_points.iter().map(|l| PathEventJson {
            kind: crate::solver::path_events::EventKind::LimitPoint,
            load_factor: l.load_factor,
            stage: None,
            detail: format!(
                "the load factor stopped rising along the arc-length path (step {})",
                l.step
            ),
        });
        events.chain(limits).collect()
    }
}

/// One load stage's outcome (`stage`, `stages`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StageJson {
    /// 0 for the scene's own loads ("base"), k for `stages[k − 1]`.
    pub index: usize,
    pub name: String,
    pub converged: bool,
    pub iterations: usize,
    pub residual: f64,
    /// s.
    pub seconds: f64,
    /// J.
    pub energy: f64,
}

impl StageJson {
    pub fn of(index: usize, name: &str, r: &Results) -> StageJson {
        StageJson {
            index,
            name: name.to_string(),
            converged: r.converged,
            iterations: r.iterations,
            residual: r.residual,
            seconds: r.seconds,
            energy: r.energy.total,
        }
    }
}

/// The `reference` block of the results JSON.
pub type ReferenceJson = ReferenceCheck;

impl From<&TargetCheck> for TargetJson {
    fn from(t: &TargetCheck) -> Self {
        TargetJson {
            shape: t.shape.into(),
            max_abs_radial_deviation: t.sphere.map(|d| d.max_abs_radial_deviation),
            rms_radial_deviation: t.sphere.map(|d| d.rms_radial_deviation),
            apex_height: t.sphere.map(|d| d.apex_height),
            max_abs_distance: t.mesh.map(|d| d.max_abs_distance),
            rms_distance: t.mesh.map(|d| d.rms_distance),
            mean_signed_distance: t.mesh.map(|d| d.mean_signed_distance),
            net: t.net.clone(),
            max_net_distance: t.net_distance.map(|d| d.0),
            rms_net_distance: t.net_distance.map(|d| d.1),
        }
    }
}

impl Results {
    pub fn new(eq: &Equilibrium, report: &NewtonReport) -> Results {
        let rods = eq
            .rods
            .iter()
            .map(|r| {
                let bending_stress: Vec<f64> = r.bending.iter().map(|b| b.stress).collect();
                RodJson {
                    name: r.name.clone(),
                    points: r.points.clone(),
                    twist: r.twist.clone(),
                    max_bending_stress: bending_stress.iter().copied().fold(0.0, f64::max),
                    bending_stress,
                    energy: r.energy,
                    length: r.length,
                    forces: r.forces.iter().map(EdgeForceJson::from).collect(),
                    utilization: r.utilization,
                    rest_points: r.rest_points.clone(),
                    target_distance: r.target_distance.clone().unwrap_or_default(),
                }
            })
            .collect();
        let joints = eq
            .joints
            .iter()
            .map(|(name, position)| JointJson {
                name: name.clone(),
                position: *position,
            })
            .collect();
        let reactions = eq
            .reactions
            .iter()
            .map(|s| ReactionJson {
                rod: s.rod.clone(),
                vertex: s.vertex,
                node: Some(s.node),
                kind: Some(s.kind.name().into()),
                force: s.reaction.force,
                moment: s.reaction.moment,
            })
            .collect();
        let loads = eq
            .loads
            .iter()
            .map(|l| LoadJson {
                rod: l.rod.clone(),
                vertex: l.vertex,
                node: l.node,
                force: l.force,
                moment: l.moment,
            })
            .collect();
        let (contacts, kkt) = match &eq.constraints {
            Some(c) => {
                let (contacts, kkt) = constraint_json(c);
                (Some(contacts), Some(kkt))
            }
            None => (None, None),
        };
        Results {
            converged: report.converged,
            iterations: report.iterations,
            load_steps: report.load_steps,
            residual: report.residual,
            seconds: report.seconds,
            residual_floor: report.residual_floor,
            tolerance: report.tolerance,
            stopped_at_floor: report.stopped_at_floor,
            stopped: report.stopped.clone(),
            mechanism: report.mechanism.as_ref().map(|d| MechanismJson {
                description: d.clone(),
            }),
            gauge: eq.gauge.clone(),
            continuation: (report.arc_length_steps > 0).then(|| ContinuationJson {
                kind: "arc_length".into(),
                steps: report.arc_length_steps,
                limit_points: report.limit_points.clone(),
            }),
            path_events: PathEventJson::of(report),
            energy: eq.energy.into(),
            rods,
            joints,
            reactions,
            loads,
            target: eq.target.as_ref().map(TargetJson::from),
            net: eq.target.as_ref().and_then(|t| t.net.clone()),
            reference: eq.reference.clone(),
            solver: SolverJson {
                factorizations: report.factorizations,
                regularized_iterations: report.regularized_iterations,
                saddle_escapes: report.saddle_escapes,
                stable: report.stable,
                factor_seconds: report.factor_seconds,
                free_unknowns: eq.free_unknowns,
                step_iterations: report.step_iterations.clone(),
                zero_modes: report.zero_modes,
                stability_note: report.stability_note.clone(),
                biased_iterations: report.biased_iterations,
                message: report.message.clone(),
            },
            contacts,
            kkt,
            stability: None,
            warnings: Vec::new(),
            utilization: eq.utilization.clone(),
            stage: None,
            stages: Vec::new(),
            extrapolation: None,
        }
    }

    /// Whether every number is finite. JSON has no NaN (serde_json would write `null`), so
    /// results with a non-finite number are never written.
    pub fn all_finite(&self) -> bool {
        let e = &self.energy;
        let fin = |v: &f64| v.is_finite();
        [
            self.residual,
            self.seconds,
            e.total,
            e.stretch,
            e.bend,
            e.twist,
            e.joints,
            e.external,
        ]
        .iter()
        .all(fin)
            && self.rods.iter().all(|r| {
                let re = &r.energy;
                r.points.iter().chain(&r.rest_points).flatten().all(fin)
                    && r.target_distance.iter().all(fin)
                    && r.twist.iter().all(fin)
                    && r.bending_stress.iter().all(fin)
                    && r.forces.iter().all(EdgeForceJson::all_finite)
                    && r.utilization.iter().all(fin)
                    && [r.max_bending_stress, r.length, re.total, re.stretch]
                        .iter()
                        .chain(&[re.bend, re.twist])
                        .all(fin)
            })
            && self.joints.iter().all(|j| j.position.iter().all(fin))
            && self
                .reactions
                .iter()
                .all(|r| r.force.iter().chain(&r.moment).all(fin))
            && self
                .loads
                .iter()
                .all(|l| l.force.iter().chain(&l.moment).all(fin))
            && self.target.as_ref().is_none_or(|t| {
                [
                    t.max_abs_radial_deviation,
                    t.rms_radial_deviation,
                    t.apex_height,
                    t.max_abs_distance,
                    t.rms_distance,
                    t.mean_signed_distance,
                ]
                .iter()
                .flatten()
                .all(fin)
            })
            && self.reference.as_ref().is_none_or(|r| r.error.is_finite())
            && self
                .contacts
                .iter()
                .flatten()
                .all(|c| c.force.iter().all(fin) && c.gap.is_finite())
            && self.utilization.as_ref().is_none_or(|u| u.max.is_finite())
    }
}

fn constraint_json(c: &ConstraintForces) -> (Vec<ContactJson>, KktJson) {
    let contacts = c
        .contacts
        .iter()
        .map(|f| {
            let (obstacle, bound) = match f.source {
                Source::Obstacle(i) => (Some(i), None),
                Source::Bound(i) => (None, Some(i)),
            };
            ContactJson {
                rod: f.rod.clone(),
                node: f.node,
                obstacle,
                bound,
                force: f.force,
                gap: f.gap,
            }
        })
        .collect();
    let k = &c.kkt;
    let cr = &k.report;
    let kkt = KktJson {
        primal_feasibility: k.primal_feasibility,
        primal_feasibility_relative: k.primal_feasibility_relative,
        complementarity: k.complementarity,
        complementarity_relative: k.complementarity_relative,
        min_multiplier: k.min_multiplier,
        stationarity: k.stationarity,
        active_set: k.active_set,
        constraints: k.constraints,
        qp_solves: cr.qp_solves,
        steps_without_qp: cr.steps_without_qp,
        polished_qps: cr.polished_qps,
        inexact_qps: cr.inexact_qps,
        qp_iterations: cr.qp_iterations,
        qp_seconds: cr.qp_seconds,
    };
    (contacts, kkt)
}
