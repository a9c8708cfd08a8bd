//! `rodnet gridshell fit` against its targets (issue 13, docs/gridshell.md): reading and
//! checking a target mesh of about 10⁵ triangles, its net and footprint, and the whole fit of a
//! hemisphere-sized net (112 crossings) split into what precedes the form finding and the rest.
//!
//! `cargo bench --bench fit`.

use std::sync::Arc;

use rodnet::gridshell::fit::footprint::{footprint, FitSpec, DEFAULT_MIN_ANGLE_DEG};
use rodnet::gridshell::fit::job;
use rodnet::gridshell::fit::net::Layout;
use rodnet::gridshell::footprint::JointChoice;
use rodnet::scene::types::Section;
use rodnet::surface::{shapes, Surface};

fn main() {
    divan::main();
}

/// 6 rings² triangles: 129 rings give 99 846.
const RINGS: usize = 129;

fn spec() -> FitSpec {
    FitSpec {
        spacing: std::f64::consts::PI / 13.0,
        origin: None,
        directions: None,
        layout: Layout::Between,
        min_angle_deg: DEFAULT_MIN_ANGLE_DEG,
        subdivide: 4,
        joint: JointChoice::Ball,
        section: Section::Circle { radius: 0.005 },
        young_modulus: 1e9,
        poisson_ratio: 0.3,
        tolerance: None,
        max_iterations: 1000,
    }
}

fn obj(rings: usize) -> String {
    shapes::to_obj(&shapes::hemisphere(1.0, rings))
}

/// Parsing, checking and indexing the OBJ text of the mesh.
#[divan::bench(args = [RINGS], sample_count = 5, sample_size = 1)]
fn read_mesh(bencher: divan::Bencher, rings: usize) {
    let text = obj(rings);
    bencher.bench(|| Surface::from_obj("h.obj", &text).unwrap().triangles.len());
}

/// Net (two compass constructions) and footprint scene on the mesh, read beforehand.
#[divan::bench(args = [24, RINGS], sample_count = 10, sample_size = 1)]
fn net_and_footprint(bencher: divan::Bencher, rings: usize) {
    let s = Arc::new(Surface::from_obj("h.obj", &obj(rings)).unwrap());
    let spec = spec();
    bencher.bench(|| {
        footprint(&s, "h.obj", &spec, u64::MAX)
            .unwrap()
            .scene
            .joints
            .len()
    });
}

/// The whole fit (net, footprint, network, form finding from the net, measurements) on a mesh
/// of 48 rings (13 824 triangles).
#[divan::bench(sample_count = 10, sample_size = 1)]
fn whole_fit(bencher: divan::Bencher) {
    let s = Arc::new(Surface::from_obj("h.obj", &obj(48)).unwrap());
    let spec = spec();
    bencher.bench(|| {
        job::run(&s, "h.obj", &spec, None, &rodnet::pipeline::Limits::NONE)
            .ok()
            .expect("fits")
            .results
            .converged
    });
}
