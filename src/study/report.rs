//! The convergence study as text: the table with its summary, and CSV.

use std::fmt::Write;

use crate::study::convergence::{Level, Measure, Study};

/// Columns of the CSV, in order.
pub const CSV_COLUMNS: [&str; 12] = [
    "level",
    "subdivide",
    "nodes",
    "dofs",
    "iterations",
    "seconds",
    "converged",
    "residual",
    "reference_error",
    "richardson_error",
    "order",
    "sphere_deviation",
];

fn opt(x: Option<f64>, f: impl Fn(f64) -> String) -> String {
    x.map(f).unwrap_or_default()
}

/// One row per level; cells that do not apply are empty.
pub fn to_csv(study: &Study) -> String {
    let mut t = CSV_COLUMNS.join(",");
    t.push('\n');
    let e = |x: f64| format!("{x:.6e}");
    for l in &study.levels {
        let _ = writeln!(
            t,
            "{},{},{},{},{},{:.6},{},{},{},{},{},{}",
            l.level,
            l.subdivide,
            l.nodes,
            l.dofs,
            l.iterations,
            l.seconds,
            l.converged,
            e(l.residual),
            opt(l.reference_error, e),
            opt(l.richardson_error, e),
            opt(l.order, |x| format!("{x:.4}")),
            opt(l.sphere_deviation, e),
        );
    }
    t
}

/// What the primary error is, in words.
pub fn error_definition(study: &Study) -> String {
    match (study.measure, &study.reference, &study.richardson) {
        (Measure::Reference, Some(r), _) => format!(
            "error = |x - x_ref| / |x_ref - x_rest| at vertex {} of rod \"{}\", against the \
             scene's reference (|x_ref - x_rest| = {:.4e} m)",
            r.vertex, r.rod, r.displacement
        ),
        (_, _, Ok(r)) => format!(
            "error = max over the {} of |x - x_R| / {:.4e} m ({}), against the Richardson \
             extrapolate x_R of levels {}-{}",
            r.points, r.scale, r.scale_name, r.levels[0], r.levels[2]
        ),
        (_, _, Err(_)) => "error against the Richardson extrapolate: not available".into(),
    }
}

/// The table and its summary, as printed on stdout.
pub fn table(study: &Study) -> String {
    let mut t = String::new();
    let _ = writeln!(
        t,
        "convergence study: {}, {} levels ({})",
        study.label,
        study.levels.len(),
        study.refinement
    );
    let _ = writeln!(t, "{}", error_definition(study));
    let extra_richardson = study.measure == Measure::Reference;
    let sphere = study.levels.iter().any(|l| l.sphere_deviation.is_some());
    let mut head = format!(
        "{:>5} {:>9} {:>8} {:>8} {:>5} {:>9} {:>10} {:>6}",
        "level", "subdivide", "nodes", "DOFs", "its", "time [s]", "error", "order"
    );
    if extra_richardson {
        let _ = write!(head, " {:>10}", "Richardson");
    }
    if sphere {
        let _ = write!(head, " {:>10}", "sphere dev");
    }
    let _ = writeln!(t, "{head}");
    for l in &study.levels {
        let sci = |x: Option<f64>| opt(x, |x| format!("{x:.3e}"));
        let _ = write!(
            t,
            "{:>5} {:>9} {:>8} {:>8} {:>5} {:>9.4} {:>10} {:>6}",
            l.level,
            l.subdivide,
            l.nodes,
            l.dofs,
            l.iterations,
            l.seconds,
            sci(study.error(l)),
            opt(l.order, |x| format!("{x:.2}")),
        );
        if extra_richardson {
            let _ = write!(t, " {:>10}", sci(l.richardson_error));
        }
        if sphere {
            let _ = write!(t, " {:>10}", sci(l.sphere_deviation));
        }
        if !l.converged {
            let _ = write!(t, "  NOT converged: {}", failure(l));
        }
        t.push('\n');
    }
    match &study.observed_order {
        Some((p, how)) => {
            let _ = writeln!(t, "observed order: {p:.2} ({how})");
        }
        None => {
            let _ = writeln!(t, "observed order: not available");
        }
    }
    match &study.richardson {
        Ok(r) => {
            let x = &r.extrapolation;
            let _ = writeln!(
                t,
                "Richardson: levels {}-{}, differences {:.3e} m and {:.3e} m, order p = {:.3}",
                r.levels[0], r.levels[2], x.coarse_difference, x.fine_difference, x.order
            );
        }
        Err(why) => {
            let _ = writeln!(t, "Richardson extrapolation not applied: {why}");
        }
    }
    if let Some(s) = study.sphere_limit {
        let _ = writeln!(
            t,
            "max |radial deviation| / R from the target sphere, extrapolated to infinitely fine \
             subdivision: {s:.4e} (the model's own deviation from the sphere, not a \
             discretization error)"
        );
    }
    let failed = study.failed_levels();
    if !failed.is_empty() {
        let _ = writeln!(
            t,
            "levels {failed:?} did not converge: they are listed but left out of the orders and \
             the extrapolation"
        );
    }
    t
}

fn failure(l: &Level) -> String {
    format!(
        "relative residual {:.3e}{}",
        l.residual,
        l.message
            .as_deref()
            .map(|m| format!(" ({m})"))
            .unwrap_or_default()
    )
}
