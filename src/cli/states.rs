//! `rodnet states SCENE.ron`: the equilibria that pushes along the lowest eigenmodes reach.

use std::path::PathBuf;

use clap::Args;

use super::output::{bad, check_outputs_creating, EXIT_OK};
use crate::io::atomic;
use crate::io::states::{StateJson, StatesJson};
use crate::pipeline::JobError;
use crate::scene::{self, SceneError};

#[derive(Args, Debug)]
pub struct StatesArgs {
    /// Scene file (RON).
    pub scene: PathBuf,
    /// At most this many states.
    #[arg(long, default_value_t = 8, value_parser = clap::value_parser!(u32).range(1..=64))]
    pub max: u32,
    /// Write states.json and state_K.json (each state's results) here [default: the current
    /// directory].
    #[arg(long)]
    pub out_dir: Option<PathBuf>,
    /// Print nothing but errors.
    #[arg(long)]
    pub quiet: bool,
    #[command(flatten)]
    pub limits: super::LimitArgs,
}

pub fn run(a: &StatesArgs) -> i32 {
    let dir = a.out_dir.clone().unwrap_or_else(|| PathBuf::from("."));
    if dir.exists() && !dir.is_dir() {
        return bad(format_args!(
            "--out-dir {}: exists and is not a directory",
            dir.display()
        ));
    }
    let (sc, src) = match scene::load(&a.scene) {
        Ok(s) => s,
        Err(e) => return bad(e),
    };
    let label = a.scene.display().to_string();
    let summary = dir.join("states.json");
    let creating = Some(dir.as_path()).filter(|d| !d.is_dir());
    if let Err(e) = check_outputs_creating(
        &[("states.json", summary.as_path())],
        &[a.scene.as_path()],
        creating,
    ) {
        return bad(e);
    }
    let settings = a.limits.values().settings_of(&sc);
    let found = match crate::jobs::states(&sc, &settings, a.max as usize) {
        Ok(f) => f,
        Err(JobError::Scene(e)) => return bad(SceneError::from_field(&label, &src, &e)),
        Err(JobError::Refused(m)) => return bad(format_args!("{label}: {m}")),
    };
    if let Some(d) = creating {
        if let Err(e) = std::fs::create_dir_all(d) {
            return bad(format_args!("cannot create {}: {e}", d.display()));
        }
    }
    let mut files = Vec::new();
    let mut states = Vec::new();
    for (k, (f, results)) in found.iter().enumerate() {
        let name = format!("state_{k}.json");
        files.push((
            dir.join(&name),
            serde_json::to_vec_pretty(results).expect("results serialize"),
        ));
        states.push(StateJson {
            energy: results.energy.total,
            stable: f.stable,
            index: f.index,
            index_at_least: f.index_at_least,
            lowest_eigenvalue: f.lowest_eigenvalue,
            distance_to_first: f.distance_to_first,
            converged: results.converged,
            iterations: results.iterations,
            found_by: f.found_by.clone(),
            results: name,
            symmetric_to: f.symmetric_to,
        });
    }
    let json = StatesJson { states };
    files.push((
        summary,
        serde_json::to_vec_pretty(&json).expect("states serialize"),
    ));
    if let Err((p, e)) = atomic::write_all(&files) {
        return bad(format_args!("cannot write {}: {e}", p.display()));
    }
    if !a.quiet {
        println!("{label}: {} state(s)", json.states.len());
        for (k, s) in json.states.iter().enumerate() {
            println!(
                "  state {k}: energy {:.9e} J, {}, index {}{}, lowest eigenvalue {:.4e} N/m ({})",
                s.energy,
                if s.stable { "stable" } else { "not stable" },
                s.index,
                if s.index_at_least { "+" } else { "" },
                s.lowest_eigenvalue,
                s.found_by
            );
        }
    }
    EXIT_OK
}
