//! The hemisphere job: generate the footprint, form-find it, compare with the analytic shapes.

use std::fmt::Write;
use std::time::Instant;

use serde::Serialize;

use crate::gridshell::footprint::{footprint, Footprint, HemisphereSpec};
use crate::gridshell::formfind::{form_find, FormFinding};
use crate::gridshell::report::{shape_metrics, ShapeMetrics};
use crate::io::results::Results;
use crate::network::Network;
use crate::pipeline::{self, Limits};
use crate::scene::types::Section;
use crate::scene::FieldError;
use crate::solver::Progress;

pub struct HemisphereRun {
    pub spec: HemisphereSpec,
    pub footprint: Footprint,
    pub network: Network,
    pub form: FormFinding,
    pub results: Results,
    pub metrics: ShapeMetrics,
    /// Radius of the starting cap over R (see [`form_find`]).
    pub start_cap: f64,
    /// Net, footprint scene and built network, s.
    pub generation_seconds: f64,
}

/// Generates and form-finds the gridshell of `spec`; `start_cap` as in [`form_find`].
pub fn run(
    spec: &HemisphereSpec,
    start_cap: f64,
    progress: Option<Progress>,
    limits: &Limits,
) -> Result<HemisphereRun, FieldError> {
    let t0 = Instant::now();
    let fp = footprint(spec);
    crate::scene::validate::validate(&fp.scene)?;
    let mut settings = limits.settings_of(&fp.scene);
    settings.progress = progress;
    let mut form = None;
    let mut metrics = None;
    let mut generation_seconds = 0.0;
    let solution = pipeline::run(
        &fp.scene,
        &settings,
        |network, settings| {
            generation_seconds = t0.elapsed().as_secs_f64();
            let f = form_find(network, settings, spec.radius, start_cap, spec.path);
            let report = f.report.clone();
            form = Some(f);
            report
        },
        |network, eq| {
            let m = shape_metrics(network, &fp.net, &fp.crossings);
            if let Some(t) = eq.target.as_mut() {
                t.net_distance = Some((m.max_net_distance, m.rms_net_distance));
            }
            metrics = Some(m);
        },
    )?;
    Ok(HemisphereRun {
        spec: spec.clone(),
        footprint: fp,
        network: solution.network,
        form: form.expect("the pipeline solves"),
        results: solution.results,
        metrics: metrics.expect("the pipeline measures"),
        start_cap,
        generation_seconds,
    })
}

/// The `gridshell` block of the results JSON.
#[derive(Debug, Clone, Serialize)]
pub struct GridshellJson {
    pub shape: &'static str,
    pub radius: f64,
    pub rods_per_family: usize,
    pub subdivide: usize,
    pub joint: &'static str,
    pub section: Section,
    pub young_modulus: f64,
    pub poisson_ratio: f64,
    pub start_cap: f64,
    pub crossings: usize,
    pub nodes: usize,
    pub generation_seconds: f64,
    pub form_finding_seconds: f64,
    /// Continuation sub-steps taken, and those retried with a smaller increment.
    pub substeps: usize,
    pub retries: usize,
    /// Relative residual that round-off alone produces (the solve converges to it when it is
    /// above the tolerance).
    pub residual_floor: f64,
    pub metrics: ShapeMetrics,
}

#[derive(Serialize)]
struct Output<'a> {
    #[serde(flatten)]
    results: &'a Results,
    gridshell: GridshellJson,
}

impl HemisphereRun {
    pub fn gridshell_json(&self) -> GridshellJson {
        let s = &self.spec;
        GridshellJson {
            shape: "hemisphere",
            radius: s.radius,
            rods_per_family: s.rods,
            subdivide: s.subdivide,
            joint: s.joint.name(),
            section: s.section,
            young_modulus: s.young_modulus,
            poisson_ratio: s.poisson_ratio,
            start_cap: self.start_cap,
            crossings: self.network.joints.len(),
            nodes: self.network.n_nodes(),
            generation_seconds: self.generation_seconds,
            form_finding_seconds: self.form.seconds,
            substeps: self.form.report.substeps,
            retries: self.form.report.retries,
            residual_floor: self.form.report.residual_floor,
            metrics: self.metrics,
        }
    }

    /// The results JSON of the contract plus the `gridshell` block.
    pub fn to_json(&self) -> Vec<u8> {
        serde_json::to_vec_pretty(&Output {
            results: &self.results,
            gridshell: self.gridshell_json(),
        })
        .expect("results serialize")
    }

    /// A short human-readable report.
    pub fn summary(&self) -> String {
        let s = &self.spec;
        let r = &self.results;
        let m = &self.metrics;
        let mut t = String::new();
        let section = match s.section {
            Section::Circle { radius } => format!("circle r = {radius:.4} m"),
            Section::Ellipse { a, b } => format!("ellipse a = {a:.4} m, b = {b:.4} m"),
            Section::Rectangle { width, height } => {
                format!("rectangle {width:.4} m × {height:.4} m")
            }
        };
        let _ = writeln!(
            t,
            "hemispherical gridshell: R = {} m, {} rods per family, subdivide {}, {} joints, {section}, E = {:.3e} Pa, nu = {}",
            s.radius,
            s.rods,
            s.subdivide,
            s.joint.name(),
            s.young_modulus,
            s.poisson_ratio
        );
        let _ = writeln!(
            t,
            "  {} crossings, {} rods, {} nodes, {} free unknowns",
            self.network.joints.len(),
            self.network.rods.len(),
            self.network.n_nodes(),
            self.network.model.n_free
        );
        let status = if !r.converged {
            "NOT converged"
        } else if r.solver.stable {
            "converged, stable (Hessian positive definite)"
        } else {
            "converged, NOT STABLE (a direction of negative curvature or of zero stiffness)"
        };
        let _ = writeln!(
            t,
            "  form finding: {status}, relative residual {:.2e} (round-off floor {:.2e})",
            r.residual, self.form.report.residual_floor
        );
        let f = &self.form.report;
        let _ = writeln!(
            t,
            "  continuation: {} load steps in {} sub-steps ({} retried), {} Newton iterations (per load step: {:?}), {} regularized",
            f.load_steps, f.substeps, f.retries, f.iterations, f.step_iterations, f.regularized_iterations
        );
        let _ = writeln!(
            t,
            "  time: generation {:.3} s, form finding {:.3} s",
            self.generation_seconds, self.form.seconds
        );
        let _ = writeln!(
            t,
            "  against the sphere (joints, over R): max |radial deviation| {:.3e}, rms {:.3e}, mean {:+.3e}; apex height {:.5}; lowest joint {:+.4}",
            m.max_abs_radial_deviation,
            m.rms_radial_deviation,
            m.mean_radial_deviation,
            m.apex_height,
            m.lowest_joint_height
        );
        let _ = writeln!(
            t,
            "  against the Chebyshev net (joint to its crossing, over R): max {:.3e}, rms {:.3e}",
            m.max_net_distance, m.rms_net_distance
        );
        if let Some(msg) = &r.solver.message {
            let _ = writeln!(t, "  solver: {msg}");
        }
        t
    }
}
