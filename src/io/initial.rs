//! Reading the state of an earlier results JSON for `rodnet solve --initial`: each rod's nodes
//! and twist angles (other keys are ignored, so results of other versions read too).

use serde::Deserialize;

use crate::network::initial::RodState;

#[derive(Deserialize)]
struct Saved {
    rods: Vec<SavedRod>,
    /// Absent in results of versions without the key: then the joints are not compared.
    joints: Option<Vec<SavedJoint>>,
}

#[derive(Deserialize)]
struct SavedJoint {
    name: String,
}

/// What `--initial` reads of a results file: the rods' states and, when listed, the joints' names.
pub struct Initial {
    pub rods: Vec<RodState>,
    pub joints: Option<Vec<String>>,
}

#[derive(Deserialize)]
struct SavedRod {
    name: String,
    points: Vec<[f64; 3]>,
    /// `null` (how serde_json writes NaN) is read as NaN, so that it is refused with its place.
    #[serde(default)]
    twist: Vec<Option<f64>>,
}

/// Parses results JSON text into rod states; the error says what is missing or malformed.
pub fn parse(text: &str) -> Result<Initial, String> {
    let saved: Saved = serde_json::from_str(text).map_err(|e| {
        format!("not a rodnet results JSON with rods: {e} (NaN and Infinity are not JSON numbers)")
    })?;
    let joints = saved
        .joints
        .map(|j| j.into_iter().map(|j| j.name).collect());
    let rods = saved
        .rods
        .into_iter()
        .map(|r| RodState {
            name: r.name,
            points: r.points,
            twist: r.twist.into_iter().map(|t| t.unwrap_or(f64::NAN)).collect(),
        })
        .collect();
    Ok(Initial { rods, joints })
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
