//! The `rodnet` command line (see docs/cli.md and docs/contract.md).

mod network;
mod plot;
pub mod progress;
mod study;

use std::io::IsTerminal;
use std::path::{Path, PathBuf};

use clap::{Args, Parser, Subcommand};

use crate::gridshell::footprint::{self, HemisphereSpec, JointChoice};
use crate::gridshell::formfind::{FormPath, DEFAULT_START_CAP};
use crate::gridshell::job as gridshell_job;
use crate::io::{atomic, csv, obj};
use crate::pipeline as job;
use crate::scene::types::Section;
use crate::scene::{self, FieldError, Scene, SceneError};

pub use network::{JointArg, NetworkArgs};
pub use plot::PlotArgs;

/// `--path` of `rodnet gridshell hemisphere`.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum PathArg {
    CapNets,
    Straight,
}
pub use study::{ConvergenceArgs, StudyCommand};

#[derive(Parser, Debug)]
#[command(
    name = "rodnet",
    version,
    about = "Discrete Elastic Rods statics for rod networks and gridshells"
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

// Parsed once per process, so the size of the `Solve` variant's options does not matter.
#[allow(clippy::large_enum_variant)]
#[derive(Subcommand, Debug)]
pub enum Command {
    /// Solve a scene (or an OBJ network, with --network) for its static equilibrium.
    Solve {
        /// Scene file (RON).
        #[arg(required_unless_present = "network")]
        scene: Option<PathBuf>,
        /// Write the results JSON here.
        #[arg(long)]
        json: Option<PathBuf>,
        /// Write the equilibrium as OBJ polylines here.
        #[arg(long)]
        obj: Option<PathBuf>,
        /// Write one CSV row per node here.
        #[arg(long)]
        csv: Option<PathBuf>,
        /// No progress output.
        #[arg(long)]
        quiet: bool,
        #[command(flatten)]
        network: NetworkArgs,
    },
    /// Draw a results JSON as a PNG: orthographic views, rods coloured by bending stress.
    Plot(PlotArgs),
    /// Elastic gridshells: generate, form-find and compare with the analytic shape.
    Gridshell {
        #[command(subcommand)]
        shape: GridshellCommand,
    },
    /// Studies that solve a problem many times: convergence under subdivision.
    Study {
        #[command(subcommand)]
        study: StudyCommand,
    },
}

#[derive(Subcommand, Debug)]
pub enum GridshellCommand {
    /// Hemispherical Chebyshev-net gridshell (Baek et al., PNAS 2018): builds the flat footprint
    /// from straight rods, moves the rod ends onto the equator, and compares the dome with the
    /// sphere and the net. With no output options it writes hemisphere.json, hemisphere.obj and
    /// hemisphere.txt into the current directory (or --out-dir).
    Hemisphere(HemisphereArgs),
}

/// Default rods per family of the gridshell job.
pub const DEFAULT_RODS: usize = 12;
/// Default edges per segment between crossings of the gridshell job.
pub const DEFAULT_SUBDIVIDE: usize = 4;
/// Largest n accepted (the net generator is tested up to 200).
pub const MAX_RODS: usize = 200;

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
    #[arg(long, value_enum, default_value_t = JointArg::Ball)]
    pub joint: JointArg,
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
    /// Relative residual tolerance (see docs/scene-format.md).
    #[arg(long, default_value_t = 1e-9)]
    pub tolerance: f64,
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
    /// Write the text report here.
    #[arg(long)]
    pub report: Option<PathBuf>,
    /// Write hemisphere.json, hemisphere.obj and hemisphere.txt into this directory (the
    /// default, into the current directory, applies when no output option is given).
    #[arg(long)]
    pub out_dir: Option<PathBuf>,
    /// No progress output.
    #[arg(long)]
    pub quiet: bool,
}

/// A cross-section with its dimensions in units of the sphere radius.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SectionRatio(pub Section);

