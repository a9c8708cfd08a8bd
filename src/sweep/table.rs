//! The merged table (`sweep.csv`): one row per point from the points' results files and the
//! manifest, with units in the header; what is missing is listed, not guessed.

use std::path::{Path, PathBuf};

use serde::Deserialize;
use serde_json::Value as Json;

use super::path;

pub const MANIFEST: &str = "manifest.json";
pub const TABLE: &str = "sweep.csv";

/// Quantities tabulated when a sweep names none.
pub fn default_quantities(hemisphere: bool) -> Vec<String> {
    let mut q = vec!["residual", "energy.total"];
    if hemisphere {
        q.extend([
            "target.max_abs_radial_deviation",
            "target.rms_radial_deviation",
            "target.apex_height",
            "target.max_net_distance",
        ]);
    } else {
        q.push("energy.bend");
    }
    q.into_iter().map(String::from).collect()
}

/// The unit of a parameter or quantity, from its last name (`1`: dimensionless or a count).
pub fn unit(name: &str) -> &'static str {
    let segs = path::segments(name).unwrap_or_default();
    let last = segs.iter().rev().find(|s| s.parse::<i64>().is_err());
    let first = segs.first().map(String::as_str).unwrap_or("");
    match (first, last.map(String::as_str).unwrap_or("")) {
        ("energy", _) | (_, "energy") => "J",
        // The target and gridshell metrics are over the sphere radius.
        ("target" | "gridshell", "max_abs_radial_deviation" | "rms_radial_deviation")
        | ("target" | "gridshell", "apex_height" | "max_net_distance" | "rms_net_distance")
        | ("gridshell", "mean_radial_deviation" | "lowest_joint_height") => "1",
        ("utilization", _) | (_, "utilization") => "1",
        (_, "young_modulus" | "shear_modulus" | "yield_strength" | "max_bending_stress") => "Pa",
        (_, "bending_stress" | "von_mises") => "Pa",
        (_, "density") => "kg/m^3",
        (_, "radius" | "width" | "height" | "a" | "b" | "length" | "points" | "position") => "m",
        (_, "rest_points" | "target_distance") => "m",
        (_, "move_to" | "gap" | "primal_feasibility") => "m",
        (_, "force" | "axial" | "shear") => "N",
        (_, "moment" | "torsion") => "N m",
        (_, "twist" | "rotate" | "angle") => "rad",
        (_, "seconds" | "time_limit" | "factor_seconds" | "form_finding_seconds") => "s",
        (_, "generation_seconds" | "qp_seconds") => "s",
        (_, "eigenvalues") => "N/m",
        (
            _,
            "rods" | "subdivide" | "load_steps" | "max_iterations" | "iterations" | "modes"
            | "section_ratio" | "poisson_ratio" | "tolerance" | "residual" | "residual_floor"
            | "start_cap" | "crossings" | "nodes" | "substeps" | "retries" | "free_unknowns"
            | "vertex" | "node",
        ) => "1",
        _ => "?",
    }
}

#[derive(Debug, Deserialize)]
pub struct Manifest {
    pub sweep: PathBuf,
    pub output: PathBuf,
    pub parameters: Vec<String>,
    pub quantities: Vec<String>,
    pub points: Vec<ManifestPoint>,
}

#[derive(Debug, Deserialize)]
pub struct ManifestPoint {
    pub index: usize,
    pub name: String,
    /// The fingerprint of the point's inputs when the manifest was written: a point file with
    /// another one was solved from other inputs (manifests written before it have none).
    #[serde(default)]
    pub fingerprint: Option<String>,
    pub parameters: serde_json::Map<String, Json>,
}

impl Manifest {
    /// Reads `DIR/manifest.json` (DIR: a sweep's output folder or a `--emit slurm` folder).
    pub fn read(dir: &Path) -> Result<Manifest, String> {
        let p = dir.join(MANIFEST);
        let text = std::fs::read(&p).map_err(|e| format!("cannot read {}: {e}", p.display()))?;
        let m: Manifest =
            serde_json::from_slice(&text).map_err(|e| format!("{}: {e}", p.display()))?;
        // Point names become file names in the output folder: a plain name, nothing that
        // reaches another folder.
        if let Some(bad) = m.points.iter().find(|q| !plain_file_name(&q.name)) {
            return Err(format!(
                "{}: point {} has the name {:?}, which is not a plain file name",
                p.display(),
                bad.index,
                bad.name
            ));
        }
        Ok(m)
    }
}

fn plain_file_name(name: &str) -> bool {
    !name.is_empty()
        && name != "."
        && name != ".."
        && !name
            .chars()
            .any(|c| c == '/' || c == '\\' || c.is_control())
}

/// One row: a point's parameters and what its file says (`None`: no file yet).
pub struct Row {
    pub index: usize,
    pub parameters: serde_json::Map<String, Json>,
    pub record: Option<Json>,
}

