//! The RON scene format (see `docs/scene-format.md`). Names follow `docs/contract.md`
//! exactly; every type rejects unknown fields so that typos are reported, not ignored.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

pub use crate::rod::section::Section;

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    #[serde(default)]
    pub materials: BTreeMap<String, Material>,
    #[serde(default)]
    pub rods: Vec<Rod>,
    #[serde(default)]
    pub joints: Vec<Joint>,
    #[serde(default)]
    pub supports: Vec<Support>,
    #[serde(default)]
    pub loads: Vec<Load>,
    #[serde(default)]
    pub obstacles: Vec<Obstacle>,
    #[serde(default)]
    pub bounds: Vec<Bound>,
    #[serde(default)]
    pub target: Option<Target>,
    /// (extension) A known equilibrium position of one input vertex, from an analytic
    /// solution: `rodnet study convergence` measures the discretization error against it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reference: Option<Reference>,
    #[serde(default)]
    pub solver: Solver,
    /// (extension) Later load stages, each solved from the equilibrium of the one before with
    /// its loads added to everything before it (docs/scene-format.md, "Stages").
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub stages: Vec<Stage>,
}

/// A load stage: loads added, from the previous stage's equilibrium, to all loads before.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Stage {
    /// Letters, digits, `-` and `_` (it names the stage's output files).
    pub name: String,
    #[serde(default)]
    pub loads: Vec<Load>,
    /// How this stage's path is followed (default: the scene's `solver.continuation`): e.g. an
    /// erection under load control, then a load stage under arc length through its limit point.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub continuation: Option<Continuation>,
}

impl Scene {
    /// The scene of stage `k` (0: the scene's own loads; k: those plus the loads of stages
    /// 1 … k), with no stages of its own.
    pub fn stage(&self, k: usize) -> Scene {
        let mut s = self.clone();
        s.stages.clear();
        for st in self.stages.iter().take(k) {
            s.loads.extend(st.loads.iter().cloned());
        }
        s
    }

    /// The scene with every stage's loads applied at once (commands that solve one load case).
    pub fn all_stages(&self) -> Scene {
        self.stage(self.stages.len())
    }

