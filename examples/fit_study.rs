//! The validation tables of docs/gridshell.md ("Gridshells on target meshes"): every
//! validation surface fitted and form-found, its deviation from the target against subdivision
//! and mesh resolution, and the hemisphere mesh's net against the analytic net.
//!
//! `cargo run --release --example fit_study [-- OUT_DIR]` (OUT_DIR: results JSON for
//! `rodnet plot`).

use std::sync::Arc;
use std::time::Instant;

use rodnet::gridshell::chebyshev::HemisphereNet;
use rodnet::gridshell::fit::compass::Seed;
use rodnet::gridshell::fit::footprint::{FitSpec, DEFAULT_MIN_ANGLE_DEG};
use rodnet::gridshell::fit::job;
use rodnet::gridshell::fit::net::{self, Layout};
use rodnet::gridshell::footprint::JointChoice;
use rodnet::scene::types::Section;
use rodnet::surface::{shapes, Surface};

type Shape = (&'static str, fn(usize) -> shapes::Mesh, Option<[f64; 3]>);

fn shapes_list() -> Vec<Shape> {
    vec![
        ("paraboloid cap", |n| shapes::paraboloid(1.0, 0.6, n), None),
        ("spheroidal dome", |n| shapes::spheroid(1.0, 0.6, n), None),
        (
            "quarter-sphere + half-cylinder vault",
            |n| shapes::vault(1.0, 2.0, n / 2),
            Some([1.0, 0.0, 1.0]),
        ),
        ("saddle", |n| shapes::saddle(1.0, 1.5, n), Some([0.0; 3])),
    ]
}

fn spec(origin: Option<[f64; 3]>, subdivide: usize) -> FitSpec {
    FitSpec {
        spacing: 0.2,
        origin,
        directions: None,
        layout: Layout::On,
        min_angle_deg: DEFAULT_MIN_ANGLE_DEG,
        subdivide,
        joint: JointChoice::Ball,
        section: Section::Circle { radius: 0.004 },
        young_modulus: 1e9,
        poisson_ratio: 0.3,
        tolerance: None,
        max_iterations: 1000,
    }
}

fn main() {
    let out = std::env::args().nth(1).map(std::path::PathBuf::from);
    println!("| surface | rods | joints | net angles (°) | max |d|/size | rms |d|/size | iterations | form finding (s) | stable (escapes) |");
    println!("|---|---|---|---|---|---|---|---|---|");
    for (name, mesh, origin) in shapes_list() {
        let s = Arc::new(Surface::from_obj(name, &shapes::to_obj(&mesh(64))).unwrap());
        let t0 = Instant::now();
        let run = job::run(
            &s,
            name,
            &spec(origin, 4),
            None,
            &rodnet::pipeline::Limits::NONE,
        )
        .ok()
        .expect("fits");
        let total = t0.elapsed().as_secs_f64();
        let t = run.results.target.as_ref().unwrap();
        let b = &run.net_block;
        println!(
            "| {name} | {} | {} | {:.1}–{:.1} | {:.2e} | {:.2e} | {} | {:.3} (whole fit {:.3}) | {} ({}) |",
            b.rods, b.joints, b.min_angle_deg, b.max_angle_deg,
            t.max_abs_distance.unwrap() / s.size, t.rms_distance.unwrap() / s.size,
            run.results.iterations, run.form_seconds, total, run.report.stable, run.report.saddle_escapes
        );
        if let Some(dir) = &out {
            let file = dir.join(format!("{}.json", name.split_whitespace().next().unwrap()));
            std::fs::write(file, serde_json::to_vec(&run.results).unwrap()).unwrap();
        }
    }
    println!();
    println!("| surface | K = 2 | K = 4 | K = 8 | rings 16 | rings 32 | rings 64 | rings 128 |");
    println!("|---|---|---|---|---|---|---|---|");
    for (name, mesh, origin) in shapes_list() {
        let mut row = format!("| {name} |");
        let fine = Arc::new(Surface::from_obj(name, &shapes::to_obj(&mesh(64))).unwrap());
        for k in [2, 4, 8] {
            let r = job::run(
                &fine,
                name,
                &spec(origin, k),
                None,
                &rodnet::pipeline::Limits::NONE,
            )
            .ok()
            .unwrap();
            let t = r.results.target.as_ref().unwrap();
            row += &format!(" {:.3e} |", t.rms_distance.unwrap() / fine.size);
        }
        for rings in [16, 32, 64, 128] {
            let s = Arc::new(Surface::from_obj(name, &shapes::to_obj(&mesh(rings))).unwrap());
            let r = job::run(
                &s,
                name,
                &spec(origin, 4),
                None,
                &rodnet::pipeline::Limits::NONE,
            )
            .ok()
            .unwrap();
            let t = r.results.target.as_ref().unwrap();
            row += &format!(" {:.3e} |", t.rms_distance.unwrap() / s.size);
        }
        println!("{row}");
    }
    println!();
    println!("| rings | triangles | mean edge (m) | max crossing error (m) | max rod-length error (m) | estimated construction error (m) |");
    println!("|---|---|---|---|---|---|");
    let exact = HemisphereNet::new(1.0, 12);
    for rings in [16, 32, 64, 128, 256] {
        let mesh = shapes::hemisphere(1.0, rings);
        let s = Surface::from_obj("h", &shapes::to_obj(&mesh)).unwrap();
        let seed = Seed {
            origin: [0.0, 0.0, 1.0],
            d1: [1.0, 0.0, 0.0],
            d2: [0.0, 1.0, 0.0],
            min_angle: DEFAULT_MIN_ANGLE_DEG.to_radians(),
        };
        let n = net::build(
            &s,
            &seed,
            exact.spacing,
            Layout::Between,
            net::DEFAULT_STEPS,
            rodnet::gridshell::fit::size::MAX_GRID_NODES,
        )
        .expect("the study's nets are small");
        let (mut dx, mut dl) = (0.0f64, 0.0f64);
        for c in &n.crossings {
            let (ru, rv) = (&n.rods[c.rods[0]], &n.rods[c.rods[1]]);
            let p = exact.crossing((rv.k + 6) as usize, (ru.k + 6) as usize);
            dx = dx.max(
                (0..3)
                    .map(|k| (p[k] - c.point[k]).powi(2))
                    .sum::<f64>()
                    .sqrt(),
            );
        }
        for r in &n.rods {
            dl = dl.max((r.length() - 2.0 * exact.half_lengths[(r.k + 6) as usize]).abs());
        }
        println!(
            "| {rings} | {} | {:.4} | {dx:.2e} | {dl:.2e} | {:.2e} |",
            mesh.1.len(),
            s.mean_edge(),
            n.construction_error
        );
    }
}
