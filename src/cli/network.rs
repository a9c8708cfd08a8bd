//! `rodnet solve --network NET.obj ...`: the options that turn an OBJ network into a scene, and
//! error messages that point back into the OBJ file or at the option at fault.

use std::path::PathBuf;

use clap::Args;

use crate::scene::obj_import::{self, Generated, NetworkOptions};
use crate::scene::types::{JointChoice, Scene, Solver};
use crate::scene::{self, FieldError};

/// Options of `solve` that build the scene from an OBJ network instead of a scene file.
#[derive(Args, Debug, Clone, Default)]
pub struct NetworkArgs {
    /// Build the scene from the `l` polylines of this OBJ file instead of a scene file.
    #[arg(long, value_name = "NET.obj", conflicts_with = "scene")]
    pub network: Option<PathBuf>,
    /// Young's modulus of every rod, Pa.
    #[arg(
        long,
        value_name = "PA",
        requires = "network",
        allow_negative_numbers = true
    )]
    pub young_modulus: Option<f64>,
    /// Poisson's ratio (give this or --shear-modulus).
    #[arg(
        long,
        value_name = "NU",
        requires = "network",
        allow_negative_numbers = true
    )]
    pub poisson_ratio: Option<f64>,
    /// Shear modulus, Pa (give this or --poisson-ratio).
    #[arg(
        long,
        value_name = "PA",
        requires = "network",
        allow_negative_numbers = true
    )]
    pub shear_modulus: Option<f64>,
    /// Radius of the rods' circular section, m.
    #[arg(
        long,
        value_name = "M",
        requires = "network",
        allow_negative_numbers = true
    )]
    pub radius: Option<f64>,
    /// Density, kg/m³ (for --gravity).
    #[arg(
        long,
        value_name = "KG_M3",
        requires = "network",
        allow_negative_numbers = true
    )]
    pub density: Option<f64>,
    /// Kind of the joints at points shared by several polylines [default: rigid].
    #[arg(long, value_enum, requires = "network")]
    pub joint: Option<JointChoice>,
    /// Equal edges per polyline segment [default: 1].
    #[arg(long, value_name = "K", requires = "network")]
    pub subdivide: Option<usize>,
    /// Pin every polyline vertex at or below this height z, m.
    #[arg(
        long,
        value_name = "Z",
        requires = "network",
        allow_negative_numbers = true
    )]
    pub pin_below: Option<f64>,
    /// Clamp every polyline vertex at or below this height z, m.
    #[arg(
        long,
        value_name = "Z",
        requires = "network",
        allow_negative_numbers = true
    )]
    pub clamp_below: Option<f64>,
    /// Pin the vertices of the OBJ object or group NAME (`o`/`g`; `p` points or polylines); repeatable.
    #[arg(long, value_name = "NAME", requires = "network")]
    pub pin_group: Vec<String>,
    /// Clamp the vertices of the OBJ object or group NAME; repeatable.
    #[arg(long, value_name = "NAME", requires = "network")]
    pub clamp_group: Vec<String>,
    /// Points closer than this are one point, m [default: 1e-6 × bounding-box diagonal].
    #[arg(
        long,
        value_name = "M",
        requires = "network",
        allow_negative_numbers = true
    )]
    pub weld: Option<f64>,
    /// Keep every 2-vertex `l` as its own rod instead of chaining them into rods.
    #[arg(long, requires = "network")]
    pub no_chain: bool,
    /// Weight along −z with this acceleration, m/s² (needs --density).
    #[arg(
        long,
        value_name = "G",
        requires = "network",
        allow_negative_numbers = true
    )]
    pub gravity: Option<f64>,
    /// Continuation steps for the loads [default: 1].
    #[arg(long, value_name = "N", requires = "network")]
    pub load_steps: Option<usize>,
    /// Relative residual tolerance [default: 1e-9].
    #[arg(
        long,
        value_name = "TOL",
        requires = "network",
        allow_negative_numbers = true
    )]
    pub tolerance: Option<f64>,
    /// Newton iterations allowed per load step [default: 200].
    #[arg(long, value_name = "N", requires = "network")]
    pub max_iterations: Option<usize>,
    /// Write the generated scene as RON here (it solves the same with `rodnet solve`).
    #[arg(long, value_name = "SCENE.ron", requires = "network")]
    pub scene_out: Option<PathBuf>,
    /// Only generate the scene (with --scene-out); do not solve.
    #[arg(long, requires = "scene_out")]
    pub scene_only: bool,
}

