//! The studies behind docs/gridshell.md: the hemispherical gridshell over rods per family,
//! subdivision, joint kind, section slenderness and starting cap, printed as Markdown rows.
//!
//! cargo run --release --example gridshell_study -- grid     # n × subdivide × joint
//! cargo run --release --example gridshell_study -- section  # r/R
//! cargo run --release --example gridshell_study -- cap      # starting cap radius
//! cargo run --release --example gridshell_study -- one N K JOINT [R_OVER_R] [CAP] [STEPS]

use rodnet::gridshell::footprint::{HemisphereSpec, JointChoice, DEFAULT_SECTION_RATIO};
use rodnet::gridshell::formfind::DEFAULT_START_CAP;
use rodnet::gridshell::job::run;
use rodnet::scene::types::Section;

fn joint(name: &str) -> JointChoice {
    JointChoice::from_name(name).unwrap_or_else(|| panic!("unknown joint {name}"))
}

const HEADER: &str = "| n | K | joint | r/R | cap | unknowns | conv. | stable | max rad. | rms rad. | mean rad. | apex | lowest | max net | rms net | steps (sub, retried) | Newton its | gen. s | form s |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|";

fn row(n: usize, k: usize, j: JointChoice, ratio: f64, cap: f64, steps: usize) {
    let mut spec = HemisphereSpec::new(1.0, n, k);
    spec.joint = j;
    spec.section = Section::Circle { radius: ratio };
    spec.load_steps = steps;
    let r = run(&spec, cap, None, &rodnet::pipeline::Limits::NONE).expect("valid footprint");
    let m = &r.metrics;
    let rep = &r.form.report;
    println!(
        "| {n} | {k} | {} | {ratio} | {cap} | {} | {} | {} | {:.3e} | {:.3e} | {:+.2e} | {:.5} | {:.3} | {:.3e} | {:.3e} | {} ({}, {}) | {} | {:.4} | {:.2} |",
        j.name(),
        r.network.model.n_free,
        if rep.converged { "yes" } else { "NO" },
        if rep.stable { "yes" } else { "no" },
        m.max_abs_radial_deviation,
        m.rms_radial_deviation,
        m.mean_radial_deviation,
        m.apex_height,
        m.lowest_joint_height,
        m.max_net_distance,
        m.rms_net_distance,
        rep.load_steps,
        rep.substeps,
        rep.retries,
        rep.iterations,
        r.generation_seconds,
        r.form.seconds,
    );
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let what = args.first().map(String::as_str).unwrap_or("grid");
    let r0 = DEFAULT_SECTION_RATIO;
    println!("{HEADER}");
    match what {
        "grid" => {
            for j in ["ball", "hinge", "rigid"] {
                for n in [8, 12, 16] {
                    for k in [1, 2, 4, 8, 16] {
                        row(n, k, joint(j), r0, DEFAULT_START_CAP, 8);
                    }
                }
            }
        }
        "section" => {
            for ratio in [0.0025, 0.005, 0.01, 0.02] {
                for k in [4, 8] {
                    row(12, k, JointChoice::Ball, ratio, DEFAULT_START_CAP, 8);
                }
            }
        }
        "cap" => {
            for cap in [0.0, 3.0, 5.0, 10.0, 20.0] {
                for (n, k) in [(8, 4), (12, 4), (8, 8)] {
                    row(n, k, JointChoice::Ball, r0, cap, 8);
                }
            }
        }
        "one" => {
            let num = |i: usize, d: f64| args.get(i).map_or(d, |s| s.parse().unwrap());
            row(
                args[1].parse().unwrap(),
                args[2].parse().unwrap(),
                joint(&args[3]),
                num(4, r0),
                num(5, DEFAULT_START_CAP),
                num(6, 8.0) as usize,
            );
        }
        other => panic!("unknown study {other}"),
    }
}
