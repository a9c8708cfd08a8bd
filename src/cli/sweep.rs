//! `rodnet sweep SWEEP.ron` (local threads, `--point I`, `--emit slurm DIR`) and
//! `rodnet sweep merge DIR`: docs/sweep.md. The work is in `crate::sweep`.

use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};

use clap::{Args, Subcommand};
use serde_json::Value as Json;

use super::output::{bad, EXIT_NOT_CONVERGED, EXIT_OK};
use crate::sweep::run::Outcome;
use crate::sweep::{slurm, table, Sweep};

#[derive(Args, Debug)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
pub struct SweepArgs {
    #[command(subcommand)]
    pub command: Option<SweepCommand>,
    /// Sweep file (RON): the base scene or generator, the parameters to vary, the output folder.
    #[arg(required = true)]
    pub sweep: Option<PathBuf>,
    /// Points solved at once, one thread each [default: the available cores].
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=1024))]
    pub jobs: Option<u32>,
    /// Solve only point I (0-based; what each task of an emitted Slurm array runs).
    #[arg(long, value_name = "I", conflicts_with = "emit")]
    pub point: Option<usize>,
    /// Solve nothing: write a job-array script for ENGINE (slurm) and the sweep's manifest into
    /// DIR.
    #[arg(long, num_args = 2, value_names = ["ENGINE", "DIR"])]
    pub emit: Option<Vec<String>>,
    /// No line per point.
    #[arg(long)]
    pub quiet: bool,
    #[command(flatten)]
    pub limits: super::LimitArgs,
}

#[derive(Subcommand, Debug)]
pub enum SweepCommand {
    /// Build sweep.csv from the points that have finished (DIR: the sweep's output folder or an
    /// --emit folder); the missing points are listed.
    Merge { dir: PathBuf },
}

pub(super) fn run(a: &SweepArgs) -> i32 {
    if let Some(SweepCommand::Merge { dir }) = &a.command {
        return merge(dir);
    }
    let Some(file) = &a.sweep else {
        return bad("a sweep file is required");
    };
    let mut sweep = match Sweep::load(file) {
        Ok(s) => s,
        Err(e) => return bad(e),
    };
    sweep.limits = a.limits.values();
    if let Some(emit) = &a.emit {
        return match (emit[0].as_str(), std::env::current_exe()) {
            ("slurm", Ok(exe)) => match slurm::emit(&sweep, &exe, std::path::Path::new(&emit[1])) {
                Ok(script) => {
                    println!(
                        "{}: {} array tasks; submit with `sbatch {}`, then `rodnet sweep merge {}`",
                        script.display(),
                        sweep.points.len(),
                        script.display(),
                        emit[1]
                    );
                    EXIT_OK
                }
                Err(e) => bad(e),
            },
            ("slurm", Err(e)) => bad(format_args!("cannot find the rodnet executable: {e}")),
            (other, _) => bad(format_args!("--emit {other}: the engines are: slurm")),
        };
    }
    if let Err(e) = sweep.write_manifest() {
        return bad(e);
    }
    if let Err(e) = sweep.check_point_files() {
        return bad(e);
    }
    let total = sweep.points.len();
    if let Some(i) = a.point {
        if i >= total {
            return bad(format_args!(
                "--point {i}: {} has {total} points (0 to {})",
                sweep.file,
                total.saturating_sub(1)
            ));
        }
        let r = sweep.run_point(i);
        report(&sweep, &r, i + 1, a.quiet);
        return match r {
            Ok(o) if converged(&o.record) => EXIT_OK,
            Ok(_) => EXIT_NOT_CONVERGED,
            Err(e) => bad(e),
        };
    }
    let jobs = a.jobs.map_or_else(
        || std::thread::available_parallelism().map_or(1, |n| n.get()),
        |j| j as usize,
    );
    let seen = AtomicUsize::new(0);
    let outcomes = sweep.run(jobs, &|r| {
        report(&sweep, r, seen.fetch_add(1, Ordering::Relaxed) + 1, a.quiet)
    });
    let (mut ok, mut failed, mut skipped) = (0, 0, 0);
    for o in &outcomes {
        match o {
            Ok(o) if converged(&o.record) => ok += 1,
            Ok(_) | Err(_) => failed += 1,
        }
        skipped += matches!(o, Ok(Outcome { skipped: true, .. })) as usize;
    }
    let table = match table::merge(&sweep.output) {
        Ok((p, _)) => p,
        Err(e) => return bad(e),
    };
    println!(
        "{total} points: {ok} converged, {failed} not converged or failed ({skipped} kept from \
         an earlier run); table {}",
        table.display()
    );
    if let Some(Err(e)) = outcomes.iter().find(|o| o.is_err()) {
        return bad(e);
    }
    if failed == 0 {
        EXIT_OK
    } else {
        EXIT_NOT_CONVERGED
    }
}

fn converged(record: &Json) -> bool {
    record.get("converged").and_then(Json::as_bool) == Some(true)
}

fn report(sweep: &Sweep, r: &Result<Outcome, String>, k: usize, quiet: bool) {
    let total = sweep.points.len();
    match r {
        Err(e) => eprintln!("[{k}/{total}] error: {e}"),
        Ok(_) if quiet => {}
        Ok(o) => {
            let name = &sweep.points[o.index].name;
            let rec = &o.record;
            let status = if o.skipped {
                "kept (results exist)".to_string()
            } else if let Some(m) = table::message(rec).filter(|_| !converged(rec)) {
                format!("NOT converged: {m}")
            } else {
                format!(
                    "converged in {} iterations, {:.3} s",
                    rec.get("iterations").and_then(Json::as_u64).unwrap_or(0),
                    rec.pointer("/sweep/seconds")
                        .and_then(Json::as_f64)
                        .unwrap_or(0.0)
                )
            };
            println!("[{k}/{total}] point {} {name}: {status}", o.index);
        }
    }
}

fn merge(dir: &std::path::Path) -> i32 {
    match table::merge(dir) {
        Ok((p, missing)) => {
            println!("{}", p.display());
            if missing.is_empty() {
                return EXIT_OK;
            }
            let list: Vec<String> = missing.iter().map(|i| i.to_string()).collect();
            eprintln!(
                "{} point(s) missing (no results file yet, or one solved from other inputs): {}",
                missing.len(),
                list.join(" ")
            );
            // An incomplete table is not a finished sweep: scripts that merge and go on must
            // see it, as they see a point that did not converge.
            EXIT_NOT_CONVERGED
        }
        Err(e) => bad(e),
    }
}
