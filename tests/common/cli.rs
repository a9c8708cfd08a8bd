//! Helpers for tests that drive the `rodnet` binary.

use std::path::PathBuf;
use std::process::{Command, Output};

pub fn rodnet() -> Command {
    Command::new(env!("CARGO_BIN_EXE_rodnet"))
}

/// A fresh, empty temporary folder for one test (`tag` and `name` keep tests apart).
pub fn tmpdir(tag: &str, name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("rodnet-{tag}-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A run's stdout and stderr together.
pub fn text(o: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    )
}
