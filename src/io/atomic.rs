//! Output files: a regular file (or a new path) is replaced atomically, so that a failed run
//! never leaves a half-written output; anything else that already exists at the path is not
//! ours to replace.
//!
//! - A new path or a regular file: the bytes go to an unnamed temporary file in the target's
//!   directory (Linux `O_TMPFILE`), which is given a name and renamed over the target only when
//!   complete. A crash while writing leaves nothing behind. Where the file system has no
//!   `O_TMPFILE` (or off Linux), a named temporary `.NAME.tmpPID` is used instead, and stale
//!   ones of that pattern, whose process is gone, are removed before each write.
//! - A symbolic link is written through (its target is truncated and written, the link stays),
//!   and so are character and block devices and pipes reached through `/dev/stdout` or
//!   `/proc/self/fd` (opened for writing, not truncated): `--json /dev/null` must not replace
//!   /dev/null. Those writes are not atomic.
//! - A directory, a symbolic link to one, a dangling link, and a FIFO or socket with a name in
//!   the file system are refused (a FIFO nobody reads would block the write forever).

use std::fs::{File, OpenOptions};
use std::io::{Error, ErrorKind, Write};
use std::path::{Path, PathBuf};

pub fn write(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    write_all(&[(path, bytes.to_vec())]).map_err(|(_, e)| e)
}

/// What is at an output path, and so how it is written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Target {
    /// Nothing, or a regular file: replaced atomically.
    Replace,
    /// A symbolic link to a regular file: written through, truncated first.
    LinkedFile,
    /// A device, or a pipe without a name (`/dev/stdout`): written through, not truncated.
    Special,
}

/// How `path` would be written, or why it cannot be.
pub fn target(path: &Path) -> std::io::Result<Target> {
    let meta = match std::fs::symlink_metadata(path) {
        Ok(m) => m,
        Err(e) if e.kind() == ErrorKind::NotFound => return Ok(Target::Replace),
        Err(e) => return Err(e),
    };
    if meta.is_file() {
        return Ok(Target::Replace);
    }
    if meta.is_dir() {
        return Err(Error::new(ErrorKind::IsADirectory, "is a directory"));
    }
    let link = meta.file_type().is_symlink();
    let resolved = match std::fs::metadata(path) {
        Ok(m) => m,
        Err(e) if link && e.kind() == ErrorKind::NotFound => {
            return Err(Error::new(
                ErrorKind::NotFound,
                "is a symbolic link to nothing (a dangling link); give the target's path",
            ))
        }
        Err(e) => return Err(e),
    };
    if resolved.is_dir() {
        Err(Error::new(
            ErrorKind::IsADirectory,
            "is a symbolic link to a directory",
        ))
    } else if resolved.is_file() {
        Ok(Target::LinkedFile)
    } else if let Some(what) = named_pipe(path, &resolved) {
        Err(Error::new(
            ErrorKind::InvalidInput,
            format!(
                "is {what}, not a regular file: writing to one with no reader waits forever; \
                 give a file, or a pipe through /dev/stdout or `>(command)`"
            ),
        ))
    } else {
        Ok(Target::Special)
    }
}

/// "a FIFO (a named pipe)" or "a socket" when `path` names one in the file system. A pipe
/// reached through `/dev/stdout` or `/proc/self/fd/N` (a shell's `|`, `>(…)`) has no path of
/// its own (its link reads `pipe:[N]`, which does not resolve): such a pipe is open at the
/// other end while the command runs, so it is written through like a device.
fn named_pipe(path: &Path, resolved: &std::fs::Metadata) -> Option<&'static str> {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        let t = resolved.file_type();
        let what = if t.is_fifo() {
            "a FIFO (a named pipe)"
        } else if t.is_socket() {
            "a socket"
        } else {
            return None;
        };
        path.canonicalize().is_ok().then_some(what)
    }
    #[cfg(not(unix))]
    {
        let _ = (path, resolved);
        None
    }
}

/// A complete temporary file waiting to be renamed over its target.
struct Temp {
    /// Unnamed (`O_TMPFILE`) until committed, or already named.
    #[cfg_attr(not(target_os = "linux"), allow(dead_code))]
    file: Option<File>,
    name: PathBuf,
}

