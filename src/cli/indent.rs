//! `rodnet indent SCENE.ron --at JOINT|ROD:VERTEX|apex --depth D`: solve the scene, then push
//! one point by displacement control; linear stiffness, force–depth curve, limit points.

use std::path::{Path, PathBuf};

use clap::Args;

use super::output::{bad, check_outputs, given, EXIT_NOT_CONVERGED, EXIT_OK};
use crate::io::indent::{curve_csv, IndentJson};
use crate::io::{atomic, curve_plot};
use crate::jobs::{self as job, IndentError};
use crate::scene::{self, SceneError};

#[derive(Args, Debug)]
pub struct IndentArgs {
    /// Scene file (RON).
    pub scene: PathBuf,
    /// The point pushed: a joint's name, ROD:VERTEX (an input vertex), or `apex` (the joint
    /// farthest against the direction; the rod vertex farthest when there are no joints).
    #[arg(long)]
    pub at: String,
    /// How far to push it, m.
    #[arg(long)]
    pub depth: f64,
    /// Direction of the push (default down: 0,0,-1). Along x, y or z the point is held along
    /// the push only (frictionless); otherwise on the line of the push (sticking).
    #[arg(long, value_name = "X,Y,Z", default_value = "0,0,-1")]
    pub direction: String,
    /// Displacement-controlled steps to the full depth.
    #[arg(long, default_value_t = 20, value_parser = clap::value_parser!(u32).range(1..=10000))]
    pub steps: u32,
    /// Write the force–depth curve as CSV here (depth m, force N).
    #[arg(long)]
    pub csv: Option<PathBuf>,
    /// Draw the force–depth curve as a PNG here.
    #[arg(long)]
    pub plot: Option<PathBuf>,
    /// Write the results as JSON here.
    #[arg(long)]
    pub json: Option<PathBuf>,
    /// Only the summary line.
    #[arg(long)]
    pub quiet: bool,
    #[command(flatten)]
    pub limits: super::LimitArgs,
}

pub fn run(a: &IndentArgs) -> i32 {
    let outs = given(&[("--csv", &a.csv), ("--plot", &a.plot), ("--json", &a.json)]);
    if let Err(e) = check_outputs(&outs, &[a.scene.as_path()]) {
        return bad(e);
    }
    let direction = match parse_direction(&a.direction) {
        Ok(d) => d,
        Err(e) => return bad(format_args!("--direction: {e}")),
    };
    if !(a.depth.is_finite() && a.depth > 0.0) {
        return bad(format_args!(
            "--depth must be a positive length in m, got {}",
            a.depth
        ));
    }
    let (sc, src) = match scene::load(&a.scene) {
        Ok(s) => s,
        Err(e) => return bad(e),
    };
    let label = a.scene.display().to_string();
    let (out, curve) = match job::indent(
        &sc,
        &a.at,
        direction,
        a.depth,
        a.steps as usize,
        &a.limits.values(),
    ) {
        Ok(i) => (i.json, i.curve),
        Err(IndentError::Scene(e)) => return bad(SceneError::from_field(&label, &src, &e)),
        Err(IndentError::NotConverged(m)) => {
            eprintln!("error: {label}: the scene itself did not converge ({m}); nothing pushed");
            return EXIT_NOT_CONVERGED;
        }
        Err(IndentError::At(e)) => return bad(format_args!("--at {}: {e}", a.at)),
        Err(IndentError::Push(e)) => return bad(format_args!("{label}: {e}")),
    };
    if let Err(e) = write(a, &out, &curve.points, &curve.limit_points) {
        return bad(e);
    }
    summary(&label, &out);
    if out.complete {
        EXIT_OK
    } else {
        eprintln!(
            "error: {label}: {}",
            out.message.clone().unwrap_or_default()
        );
        EXIT_NOT_CONVERGED
    }
}

fn write(
    a: &IndentArgs,
    out: &IndentJson,
    points: &[(f64, f64)],
    limits: &[(f64, f64)],
) -> Result<(), String> {
    let mut files: Vec<(&Path, Vec<u8>)> = Vec::new();
    if let Some(p) = &a.json {
        let b = serde_json::to_vec_pretty(out).map_err(|e| format!("cannot encode JSON: {e}"))?;
        files.push((p, b));
    }
    if let Some(p) = &a.csv {
        files.push((p, curve_csv(points).into_bytes()));
    }
    if let Some(p) = &a.plot {
        let stable: Vec<bool> = out.curve_stability.iter().map(|s| s.stable).collect();
        let png = curve_plot::curve(
            points,
            &stable,
            limits,
            ("depth (m)", "force (N)"),
            "Indentation: force against depth",
            (900, 600),
        )?;
        files.push((p, png));
    }
    atomic::write_all(&files).map_err(|(p, e)| format!("cannot write {}: {e}", p.display()))
}

fn summary(label: &str, o: &IndentJson) {
    use crate::solver::path_events::EventKind::Snap;
    for e in &o.path_events {
        eprintln!(
            "warning: {label}: the push passed a {} at {:.4e} m depth: {}",
            e.kind.name(),
            e.load_factor * o.depth,
            e.detail
        );
    }
    let k = o.linear_stiffness.map_or_else(
        || "none (unstable state)".into(),
        |k| format!("{k:.6e} N/m"),
    );
    let last = o.curve.last().copied().unwrap_or([0.0, 0.0]);
    println!(
        "{label}: pushed {} vertex {} by {:.4e} m ({}): linear stiffness {k}; force {:.6e} N at \
         depth {:.4e} m; {} limit point(s); {}; {} Newton iterations, {:.3} s",
        o.rod,
        o.vertex,
        o.depth,
        if o.frictionless {
            "frictionless"
        } else {
            "sticking"
        },
        last[1],
        last[0],
        o.limit_points.len(),
        match (
            o.bifurcations.first(),
            o.path_events.iter().find(|e| e.kind == Snap)
        ) {
            (None, None) => "no loss of stability".to_string(),
            (Some(b), _) => format!(
                "{} loss(es) of stability, the first at depth {:.4e} m, force {:.6e} N",
                o.bifurcations.len(),
                b.depth,
                b.force
            ),
            (None, Some(e)) => format!(
                "snapped {} time(s) (path_events), the first at depth {:.4e} m",
                o.path_events.iter().filter(|e| e.kind == Snap).count(),
                e.load_factor * o.depth
            ),
        },
        o.iterations,
        o.seconds
    );
}

fn parse_direction(s: &str) -> Result<[f64; 3], String> {
    let v: Vec<f64> = s
        .split(',')
        .map(|t| t.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|e| format!("expected X,Y,Z, got {s:?} ({e})"))?;
    let [x, y, z] = v[..] else {
        return Err(format!("expected three numbers X,Y,Z, got {s:?}"));
    };
    let n = (x * x + y * y + z * z).sqrt();
    if !(n.is_finite() && n > 1e-150) {
        return Err(format!("must be a finite, non-zero direction, got {s:?}"));
    }
    Ok([x / n, y / n, z / n])
}
