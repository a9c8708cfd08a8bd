//! Prints the Newton history of a scene (load step, iteration, relative residual, energy) and
//! the solver report: `cargo run --release --example trace -- SCENE.ron`.
use rodnet::pipeline::{settings_of, solve_scene};
fn cb(step: usize, it: usize, res: f64, e: f64) {
    eprintln!("step {step} it {it} res {res:.3e} e {e:.15e}");
}
fn main() {
    let path = std::env::args().nth(1).unwrap();
    let (s, _) = rodnet::scene::load(std::path::Path::new(&path)).unwrap();
    let mut st = settings_of(&s);
    st.progress = Some(std::sync::Arc::new(cb));
    let sol = solve_scene(&s, &st).unwrap();
    eprintln!("{:?}", sol.report);
}