impl Temp {
    fn discard(self) {
        if self.file.is_none() {
            let _ = std::fs::remove_file(&self.name);
        }
    }

    /// Renames the temporary over `path`; `bytes` are its content, written again to a named
    /// temporary if the unnamed one cannot be given a name.
    fn commit(self, path: &Path, bytes: &[u8]) -> std::io::Result<()> {
        #[cfg(target_os = "linux")]
        if let Some(f) = &self.file {
            if linux::link(f, &self.name).is_err() {
                named_temp(&self.name, bytes)?;
            }
        }
        #[cfg(not(target_os = "linux"))]
        let _ = bytes;
        std::fs::rename(&self.name, path).inspect_err(|_| {
            let _ = std::fs::remove_file(&self.name);
        })
    }
}

/// Writes several files so that either all of them are replaced or none is: every temporary
/// file is written first, and only then are they renamed. Outputs written through (links,
/// devices) are written after all temporaries and before the renames. On failure returns the
/// path at fault.
pub fn write_all<P: AsRef<Path>>(files: &[(P, Vec<u8>)]) -> Result<(), (PathBuf, Error)> {
    let mut kinds = Vec::with_capacity(files.len());
    for (p, _) in files {
        kinds.push(target(p.as_ref()).map_err(|e| (p.as_ref().to_path_buf(), e))?);
    }
    let mut temps: Vec<Temp> = Vec::new();
    let discard = |temps: Vec<Temp>| temps.into_iter().for_each(Temp::discard);
    for ((p, bytes), kind) in files.iter().zip(&kinds) {
        if *kind != Target::Replace {
            continue;
        }
        match write_temp(p.as_ref(), bytes) {
            Ok(t) => temps.push(t),
            Err(e) => {
                discard(temps);
                return Err((p.as_ref().to_path_buf(), e));
            }
        }
    }
    for ((p, bytes), kind) in files.iter().zip(&kinds) {
        if *kind == Target::Replace {
            continue;
        }
        if let Err(e) = write_through(p.as_ref(), bytes, *kind == Target::LinkedFile) {
            discard(temps);
            return Err((p.as_ref().to_path_buf(), e));
        }
    }
    let mut temps = temps.into_iter();
    let replaced = files
        .iter()
        .zip(&kinds)
        .filter(|(_, k)| **k == Target::Replace);
    for (p, bytes) in replaced.map(|(f, _)| f) {
        let Some(t) = temps.next() else { break };
        if let Err(e) = t.commit(p.as_ref(), bytes) {
            // Renames within a directory only fail for reasons (permissions, a directory put
            // in the way meanwhile) that the earlier files do not share; the rest is removed.
            discard(temps.collect());
            return Err((p.as_ref().to_path_buf(), e));
        }
    }
    Ok(())
}

/// Writes into what is at `path` without replacing it.
fn write_through(path: &Path, bytes: &[u8], truncate: bool) -> std::io::Result<()> {
    let mut f = OpenOptions::new()
        .write(true)
        .truncate(truncate)
        .open(path)?;
    f.write_all(bytes)?;
    f.flush()
}

/// The directory an output goes into ("." for a bare file name) and the name of its
/// temporary file, `.NAME.tmpPID`.
fn temp_name(path: &Path) -> std::io::Result<(PathBuf, PathBuf)> {
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let name = path
        .file_name()
        .ok_or_else(|| Error::other("output path has no file name"))?;
    let mut tmp = std::ffi::OsString::from(".");
    tmp.push(name);
    tmp.push(format!(".tmp{}", std::process::id()));
    Ok((dir.to_path_buf(), dir.join(tmp)))
}

/// Writes `bytes` to a temporary file beside `path`.
fn write_temp(path: &Path, bytes: &[u8]) -> std::io::Result<Temp> {
    let (dir, name) = temp_name(path)?;
    remove_stale_temps(&dir, path);
    #[cfg(target_os = "linux")]
    if let Some(file) = linux::unnamed(&dir, bytes)? {
        return Ok(Temp {
            file: Some(file),
            name,
        });
    }
    named_temp(&name, bytes)?;
    Ok(Temp { file: None, name })
}

