//! `rodnet gridshell hemisphere`: the clap options (the job's options and their checks are
//! `gridshell::options`'s), and the job (footprint scene, form finding, report).

use std::path::{Path, PathBuf};

use clap::Args;

use super::output::{atomic_write, bad, check_outputs_creating, diagnostic, given};
use super::output::{GridshellFormats, ResultOutputs};
use super::output::{EXIT_NOT_CONVERGED, EXIT_OK};
use super::progress::{self, show_progress};
use crate::gridshell::footprint::{self, HemisphereSpec, JointChoice};
use crate::gridshell::formfind::{FormPath, DEFAULT_START_CAP};
use crate::gridshell::job as gridshell_job;
use crate::gridshell::options::{parse_section, HemisphereOptions, SectionRatio};
use crate::gridshell::options::{DEFAULT_RODS, DEFAULT_SUBDIVIDE};
use crate::io::atomic;
use crate::io::formats::Solved;
use crate::scene::types::Scene;
use crate::scene::{self, FieldError};

/// `--path` of `rodnet gridshell hemisphere`.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum PathArg {
    CapNets,
    Straight,
}

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
    #[command(flatten)]
    pub results: ResultOutputs<GridshellFormats>,
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

impl HemisphereArgs {
    /// The job's options (checked by [`HemisphereOptions::spec`]).
    pub fn options(&self) -> HemisphereOptions {
        HemisphereOptions {
            radius: self.radius,
            rods: self.rods,
            subdivide: self.subdivide,
            joint: self.joint,
            section: self.section,
            young_modulus: self.young_modulus,
            poisson_ratio: self.poisson_ratio,
            load_steps: self.load_steps,
            tolerance: self.tolerance,
            start_cap: self.start_cap,
            path: match self.path {
                PathArg::CapNets => FormPath::CapNets,
                PathArg::Straight => FormPath::Straight,
            },
            modes: self.modes.map(|k| k as usize),
        }
    }
}

/// Checks the numbers clap cannot check by type.
pub fn hemisphere_spec(a: &HemisphereArgs) -> Result<HemisphereSpec, String> {
    a.options().spec()
}

/// The result files of the job.
struct Outputs {
    results: ResultOutputs<GridshellFormats>,
    report: Option<PathBuf>,
    /// Where the default names go (--out-dir, or the current directory when no output option
    /// is given); created, if need be, only once everything has been checked.
    dir: Option<PathBuf>,
}

impl Outputs {
    fn list<'a>(&'a self, a: &'a HemisphereArgs) -> Vec<(&'static str, &'a Path)> {
        let mut list = given(&[("--scene-out", &a.scene_out)]);
        list.extend(self.results.list());
        list.extend(given(&[("--report", &self.report)]));
        list
    }
}

/// The files asked for, with the default names in --out-dir (or the current directory when no
/// output option is given).
fn outputs(a: &HemisphereArgs) -> Result<Outputs, String> {
    let explicit = a.results.any() || a.report.is_some() || a.scene_out.is_some();
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
        results: a.results.clone(),
        report: a.report.clone(),
        dir,
    };
    if let Some(d) = &out.dir {
        out.results = out.results.or_defaults(d, "hemisphere");
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
    let spec = match a.options().spec() {
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
    if !out.results.any() && out.report.is_none() {
        return EXIT_OK;
    }

    let tracker = progress::Tracker::begin(spec.load_steps, show_progress(a.quiet));
    let result = gridshell_job::run(&spec, a.start_cap, Some(tracker.hook()), &a.limits.values());
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
    let json = run.to_json();
    let solved = Solved {
        results: r,
        equilibrium: None,
        json: Some(&json),
    };
    let mut files = match out.results.files(&solved, Path::to_path_buf) {
        Ok(f) => f,
        Err(e) => return bad(e),
    };
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

#[cfg(test)]
mod tests {
    use clap::Parser;

    use super::*;

    #[derive(Parser)]
    struct Command {
        #[command(flatten)]
        args: HemisphereArgs,
    }

    /// The command's defaults are the job's (sweeps and Python start from the latter).
    #[test]
    fn the_commands_defaults_are_the_options_defaults() {
        let c = Command::try_parse_from(["hemisphere"]).unwrap();
        assert_eq!(c.args.options(), HemisphereOptions::default());
    }
}
