//! Atomic file writes: write to a temporary file beside the target, then rename, so that a failed
//! run never leaves a half-written output.

use std::io::Write;
use std::path::{Path, PathBuf};

pub fn write(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let tmp = write_temp(path, bytes)?;
    std::fs::rename(&tmp, path).inspect_err(|_| {
        let _ = std::fs::remove_file(&tmp);
    })
}

/// Writes several files so that either all of them are replaced or none is: every temporary
/// file is written first, and only then are they renamed. On failure returns the path at fault.
pub fn write_all<P: AsRef<Path>>(files: &[(P, Vec<u8>)]) -> Result<(), (PathBuf, std::io::Error)> {
    let mut temps: Vec<PathBuf> = Vec::new();
    let cleanup = |temps: &[PathBuf]| {
        for t in temps {
            let _ = std::fs::remove_file(t);
        }
    };
    for (p, bytes) in files {
        match write_temp(p.as_ref(), bytes) {
            Ok(t) => temps.push(t),
            Err(e) => {
                cleanup(&temps);
                return Err((p.as_ref().to_path_buf(), e));
            }
        }
    }
    for (k, ((p, _), t)) in files.iter().zip(&temps).enumerate() {
        if let Err(e) = std::fs::rename(t, p.as_ref()) {
            // Renames within a directory only fail for reasons (permissions, a directory in the
            // way) that the earlier files do not share; what is left unrenamed is removed.
            cleanup(&temps[k..]);
            return Err((p.as_ref().to_path_buf(), e));
        }
    }
    Ok(())
}

/// Writes `bytes` to a temporary file beside `path` and returns its name.
fn write_temp(path: &Path, bytes: &[u8]) -> std::io::Result<PathBuf> {
    let dir = path.parent().filter(|p| !p.as_os_str().is_empty());
    let name = path
        .file_name()
        .ok_or_else(|| std::io::Error::other("output path has no file name"))?;
    let mut tmp_name = std::ffi::OsString::from(".");
    tmp_name.push(name);
    tmp_name.push(format!(".tmp{}", std::process::id()));
    let tmp = match dir {
        Some(d) => d.join(&tmp_name),
        None => Path::new(&tmp_name).to_path_buf(),
    };
    let result = (|| {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()
    })();
    match result {
        Ok(()) => Ok(tmp),
        Err(e) => {
            let _ = std::fs::remove_file(&tmp);
            Err(e)
        }
    }
}
