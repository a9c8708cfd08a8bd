//! `rodnet sweep SWEEP.ron --emit slurm DIR`: a Slurm job-array script, one array task per
//! point, each running `rodnet sweep SWEEP.ron --point $SLURM_ARRAY_TASK_ID`, and the
//! manifest that `rodnet sweep merge DIR` builds the table from. Slurm schedules; rodnet only
//! writes what it needs.

use std::path::{Path, PathBuf};

use super::table::MANIFEST;
use super::Sweep;

pub const SCRIPT: &str = "sweep.sbatch";

/// Single-quoted for the shell.
fn sh(p: &Path) -> String {
    format!("'{}'", p.display().to_string().replace('\'', "'\\''"))
}

/// The job-array script for `sweep`, run by `exe`.
pub fn script(sweep: &Sweep, exe: &Path, dir: &Path) -> String {
    let abs = |p: &Path| std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf());
    let n = sweep.points.len();
    format!(
        "#!/bin/bash\n\
         # Written by `rodnet sweep --emit slurm`: one array task per point of {file}\n\
         # ({n} points). Submit with `sbatch {script}`; when tasks have finished, build the table\n\
         # with `rodnet sweep merge {dir}`. A task whose point has results already does nothing.\n\
         #SBATCH --job-name=rodnet-sweep\n\
         #SBATCH --array=0-{last}\n\
         #SBATCH --ntasks=1\n\
         #SBATCH --cpus-per-task=1\n\
         #SBATCH --output={logs}/%A_%a.out\n\
         set -euo pipefail\n\
         exec {exe} sweep {sweep_file} --point \"${{SLURM_ARRAY_TASK_ID:?not run as a Slurm array task}}\"\n",
        file = sweep.file,
        script = abs(&dir.join(SCRIPT)).display(),
        dir = abs(dir).display(),
        last = n.saturating_sub(1),
        logs = abs(&dir.join("logs")).display(),
        exe = sh(&abs(exe)),
        sweep_file = sh(&abs(Path::new(&sweep.file))),
    )
}

/// Refuses a path with a control character (a newline, a tab, an escape): the script names
/// the paths in comments and `#SBATCH` lines, where no shell quoting applies, so a newline in
/// one would start a line of its own, a command.
fn plain(what: &str, p: &Path) -> Result<(), String> {
    let text = p.to_string_lossy();
    match text.chars().find(|c| c.is_control()) {
        Some(c) => Err(format!(
            "{what} {:?} holds the control character {:?}: a job script cannot name it safely; \
             rename it",
            text, c
        )),
        None => Ok(()),
    }
}

/// Writes the script (executable) and the manifest into `dir` (created); returns the script.
/// Paths with control characters are refused before anything is written.
pub fn emit(sweep: &Sweep, exe: &Path, dir: &Path) -> Result<PathBuf, String> {
    plain("the sweep file", Path::new(&sweep.file))?;
    plain("the sweep's output folder", &sweep.output)?;
    plain("the script folder", dir)?;
    plain("the rodnet executable", exe)?;
    for p in [Path::new(&sweep.file), dir, exe] {
        let abs = std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf());
        plain("the absolute path", &abs)?;
    }
    std::fs::create_dir_all(dir.join("logs"))
        .map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    let script_path = dir.join(SCRIPT);
    let manifest = serde_json::to_vec_pretty(&sweep.manifest()).expect("JSON serializes");
    crate::io::atomic::write_all(&[
        (script_path.clone(), script(sweep, exe, dir).into_bytes()),
        (dir.join(MANIFEST), manifest),
    ])
    .map_err(|(p, e)| format!("cannot write {}: {e}", p.display()))?;
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        let _ = std::fs::set_permissions(&script_path, std::fs::Permissions::from_mode(0o755));
    }
    Ok(script_path)
}