impl SectionRatio {
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

fn parse_section(s: &str) -> Result<SectionRatio, String> {
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

/// Exit codes of the contract.
pub const EXIT_OK: i32 = 0;
pub const EXIT_NOT_CONVERGED: i32 = 1;
pub const EXIT_BAD_INPUT: i32 = 2;

pub fn show_progress(quiet: bool) -> bool {
    !quiet && std::io::stderr().is_terminal()
}

pub fn run(cli: Cli) -> i32 {
    match cli.command {
        Command::Solve {
            scene,
            json,
            obj,
            csv,
            quiet,
            network,
        } => {
            let outputs = Outputs { json, obj, csv };
            match (scene, &network.network) {
                (Some(path), _) => match network.first_given() {
                    Some(flag) => bad(format_args!(
                        "{flag} builds a scene from --network NET.obj; it does not apply to the \
                         scene file {} (edit the scene instead)",
                        path.display()
                    )),
                    None => solve(&path, outputs, quiet),
                },
                (None, Some(net)) => solve_network(&net.clone(), &network, outputs, quiet),
                // clap requires one of the two.
                (None, None) => EXIT_BAD_INPUT,
            }
        }
        Command::Gridshell {
            shape: GridshellCommand::Hemisphere(args),
        } => hemisphere(args),
        Command::Plot(args) => plot::run(&args),
        Command::Study {
            study: StudyCommand::Convergence(args),
        } => study::run(&args),
    }
}

/// Where the scene came from, to turn errors found while building it into messages.
enum Source {
    Scene { file: String, src: String },
    Network(Box<network::NetworkScene>),
}

impl Source {
    fn describe(&self, e: &FieldError) -> String {
        match self {
            Source::Scene { file, src } => SceneError::from_field(file, src, e).to_string(),
            Source::Network(n) => n.describe(e),
        }
    }
}

struct Outputs {
    json: Option<PathBuf>,
    obj: Option<PathBuf>,
    csv: Option<PathBuf>,
}

impl Outputs {
    fn list(&self) -> Vec<(&'static str, &Path)> {
        [
            ("--json", &self.json),
            ("--obj", &self.obj),
            ("--csv", &self.csv),
        ]
        .into_iter()
        .filter_map(|(f, p)| p.as_deref().map(|p| (f, p)))
        .collect()
    }
}

fn atomic_write(p: &Path, bytes: &[u8]) -> Result<(), String> {
    atomic::write(p, bytes).map_err(|e| format!("cannot write {}: {e}", p.display()))
}

fn bad(msg: impl std::fmt::Display) -> i32 {
    eprintln!("error: {msg}");
    EXIT_BAD_INPUT
}

fn solve(path: &Path, outputs: Outputs, quiet: bool) -> i32 {
    if let Err(e) = check_outputs(&outputs.list(), &[path]) {
        return bad(e);
    }
    let (sc, src) = match scene::load(path) {
        Ok(s) => s,
        Err(e) => return bad(e),
    };
    let source = Source::Scene {
        file: path.display().to_string(),
        src,
    };
    solve_and_write(&path.display().to_string(), &sc, &source, outputs, quiet)
}

fn solve_network(path: &Path, args: &NetworkArgs, outputs: Outputs, quiet: bool) -> i32 {
    let mut all = outputs.list();
    if let Some(p) = &args.scene_out {
        all.push(("--scene-out", p));
    }
    if let Err(e) = check_outputs(&all, &[path]) {
        return bad(e);
    }
    let net = match network::load(path, args) {
        Ok(n) => n,
        Err(e) => return bad(e),
    };
    if let Some(p) = &args.scene_out {
        let command: Vec<String> = std::env::args().collect();
        let text = match network::scene_ron(&net, &command.join(" ")) {
            Ok(t) => t,
            Err(e) => return bad(e),
        };
        if let Err(e) = atomic_write(p, text.as_bytes()) {
            return bad(e);
        }
        if args.scene_only {
            return EXIT_OK;
        }
    }
    let scene = net.scene().clone();
    let label = path.display().to_string();
    solve_and_write(
        &label,
        &scene,
        &Source::Network(Box::new(net)),
        outputs,
        quiet,
    )
}

/// Refuses outputs that would certainly fail or destroy an input, before any work is done: a
/// missing directory, a directory as file name, the same file twice, an output over an input.
fn check_outputs(outputs: &[(&str, &Path)], inputs: &[&Path]) -> Result<(), String> {
    let id = |p: &Path| -> Option<PathBuf> {
        let name = p.file_name()?;
        let dir = match p.parent().filter(|d| !d.as_os_str().is_empty()) {
            Some(d) => d.canonicalize().ok()?,
            None => std::env::current_dir().ok()?,
        };
        Some(dir.join(name))
    };
    let inputs: Vec<PathBuf> = inputs.iter().filter_map(|p| id(p)).collect();
    let mut seen: Vec<(&str, PathBuf)> = Vec::new();
    for &(flag, p) in outputs {
        let shown = p.display();
        if p.file_name().is_none() {
            return Err(format!("{flag} {shown}: not a file name"));
        }
        if let Some(d) = p.parent().filter(|d| !d.as_os_str().is_empty()) {
            if !d.is_dir() {
                return Err(format!(
                    "{flag} {shown}: directory {} does not exist",
                    d.display()
                ));
            }
        }
        if p.is_dir() {
            return Err(format!("{flag} {shown}: is a directory"));
        }
        let Some(full) = id(p) else { continue };
        if inputs.contains(&full) {
            return Err(format!(
                "{flag} {shown}: is an input file; refusing to overwrite it"
            ));
        }
        if let Some((other, _)) = seen.iter().find(|(_, q)| *q == full) {
            return Err(format!("{flag} {shown}: same file as {other}"));
        }
        seen.push((flag, full));
    }
    Ok(())
}

fn solve_and_write(label: &str, sc: &Scene, source: &Source, outputs: Outputs, quiet: bool) -> i32 {
    let mut settings = job::settings_of(sc);
    progress::begin(settings.load_steps, show_progress(quiet));
    settings.progress = Some(std::sync::Arc::new(progress::hook));
    let result = job::solve_scene(sc, &settings);
    let seen = progress::finish();
    let sol = match result {
        Ok(s) => s,
        Err(e) => return bad(source.describe(&e)),
    };
    let r = &sol.results;
    let steps = settings.load_steps;
    // Where the solve was when it stopped, for failure messages.
    let stage = || {
        let step = seen.last.map_or(1, |s| s.step);
        let largest = match seen.largest_in_step {
            Some(b) => format!(
                "; largest relative residual in load step {step}/{steps}: {:.3e} (iteration {})",
                b.residual, b.iteration
            ),
            None => String::new(),
        };
        (step, largest)
    };
    if !r.all_finite() {
        let (step, largest) = stage();
        eprintln!(
            "error: {label}: the Newton solve diverged at load step {step}/{steps} (non-finite \
             values: {}){largest}; no results written",
            sol.report
                .message
                .as_deref()
                .unwrap_or("no further diagnostic")
        );
        return EXIT_NOT_CONVERGED;
    }
    let mut files: Vec<(&Path, Vec<u8>)> = Vec::new();
    if let Some(p) = &outputs.json {
        match serde_json::to_vec_pretty(r) {
            Ok(b) => files.push((p, b)),
            Err(e) => return bad(format_args!("cannot encode the results as JSON: {e}")),
        }
    }
    if let Some(p) = &outputs.obj {
        files.push((p, obj::to_obj(r).into_bytes()));
    }
    if let Some(p) = &outputs.csv {
        files.push((p, csv::to_csv(&sol.equilibrium).into_bytes()));
    }
    if let Err((p, e)) = atomic::write_all(&files) {
        return bad(format_args!("cannot write {}: {e}", p.display()));
    }
    println!(
        "{label}: {} in {} iterations over {} load step(s), relative residual {:.3e}, energy {:.9e} J, {:.3} s{}",
        if r.converged { "converged" } else { "NOT converged" },
        r.iterations,
        r.load_steps,
        r.residual,
        r.energy.total,
        r.seconds,
        if !r.converged || r.solver.stable {
            ""
        } else {
            " (unstable: the Hessian has a direction of negative curvature)"
        }
    );
    if r.converged {
        if let Some(m) = &sol.report.message {
            eprintln!("rodnet: {m}");
        }
        EXIT_OK
    } else {
        let (step, largest) = stage();
        eprintln!(
            "error: {label}: the Newton solve stopped at load step {step}/{steps}: {}{largest}; \
             results written with \"converged\": false",
            sol.report
                .message
                .as_deref()
                .unwrap_or("no further diagnostic")
        );
        EXIT_NOT_CONVERGED
    }
}

/// Checks the numbers clap cannot check by type.
fn hemisphere_spec(a: &HemisphereArgs) -> Result<HemisphereSpec, String> {
    let positive = |x: f64| x.is_finite() && x > 0.0;
    if !positive(a.radius) {
        return Err(format!(
            "--radius must be positive and finite, got {}",
            a.radius
        ));
    }
    if !(1..=MAX_RODS).contains(&a.rods) {
        return Err(format!("--rods must be in 1..={MAX_RODS}, got {}", a.rods));
    }
    if a.subdivide == 0 {
        return Err("--subdivide must be at least 1".into());
    }
    if !positive(a.young_modulus) {
        return Err(format!(
            "--young-modulus must be positive and finite, got {}",
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
    if !positive(a.tolerance) {
        return Err(format!("--tolerance must be positive, got {}", a.tolerance));
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
    spec.joint = match a.joint {
        JointArg::Ball => JointChoice::Ball,
        JointArg::Hinge => JointChoice::Hinge,
        JointArg::Rigid => JointChoice::Rigid,
        JointArg::Elastic => JointChoice::Elastic,
    };
    spec.section = a.section.scaled(a.radius);
    spec.young_modulus = a.young_modulus;
    spec.poisson_ratio = a.poisson_ratio;
    spec.load_steps = a.load_steps;
    spec.tolerance = a.tolerance;
    Ok(spec)
}

fn hemisphere(a: HemisphereArgs) -> i32 {
    let spec = match hemisphere_spec(&a) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: {e}");
            return EXIT_BAD_INPUT;
        }
    };
    let explicit =
        a.json.is_some() || a.obj.is_some() || a.report.is_some() || a.scene_out.is_some();
    let default_dir = match (&a.out_dir, explicit) {
        (Some(d), _) => Some(d.clone()),
        (None, false) => Some(PathBuf::from(".")),
        (None, true) => None,
    };
    let (mut json, mut obj_out, mut report) = (a.json.clone(), a.obj.clone(), a.report.clone());
    if let Some(d) = &default_dir {
        if let Err(e) = std::fs::create_dir_all(d) {
            eprintln!("error: cannot create {}: {e}", d.display());
            return EXIT_BAD_INPUT;
        }
        json.get_or_insert_with(|| d.join("hemisphere.json"));
        obj_out.get_or_insert_with(|| d.join("hemisphere.obj"));
        report.get_or_insert_with(|| d.join("hemisphere.txt"));
    }
    if let Some(p) = &a.scene_out {
        let fp = footprint::footprint(&spec);
        if let Err(e) = scene::validate::validate(&fp.scene) {
            eprintln!(
                "error: the generated scene is invalid: {}: {}",
                e.path(),
                e.message
            );
            return EXIT_BAD_INPUT;
        }
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
            footprint::to_ron(&fp.scene)
        );
        if let Err(e) = atomic::write(p, text.as_bytes()) {
            eprintln!("error: cannot write {}: {e}", p.display());
            return EXIT_BAD_INPUT;
        }
    }
    if json.is_none() && obj_out.is_none() && report.is_none() {
        return EXIT_OK;
    }

    progress::begin(spec.load_steps, show_progress(a.quiet));
    let result = gridshell_job::run(
        &spec,
        a.start_cap,
        Some(std::sync::Arc::new(progress::hook)),
    );
    let _ = progress::finish();
    let run = match result {
        Ok(r) => r,
        Err(e) => {
            eprintln!(
                "error: the generated scene is invalid: {}: {}",
                e.path(),
                e.message
            );
            return EXIT_BAD_INPUT;
        }
    };
    let r = &run.results;
    if !r.all_finite() {
        eprintln!(
            "error: the form finding produced non-finite values ({}); no results written",
            r.solver
                .message
                .as_deref()
                .unwrap_or("no further diagnostic")
        );
        return EXIT_NOT_CONVERGED;
    }
    let summary = run.summary();
    let mut outputs: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    if let Some(p) = json {
        outputs.push((p, run.to_json()));
    }
    if let Some(p) = obj_out {
        outputs.push((p, obj::to_obj(r).into_bytes()));
    }
    if let Some(p) = report {
        outputs.push((p, summary.clone().into_bytes()));
    }
    for (p, bytes) in outputs {
        if let Err(e) = atomic::write(&p, &bytes) {
            eprintln!("error: cannot write {}: {e}", p.display());
            return EXIT_BAD_INPUT;
        }
    }
    print!("{summary}");
    if r.converged {
        EXIT_OK
    } else {
        eprintln!(
            "rodnet: form finding did not converge: {}",
            r.solver
                .message
                .as_deref()
                .unwrap_or("no further diagnostic")
        );
        EXIT_NOT_CONVERGED
    }
}
