//! Prints the Newton history of the hemisphere form finding (load step, iteration, relative
//! residual, energy): `cargo run --release --example trace_gridshell -- [RODS] [SUBDIVIDE] [LOAD_STEPS]`.
use rodnet::gridshell::footprint::HemisphereSpec;
use rodnet::gridshell::formfind::DEFAULT_START_CAP;
fn cb(step: usize, it: usize, res: f64, e: f64) {
    eprintln!("step {step} it {it} res {res:.3e} e {e:.15e}");
}
fn main() {
    let mut a = std::env::args().skip(1);
    let rods = a.next().map_or(12, |n| n.parse().unwrap());
    let subdivide = a.next().map_or(4, |k| k.parse().unwrap());
    let mut spec = HemisphereSpec::new(1.0, rods, subdivide);
    spec.load_steps = a.next().map_or(1, |k| k.parse().unwrap());
    let run = rodnet::gridshell::job::run(
        &spec,
        DEFAULT_START_CAP,
        Some(std::sync::Arc::new(cb)),
        &rodnet::pipeline::Limits::NONE,
    )
    .unwrap();
    eprintln!("{:?}", run.form.report);
}