    /// The name of stage `k`: "base" for the scene's own loads.
    pub fn stage_name(&self, k: usize) -> &str {
        match k {
            0 => "base",
            _ => &self.stages[k - 1].name,
        }
    }
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Material {
    /// Pa.
    pub young_modulus: f64,
    /// Dimensionless, in (−1, 0.5]; exactly one of `poisson_ratio` and `shear_modulus`.
    #[serde(default)]
    pub poisson_ratio: Option<f64>,
    /// Pa.
    #[serde(default)]
    pub shear_modulus: Option<f64>,
    /// kg/m³.
    #[serde(default)]
    pub density: f64,
    pub section: Section,
    /// Pa (optional): the results then report each rod's utilization (docs/internal-forces.md).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub yield_strength: Option<f64>,
}

impl Material {
    pub fn shear(&self) -> f64 {
        match (self.shear_modulus, self.poisson_ratio) {
            (Some(g), _) => g,
            (None, Some(nu)) => self.young_modulus / (2.0 * (1.0 + nu)),
            (None, None) => self.young_modulus / 3.0,
        }
    }
}

fn one() -> usize {
    1
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Rod {
    pub name: String,
    pub material: String,
    /// Rest centreline, m.
    pub points: Vec<[f64; 3]>,
    #[serde(default = "one")]
    pub subdivide: usize,
    #[serde(default)]
    pub closed: bool,
    /// First material axis at the first edge (projected onto the plane normal to it).
    #[serde(default)]
    pub normal: Option<[f64; 3]>,
    /// (extension) Gregory's end correction of the bending weights beside clamps and joints
    /// (`network/build/end_weights.rs`); `false` keeps the plain Voronoi weights.
    #[serde(default = "yes", skip_serializing_if = "is_yes")]
    pub end_correction: bool,
}

fn yes() -> bool {
    true
}

fn is_yes(b: &bool) -> bool {
    *b
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Joint {
    pub name: String,
    pub at: Vec<(String, usize)>,
    pub kind: JointKind,
    /// Hinge axis (default: cross product of the first two incident tangents).
    #[serde(default)]
    pub normal: Option<[f64; 3]>,
}

/// A joint kind without parameters, as the CLI (`--joint`), the generated scenes (hemisphere,
/// fitted and OBJ networks) and Python name it; `JointChoice::kind` (`network/joint/`) makes the
/// scene's [`JointKind`] of it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum JointChoice {
    Rigid,
    Hinge,
    Ball,
    /// The VPS joint of Baek et al. 2018 scaled to the rods (docs/gridshell.md).
    Elastic,
}

impl JointChoice {
    pub const ALL: [JointChoice; 4] = [
        JointChoice::Rigid,
        JointChoice::Hinge,
        JointChoice::Ball,
        JointChoice::Elastic,
    ];

    /// Its name in `--joint`, sweep files and Python.
    pub fn name(self) -> &'static str {
        match self {
            JointChoice::Rigid => "rigid",
            JointChoice::Hinge => "hinge",
            JointChoice::Ball => "ball",
            JointChoice::Elastic => "elastic",
        }
    }

    pub fn from_name(name: &str) -> Option<JointChoice> {
        JointChoice::ALL.into_iter().find(|j| j.name() == name)
    }
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum JointKind {
    Rigid,
    Hinge,
    Ball,
    /// Written `Elastic(bending: .., twist: .., scissor: ..)` or `Elastic(cylinder: ..)`; see
    /// [`ElasticJoint`] for the fields.
    Elastic {
        #[serde(default)]
        bending: Option<f64>,
        #[serde(default)]
        twist: Option<f64>,
        #[serde(default)]
        scissor: Option<f64>,
        #[serde(default)]
        cylinder: Option<JointCylinder>,
        #[serde(default)]
        translation: Option<f64>,
    },
}

impl JointKind {
    /// The elastic joint's parameters, if this is one.
    pub fn elastic(&self) -> Option<ElasticJoint> {
        match self {
            JointKind::Elastic {
                bending,
                twist,
                scissor,
                cylinder,
                translation,
            } => Some(ElasticJoint {
                bending: *bending,
                twist: *twist,
                scissor: *scissor,
                cylinder: cylinder.clone(),
                translation: *translation,
            }),
            _ => None,
        }
    }

    pub fn from_elastic(e: ElasticJoint) -> JointKind {
        JointKind::Elastic {
            bending: e.bending,
            twist: e.twist,
            scissor: e.scissor,
            cylinder: e.cylinder,
            translation: e.translation,
        }
    }
}

/// Elastic joint: rotational springs between each incident rod's frame and the joint's frame,
/// about the rod's bending axes, its twist axis, and the joint normal (scissor).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ElasticJoint {
    /// N·m/rad.
    #[serde(default)]
    pub bending: Option<f64>,
    /// N·m/rad.
    #[serde(default)]
    pub twist: Option<f64>,
    /// N·m/rad.
    #[serde(default)]
    pub scissor: Option<f64>,
    /// Derive the three stiffnesses from a joint cylinder instead.
    #[serde(default)]
    pub cylinder: Option<JointCylinder>,
    /// N/m; when given, each rod keeps its own node at the joint, tied to the joint's centre by a
    /// spring of this stiffness. Default: the rods share one node.
    #[serde(default)]
    pub translation: Option<f64>,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JointCylinder {
    pub young_modulus: f64,
    #[serde(default)]
    pub poisson_ratio: Option<f64>,
    pub diameter: f64,
    pub height: f64,
}

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum SupportKind {
    Pin,
    Clamp,
    /// The node stays on the plane through its position (or its `move_to`) with this normal,
    /// free within it. Normals along x, y or z only (docs/scene-format.md).
    Roller {
        normal: [f64; 3],
    },
    /// Springs to the node's rest position (or its `move_to`), N/m, and rotational springs to
    /// its rest orientation (or its `rotate_by`), N·m/rad, along `axes` (default the world's);
    /// a zero stiffness leaves that direction free.
    Spring {
        #[serde(default)]
        stiffness: [f64; 3],
        #[serde(default)]
        rotational: Option<[f64; 3]>,
        #[serde(default)]
        axes: Option<[[f64; 3]; 3]>,
    },
}

impl SupportKind {
    /// The coordinate axis a Roller holds (its normal's one non-zero component).
    /// A Spring's axes (the world's unless given), unit length.
    pub fn spring_axes(&self) -> [[f64; 3]; 3] {
        match self {
            SupportKind::Spring { axes: Some(a), .. } => a.map(|v| {
                let n = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
                v.map(|x| x / n)
            }),
            _ => [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        }
    }

    /// A Spring's rotational stiffnesses, if it has any that are not zero.
    pub fn rotational_stiffness(&self) -> Option<[f64; 3]> {
        match self {
            SupportKind::Spring {
                rotational: Some(k),
                ..
            } if k.iter().any(|x| *x != 0.0) => Some(*k),
            _ => None,
        }
    }

    pub fn roller_axis(&self) -> Option<usize> {
        match self {
            SupportKind::Roller { normal } => {
                let nz: Vec<usize> = (0..3).filter(|&k| normal[k] != 0.0).collect();
                (nz.len() == 1).then(|| nz[0])
            }
            _ => None,
        }
    }
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Support {
    pub rod: String,
    pub vertex: usize,
    pub kind: SupportKind,
    #[serde(default)]
    pub move_to: Option<[f64; 3]>,
    /// Clamps only: rotate the clamp's frame by this rotation vector (axis × angle, rad) over
    /// the load steps.
    #[serde(default)]
    pub rotate_by: Option<[f64; 3]>,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Load {
    /// N.
    Force {
        rod: String,
        vertex: usize,
        force: [f64; 3],
    },
    /// m/s².
    Gravity { g: [f64; 3] },
    /// N·m.
    Torque {
        rod: String,
        vertex: usize,
        torque: [f64; 3],
    },
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Obstacle {
    /// Half-space: the side `normal` points to is free (m).
    Plane { point: [f64; 3], normal: [f64; 3] },
    /// Solid ball (m).
    Sphere { center: [f64; 3], radius: f64 },
    /// Solid infinite circular cylinder around the line through `point` along `axis` (m).
    Cylinder {
        point: [f64; 3],
        axis: [f64; 3],
        radius: f64,
    },
}

/// Simple bounds on node coordinates (m): `min[k] <= x[k] <= max[k]` for each given component,
/// on the centreline nodes of one rod (or of every rod), optionally only at some input vertices.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Bound {
    /// Rod whose nodes are bounded; default every rod.
    #[serde(default)]
    pub rod: Option<String>,
    /// Input vertices of `rod` (vertex k is node k·subdivide); default every node of the rod.
    #[serde(default)]
    pub vertices: Option<Vec<usize>>,
    #[serde(default)]
    pub min: [Option<f64>; 3],
    #[serde(default)]
    pub max: [Option<f64>; 3],
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Target {
    Sphere {
        center: [f64; 3],
        radius: f64,
    },
    /// A triangle mesh in an OBJ file, `path` relative to the scene file.
    Mesh {
        path: String,
        /// The mesh, once read and checked (`scene::parse` reads it).
        #[serde(skip)]
        surface: LoadedSurface,
    },
}

/// A target mesh read from its file. Equal whenever the paths are: the mesh is the file's.
#[derive(Clone, Default)]
pub struct LoadedSurface(pub Option<std::sync::Arc<crate::surface::Surface>>);

impl PartialEq for LoadedSurface {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

impl std::fmt::Debug for LoadedSurface {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match &self.0 {
            Some(s) => write!(f, "{s:?}"),
            None => write!(f, "(not read)"),
        }
    }
}

/// The equilibrium position of input vertex `vertex` of rod `rod`, m (vertex k is node
/// k·subdivide, so it exists at every subdivision).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Reference {
    pub rod: String,
    pub vertex: usize,
    pub position: [f64; 3],
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Solver {
    /// Relative residual tolerance; None: automatic, `DEFAULT_TOLERANCE` or the round-off floor
    /// of the final state where that is higher (docs/scene-format.md).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tolerance: Option<f64>,
    #[serde(default = "default_max_iterations")]
    pub max_iterations: usize,
    #[serde(default = "one")]
    pub load_steps: usize,
    /// Seconds after which the solve stops with its last iterate.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub time_limit: Option<f64>,
    /// Which side a symmetric problem leaves its symmetric state toward (a direction in space);
    /// the final equilibrium is the unperturbed problem's (docs/design.md).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub buckle_toward: Option<[f64; 3]>,
    /// `Load` (default: increments of the load factor) or `ArcLength` (through limit points).
    #[serde(default, skip_serializing_if = "is_load")]
    pub continuation: Continuation,
}

/// How the path from the rest state to the full loads is followed.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum Continuation {
    /// Increments of the load factor, adaptive.
    #[default]
    Load,
    /// Pseudo-arclength: follows the path through limit points (snap-through).
    ArcLength,
}

fn is_load(c: &Continuation) -> bool {
    *c == Continuation::Load
}

pub const DEFAULT_TOLERANCE: f64 = 1e-9;

fn default_max_iterations() -> usize {
    1000
}

impl Default for Solver {
    fn default() -> Self {
        Solver {
            tolerance: None,
            max_iterations: default_max_iterations(),
            load_steps: 1,
            time_limit: None,
            buckle_toward: None,
            continuation: Continuation::Load,
        }
    }
}