impl NetworkArgs {
    /// The first network-only option given, if any. (clap's `requires` does not fire when the
    /// required `--network` conflicts with the scene that was given, so this is checked here.)
    pub fn first_given(&self) -> Option<&'static str> {
        let a = self;
        [
            ("--young-modulus", a.young_modulus.is_some()),
            ("--poisson-ratio", a.poisson_ratio.is_some()),
            ("--shear-modulus", a.shear_modulus.is_some()),
            ("--radius", a.radius.is_some()),
            ("--density", a.density.is_some()),
            ("--joint", a.joint.is_some()),
            ("--subdivide", a.subdivide.is_some()),
            ("--pin-below", a.pin_below.is_some()),
            ("--clamp-below", a.clamp_below.is_some()),
            ("--pin-group", !a.pin_group.is_empty()),
            ("--clamp-group", !a.clamp_group.is_empty()),
            ("--weld", a.weld.is_some()),
            ("--no-chain", a.no_chain),
            ("--gravity", a.gravity.is_some()),
            ("--load-steps", a.load_steps.is_some()),
            ("--tolerance", a.tolerance.is_some()),
            ("--max-iterations", a.max_iterations.is_some()),
            ("--scene-out", a.scene_out.is_some()),
            ("--scene-only", a.scene_only),
        ]
        .into_iter()
        .find(|(_, given)| *given)
        .map(|(flag, _)| flag)
    }
}

/// A scene generated from an OBJ file, with what is needed to locate errors in it.
pub struct NetworkScene {
    pub file: String,
    pub generated: Generated,
}

impl NetworkScene {
    pub fn scene(&self) -> &Scene {
        &self.generated.scene
    }

    /// Locates an error of the generated scene in the OBJ file or names the option at fault.
    pub fn describe(&self, e: &FieldError) -> String {
        let g = &self.generated;
        let s = &g.scene;
        let file = &self.file;
        let field = if e.field.is_empty() {
            String::new()
        } else {
            format!("{}: ", e.field)
        };
        let index = match e.item {
            crate::scene::locate::Item::Index(i) => Some(i),
            _ => None,
        };
        match (e.section, index) {
            ("rods", Some(i)) if i < g.rod_lines.len() => format!(
                "{file}:{}: polyline (rod \"{}\"): {field}{}",
                g.rod_lines[i], s.rods[i].name, e.message
            ),
            ("joints", Some(i)) if i < g.joint_lines.len() => format!(
                "{file}:{}: joint \"{}\" at this vertex: {field}{}",
                g.joint_lines[i], s.joints[i].name, e.message
            ),
            ("supports", Some(i)) if i < g.support_lines.len() => format!(
                "{file}:{}: support at this vertex: {field}{}",
                g.support_lines[i], e.message
            ),
            ("materials", _) => {
                let flag = match e.field.as_str() {
                    "young_modulus" => "--young-modulus",
                    "poisson_ratio" => "--poisson-ratio",
                    "shear_modulus" => "--shear-modulus",
                    "density" => "--density",
                    "section" => "--radius",
                    _ => "material options",
                };
                format!("{flag}: {}", e.message)
            }
            ("solver", _) => {
                let flag = match e.field.as_str() {
                    "tolerance" => "--tolerance",
                    "max_iterations" => "--max-iterations",
                    _ => "--load-steps",
                };
                format!("{flag}: {}", e.message)
            }
            ("loads", _) => format!(
                "{file}: {}; supports come from --pin-below, --clamp-below, --pin-group or --clamp-group",
                e.message
            ),
            _ => format!("{file}: {}: {}", e.path(), e.message),
        }
    }
}

