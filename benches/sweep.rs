//! A sweep of 64 small scenes on 1 and 2 threads (`cargo bench --bench sweep`): the speed-up of
//! independent solves, one per thread, over the serial run (docs/sweep.md, "Performance").

use std::path::PathBuf;
use std::sync::atomic::{AtomicUsize, Ordering};

use rodnet::sweep::Sweep;

fn main() {
    divan::main();
}

/// The cantilever of networks/ over 8 Young's moduli × 8 tip loads: 64 solves of 40 edges.
fn sweep(output: &std::path::Path) -> Sweep {
    let src = format!(
        r#"Sweep(
            scene: "{root}/networks/cantilever.ron",
            grid: {{
                "materials.steel.young_modulus": [1e8, 1.5e8, 2e8, 3e8, 4e8, 6e8, 8e8, 1e9],
                "loads[0].force[1]": [-0.2, -0.4, -0.6, -0.8, -1.0, -1.2, -1.4, -1.6],
            }},
            output: "{out}",
        )"#,
        root = env!("CARGO_MANIFEST_DIR"),
        out = output.display()
    );
    Sweep::parse("bench.ron", &src, std::path::Path::new("."), None).expect("valid sweep")
}

static RUN: AtomicUsize = AtomicUsize::new(0);

fn fresh() -> PathBuf {
    let d = std::env::temp_dir().join(format!(
        "rodnet-bench-sweep-{}-{}",
        std::process::id(),
        RUN.fetch_add(1, Ordering::Relaxed)
    ));
    let _ = std::fs::remove_dir_all(&d);
    d
}

#[divan::bench(args = [1, 2], sample_count = 5, sample_size = 1)]
fn sixty_four_cantilevers(bencher: divan::Bencher, jobs: usize) {
    bencher
        .with_inputs(|| {
            let d = fresh();
            (sweep(&d), d)
        })
        .bench_local_values(|(s, d)| {
            let out = s.run(jobs, &|_| {});
            assert!(out.iter().all(|o| o.is_ok()));
            let _ = std::fs::remove_dir_all(&d);
        });
}
