//! What the commands share about their outputs: exit codes, error messages on stderr, and the
//! checks and atomic writes of output files.

use std::marker::PhantomData;
use std::path::{Path, PathBuf};

use crate::io::atomic;
use crate::io::formats::{Format, Solved, FORMATS};

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

/// The output options that were given, as (flag, path), for [`check_outputs`].
pub(super) fn given<'f, 'p>(
    options: &[(&'f str, &'p Option<PathBuf>)],
) -> Vec<(&'f str, &'p Path)> {
    options
        .iter()
        .filter_map(|&(f, p)| p.as_deref().map(|p| (f, p)))
        .collect()
}

/// Which of the [`FORMATS`] a command offers, and with which help texts.
pub trait Offer {
    /// The gridshell commands keep no equilibrium, only its results.
    const GRIDSHELL: bool;
}

/// `rodnet solve`'s outputs: every format.
#[derive(Debug, Clone)]
pub struct SolveFormats;
impl Offer for SolveFormats {
    const GRIDSHELL: bool = false;
}

/// The gridshell commands' outputs: the formats made from the results alone.
#[derive(Debug, Clone)]
pub struct GridshellFormats;
impl Offer for GridshellFormats {
    const GRIDSHELL: bool = true;
}

/// The result files asked for, one option per format of [`FORMATS`] that the command offers
/// (`#[command(flatten)]`).
#[derive(Debug, Clone)]
pub struct ResultOutputs<K> {
    paths: Vec<Option<PathBuf>>,
    offer: PhantomData<K>,
}

impl<K: Offer> ResultOutputs<K> {
    fn offered() -> impl Iterator<Item = (usize, &'static Format)> {
        FORMATS
            .iter()
            .enumerate()
            .filter(|(_, f)| !(K::GRIDSHELL && f.needs_equilibrium))
    }

    /// No outputs.
    pub fn none() -> Self {
        ResultOutputs {
            paths: vec![None; FORMATS.len()],
            offer: PhantomData,
        }
    }

    /// Whether any was asked for.
    pub fn any(&self) -> bool {
        self.paths.iter().any(Option::is_some)
    }

    /// The outputs that were given, as (flag, path), for [`check_outputs`].
    pub fn list(&self) -> Vec<(&'static str, &Path)> {
        FORMATS
            .iter()
            .zip(&self.paths)
            .filter_map(|(f, p)| p.as_deref().map(|p| (f.flag, p)))
            .collect()
    }

    /// Puts the formats that have a default name where none was given: `dir/STEM.EXT`.
    pub fn or_defaults(mut self, dir: &Path, stem: &str) -> Self {
        for (f, p) in FORMATS.iter().zip(&mut self.paths) {
            if let Some(ext) = f.default_ext {
                p.get_or_insert_with(|| dir.join(format!("{stem}.{ext}")));
            }
        }
        self
    }

    /// The files asked for, at `at(path)`, in the order of [`FORMATS`].
    pub fn files(
        &self,
        solved: &Solved,
        at: impl Fn(&Path) -> PathBuf,
    ) -> Result<Vec<(PathBuf, Vec<u8>)>, String> {
        let mut files = Vec::new();
        for (f, p) in FORMATS.iter().zip(&self.paths) {
            if let Some(p) = p {
                files.push((at(p), (f.bytes)(p, solved)?));
            }
        }
        Ok(files)
    }
}

impl<K: Offer> clap::FromArgMatches for ResultOutputs<K> {
    fn from_arg_matches(m: &clap::ArgMatches) -> Result<Self, clap::Error> {
        let mut out = Self::none();
        out.update_from_arg_matches(m)?;
        Ok(out)
    }

    fn update_from_arg_matches(&mut self, m: &clap::ArgMatches) -> Result<(), clap::Error> {
        for (i, f) in Self::offered() {
            if let Some(p) = m.get_one::<PathBuf>(f.name) {
                self.paths[i] = Some(p.clone());
            }
        }
        Ok(())
    }
}

impl<K: Offer> clap::Args for ResultOutputs<K> {
    fn augment_args(cmd: clap::Command) -> clap::Command {
        Self::offered().fold(cmd, |cmd, (_, f)| {
            let help = match f.gridshell_help {
                Some(h) if K::GRIDSHELL => h,
                _ => f.help,
            };
            let arg = clap::Arg::new(f.name)
                .long(&f.flag[2..])
                .value_name(f.value_name)
                .help(help)
                .action(clap::ArgAction::Set);
            cmd.arg(match f.check {
                Some(check) => arg.value_parser(move |s: &str| {
                    let p = PathBuf::from(s);
                    check(&p).map(|()| p)
                }),
                None => arg.value_parser(clap::value_parser!(PathBuf)),
            })
        })
    }

    fn augment_args_for_update(cmd: clap::Command) -> clap::Command {
        Self::augment_args(cmd)
    }
}
