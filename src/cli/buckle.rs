//! `rodnet buckle SCENE.ron`: linear buckling factors and modes about the scene's rest state (a
//! staged scene: about its equilibrium before the stage whose loads they scale).

use std::path::{Path, PathBuf};

use clap::Args;

use super::output::{bad, check_outputs, given, EXIT_OK};
use crate::io::atomic;
use crate::jobs::BuckleError;
use crate::scene::{self, SceneError};

#[derive(Args, Debug)]
pub struct BuckleArgs {
    /// Scene file (RON).
    pub scene: PathBuf,
    /// How many critical factors (and modes) to find.
    #[arg(long, value_name = "K", default_value_t = 4, value_parser = clap::value_parser!(u32).range(1..=100))]
    pub modes: u32,
    /// Write the factors and modes as JSON here.
    #[arg(long)]
    pub json: Option<PathBuf>,
    /// Write the mode shapes here, one OBJ object per mode.
    #[arg(long, value_name = "OUT.obj")]
    pub modes_obj: Option<PathBuf>,
    /// Only the linear factors: skip the check of the first one along the nonlinear load path.
    #[arg(long)]
    pub linear_only: bool,
    /// A scene with stages: the stage whose loads the factors scale, about the equilibrium after
    /// the stages before it (default: the last stage; "base": the scene's own loads, about rest).
    #[arg(long, value_name = "NAME")]
    pub stage: Option<String>,
    /// Print only the factors.
    #[arg(long)]
    pub quiet: bool,
    #[command(flatten)]
    pub limits: super::LimitArgs,
}

pub fn run(a: &BuckleArgs) -> i32 {
    let outs = given(&[("--json", &a.json), ("--modes-obj", &a.modes_obj)]);
    if let Err(e) = check_outputs(&outs, &[a.scene.as_path()]) {
        return bad(e);
    }
    let (sc, src) = match scene::load(&a.scene) {
        Ok(s) => s,
        Err(e) => return bad(e),
    };
    let label = a.scene.display().to_string();
    let buckling = match crate::jobs::buckle(
        &sc,
        a.modes as usize,
        a.linear_only,
        a.stage.as_deref(),
        &a.limits.values(),
    ) {
        Ok(b) => b,
        Err(BuckleError::Scene(e)) => return bad(SceneError::from_field(&label, &src, &e)),
        Err(BuckleError::Analysis(e)) => return bad(format_args!("{label}: {e}")),
    };
    let (net, b, json) = (&buckling.network, &buckling.linear, &buckling.json);
    if !b.converged {
        eprintln!(
            "warning: the factors did not settle within {} rounds; converged is false in the JSON",
            b.rounds
        );
    }
    let path = &json.path;
    let mut files: Vec<(&Path, Vec<u8>)> = Vec::new();
    if let Some(p) = &a.json {
        match serde_json::to_vec_pretty(json) {
            Ok(bytes) => files.push((p, bytes)),
            Err(e) => return bad(format_args!("cannot encode the results as JSON: {e}")),
        }
    }
    if let Some(p) = &a.modes_obj {
        let labels: Vec<String> = b
            .factors
            .iter()
            .enumerate()
            .map(|(i, f)| format!("mode_{} factor {f:.6e}", i + 1))
            .collect();
        files.push((
            p,
            crate::jobs::modes_obj(net, &labels, &b.modes).into_bytes(),
        ));
    }
    if let Err((p, e)) = atomic::write_all(&files) {
        return bad(format_args!("cannot write {}: {e}", p.display()));
    }
    match json.about_stage.as_deref() {
        Some("rest") => println!("{label}: about the rest state, scaling the scene's own loads"),
        Some(about) => println!(
            "{label}: about the equilibrium after stage {about:?}, scaling the next stage's loads"
        ),
        None => {}
    }
    let factors = b
        .factors
        .iter()
        .map(|f| format!("{f:.6e}"))
        .collect::<Vec<_>>()
        .join(", ");
    // A path that never loses stability makes the linear factors no buckling loads: they are
    // not headlined as critical.
    let headline = match path.as_ref().map(|p| p.kind.as_str()) {
        Some("no_buckling") => "linear buckling factors (not reached: the path stays stable)",
        Some("imperfect_bifurcation") => {
            "linear buckling factors (not reached: the path turns smoothly)"
        }
        _ => "critical load factors",
    };
    if b.factors.is_empty() {
        println!("{label}: no positive critical load factor: the loads do not make it buckle");
    } else {
        println!(
            "{label}: {headline} {factors} ({} subspace rounds, {:.3} s)",
            b.rounds, b.seconds
        );
    }
    if let Some(pc) = &path {
        match (pc.critical_load_factor, b.factors.first()) {
            (Some(f), Some(&lin)) => {
                println!(
                    "  along the load path: {} at {f:.6e} ({} equilibria, {} Newton iterations){}",
                    if pc.kind == "bifurcation" {
                        "the path's state turns unstable and leaves it (a bifurcation)"
                    } else {
                        "the lowest eigenvalue crosses zero"
                    },
                    pc.samples.len() - 1,
                    pc.iterations,
                    if (f - lin).abs() > 0.01 * lin {
                        "; the structure deforms before it buckles: trust this factor, not the \
                         linear one"
                    } else {
                        ""
                    }
                );
            }
            _ => println!(
                "  along the load path: {}",
                pc.note.as_deref().unwrap_or("no crossing")
            ),
        }
    }
    EXIT_OK
}