/// The table's rows: every point of the manifest, with its results file if there is one.
pub fn rows(m: &Manifest) -> Vec<Row> {
    m.points
        .iter()
        .map(|p| Row {
            index: p.index,
            parameters: p.parameters.clone(),
            record: std::fs::read(m.output.join(format!("{}.json", p.name)))
                .ok()
                .and_then(|t| serde_json::from_slice::<Json>(&t).ok())
                .filter(|r| {
                    p.fingerprint.as_deref().is_none_or(|f| {
                        r.pointer("/sweep/fingerprint").and_then(Json::as_str) == Some(f)
                    })
                }),
        })
        .collect()
}

fn cell(v: Option<&Json>) -> String {
    match v {
        None | Some(Json::Null) => String::new(),
        Some(Json::String(s)) => quote(s),
        Some(Json::Bool(b)) => b.to_string(),
        Some(Json::Number(n)) => n.to_string(),
        Some(other) => quote(&other.to_string()),
    }
}

fn quote(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// The message of a point: its error, or why its solve stopped when it did not converge.
pub fn message(record: &Json) -> Option<String> {
    if let Some(e) = record.pointer("/sweep/error").and_then(Json::as_str) {
        return Some(e.to_string());
    }
    let converged = record
        .get("converged")
        .and_then(Json::as_bool)
        .unwrap_or(false);
    (!converged)
        .then(|| record.pointer("/solver/message").and_then(Json::as_str))
        .flatten()
        .map(String::from)
}

/// The CSV text: parameters, `converged`, `iterations`, `seconds`, the quantities and
/// `message`; missing points have only their parameters.
pub fn csv(m: &Manifest, rows: &[Row]) -> String {
    let mut head: Vec<String> = vec!["point".into()];
    head.extend(m.parameters.iter().map(|p| format!("{p} [{}]", unit(p))));
    head.extend([
        "converged".into(),
        "iterations [1]".into(),
        "seconds [s]".into(),
    ]);
    head.extend(m.quantities.iter().map(|q| format!("{q} [{}]", unit(q))));
    head.push("message".into());
    let mut out = head.iter().map(|h| quote(h)).collect::<Vec<_>>().join(",");
    out.push('\n');
    for r in rows {
        let mut line = vec![r.index.to_string()];
        line.extend(m.parameters.iter().map(|p| cell(r.parameters.get(p))));
        match &r.record {
            Some(rec) => {
                line.push(cell(rec.get("converged")));
                line.push(cell(rec.get("iterations")));
                line.push(cell(rec.pointer("/sweep/seconds")));
                line.extend(m.quantities.iter().map(|q| cell(path::get(rec, q))));
                line.push(message(rec).map_or(String::new(), |s| quote(&s)));
            }
            None => {
                line.extend(std::iter::repeat_n(String::new(), 3 + m.quantities.len()));
                line.push("missing".into());
            }
        }
        out.push_str(&line.join(","));
        out.push('\n');
    }
    out
}

/// Builds `sweep.csv` in the output folder from what finished; returns its path and the
/// missing points' indices.
pub fn merge(dir: &Path) -> Result<(PathBuf, Vec<usize>), String> {
    let m = Manifest::read(dir)?;
    let rows = rows(&m);
    let missing: Vec<usize> = rows
        .iter()
        .filter(|r| r.record.is_none())
        .map(|r| r.index)
        .collect();
    // The table goes into the output folder the manifest names; a hand-edited manifest must not
    // make merge write elsewhere: that folder is the manifest's own or holds its points' files.
    let same = |a: &Path, b: &Path| match (a.canonicalize(), b.canonicalize()) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    };
    let holds_points = m
        .points
        .iter()
        .any(|q| m.output.join(format!("{}.json", q.name)).is_file());
    if !same(&m.output, dir) && !holds_points {
        return Err(format!(
            "{}: its output folder {} is not the manifest's folder and holds none of its \
             points' results: not writing there",
            dir.join(MANIFEST).display(),
            m.output.display()
        ));
    }
    let p = m.output.join(TABLE);
    std::fs::create_dir_all(&m.output)
        .map_err(|e| format!("cannot create {}: {e}", m.output.display()))?;
    crate::io::atomic::write(&p, csv(&m, &rows).as_bytes())
        .map_err(|e| format!("cannot write {}: {e}", p.display()))?;
    Ok((p, missing))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn units_follow_the_last_name() {
        assert_eq!(unit("energy.total"), "J");
        assert_eq!(unit("materials.steel.young_modulus"), "Pa");
        assert_eq!(unit("rods.beam.points[-1][1]"), "m");
        assert_eq!(unit("reactions[0].moment[2]"), "N m");
        assert_eq!(unit("rods.beam.bending_stress[3]"), "Pa");
        assert_eq!(unit("utilization.max"), "1");
        assert_eq!(unit("target.apex_height"), "1");
        assert_eq!(unit("something.else"), "?");
        assert_eq!(quote("a,b"), "\"a,b\"");
        assert_eq!(quote("say \"x\""), "\"say \"\"x\"\"\"");
    }
}
