//! Eigen-analysis, linear buckling and indentation costs (`cargo bench --bench stability`),
//! issue 14's targets: the lowest 10 modes of the n = 12, K = 8 hemisphere (< 0.2 s), its linear
//! indentation stiffness after form finding (< 0.05 s), linear buckling of the Euler column.

use rodnet::gridshell::footprint::HemisphereSpec;
use rodnet::gridshell::formfind::DEFAULT_START_CAP;
use rodnet::gridshell::job::{run, HemisphereRun};
use rodnet::network::indent::linear_stiffness;
use rodnet::network::stability::{analyse, buckling};

fn main() {
    divan::main();
}

fn dome() -> HemisphereRun {
    let r = run(
        &HemisphereSpec::new(1.0, 12, 8),
        DEFAULT_START_CAP,
        None,
        &rodnet::pipeline::Limits::NONE,
    )
    .expect("footprint");
    assert!(r.form.report.converged && r.form.report.stable);
    r
}

#[divan::bench(sample_count = 10)]
fn hemisphere_12x8_ten_modes(bencher: divan::Bencher) {
    let mut r = dome();
    bencher.bench_local(|| {
        let s = analyse(&mut r.network, 10).expect("modes");
        assert!(s.converged && s.stable);
        divan::black_box(s);
    });
}

#[divan::bench(sample_count = 10)]
fn hemisphere_12x8_apex_stiffness(bencher: divan::Bencher) {
    let mut r = dome();
    let node = r
        .network
        .joints
        .iter()
        .max_by(|a, b| {
            let z = |n: usize| r.network.model.position(n)[2];
            z(a.node).total_cmp(&z(b.node))
        })
        .expect("joints")
        .node;
    bencher.bench_local(|| {
        let k = linear_stiffness(&mut r.network, node, [0.0, 0.0, -1.0]).expect("stiffness");
        divan::black_box(k);
    });
}

#[divan::bench(sample_count = 20)]
fn euler_column_buckling(bencher: divan::Bencher) {
    let path = format!("{}/networks/euler_column.ron", env!("CARGO_MANIFEST_DIR"));
    let scene = rodnet::scene::load(std::path::Path::new(&path))
        .expect("scene")
        .0;
    bencher.bench_local(|| {
        let mut net = rodnet::network::build(&scene).expect("network");
        let b = buckling(&mut net, 4).expect("factors");
        divan::black_box(b);
    });
}
