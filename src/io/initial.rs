//! Reading the state of an earlier results JSON for `rodnet solve --initial`: each rod's nodes
//! and twist angles (other keys are ignored, so results of other versions read too).

use serde::Deserialize;

use crate::network::initial::RodState;

#[derive(Deserialize)]
struct Saved {
    rods: Vec<SavedRod>,
}

#[derive(Deserialize)]
struct SavedRod {
    name: String,
    points: Vec<[f64; 3]>,
    #[serde(default)]
    twist: Vec<f64>,
}

/// Parses results JSON text into rod states; the error says what is missing or malformed.
pub fn parse(text: &str) -> Result<Vec<RodState>, String> {
    let saved: Saved = serde_json::from_str(text)
        .map_err(|e| format!("not a rodnet results JSON with rods: {e}"))?;
    Ok(saved
        .rods
        .into_iter()
        .map(|r| RodState {
            name: r.name,
            points: r.points,
            twist: r.twist,
        })
        .collect())
}

/// The rod states of results in memory (a solve's, a sweep's), as `--initial` reads them.
pub fn of_results(r: &crate::io::results::Results) -> Vec<RodState> {
    r.rods
        .iter()
        .map(|r| RodState {
            name: r.name.clone(),
            points: r.points.clone(),
            twist: r.twist.clone(),
        })
        .collect()
}
