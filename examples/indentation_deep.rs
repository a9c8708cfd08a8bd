//! Deep indentation of hemispherical gridshells (docs/indentation.md): each net form-found as in
//! `indentation_study`, then pushed straight down at its highest joint by displacement control
//! (`network::indent::push`, a frictionless point indenter) to 0.3 R, over n, r/R and joint
//! kind. Reports the force at 0.1, 0.2 and 0.3 R, the secant stiffness over the linear one,
//! the smallest tangent stiffness, and any limit point (a force maximum: where a
//! force-controlled push would snap), and draws F/(K R) and the secant ratio against depth.
//!
//! cargo run --release --example indentation_deep -- [CSV_PATH [PNG_DIR [DEPTH_OVER_R]]]
//!
//! With a depth (over R) other than 0.3, a smaller set is pushed that far, 100 steps per R.

use rodnet::gridshell::footprint::{HemisphereSpec, JointChoice};
use rodnet::gridshell::formfind::DEFAULT_START_CAP;
use rodnet::gridshell::job::run;
use rodnet::io::xy_plot::{chart, Axis, Marker, Series};
use rodnet::network::indent::{linear_stiffness, push, Curve, Push};
use rodnet::pipeline::settings_of;
use rodnet::scene::types::Section;

struct Case {
    joint: JointChoice,
    n: usize,
    ratio: f64,
    k: f64,
    /// The pushed point before the push, m.
    at: [f64; 3],
    curve: Curve,
    form_seconds: f64,
}

fn one(joint: JointChoice, n: usize, ratio: f64, depth: f64) -> Result<Case, String> {
    let mut spec = HemisphereSpec::new(1.0, n, 4);
    spec.joint = joint;
    spec.section = Section::Circle { radius: ratio };
    let t0 = std::time::Instant::now();
    let mut r = run(
        &spec,
        DEFAULT_START_CAP,
        None,
        &rodnet::pipeline::Limits::NONE,
    )
    .map_err(|e| e.message)?;
    let form_seconds = t0.elapsed().as_secs_f64();
    if !(r.form.report.converged && r.form.report.stable) {
        return Err("form finding did not reach a stable state".into());
    }
    let scene = r.footprint.scene.all_stages();
    // The pushed point is the highest joint's vertex on its first rod: for elastic joints that
    // is the rod's node, not the joint's centre node (the linear K here is of the same node).
    let (rod, vertex, node) = scene
        .joints
        .iter()
        .filter_map(|j| {
            let (rod, v) = j.at[0].clone();
            let node = r.network.rod(&rod)?.vertex_node(v)?;
            Some((rod, v, node))
        })
        .max_by(|a, b| {
            let z = |n: usize| r.network.model.position(n)[2];
            z(a.2).total_cmp(&z(b.2))
        })
        .ok_or("no joint")?;
    let k = linear_stiffness(&mut r.network, node, [0.0, 0.0, -1.0])?;
    let how = Push {
        rod,
        vertex,
        direction: [0.0, 0.0, -1.0],
        depth: depth * spec.radius,
        steps: (100.0 * depth).round() as usize,
    };
    let curve = push(&scene, &r.network, &how, &settings_of(&scene))?;
    Ok(Case {
        joint,
        n,
        ratio,
        k,
        at: r.network.model.position(node),
        curve,
        form_seconds,
    })
}

/// The force at depth d by linear interpolation on the curve (None past its end).
fn force_at(c: &Curve, d: f64) -> Option<f64> {
    c.points.windows(2).find_map(|w| {
        let ((d0, f0), (d1, f1)) = (w[0], w[1]);
        (d0 <= d && d <= d1 + 1e-12).then(|| f0 + (f1 - f0) * (d - d0) / (d1 - d0))
    })
}

