//! The `rodnet` command line (see docs/cli.md and ../shared/contract.md).

use std::io::IsTerminal;
use std::path::PathBuf;

use clap::{Parser, Subcommand};

use crate::io::{atomic, csv, obj};
use crate::job;
use crate::scene::{self, SceneError};

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

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Solve a scene for its static equilibrium.
    Solve {
        /// Scene file (RON).
        scene: PathBuf,
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
    },
}

/// Exit codes of the contract.
pub const EXIT_OK: i32 = 0;
pub const EXIT_NOT_CONVERGED: i32 = 1;
pub const EXIT_BAD_INPUT: i32 = 2;

pub fn show_progress(quiet: bool) -> bool {
    !quiet && std::io::stderr().is_terminal()
}

fn progress_line(step: usize, it: usize, res: f64, e: f64) {
    eprint!("\r  load step {step:>4}  iteration {it:>4}  residual {res:9.3e}  energy {e:12.6e}   ");
}

pub fn run(cli: Cli) -> i32 {
    match cli.command {
        Command::Solve {
            scene,
            json,
            obj,
            csv,
            quiet,
        } => solve(scene, json, obj, csv, quiet),
    }
}

fn solve(
    path: PathBuf,
    json: Option<PathBuf>,
    obj_out: Option<PathBuf>,
    csv_out: Option<PathBuf>,
    quiet: bool,
) -> i32 {
    let (sc, src) = match scene::load(&path) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: {e}");
            return EXIT_BAD_INPUT;
        }
    };
    let progress = show_progress(quiet);
    let mut settings = job::settings_of(&sc);
    if progress {
        settings.progress = Some(progress_line);
    }
    let sol = match job::solve_scene(&sc, &settings) {
        Ok(s) => s,
        Err(e) => {
            let e = SceneError::from_field(&path.display().to_string(), &src, &e);
            eprintln!("error: {e}");
            return EXIT_BAD_INPUT;
        }
    };
    if progress {
        eprintln!();
    }
    let r = &sol.results;
    if !r.all_finite() {
        eprintln!(
            "error: the solve produced non-finite values ({}); no results written",
            sol.report
                .message
                .as_deref()
                .unwrap_or("no further diagnostic")
        );
        return EXIT_NOT_CONVERGED;
    }
    let mut outputs: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    if let Some(p) = json {
        outputs.push((p, serde_json::to_vec_pretty(r).expect("results serialize")));
    }
    if let Some(p) = obj_out {
        outputs.push((p, obj::to_obj(r).into_bytes()));
    }
    if let Some(p) = csv_out {
        outputs.push((p, csv::to_csv(&sol.network, r).into_bytes()));
    }
    for (p, bytes) in outputs {
        if let Err(e) = atomic::write(&p, &bytes) {
            eprintln!("error: cannot write {}: {e}", p.display());
            return EXIT_BAD_INPUT;
        }
    }
    println!(
        "{}: {} in {} iterations over {} load step(s), relative residual {:.3e}, energy {:.9e} J, {:.3} s{}",
        path.display(),
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
    if let Some(m) = &sol.report.message {
        eprintln!("rodnet: {m}");
    }
    if r.converged {
        EXIT_OK
    } else {
        EXIT_NOT_CONVERGED
    }
}
