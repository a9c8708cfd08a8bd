//! `rodnet plot RESULT.json -o VIEW.png`.

use std::path::PathBuf;

use clap::Args;

use super::output::{atomic_write, bad, check_outputs, EXIT_OK};
use crate::io::plot::{self, Quantity};
use crate::scene;

/// The quantity that colours the rods.
#[derive(clap::ValueEnum, Debug, Clone, Copy, PartialEq, Eq)]
pub enum ColorArg {
    /// Extreme-fibre bending stress, Pa.
    Bending,
    /// Axial force, N (tension positive).
    Axial,
    /// Von Mises stress over yield strength (materials with a yield_strength).
    Utilization,
    /// Signed distance to the scene's target, m (scenes with a target).
    Distance,
}

impl From<ColorArg> for Quantity {
    fn from(c: ColorArg) -> Quantity {
        match c {
            ColorArg::Bending => Quantity::Bending,
            ColorArg::Axial => Quantity::Axial,
            ColorArg::Utilization => Quantity::Utilization,
            ColorArg::Distance => Quantity::Distance,
        }
    }
}

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
    /// Colour the rods by this quantity; an error if the results do not have it [default:
    /// bending, or plain rods for results without stresses].
    #[arg(long, value_enum)]
    pub color: Option<ColorArg>,
    /// Draw the deformed shape with its displacements from the rest shape (drawn beneath it)
    /// multiplied by this factor.
    #[arg(long, default_value_t = 1.0, value_name = "S", value_parser = positive)]
    pub deflection_scale: f64,
}

fn positive(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(x) if x.is_finite() && x > 0.0 => Ok(x),
        _ => Err(format!("{s}: needs a positive number")),
    }
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
    let quantity = a.color.map(Quantity::from);
    let picture = match plot::read(&file, &text, quantity, a.deflection_scale) {
        Ok(p) => p,
        Err(e) => return bad(e),
    };
    let title = a.title.clone().unwrap_or_else(|| {
        let name = a
            .result
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        format!("rodnet   {name}   rods: {}", picture.rods.len())
    });
    let png = match plot::render(&picture, a.width, a.height, &title) {
        Ok(p) => p,
        Err(e) => return bad(e),
    };
    if let Err(e) = atomic_write(&a.output, &png) {
        return bad(e);
    }
    let (caption, unit) = picture.quantity.caption();
    println!(
        "{}: {} rods coloured by {caption} from {:.4e} to {:.4e} {unit}",
        a.output.display(),
        picture.rods.len(),
        picture.range.0,
        picture.range.1,
    );
    EXIT_OK
}