/// The smallest tangent stiffness (finite differences over the steps) and its mid-depth.
fn min_tangent(c: &Curve) -> (f64, f64) {
    c.points
        .windows(2)
        .map(|w| {
            (
                (w[1].1 - w[0].1) / (w[1].0 - w[0].0),
                0.5 * (w[0].0 + w[1].0),
            )
        })
        .fold((f64::INFINITY, 0.0), |a, b| if b.0 < a.0 { b } else { a })
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut cases = Vec::new();
    let depth: f64 = args
        .get(2)
        .map_or(0.3, |d| d.parse().expect("a depth over R"));
    let mut plan = Vec::new();
    if depth == 0.3 {
        for n in [8, 9, 12, 13, 16] {
            for ratio in [2e-3, 5e-3, 1e-2] {
                plan.push((JointChoice::Ball, n, ratio));
            }
        }
        for joint in [JointChoice::Hinge, JointChoice::Elastic, JointChoice::Rigid] {
            for n in [8, 9, 12, 13, 16] {
                plan.push((joint, n, 5e-3));
            }
        }
    } else {
        for n in [8, 9, 12, 13] {
            plan.push((JointChoice::Ball, n, 5e-3));
        }
        for joint in [JointChoice::Hinge, JointChoice::Elastic, JointChoice::Rigid] {
            plan.push((joint, 12, 5e-3));
        }
    }
    println!(
        "| joint | n | r/R | pushed (x, y, z)/R | K (N/m) | F(0.1R) | F(0.2R) | F(0.3R) (N) | F/(Kδ) at 0.1, 0.2, 0.3 R | min tangent/K at δ/R | limit points (δ/R, F) | complete | iterations | s (form + push) |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    let mut csv = String::from("joint,n,r_over_R,K_N_per_m,depth_over_R,force_N\n");
    for (joint, n, ratio) in plan {
        let c = match one(joint, n, ratio, depth) {
            Ok(c) => c,
            Err(e) => {
                println!("| {} | {n} | {ratio} | {e} |", joint.name());
                continue;
            }
        };
        let f = [0.1, 0.2, 0.3].map(|d| force_at(&c.curve, d));
        let show = |x: Option<f64>, s: f64| x.map_or("–".into(), |x| format!("{:.4}", x * s));
        let secant: Vec<String> = [0.1, 0.2, 0.3]
            .iter()
            .zip(f)
            .map(|(d, x)| show(x, 1.0 / (c.k * d)))
            .collect();
        let (t, at) = min_tangent(&c.curve);
        let lims: Vec<String> = c
            .curve
            .limit_points
            .iter()
            .map(|(d, f)| format!("({d:.3}, {f:.4})"))
            .collect();
        println!(
            "| {} | {n} | {ratio} | ({:.3}, {:.3}, {:.3}) | {:.4} | {} | {} | {} | {} | {:.3} at {at:.3} | {} | {} | {} | {:.1} + {:.1} |",
            joint.name(),
            c.at[0],
            c.at[1],
            c.at[2],
            c.k,
            show(f[0], 1.0),
            show(f[1], 1.0),
            show(f[2], 1.0),
            secant.join(", "),
            t / c.k,
            if lims.is_empty() { "none".into() } else { lims.join(" ") },
            c.curve.complete,
            c.curve.iterations,
            c.form_seconds,
            c.curve.seconds
        );
        if let Some(m) = &c.curve.message {
            println!("|   | {m} |");
        }
        for (d, f) in &c.curve.points {
            csv.push_str(&format!("{},{n},{ratio},{},{d},{f}\n", joint.name(), c.k));
        }
        cases.push(c);
    }
    if let Some(p) = args.first() {
        std::fs::write(p, csv).expect("write the CSV");
    }
    if let Some(dir) = args.get(1) {
        plot(&cases, dir, depth);
    }
}

/// F/(K R) and F/(K δ) against δ/R at r/R = 5e-3, coloured by joint kind: n = 12 solid (a cell
/// centre at the pole), n = 13 dashed (a crossing at the pole).
fn plot(cases: &[Case], dir: &str, depth: f64) {
    let colour = |j: JointChoice| match j {
        JointChoice::Ball => [31, 119, 180],
        JointChoice::Hinge => [44, 160, 44],
        JointChoice::Elastic => [230, 120, 20],
        JointChoice::Rigid => [214, 39, 40],
    };
    let (mut force, mut secant) = (Vec::new(), Vec::new());
    for c in cases
        .iter()
        .filter(|c| c.ratio == 5e-3 && (c.n == 12 || c.n == 13))
    {
        let s = |points: Vec<(f64, f64)>| Series {
            name: format!("{} n = {}", c.joint.name(), c.n),
            colour: colour(c.joint),
            points,
            line: true,
            dashed: c.n == 13,
            marker: Marker::None,
        };
        force.push(s(c
            .curve
            .points
            .iter()
            .map(|&(d, f)| (d, f / c.k))
            .collect()));
        secant.push(s(c
            .curve
            .points
            .iter()
            .skip(1)
            .map(|&(d, f)| (d, f / (c.k * d)))
            .collect()));
    }
    let x = Axis {
        label: "depth δ/R".into(),
        log: false,
        ticks: Some(
            (0..=(depth / 0.05).round() as usize)
                .map(|k| 0.05 * k as f64)
                .filter(|t| depth <= 0.3 || (t * 20.0).round() % 2.0 == 0.0)
                .collect(),
        ),
    };
    let lin = |label: &str| Axis {
        label: label.into(),
        log: false,
        ticks: None,
    };
    for (name, series, y, title) in [
        (
            "indentation_deep_force.png",
            &force,
            lin("F / (K R)"),
            "Deep indentation at the top, r/R = 0.005: force over linear stiffness",
        ),
        (
            "indentation_deep_secant.png",
            &secant,
            lin("secant stiffness F/(K δ)"),
            "Deep indentation at the top, r/R = 0.005: secant over linear stiffness",
        ),
    ] {
        let png = chart(series, (&x, &y), title, (1000, 900)).expect("a chart");
        let path = if depth == 0.3 {
            format!("{dir}/{name}")
        } else {
            format!("{dir}/{}_{depth}.png", name.trim_end_matches(".png"))
        };
        std::fs::write(&path, png).expect("write the PNG");
        println!("wrote {path}");
    }
}
