//! Solves a scene many times (for profiling): `cargo run --release --example repeat -- SCENE N`.
use rodnet::pipeline::{settings_of, solve_scene};
fn main() {
    let path = std::env::args().nth(1).unwrap();
    let n: usize = std::env::args().nth(2).map_or(100, |s| s.parse().unwrap());
    let (s, _) = rodnet::scene::load(std::path::Path::new(&path)).unwrap();
    let st = settings_of(&s);
    let t0 = std::time::Instant::now();
    for _ in 0..n {
        let sol = solve_scene(&s, &st).unwrap();
        std::hint::black_box(sol);
    }
    eprintln!(
        "{:.3} ms per solve",
        t0.elapsed().as_secs_f64() * 1e3 / n as f64
    );
}
