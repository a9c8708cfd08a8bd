//! `rodnet gridshell fit TARGET.obj`: the options, their checks, and the job's outputs.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use clap::Args;

use super::output::{bad, check_outputs_creating, diagnostic, given};
use super::output::{GridshellFormats, ResultOutputs};
use super::output::{EXIT_NOT_CONVERGED, EXIT_OK};
use super::progress::{self, show_progress};
use crate::gridshell::fit::footprint::{FitSpec, DEFAULT_MIN_ANGLE_DEG};
use crate::gridshell::fit::job::{self, FitError};
use crate::gridshell::fit::net::Layout;
use crate::gridshell::footprint::to_ron;
use crate::gridshell::options::{parse_section, SectionRatio};
use crate::io::formats::Solved;
use crate::io::{atomic, footprint as fab};
use crate::scene::types::JointChoice;
use crate::scene::types::{Section, Solver};
use crate::surface::Surface;

#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum LayoutArg {
    On,
    Between,
}

#[derive(Args, Debug)]
pub struct FitArgs {
    /// Target surface: an OBJ triangle mesh (v and f records), metres.
    pub target: PathBuf,
    /// Net spacing a (rod length between crossings), m.
    #[arg(long)]
    pub spacing: f64,
    /// Where the two generators cross, projected onto the surface [default: the highest vertex].
    #[arg(long, value_parser = parse_point)]
    pub origin: Option<[f64; 3]>,
    /// The generators' directions at the origin, X1,Y1,Z1:X2,Y2,Z2, projected onto the tangent
    /// plane [default: x and y].
    #[arg(long, value_parser = parse_directions)]
    pub directions: Option<([f64; 3], [f64; 3])>,
    /// Rods on the generators (offsets k·a) or between them ((k + 1/2)·a).
    #[arg(long, value_enum, default_value_t = LayoutArg::On)]
    pub layout: LayoutArg,
    /// Locking angle, degrees: a rod stops where the net's cells close below it.
    #[arg(long, default_value_t = DEFAULT_MIN_ANGLE_DEG)]
    pub min_angle: f64,
    /// Equal edges per segment between neighbouring crossings.
    #[arg(long, default_value_t = super::DEFAULT_SUBDIVIDE)]
    pub subdivide: usize,
    #[arg(long, value_enum, default_value_t = JointChoice::Ball)]
    pub joint: JointChoice,
    /// Rod cross-section in metres: circle:r, ellipse:a,b or rectangle:w,h [default: a circle
    /// of radius a/50].
    #[arg(long, value_parser = parse_section)]
    pub section: Option<SectionRatio>,
    /// Young's modulus E, Pa.
    #[arg(long, default_value_t = 1e9)]
    pub young_modulus: f64,
    #[arg(long, default_value_t = 0.3)]
    pub poisson_ratio: f64,
    /// Relative residual tolerance [default: automatic].
    #[arg(long)]
    pub tolerance: Option<f64>,
    /// Write the footprint scene (RON) here.
    #[arg(long)]
    pub scene_out: Option<PathBuf>,
    #[command(flatten)]
    pub results: ResultOutputs<GridshellFormats>,
    /// Write the text report here.
    #[arg(long)]
    pub report: Option<PathBuf>,
    /// Write the cut list (one row per rod: family, offset, length, crossing positions) here.
    #[arg(long)]
    pub footprint_csv: Option<PathBuf>,
    /// Write the flat footprint to scale (SVG, millimetres) here.
    #[arg(long)]
    pub footprint_svg: Option<PathBuf>,
    /// Write STEM-gridshell.{json,obj,txt} here (the default, into the current directory,
    /// when no output option is given).
    #[arg(long)]
    pub out_dir: Option<PathBuf>,
    /// Eigen-analysis of the shell: the lowest K eigenvalues (N/m) as a "stability" block in
    /// the results JSON, as for `rodnet solve --modes`.
    #[arg(long, value_name = "K", value_parser = clap::value_parser!(u32).range(1..=200))]
    pub modes: Option<u32>,
    #[arg(long)]
    pub quiet: bool,
    #[command(flatten)]
    pub limits: super::LimitArgs,
}

fn parse_point(s: &str) -> Result<[f64; 3], String> {
    let v: Vec<f64> = s
        .split(',')
        .map(|x| x.trim().parse::<f64>().ok().filter(|x| x.is_finite()))
        .collect::<Option<_>>()
        .ok_or_else(|| format!("expected X,Y,Z with finite numbers, got {s:?}"))?;
    <[f64; 3]>::try_from(v).map_err(|_| format!("expected X,Y,Z, got {s:?}"))
}

fn parse_directions(s: &str) -> Result<([f64; 3], [f64; 3]), String> {
    let (a, b) = s
        .split_once(':')
        .ok_or_else(|| format!("expected X1,Y1,Z1:X2,Y2,Z2, got {s:?}"))?;
    Ok((parse_point(a)?, parse_point(b)?))
}

fn spec_of(a: &FitArgs) -> Result<FitSpec, String> {
    let section = a.section.map_or(
        Section::Circle {
            radius: a.spacing / 50.0,
        },
        |s| s.0,
    );
    let spec = FitSpec {
        spacing: a.spacing,
        origin: a.origin,
        directions: a.directions,
        layout: match a.layout {
            LayoutArg::On => Layout::On,
            LayoutArg::Between => Layout::Between,
        },
        min_angle_deg: a.min_angle,
        subdivide: a.subdivide,
        joint: a.joint,
        section,
        young_modulus: a.young_modulus,
        poisson_ratio: a.poisson_ratio,
        tolerance: a.tolerance,
        max_iterations: Solver::default().max_iterations,
    };
    spec.check()
        .map_err(|(option, m)| format!("--{option} {m}"))?;
    Ok(spec)
}

