//! What the commands share about their outputs: exit codes, error messages on stderr, and the
//! checks and atomic writes of output files.

use std::path::{Path, PathBuf};

use crate::io::atomic;

/// Exit codes of the contract.
pub const EXIT_OK: i32 = 0;
pub const EXIT_NOT_CONVERGED: i32 = 1;
pub const EXIT_BAD_INPUT: i32 = 2;

/// Reports bad input and returns its exit code.
pub(super) fn bad(msg: impl std::fmt::Display) -> i32 {
    eprintln!("error: {msg}");
    EXIT_BAD_INPUT
}

/// A solver's message for a failure report.
pub(super) fn diagnostic(message: &Option<String>) -> &str {
    message.as_deref().unwrap_or("no further diagnostic")
}

pub(super) fn atomic_write(p: &Path, bytes: &[u8]) -> Result<(), String> {
    atomic::write(p, bytes).map_err(|e| format!("cannot write {}: {e}", p.display()))
}

/// Refuses outputs that would certainly fail or destroy an input, before any work is done: a
/// missing directory, a directory (or a link to one, or a dangling link) as file name, the same
/// file twice (also through links), an output over an input.
pub(super) fn check_outputs(outputs: &[(&str, &Path)], inputs: &[&Path]) -> Result<(), String> {
    check_outputs_creating(outputs, inputs, None)
}

/// [`check_outputs`] for outputs some of which go into `creating`, a directory that does not
/// exist yet and will be created after the checks.
pub(super) fn check_outputs_creating(
    outputs: &[(&str, &Path)],
    inputs: &[&Path],
    creating: Option<&Path>,
) -> Result<(), String> {
    let inputs: Vec<PathBuf> = inputs.iter().filter_map(|p| identity(p)).collect();
    let mut seen: Vec<(&str, PathBuf)> = Vec::new();
    for &(flag, p) in outputs {
        let shown = p.display();
        if p.file_name().is_none() {
            return Err(format!("{flag} {shown}: not a file name"));
        }
        if let Some(d) = p.parent().filter(|d| !d.as_os_str().is_empty()) {
            let created = creating.is_some_and(|c| d.starts_with(c));
            if !created && !d.is_dir() {
                return Err(format!(
                    "{flag} {shown}: directory {} does not exist",
                    d.display()
                ));
            }
        }
        let kind = atomic::target(p).map_err(|e| format!("{flag} {shown}: {e}"))?;
        let Some(full) = identity(p) else { continue };
        if inputs.contains(&full) {
            return Err(format!(
                "{flag} {shown}: is an input file; refusing to overwrite it"
            ));
        }
        // Devices and FIFOs are written through, and twice is harmless (two outputs to
        // /dev/null, or both to /dev/stdout).
        if kind == atomic::Target::Special {
            continue;
        }
        if let Some((other, _)) = seen.iter().find(|(_, q)| *q == full) {
            return Err(format!("{flag} {shown}: same file as {other}"));
        }
        seen.push((flag, full));
    }
    Ok(())
}

/// The file a path names, for comparisons: an existing file through its links, otherwise its
/// nearest existing directory made canonical and the rest of the path.
fn identity(p: &Path) -> Option<PathBuf> {
    if let Ok(c) = p.canonicalize() {
        return Some(c);
    }
    let mut tail = vec![p.file_name()?];
    let mut dir = p.parent()?;
    loop {
        let d = if dir.as_os_str().is_empty() {
            Path::new(".")
        } else {
            dir
        };
        if let Ok(mut c) = d.canonicalize() {
            c.extend(tail.iter().rev());
            return Some(c);
        }
        tail.push(d.file_name()?);
        dir = d.parent()?;
    }
}

/// A `--vtk` file name: its extension picks the dataset (checked when the options are parsed).
pub(super) fn vtk_path(s: &str) -> Result<PathBuf, String> {
    let p = PathBuf::from(s);
    crate::io::vtk::Format::of(&p)?;
    Ok(p)
}

/// The VTK file of `r` for `p`, named .vtp or .vtu ([`vtk_path`]).
pub(super) fn vtk_bytes(p: &Path, r: &crate::io::results::Results) -> Result<Vec<u8>, String> {
    let format = crate::io::vtk::Format::of(p)?;
    Ok(crate::io::vtk::to_vtk(r, format).into_bytes())
}

/// The output options that were given, as (flag, path), for [`check_outputs`].
pub(super) fn given<'f, 'p>(
    options: &[(&'f str, &'p Option<PathBuf>)],
) -> Vec<(&'f str, &'p Path)> {
    options
        .iter()
        .filter_map(|&(f, p)| p.as_deref().map(|p| (f, p)))
        .collect()
}
