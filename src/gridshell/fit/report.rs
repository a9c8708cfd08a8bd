//! The fit job's text report.

use std::fmt::Write;

use super::job::FitRun;

pub fn summary(run: &FitRun) -> String {
    let mut s = String::new();
    let net = &run.footprint.net;
    let b = &run.net_block;
    let r = &run.results;
    let _ = writeln!(
        s,
        "gridshell fit: spacing {} m, {} rods, {} joints ({} joint), net angles {:.1}°–{:.1}°",
        net.spacing,
        b.rods,
        b.joints,
        run.spec.joint.name(),
        b.min_angle_deg,
        b.max_angle_deg
    );
    let _ = writeln!(
        s,
        "net: compass with {} and {} steps per spacing, extrapolated; estimated construction \
         error {:.2e} m; {} s",
        net.steps[0],
        net.steps[1],
        net.construction_error,
        fmt_s(run.net_seconds)
    );
    let stops = run.stops();
    if stops.is_empty() {
        let _ = writeln!(s, "every rod reaches the boundary");
    } else {
        let _ = writeln!(
            s,
            "{} rod ends stop inside the surface (pinned there):",
            stops.len()
        );
        for line in &stops {
            let _ = writeln!(s, "  {line}");
        }
    }
    if run.footprint.dropped_rods > 0 {
        let _ = writeln!(
            s,
            "{} net rods crossed by no other rod were left out",
            run.footprint.dropped_rods
        );
    }
    let _ = writeln!(
        s,
        "form finding: {} from the net, {} Newton iterations, relative residual {:.2e}, {} s",
        if r.converged {
            "converged"
        } else {
            "NOT converged"
        },
        r.iterations,
        r.residual,
        fmt_s(run.form_seconds)
    );
    if !run.from_net {
        let _ = writeln!(
            s,
            "  (Newton from the net failed; solved from the flat footprint along its buckling path)"
        );
    }
    let escapes = run.report.saddle_escapes;
    if escapes > 0 {
        let _ = writeln!(
            s,
            "  the equilibrium nearest the net was unstable: left along negative curvature {escapes} \
             time(s) to the state reported"
        );
    }
    let _ = writeln!(
        s,
        "  state: {}",
        if run.report.stable {
            "stable (positive definite Hessian)"
        } else {
            "NOT shown stable"
        }
    );
    if let Some(m) = r.target.as_ref() {
        if let (Some(max), Some(rms), Some(mean)) =
            (m.max_abs_distance, m.rms_distance, m.mean_signed_distance)
        {
            let _ = writeln!(
                s,
                "shell to target (joints): max |d| {max:.4e} m, rms {rms:.4e} m, mean signed \
                 {mean:.4e} m"
            );
        }
    }
    let _ = writeln!(
        s,
        "joints to the net: max {:.4e} m, rms {:.4e} m",
        b.max_net_distance, b.rms_net_distance
    );
    s
}

fn fmt_s(x: f64) -> String {
    format!("{x:.3}")
}