struct Outputs {
    results: ResultOutputs<GridshellFormats>,
    report: Option<PathBuf>,
    dir: Option<PathBuf>,
}

fn outputs(a: &FitArgs) -> Result<Outputs, String> {
    let explicit = a.results.any()
        || a.report.is_some()
        || a.scene_out.is_some()
        || a.footprint_csv.is_some()
        || a.footprint_svg.is_some();
    let dir = match (&a.out_dir, explicit) {
        (Some(d), _) => Some(d.clone()),
        (None, false) => Some(PathBuf::from(".")),
        (None, true) => None,
    };
    if let Some(d) = dir.as_ref().filter(|d| d.exists() && !d.is_dir()) {
        return Err(format!(
            "--out-dir {}: exists and is not a directory",
            d.display()
        ));
    }
    let stem = a
        .target
        .file_stem()
        .map_or("target".into(), |s| s.to_string_lossy().into_owned());
    let mut out = Outputs {
        results: a.results.clone(),
        report: a.report.clone(),
        dir,
    };
    if let Some(d) = &out.dir {
        out.results = out.results.or_defaults(d, &format!("{stem}-gridshell"));
        out.report
            .get_or_insert_with(|| d.join(format!("{stem}-gridshell.txt")));
    }
    Ok(out)
}

pub(super) fn run(a: FitArgs) -> i32 {
    let spec = match spec_of(&a) {
        Ok(s) => s,
        Err(e) => return bad(e),
    };
    let out = match outputs(&a) {
        Ok(o) => o,
        Err(e) => return bad(e),
    };
    let mut list = given(&[("--scene-out", &a.scene_out)]);
    list.extend(out.results.list());
    list.extend(given(&[
        ("--report", &out.report),
        ("--footprint-csv", &a.footprint_csv),
        ("--footprint-svg", &a.footprint_svg),
    ]));
    let creating = out.dir.as_deref().filter(|d| !d.is_dir());
    if let Err(e) = check_outputs_creating(&list, &[a.target.as_path()], creating) {
        return bad(e);
    }
    let surface = match Surface::load(&a.target, crate::scene::MAX_MESH_BYTES) {
        Ok(s) => Arc::new(s),
        Err(e) => return bad(e),
    };
    // The scene names the mesh by its absolute path, so that it reads wherever it is written.
    let mesh_path = std::fs::canonicalize(&a.target)
        .unwrap_or_else(|_| a.target.clone())
        .display()
        .to_string();
    let tracker = progress::Tracker::begin(1, show_progress(a.quiet));
    let result = job::run(
        &surface,
        &mesh_path,
        &spec,
        Some(tracker.hook()),
        &a.limits.values(),
    );
    tracker.finish();
    let mut run = match result {
        Ok(r) => r,
        Err(FitError::Net(e)) => return bad(format_args!("{}: {e}", a.target.display())),
        Err(FitError::Scene(e)) => {
            return bad(format_args!(
                "the generated scene is invalid: {}: {}",
                e.path(),
                e.message
            ))
        }
    };
    if let (Some(k), true) = (a.modes, run.results.all_finite()) {
        match crate::network::stability::analyse(&mut run.network, k as usize) {
            Ok(st) => run.results.stability = Some((&st).into()),
            Err(e) => return bad(format_args!("eigen-analysis: {e}")),
        }
    }
    if let Some(d) = creating {
        if let Err(e) = std::fs::create_dir_all(d) {
            return bad(format_args!("cannot create {}: {e}", d.display()));
        }
    }
    let r = &run.results;
    if !r.all_finite() {
        eprintln!(
            "error: the form finding produced non-finite values ({}); no results written",
            diagnostic(&r.solver.message)
        );
        return EXIT_NOT_CONVERGED;
    }
    let summary = run.summary();
    let rods = run.footprint_rods();
    let solved = Solved {
        results: r,
        equilibrium: None,
        json: None,
    };
    let results = match out.results.files(&solved, Path::to_path_buf) {
        Ok(f) => f,
        Err(e) => return bad(e),
    };
    let mut files: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    if let Some(p) = &a.scene_out {
        files.push((p.clone(), scene_text(&run, &a.target).into_bytes()));
    }
    files.extend(results);
    let mut add = |p: &Option<PathBuf>, bytes: Vec<u8>| {
        if let Some(p) = p {
            files.push((p.clone(), bytes));
        }
    };
    add(&out.report, summary.clone().into_bytes());
    add(&a.footprint_csv, fab::cut_list_csv(&rods).into_bytes());
    add(&a.footprint_svg, fab::footprint_svg(&rods).into_bytes());
    if let Err((p, e)) = atomic::write_all(&files) {
        return bad(format_args!("cannot write {}: {e}", p.display()));
    }
    if !a.quiet {
        print!("{summary}");
    }
    if r.converged {
        EXIT_OK
    } else {
        eprintln!(
            "rodnet: form finding did not converge: {}",
            diagnostic(&r.solver.message)
        );
        EXIT_NOT_CONVERGED
    }
}

fn scene_text(run: &job::FitRun, target: &Path) -> String {
    format!(
        "// Footprint of a Chebyshev-net gridshell fitted to {} by `rodnet gridshell fit`:\n\
         // spacing {} m, {} rods, {} joints. The rods lie flat in the footprint plane and\n\
         // `move_to` brings each rod end onto its boundary point; `buckle_toward` picks the\n\
         // surface's side (docs/gridshell.md).\n{}\n",
        target.display(),
        run.spec.spacing,
        run.footprint.scene.rods.len(),
        run.footprint.scene.joints.len(),
        to_ron(&run.footprint.scene)
    )
}
