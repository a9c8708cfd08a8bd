//! The `rodnet` command line (see docs/cli.md and docs/contract.md): the clap tree and the
//! dispatch to one module per command.

mod buckle;
mod fit;
mod gridshell;
mod indent;
mod limits;
mod network;
mod output;
mod plot;
pub mod progress;
mod solve;
mod states;
mod study;
mod sweep;

use std::path::PathBuf;

use clap::{Parser, Subcommand};

pub use crate::gridshell::options::{SectionRatio, DEFAULT_RODS, DEFAULT_SUBDIVIDE, MAX_RODS};
pub use buckle::BuckleArgs;
pub use gridshell::{hemisphere_spec, HemisphereArgs, PathArg};
pub use indent::IndentArgs;
pub use limits::{parse_bytes, LimitArgs};
pub use network::NetworkArgs;
pub use output::{EXIT_BAD_INPUT, EXIT_NOT_CONVERGED, EXIT_OK};
pub use plot::PlotArgs;
pub use progress::show_progress;
pub use study::{ConvergenceArgs, StudyCommand};
pub use sweep::{SweepArgs, SweepCommand};

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
        #[command(flatten)]
        results: output::ResultOutputs<output::SolveFormats>,
        /// Eigen-analysis at the equilibrium: the lowest K eigenvalues (N/m) and whether the
        /// state is stable, as a "stability" block in the results JSON.
        #[arg(long, value_name = "K", value_parser = clap::value_parser!(u32).range(1..=200))]
        modes: Option<u32>,
        /// Write the --modes shapes here, one OBJ object per mode.
        #[arg(long, value_name = "OUT.obj", requires = "modes")]
        modes_obj: Option<PathBuf>,
        /// Start from an earlier results JSON of the same scene (same rods and subdivision):
        /// Newton at the full loads and motions from its state, e.g. a second stage with a load
        /// added to a form-found shell. Falls back to the solve from rest if Newton fails there.
        #[arg(long, value_name = "RESULTS.json")]
        initial: Option<PathBuf>,
        /// Also solve at twice every rod's subdivision (starting from this solution) and report
        /// the Richardson extrapolate of the two with the error estimate (results `extrapolation`;
        /// the other outputs are the finer solve's).
        #[arg(long, conflicts_with = "initial")]
        extrapolate: bool,
        /// With --extrapolate: 3 also solves at four times the subdivision and removes the h²
        /// and h³ terms of the error together, measuring its order (2: the h² term only).
        #[arg(long, value_name = "2|3", requires = "extrapolate", default_value_t = 2,
              value_parser = clap::value_parser!(u8).range(2..=3))]
        levels: u8,
        /// No progress output.
        #[arg(long)]
        quiet: bool,
        #[command(flatten)]
        network: NetworkArgs,
        #[command(flatten)]
        limits: LimitArgs,
    },
    /// Linear buckling: the factors by which the scene's loads (and prescribed motions) can be
    /// multiplied before the structure buckles, and their modes.
    Buckle(BuckleArgs),
    /// Indentation: solve the scene, then push one point by displacement control; its linear
    /// stiffness, the force–depth curve and its limit points.
    Indent(IndentArgs),
    /// Multiple equilibria: from the scene's equilibrium, pushes along the lowest eigenmodes
    /// settled by Newton; each state's energy, stability and index (states.json) and results.
    States(states::StatesArgs),
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
    /// Parameter sweeps: one independent solve per point, in parallel on the local cores or
    /// as a Slurm job array (docs/sweep.md).
    Sweep(SweepArgs),
}

#[derive(Subcommand, Debug)]
pub enum GridshellCommand {
    /// Hemispherical Chebyshev-net gridshell (Baek et al., PNAS 2018): builds the flat footprint
    /// from straight rods, moves the rod ends onto the equator, and compares the dome with the
    /// sphere and the net. With no output options it writes hemisphere.json, hemisphere.obj and
    /// hemisphere.txt into the current directory (or --out-dir).
    Hemisphere(HemisphereArgs),
    /// Gridshell fitted to a target surface (an OBJ triangle mesh): the Chebyshev net on it by
    /// the compass construction, the flat footprint that builds it, its form finding from the
    /// net, and its distances to the target and the net (docs/gridshell.md). With no output
    /// options it writes STEM-gridshell.json, .obj and .txt into the current directory.
    Fit(fit::FitArgs),
}

pub fn run(cli: Cli) -> i32 {
    match cli.command {
        Command::Solve {
            scene,
            results,
            modes,
            modes_obj,
            initial,
            extrapolate,
            levels,
            quiet,
            network,
            limits,
        } => solve::run(
            scene,
            solve::Outputs {
                results,
                modes: modes.map(|k| k as usize),
                modes_obj,
                initial,
                extrapolate: extrapolate.then_some(levels as usize),
            },
            quiet,
            &network,
            &limits.values(),
        ),
        Command::Buckle(args) => buckle::run(&args),
        Command::Indent(args) => indent::run(&args),
        Command::Gridshell {
            shape: GridshellCommand::Hemisphere(args),
        } => gridshell::run(args),
        Command::Gridshell {
            shape: GridshellCommand::Fit(args),
        } => fit::run(args),
        Command::States(args) => states::run(&args),
        Command::Plot(args) => plot::run(&args),
        Command::Study {
            study: StudyCommand::Convergence(args),
        } => study::run(&args),
        Command::Sweep(args) => sweep::run(&args),
    }
}
