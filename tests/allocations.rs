//! Newton iterations do not allocate: every buffer of the step, the line search, the
//! corrections and the assembly is made before the first iteration and reused. Counted with a
//! global allocator between the solver's progress reports of consecutive iterations.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

use rodnet::pipeline::{settings_of, solve_scene};
use rodnet::scene::load;
use rodnet::solver::linalg::SparseCholesky;

struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// The tests count the same global allocations: one at a time.
static SERIAL: Mutex<()> = Mutex::new(());

/// Progress reports recorded without allocating: (iterations so far, allocations so far).
const REPORTS: usize = 4096;
static SEEN: AtomicUsize = AtomicUsize::new(0);
static ITERATIONS: [AtomicUsize; REPORTS] = [const { AtomicUsize::new(0) }; REPORTS];
static COUNTS: [AtomicUsize; REPORTS] = [const { AtomicUsize::new(0) }; REPORTS];

/// The allocations of each iteration of the scene's solve (between the reports of one
/// iteration and the next), and the sub-steps taken and retried. The last iteration of a
/// sub-step also holds the next sub-step's start: its snapshot and its prediction (a retried
/// sub-step ends without a report of its last iteration).
fn allocations_per_iteration(name: &str) -> (Vec<usize>, usize, usize) {
    let path = format!("{}/networks/{name}.ron", env!("CARGO_MANIFEST_DIR"));
    let (scene, _) = load(std::path::Path::new(&path)).unwrap();
    SEEN.store(0, Ordering::SeqCst);
    let settings = settings_of(&scene).progress(|_, iterations, _, _| {
        let k = SEEN.fetch_add(1, Ordering::SeqCst);
        if k < REPORTS {
            COUNTS[k].store(ALLOCATIONS.load(Ordering::SeqCst), Ordering::SeqCst);
            ITERATIONS[k].store(iterations, Ordering::SeqCst);
        }
    });
    // Inside a pool's worker, the assembly's parallel loops use the worker's own queue; from
    // outside, each would be injected into the pool's shared queue, which allocates a block
    // every 63 jobs. One worker: with two, a worker's job queue grows and shrinks its buffer
    // when the other is slow to steal (a loaded machine), which allocates twice in whatever
    // iteration it happens (1 of 6 runs with both cores busy, and a CI run beside builds).
    // rodnet's own code is the same at any thread count.
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let s = pool.install(|| solve_scene(&scene, &settings).unwrap());
    assert!(s.report.converged, "{name}: {:?}", s.report.message);
    let seen = SEEN.load(Ordering::SeqCst).min(REPORTS);
    let at = |k: usize| {
        (
            ITERATIONS[k].load(Ordering::SeqCst),
            COUNTS[k].load(Ordering::SeqCst),
        )
    };
    let counts = (1..seen)
        .filter(|&k| at(k).0 == at(k - 1).0 + 1)
        .map(|k| at(k).1 - at(k - 1).1)
        .collect();
    (counts, s.report.substeps, s.report.retries)
}

/// A gridshell lift, a buckled strip, a post-buckled column and a straight rod closed into a
/// ring by its clamps (corrections, length repairs, regularized
/// steps, saddle escapes, sub-steps and retries). A solve builds its length projector in the
/// first iteration that needs one (the first prediction to project, or the first line search
/// that tries the geometric curve: any iteration, its allocations grow with the network);
/// besides that one, only iterations that end a sub-step allocate (the next one's snapshot and
/// prediction, a retry's failure message), a bounded number of times whatever the network's
/// size (before, every iteration allocated about 14 times).
#[test]
fn newton_iterations_do_not_allocate() {
    let _one_at_a_time = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    for name in [
        "hemisphere_lift_n4",
        "buckled_strip",
        "euler_column_postbuckled",
        "extreme/ring",
    ] {
        let (counts, substeps, retries) = allocations_per_iteration(name);
        // Enough iterations to see the loop's steady state (16 for the strip, 40–100 for the
        // others since the second-order predictor).
        assert!(counts.len() > 12, "{name}: {} iterations", counts.len());
        let mut later = counts[1..].to_vec();
        later.sort_unstable_by(|a, b| b.cmp(a));
        let allocating = later.iter().filter(|&&c| c > 0).count();
        // The largest may be the projector's iteration; every other is bounded.
        let most = later.get(1).copied().unwrap_or(0);
        assert!(
            allocating <= substeps + retries + 1 && most <= 80,
            "{name}: {substeps} sub-steps, {retries} retries, allocations per iteration {counts:?}"
        );
    }
}

/// Solves with a factor large enough to be split over two threads (`supernodal_solve.rs`) do
/// not allocate: their scratch is made with the factorization object. An m × m grid Laplacian
/// (shifted to be positive definite).
#[test]
fn split_solves_do_not_allocate() {
    let _one_at_a_time = SERIAL.lock().unwrap_or_else(|e| e.into_inner());
    let m = 300;
    let n = m * m;
    let mut pairs = vec![];
    for k in 0..n {
        pairs.push((k, k));
        pairs.extend((k % m + 1 < m).then_some((k, k + 1)));
        pairs.extend((k + m < n).then_some((k, k + m)));
    }
    let (mut chol, slots) = SparseCholesky::new(n, &pairs);
    for (k, &(r, c)) in pairs.iter().enumerate() {
        chol.values[slots[k]] = if r == c { 4.1 } else { -1.0 };
    }
    chol.factor(0.0).unwrap();
    assert!(
        chol.solves_in_parallel(),
        "{} factor values: too few to split",
        chol.factor_nnz()
    );
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let mut x: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).sin()).collect();
    pool.install(|| {
        let before = ALLOCATIONS.load(Ordering::SeqCst);
        for _ in 0..3 {
            chol.solve(&mut x);
        }
        assert_eq!(ALLOCATIONS.load(Ordering::SeqCst), before);
    });
}
