//! `rodnet gridshell hemisphere`: the options, their checks, and the job (footprint scene,
//! form finding, report).

use std::path::{Path, PathBuf};

use clap::Args;

use super::output::{atomic_write, bad, check_outputs_creating, diagnostic, given, vtk_bytes};
use super::output::{EXIT_NOT_CONVERGED, EXIT_OK};
use super::progress::{self, show_progress};
use crate::gridshell::footprint::{self, HemisphereSpec, JointChoice};
use crate::gridshell::formfind::{FormPath, DEFAULT_START_CAP};
use crate::gridshell::job as gridshell_job;
use crate::io::{atomic, obj};
use crate::scene::types::{Scene, Section};
use crate::scene::{self, FieldError};

/// `--path` of `rodnet gridshell hemisphere`.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum PathArg {
    CapNets,
    Straight,
}

/// Default rods per family of the gridshell job.
pub const DEFAULT_RODS: usize = 12;
/// Default edges per segment between crossings of the gridshell job.
pub const DEFAULT_SUBDIVIDE: usize = 4;
/// Largest n accepted (the net generator is tested up to 200).
pub const MAX_RODS: usize = 200;
/// Range of --radius, m.
pub const MIN_RADIUS: f64 = 1e-6;
pub const MAX_RADIUS: f64 = 1e6;
/// Largest --section dimension, in units of R.
pub const MAX_SECTION_RATIO: f64 = 1.0;

#[derive(Args, Debug)]
pub struct HemisphereArgs {
    /// Sphere radius R, m.
    #[arg(long, default_value_t = 1.0)]
    pub radius: f64,
    /// Rods per family n.
    #[arg(long, default_value_t = DEFAULT_RODS)]
    pub rods: usize,
    /// Equal edges per segment between neighbouring crossings (and between the last crossing
    /// and a rod end).
    #[arg(long, default_value_t = DEFAULT_SUBDIVIDE)]
    pub subdivide: usize,
    /// Joint at every crossing.
    #[arg(long, value_enum, default_value_t = JointChoice::Ball)]
    pub joint: JointChoice,
    /// Rod cross-section, dimensions in units of R: circle:r, ellipse:a,b or rectangle:w,h
    /// (the first dimension lies tangent to the shell).
    #[arg(long, default_value = "circle:0.005", value_parser = parse_section)]
    pub section: SectionRatio,
    /// Young's modulus E, Pa (the shape does not depend on it).
    #[arg(long, default_value_t = 1e9)]
    pub young_modulus: f64,
    /// Poisson's ratio ν (shear modulus E/(2(1+ν))).
    #[arg(long, default_value_t = 0.3)]
    pub poisson_ratio: f64,
    /// Steps of the ends through caps of growing curvature, from the starting cap to the
    /// hemisphere (a step that does not converge is halved; with --start-cap 0, steps of the
    /// solver's straight-line continuation).
    #[arg(long, default_value_t = 1)]
    pub load_steps: usize,
    /// Relative residual tolerance [default: automatic, 1e-9 or the round-off floor where
    /// higher] (see docs/scene-format.md).
    #[arg(long)]
    pub tolerance: Option<f64>,
    /// Radius of the shallow cap, over R, onto which the footprint is first bent (upward and
    /// without stretching) to break the up-down symmetry; 0 starts from the flat footprint.
    #[arg(long, default_value_t = DEFAULT_START_CAP)]
    pub start_cap: f64,
    /// How the rod ends travel from the starting cap to the equator: through the nets of caps
    /// of growing curvature, or on straight lines (docs/gridshell.md).
    #[arg(long, value_enum, default_value_t = PathArg::CapNets)]
    pub path: PathArg,
    /// Write the footprint scene (RON) here; alone, without other outputs, nothing is solved.
    #[arg(long)]
    pub scene_out: Option<PathBuf>,
    /// Write the results JSON here.
    #[arg(long)]
    pub json: Option<PathBuf>,
    /// Write the equilibrium as OBJ polylines here.
    #[arg(long)]
    pub obj: Option<PathBuf>,
    /// Write the equilibrium as VTK XML here (.vtp or .vtu, as `rodnet solve --vtk`).
    #[arg(long, value_name = "F.vtp", value_parser = super::output::vtk_path)]
    pub vtk: Option<PathBuf>,
    /// Write the text report here.
    #[arg(long)]
    pub report: Option<PathBuf>,
    /// Write hemisphere.json, hemisphere.obj and hemisphere.txt into this directory (the
    /// default, into the current directory, applies when no output option is given).
    #[arg(long)]
    pub out_dir: Option<PathBuf>,
    /// Eigen-analysis of the dome: the lowest K eigenvalues (N/m) as a "stability" block in the
    /// results JSON, as for `rodnet solve --modes`.
    #[arg(long, value_name = "K", value_parser = clap::value_parser!(u32).range(1..=200))]
    pub modes: Option<u32>,
    /// No progress output.
    #[arg(long)]
    pub quiet: bool,
    #[command(flatten)]
    pub limits: super::LimitArgs,
}