/// Upper bound on the size of an OBJ network file, bytes (like scene files).
const MAX_OBJ_BYTES: u64 = 1 << 30;

/// Reads the OBJ file and generates the validated scene; errors are full messages.
/// `memory`: the limit (bytes, `u64::MAX`: none) the OBJ's size is checked against.
pub fn load(path: &std::path::Path, a: &NetworkArgs, memory: u64) -> Result<NetworkScene, String> {
    let file = path.display().to_string();
    let young_modulus = a
        .young_modulus
        .ok_or("--network needs --young-modulus (Pa)")?;
    let radius = a.radius.ok_or("--network needs --radius (m)")?;
    if a.poisson_ratio.is_none() && a.shear_modulus.is_none() {
        return Err("--network needs --poisson-ratio or --shear-modulus".into());
    }
    if let Some(g) = a.gravity {
        if !(g.is_finite() && g >= 0.0) {
            return Err(format!(
                "--gravity: must be a non-negative acceleration (it acts along -z), got {g}"
            ));
        }
        if a.density.unwrap_or(0.0) == 0.0 {
            return Err("--gravity needs --density (kg/m³): the rods weigh nothing".into());
        }
    }
    let src = scene::read_text(path, "network", MAX_OBJ_BYTES).map_err(|e| e.to_string())?;
    let at = |e: obj_import::ObjError| match e.line {
        Some(l) => format!("{file}:{l}: {}", e.message),
        None => format!("{file}: {}", e.message),
    };
    obj_import::size::check(
        &src,
        a.subdivide.unwrap_or(1),
        memory,
        crate::network::budget::MIN_BYTES_PER_NODE / 2,
        crate::network::budget::bytes_text,
    )
    .map_err(at)?;
    let obj = obj_import::parse(&src).map_err(at)?;
    let defaults = Solver::default();
    let opts = NetworkOptions {
        young_modulus,
        poisson_ratio: a.poisson_ratio,
        shear_modulus: a.shear_modulus,
        density: a.density.unwrap_or(0.0),
        radius,
        joint: a
            .joint
            .unwrap_or(JointChoice::Rigid)
            .kind(young_modulus, radius),
        subdivide: a.subdivide.unwrap_or(1),
        pin_below: a.pin_below,
        clamp_below: a.clamp_below,
        pin_groups: a.pin_group.clone(),
        clamp_groups: a.clamp_group.clone(),
        weld: a.weld,
        chain: !a.no_chain,
        gravity: a.gravity,
        solver: Solver {
            tolerance: a.tolerance.or(defaults.tolerance),
            max_iterations: a.max_iterations.unwrap_or(defaults.max_iterations),
            load_steps: a.load_steps.unwrap_or(defaults.load_steps),
            time_limit: None,
            buckle_toward: None,
            continuation: Default::default(),
        },
    };
    let generated = obj_import::to_scene(&obj, &opts).map_err(at)?;
    let net = NetworkScene { file, generated };
    scene::validate::validate(net.scene()).map_err(|e| net.describe(&e))?;
    Ok(net)
}

/// The generated scene as RON, headed by where it came from.
pub fn scene_ron(net: &NetworkScene, command: &str) -> Result<String, String> {
    let cfg = ron::ser::PrettyConfig::new()
        .struct_names(true)
        .depth_limit(4);
    let body = ron::ser::to_string_pretty(net.scene(), cfg)
        .map_err(|e| format!("cannot write the scene as RON: {e}"))?;
    Ok(format!(
        "// Generated by rodnet from {} (weld tolerance {:.3e} m):\n//   {command}\n{body}\n",
        net.file, net.generated.weld_tolerance
    ))
}
