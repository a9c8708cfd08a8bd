//! The fill-reducing ordering changes the cost of a factorization, never the answer: the grid and
//! star reference networks solved with AMD and with geometric nested dissection agree.

use rodnet::pipeline::{settings_of, solve_scene};
use rodnet::scene::load;
use rodnet::solver::Ordering;

#[test]
fn nested_dissection_and_amd_give_the_same_equilibrium() {
    for name in ["grid", "star", "l_frame"] {
        let path = format!("{}/networks/{name}.ron", env!("CARGO_MANIFEST_DIR"));
        let (scene, _) = load(std::path::Path::new(&path)).unwrap();
        let solve = |o: Ordering| {
            let s = solve_scene(&scene, &settings_of(&scene).ordering(o)).unwrap();
            assert!(s.report.converged, "{name} {o:?}: {:?}", s.report.message);
            s.network.model.state.q.clone()
        };
        let (a, b) = (solve(Ordering::Amd), solve(Ordering::NestedDissection));
        let scale = a.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let diff = a
            .iter()
            .zip(&b)
            .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
        assert!(diff <= 1e-9 * scale, "{name}: {diff:.3e} of {scale:.3e}");
    }
}