/// A cross-section with its dimensions in units of the sphere radius.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SectionRatio(pub Section);

impl SectionRatio {
    fn dims(self) -> Vec<f64> {
        match self.0 {
            Section::Circle { radius } => vec![radius],
            Section::Ellipse { a, b } => vec![a, b],
            Section::Rectangle { width, height } => vec![width, height],
        }
    }

    fn scaled(self, r: f64) -> Section {
        match self.0 {
            Section::Circle { radius } => Section::Circle { radius: radius * r },
            Section::Ellipse { a, b } => Section::Ellipse { a: a * r, b: b * r },
            Section::Rectangle { width, height } => Section::Rectangle {
                width: width * r,
                height: height * r,
            },
        }
    }
}

pub(super) fn parse_section(s: &str) -> Result<SectionRatio, String> {
    let (kind, dims) = s
        .split_once(':')
        .ok_or_else(|| format!("expected circle:r, ellipse:a,b or rectangle:w,h, got {s:?}"))?;
    let dims: Vec<f64> = dims
        .split(',')
        .map(|d| {
            d.trim()
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite() && *v > 0.0)
                .ok_or_else(|| format!("section dimension {d:?} is not a positive number"))
        })
        .collect::<Result<_, _>>()?;
    let section = match (kind, dims.as_slice()) {
        ("circle", &[radius]) => Section::Circle { radius },
        ("ellipse", &[a, b]) => Section::Ellipse { a, b },
        ("rectangle", &[width, height]) => Section::Rectangle { width, height },
        _ => {
            return Err(format!(
                "expected circle:r, ellipse:a,b or rectangle:w,h, got {s:?}"
            ))
        }
    };
    Ok(SectionRatio(section))
}