/// Writes `bytes` to the temporary file `name`, removed again on failure.
fn named_temp(name: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let result = (|| {
        let mut f = File::create(name)?;
        f.write_all(bytes)?;
        f.sync_all()
    })();
    result.inspect_err(|_| {
        let _ = std::fs::remove_file(name);
    })
}

/// Removes the named temporaries `.NAME.tmpPID` of `path` left by processes that no longer
/// run (a crash between writing and renaming, or a file system without `O_TMPFILE`). Those of
/// live processes, which may be writing the same output now, are left alone.
pub fn remove_stale_temps(dir: &Path, path: &Path) {
    let Some(name) = path.file_name().and_then(|n| n.to_str()) else {
        return;
    };
    let prefix = format!(".{name}.tmp");
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let file = entry.file_name();
        let Some(pid) = file
            .to_str()
            .and_then(|f| f.strip_prefix(&prefix))
            .filter(|d| !d.is_empty() && d.bytes().all(|b| b.is_ascii_digit()))
            .and_then(|d| d.parse::<u32>().ok())
        else {
            continue;
        };
        let regular = entry.file_type().is_ok_and(|t| t.is_file());
        if regular && pid != std::process::id() && !process_alive(pid) {
            let _ = std::fs::remove_file(entry.path());
        }
    }
}

/// Whether a process with this id runs (or may run: when it cannot be told, yes).
fn process_alive(pid: u32) -> bool {
    #[cfg(unix)]
    {
        let Ok(pid) = libc::pid_t::try_from(pid) else {
            return true;
        };
        if pid <= 0 {
            return true;
        }
        // Signal 0 only checks: EPERM means the process exists but belongs to someone else.
        // SAFETY: kill with signal 0 sends nothing and touches no memory.
        let r = unsafe { libc::kill(pid, 0) };
        r == 0 || Error::last_os_error().raw_os_error() != Some(libc::ESRCH)
    }
    #[cfg(not(unix))]
    {
        let _ = pid;
        true
    }
}

#[cfg(target_os = "linux")]
mod linux {
    use std::ffi::CString;
    use std::fs::{File, OpenOptions};
    use std::io::{Error, Write};
    use std::os::fd::AsRawFd;
    use std::os::unix::ffi::OsStrExt;
    use std::os::unix::fs::OpenOptionsExt;
    use std::path::Path;

    /// An unnamed file in `dir` holding `bytes`, or None where the file system (or /proc,
    /// needed to name it later) does not support it.
    pub(super) fn unnamed(dir: &Path, bytes: &[u8]) -> std::io::Result<Option<File>> {
        if !Path::new("/proc/self/fd").is_dir() {
            return Ok(None);
        }
        let mut f = match OpenOptions::new()
            .write(true)
            .custom_flags(libc::O_TMPFILE)
            .mode(0o666)
            .open(dir)
        {
            Ok(f) => f,
            // EOPNOTSUPP: no O_TMPFILE on this file system; EISDIR/EINVAL: a kernel without it.
            Err(e)
                if matches!(
                    e.raw_os_error(),
                    Some(libc::EOPNOTSUPP | libc::EISDIR | libc::EINVAL)
                ) =>
            {
                return Ok(None)
            }
            Err(e) => return Err(e),
        };
        f.write_all(bytes)?;
        f.sync_all()?;
        Ok(Some(f))
    }

    /// Gives the unnamed file `f` the name `name` (replacing a stale file of that name: it
    /// carries this process's id, so no live process writes it).
    pub(super) fn link(f: &File, name: &Path) -> std::io::Result<()> {
        let _ = std::fs::remove_file(name);
        let from = CString::new(format!("/proc/self/fd/{}", f.as_raw_fd()))?;
        let to = CString::new(name.as_os_str().as_bytes())?;
        // SAFETY: both are valid NUL-terminated strings that outlive the call.
        let r = unsafe {
            libc::linkat(
                libc::AT_FDCWD,
                from.as_ptr(),
                libc::AT_FDCWD,
                to.as_ptr(),
                libc::AT_SYMLINK_FOLLOW,
            )
        };
        if r == 0 {
            Ok(())
        } else {
            Err(Error::last_os_error())
        }
    }
}
