//! `rodnet plot RESULT.json -o VIEW.png`.

use std::path::PathBuf;

use clap::Args;

use super::output::{atomic_write, bad, check_outputs, EXIT_OK};
use crate::io::plot;
use crate::scene;

#[derive(Args, Debug, Clone)]
pub struct PlotArgs {
    /// Results JSON written by `rodnet solve --json`.
    pub result: PathBuf,
    /// The PNG to write.
    #[arg(short, long, value_name = "VIEW.png")]
    pub output: PathBuf,
    /// Width in pixels.
    #[arg(long, default_value_t = 1200, value_parser = clap::value_parser!(u32).range(200..=8000))]
    pub width: u32,
    /// Height in pixels.
    #[arg(long, default_value_t = 900, value_parser = clap::value_parser!(u32).range(200..=8000))]
    pub height: u32,
    /// Title drawn at the top [default: the results file name].
    #[arg(long)]
    pub title: Option<String>,
}

/// Results JSON files larger than this are refused before reading, bytes.
pub(super) const MAX_JSON_BYTES: u64 = 1 << 30;

pub fn run(a: &PlotArgs) -> i32 {
    if let Err(e) = check_outputs(&[("--output", &a.output)], &[&a.result]) {
        return bad(e);
    }
    let file = a.result.display().to_string();
    let text = match scene::read_text(&a.result, "results", MAX_JSON_BYTES) {
        Ok(t) => t,
        Err(e) => return bad(e),
    };
    let rods = match plot::rods_from_json(&file, &text) {
        Ok(r) => r,
        Err(e) => return bad(e),
    };
    let title = a.title.clone().unwrap_or_else(|| {
        let name = a
            .result
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        format!("RODNET  {name}  RODS: {}", rods.len())
    });
    let png = match plot::render(&rods, a.width, a.height, &title) {
        Ok(p) => p,
        Err(e) => return bad(e),
    };
    if let Err(e) = atomic_write(&a.output, &png) {
        return bad(e);
    }
    let smax = rods
        .iter()
        .flat_map(|r| r.stress.iter())
        .copied()
        .fold(0.0, f64::max);
    println!(
        "{}: {} rods, largest bending stress {smax:.4e} Pa",
        a.output.display(),
        rods.len()
    );
    EXIT_OK
}