/// Checks the numbers clap cannot check by type.
pub fn hemisphere_spec(a: &HemisphereArgs) -> Result<HemisphereSpec, String> {
    let positive = |x: f64| x.is_finite() && x > 0.0;
    // Every length of the footprint is R times a ratio of order one; outside this range its
    // squares and the section's rigidities (r⁴ E) leave the doubles, and the net's sizes with
    // them (a non-finite length once asked for endless subdivisions).
    if !(MIN_RADIUS..=MAX_RADIUS).contains(&a.radius) {
        return Err(format!(
            "--radius must lie in [{MIN_RADIUS:e}, {MAX_RADIUS:e}] m, got {:e}",
            a.radius
        ));
    }
    if !(1..=MAX_RODS).contains(&a.rods) {
        return Err(format!("--rods must be in 1..={MAX_RODS}, got {}", a.rods));
    }
    if a.subdivide == 0 {
        return Err("--subdivide must be at least 1".into());
    }
    let nodes = crate::gridshell::footprint::estimated_nodes(a.rods, a.subdivide);
    if nodes > scene::validate::MAX_NODES {
        return Err(format!(
            "--rods {} --subdivide {} would give about {} nodes (1.5 n² K), above the limit \
             of {}; reduce --subdivide",
            a.rods,
            a.subdivide,
            nodes,
            scene::validate::MAX_NODES
        ));
    }
    if let Some(d) = a
        .section
        .dims()
        .into_iter()
        .find(|&d| d > MAX_SECTION_RATIO)
    {
        return Err(format!(
            "--section dimensions are in units of R and must be at most {MAX_SECTION_RATIO} \
             (a rod as thick as the sphere), got {d:e}"
        ));
    }
    if !(positive(a.young_modulus) && a.young_modulus <= scene::validate::MAX_MAGNITUDE) {
        return Err(format!(
            "--young-modulus must be positive and finite (at most {:e} Pa), got {}",
            scene::validate::MAX_MAGNITUDE,
            a.young_modulus
        ));
    }
    if !(a.poisson_ratio.is_finite() && a.poisson_ratio > -1.0 && a.poisson_ratio <= 0.5) {
        return Err(format!(
            "--poisson-ratio must lie in (-1, 0.5], got {}",
            a.poisson_ratio
        ));
    }
    if a.load_steps == 0 || a.load_steps > scene::validate::MAX_LOAD_STEPS {
        return Err(format!(
            "--load-steps must be in 1..={}",
            scene::validate::MAX_LOAD_STEPS
        ));
    }
    if let Some(t) = a.tolerance.filter(|t| !positive(*t)) {
        return Err(format!("--tolerance must be positive, got {t}"));
    }
    if !(a.start_cap == 0.0 || (a.start_cap.is_finite() && a.start_cap >= 1.0)) {
        return Err(format!(
            "--start-cap must be 0 (flat start), 1 (the analytic net) or a finite ratio above 1, got {}",
            a.start_cap
        ));
    }
    let mut spec = HemisphereSpec::new(a.radius, a.rods, a.subdivide);
    spec.path = match a.path {
        PathArg::CapNets => FormPath::CapNets,
        PathArg::Straight => FormPath::Straight,
    };
    spec.joint = a.joint;
    spec.section = a.section.scaled(a.radius);
    spec.young_modulus = a.young_modulus;
    spec.poisson_ratio = a.poisson_ratio;
    spec.load_steps = a.load_steps;
    spec.tolerance = a.tolerance;
    Ok(spec)
}

/// The result files of the job.
struct Outputs {
    json: Option<PathBuf>,
    obj: Option<PathBuf>,
    report: Option<PathBuf>,
    /// Where the default names go (--out-dir, or the current directory when no output option
    /// is given); created, if need be, only once everything has been checked.
    dir: Option<PathBuf>,
}

impl Outputs {
    fn list<'a>(&'a self, a: &'a HemisphereArgs) -> Vec<(&'static str, &'a Path)> {
        given(&[
            ("--scene-out", &a.scene_out),
            ("--json", &self.json),
            ("--obj", &self.obj),
            ("--vtk", &a.vtk),
            ("--report", &self.report),
        ])
    }
}

/// The files asked for, with the default names in --out-dir (or the current directory when no
/// output option is given).
fn outputs(a: &HemisphereArgs) -> Result<Outputs, String> {
    let explicit = a.json.is_some()
        || a.obj.is_some()
        || a.report.is_some()
        || a.scene_out.is_some()
        || a.vtk.is_some();
    let dir = match (&a.out_dir, explicit) {
        (Some(d), _) => Some(d.clone()),
        (None, false) => Some(PathBuf::from(".")),
        (None, true) => None,
    };
    if let Some(d) = &dir {
        if d.exists() && !d.is_dir() {
            return Err(format!(
                "--out-dir {}: exists and is not a directory",
                d.display()
            ));
        }
    }
    let mut out = Outputs {
        json: a.json.clone(),
        obj: a.obj.clone(),
        report: a.report.clone(),
        dir,
    };
    if let Some(d) = &out.dir {
        out.json.get_or_insert_with(|| d.join("hemisphere.json"));
        out.obj.get_or_insert_with(|| d.join("hemisphere.obj"));
        out.report.get_or_insert_with(|| d.join("hemisphere.txt"));
    }
    Ok(out)
}

fn invalid(spec: &HemisphereSpec, e: &FieldError) -> String {
    if let Some(rest) = e.message.strip_prefix(crate::network::budget::REFUSAL) {
        // The generated scene's sizes come from the options, not from a rod the user wrote.
        return format!(
            "--rods {} --subdivide {}: the gridshell is too large for the memory limit{} \
             (reduce --rods or --subdivide, or raise --max-memory)",
            spec.rods,
            spec.subdivide,
            rest.split(" (this rod has").next().unwrap_or(rest)
        );
    }
    format!(
        "the generated scene is invalid: {}: {}",
        e.path(),
        e.message
    )
}

