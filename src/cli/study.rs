//! `rodnet study convergence`: docs/convergence.md.

use std::path::{Path, PathBuf};

use clap::{Args, Subcommand, ValueEnum};

use super::output::{bad, check_outputs, given, EXIT_NOT_CONVERGED, EXIT_OK};
use super::progress::{self, show_progress};
use crate::gridshell::footprint::DEFAULT_SECTION_RATIO;
use crate::gridshell::formfind::DEFAULT_START_CAP;
use crate::gridshell::options::{HemisphereOptions, SectionRatio, DEFAULT_RODS};
use crate::io::atomic;
use crate::scene::types::JointChoice;
use crate::scene::{self, types::Section};
use crate::study::convergence::{analyse, plan, Problem};
use crate::study::{plot, report};

#[derive(Subcommand, Debug)]
pub enum StudyCommand {
    /// Solve a scene at successively finer subdivisions (every rod's subdivide doubled per
    /// level) and measure the discretization error of each level: against the scene's
    /// `reference` when it has one, otherwise against the Richardson extrapolate of the finest
    /// levels. Prints a table; writes CSV and an error-versus-time plot on request.
    Convergence(ConvergenceArgs),
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum GridshellShape {
    Hemisphere,
}

/// Default edges per crossing spacing of the coarsest gridshell level.
pub const DEFAULT_GRIDSHELL_SUBDIVIDE: usize = 2;
/// Size of the plot, pixels.
const PLOT_SIZE: (u32, u32) = (960, 680);

#[derive(Args, Debug)]
pub struct ConvergenceArgs {
    /// Scene file (RON); its own subdivisions are the first level.
    #[arg(required_unless_present = "gridshell")]
    pub scene: Option<PathBuf>,
    /// Study the generated gridshell instead of a scene: its footprint at --subdivide is
    /// refined level by level and form-found as by `rodnet gridshell hemisphere`.
    #[arg(long, value_enum, conflicts_with = "scene")]
    pub gridshell: Option<GridshellShape>,
    /// Number of levels, the first at the scene's own subdivisions.
    #[arg(long, default_value_t = 5)]
    pub levels: usize,
    /// Write one CSV row per level here.
    #[arg(long, value_name = "FILE.csv")]
    pub csv: Option<PathBuf>,
    /// Draw the error against the solve time, log-log, as a PNG here.
    #[arg(long, value_name = "FILE.png")]
    pub plot: Option<PathBuf>,
    /// No progress output.
    #[arg(long)]
    pub quiet: bool,
    #[command(flatten)]
    pub limits: super::LimitArgs,
    /// Gridshell: rods per family n [default: 12].
    #[arg(long, conflicts_with = "scene", requires = "gridshell")]
    pub rods: Option<usize>,
    /// Gridshell: edges per crossing spacing at the first level [default: 2].
    #[arg(long, conflicts_with = "scene", requires = "gridshell")]
    pub subdivide: Option<usize>,
    /// Gridshell: joint at every crossing [default: ball].
    #[arg(long, value_enum, conflicts_with = "scene", requires = "gridshell")]
    pub joint: Option<JointChoice>,
    /// Gridshell: radius of the starting cap over R, as for `rodnet gridshell hemisphere`
    /// [default: 5].
    #[arg(long, conflicts_with = "scene", requires = "gridshell")]
    pub start_cap: Option<f64>,
}

/// The gridshell problem, with the checks and defaults of `rodnet gridshell hemisphere`.
fn hemisphere_problem(a: &ConvergenceArgs) -> Result<Problem, String> {
    let h = HemisphereOptions {
        rods: a.rods.unwrap_or(DEFAULT_RODS),
        subdivide: a.subdivide.unwrap_or(DEFAULT_GRIDSHELL_SUBDIVIDE),
        joint: a.joint.unwrap_or(JointChoice::Ball),
        section: SectionRatio(Section::Circle {
            radius: DEFAULT_SECTION_RATIO,
        }),
        start_cap: a.start_cap.unwrap_or(DEFAULT_START_CAP),
        ..HemisphereOptions::default()
    };
    let spec = h.spec()?;
    Ok(Problem::Hemisphere {
        spec,
        start_cap: h.start_cap,
    })
}

pub fn run(a: &ConvergenceArgs) -> i32 {
    let outputs = given(&[("--csv", &a.csv), ("--plot", &a.plot)]);
    let inputs: Vec<&Path> = a.scene.as_deref().into_iter().collect();
    if let Err(e) = check_outputs(&outputs, &inputs) {
        return bad(e);
    }
    let problem = match &a.scene {
        Some(path) => match scene::load(path) {
            Ok((scene, src)) => {
                let file = path.display().to_string();
                for w in scene::validate::warnings(&scene) {
                    eprintln!(
                        "warning: {}",
                        scene::SceneError::from_field(&file, &src, &w)
                    );
                }
                // A study refines one load case: a staged scene's loads all together.
                Problem::Scene {
                    file,
                    src,
                    scene: Box::new(scene.all_stages()),
                }
            }
            Err(e) => return bad(e),
        },
        None => match hemisphere_problem(a) {
            Ok(p) => p,
            Err(e) => return bad(e),
        },
    };
    let plan = match plan(&problem, a.levels, &a.limits.values()) {
        Ok(p) => p,
        Err(e) => return bad(e),
    };
    let show = show_progress(a.quiet);
    let mut levels = Vec::with_capacity(plan.levels());
    for i in 0..plan.levels() {
        let tracker = progress::Tracker::begin(plan.load_steps(), show);
        let level = plan.solve(i, Some(tracker.hook()));
        tracker.finish();
        if show {
            eprintln!(
                "level {}/{}: subdivide {}, {} nodes, {} in {} iterations, {:.3} s",
                level.level,
                plan.levels(),
                level.subdivide,
                level.nodes,
                if level.converged {
                    "converged"
                } else {
                    "NOT converged"
                },
                level.iterations,
                level.seconds
            );
        }
        levels.push(level);
    }
    let study = analyse(&plan, levels);
    let table = report::table(&study);
    let mut files: Vec<(&Path, Vec<u8>)> = Vec::new();
    if let Some(p) = &a.csv {
        files.push((p, report::to_csv(&study).into_bytes()));
    }
    // A plot that cannot be drawn (no level with a positive error) does not cost the table.
    let mut plot_error = None;
    if let Some(p) = &a.plot {
        let name = match &a.scene {
            Some(s) => s
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default(),
            None => study.label.clone(),
        };
        let title = format!("CONVERGENCE UNDER SUBDIVISION: {name}");
        let series = plot::series_of(&study);
        match plot::error_vs_time(&series, &title, PLOT_SIZE.0, PLOT_SIZE.1) {
            Ok(png) => files.push((p, png)),
            Err(e) => plot_error = Some(format!("cannot draw {}: {e}", p.display())),
        }
    }
    if let Err((p, e)) = atomic::write_all(&files) {
        return bad(format_args!("cannot write {}: {e}", p.display()));
    }
    print!("{table}");
    if let Some(e) = plot_error {
        let csv = match &a.csv {
            Some(p) => format!("{} was written", p.display()),
            None => "nothing was written".into(),
        };
        eprintln!("error: {e}; {csv}");
        return EXIT_NOT_CONVERGED;
    }
    if study.all_converged() {
        EXIT_OK
    } else {
        let failed = study.failed_levels();
        eprintln!(
            "error: {}: level(s) {failed:?} did not converge (reported in the table, left out of \
             the error analysis)",
            study.label
        );
        EXIT_NOT_CONVERGED
    }
}
