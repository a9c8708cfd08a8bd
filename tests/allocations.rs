//! Newton iterations do not allocate: every buffer of the step, the line search, the
//! corrections and the assembly is made before the first iteration and reused. Counted with a
//! global allocator between the solver's progress reports of consecutive iterations.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

use rodnet::pipeline::{settings_of, solve_scene};
use rodnet::scene::load;

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

/// Progress reports recorded without allocating: (iterations so far, allocations so far).
const REPORTS: usize = 4096;
static SEEN: AtomicUsize = AtomicUsize::new(0);
static ITERATIONS: [AtomicUsize; REPORTS] = [const { AtomicUsize::new(0) }; REPORTS];
static COUNTS: [AtomicUsize; REPORTS] = [const { AtomicUsize::new(0) }; REPORTS];

/// The allocations of each iteration of the scene's solve (between the reports of one
/// iteration and the next), and the sub-steps retried. A retried sub-step ends without a
/// report of its last iteration, so its count also holds the snapshot that starts the next
/// sub-step.
fn allocations_per_iteration(name: &str) -> (Vec<usize>, usize) {
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
    // every 63 jobs.
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
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
    (counts, s.report.retries)
}

/// A gridshell lift, a buckled strip, a post-buckled column and a straight rod closed into a
/// ring by its clamps (corrections, length repairs, regularized
/// steps, saddle escapes, sub-steps and retries). A solve builds its length projector in the
/// first iteration that needs one; after it, allocations are only those of retried sub-steps
/// (their failure message and the next sub-step's snapshot; before, every iteration allocated
/// about 14 times).
#[test]
fn newton_iterations_do_not_allocate() {
    for name in [
        "hemisphere_lift_n4",
        "buckled_strip",
        "euler_column_postbuckled",
        "extreme/ring",
    ] {
        let (counts, retries) = allocations_per_iteration(name);
        // Enough iterations to see the loop's steady state (28 for the strip, 48–112 for the
        // others since the line search repairs lengths).
        assert!(counts.len() > 20, "{name}: {} iterations", counts.len());
        let later: usize = counts[1..].iter().sum();
        assert!(
            later <= 20 * retries,
            "{name}: {retries} retries, allocations per iteration {counts:?}"
        );
    }
}
