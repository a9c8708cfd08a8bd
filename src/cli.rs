//! The `rodnet` command line (see docs/cli.md and ../shared/contract.md).

mod network;
mod plot;
pub mod progress;

use std::io::IsTerminal;
use std::path::{Path, PathBuf};

use clap::{Parser, Subcommand};

use crate::io::{atomic, csv, obj};
use crate::job;
use crate::scene::{self, FieldError, Scene, SceneError};

pub use network::{JointArg, NetworkArgs};
pub use plot::PlotArgs;

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
        Command::Plot(args) => plot::run(&args),
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
    settings.progress = Some(progress::hook);
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
        files.push((p, csv::to_csv(&sol.network, r).into_bytes()));
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