/// Writes the footprint scene (validated), headed by how it was made.
fn write_scene(spec: &HemisphereSpec, scene: &Scene, p: &Path) -> Result<(), String> {
    let text = format!(
        "// Hemispherical Chebyshev-net gridshell footprint, written by `rodnet gridshell hemisphere`:\n\
         // R = {} m, {} rods per family, subdivide {}, {} joints. The rods lie flat in z = 0 and\n\
         // `move_to` brings each rod end onto the equator. The scene is symmetric under z -> -z:\n\
         // the dome and its mirror image solve it equally. `rodnet gridshell hemisphere` selects\n\
         // the dome by starting from the footprint bent onto a shallow cap (docs/gridshell.md).\n{}\n",
        spec.radius,
        spec.rods,
        spec.subdivide,
        spec.joint.name(),
        footprint::to_ron(scene)
    );
    atomic_write(p, text.as_bytes())
}

pub(super) fn run(a: HemisphereArgs) -> i32 {
    let spec = match hemisphere_spec(&a) {
        Ok(s) => s,
        Err(e) => return bad(e),
    };
    // Everything that can be refused is checked before the output directory is created.
    let out = match outputs(&a) {
        Ok(o) => o,
        Err(e) => return bad(e),
    };
    let creating = out.dir.as_deref().filter(|d| !d.is_dir());
    if let Err(e) = check_outputs_creating(&out.list(&a), &[], creating) {
        return bad(e);
    }
    let fp = footprint::footprint(&spec);
    if let Err(e) = scene::validate::validate(&fp.scene) {
        return bad(invalid(&spec, &e));
    }
    if let Some(d) = creating {
        if let Err(e) = std::fs::create_dir_all(d) {
            return bad(format_args!("cannot create {}: {e}", d.display()));
        }
    }
    if let Some(p) = &a.scene_out {
        if let Err(e) = write_scene(&spec, &fp.scene, p) {
            return bad(e);
        }
    }
    if out.json.is_none() && out.obj.is_none() && out.report.is_none() && a.vtk.is_none() {
        return EXIT_OK;
    }

    let tracker = progress::Tracker::begin(spec.load_steps, show_progress(a.quiet));
    let result = gridshell_job::run(&spec, a.start_cap, Some(tracker.hook()));
    tracker.finish();
    let mut run = match result {
        Ok(r) => r,
        Err(e) => return bad(invalid(&spec, &e)),
    };
    if let (Some(k), true) = (a.modes, run.results.all_finite()) {
        match crate::network::stability::analyse(&mut run.network, k as usize) {
            Ok(st) => run.results.stability = Some((&st).into()),
            Err(e) => return bad(format_args!("eigen-analysis: {e}")),
        }
    }
    let r = &run.results;
    let diagnostic = diagnostic(&r.solver.message);
    if !r.all_finite() {
        eprintln!(
            "error: the form finding produced non-finite values ({diagnostic}); no results written"
        );
        return EXIT_NOT_CONVERGED;
    }
    let summary = run.summary();
    let mut files: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    if let Some(p) = out.json {
        files.push((p, run.to_json()));
    }
    if let Some(p) = out.obj {
        files.push((p, obj::to_obj(r).into_bytes()));
    }
    if let Some(p) = &a.vtk {
        match vtk_bytes(p, r) {
            Ok(b) => files.push((p.clone(), b)),
            Err(e) => return bad(e),
        }
    }
    if let Some(p) = out.report {
        files.push((p, summary.clone().into_bytes()));
    }
    if let Err((p, e)) = atomic::write_all(&files) {
        return bad(format_args!("cannot write {}: {e}", p.display()));
    }
    print!("{summary}");
    if r.converged {
        EXIT_OK
    } else {
        eprintln!("rodnet: form finding did not converge: {diagnostic}");
        EXIT_NOT_CONVERGED
    }
}
