//! Where a solve runs: on a worker of rayon's pool.
//!
//! A caller outside the pool hands each parallel loop (term derivatives, energies) to the
//! workers and sleeps until they finish: a wake-up per loop, tens of them per Newton
//! iteration, and the caller's own core takes no part in the work. Run from a worker, a loop
//! is split by work stealing and the calling thread computes its share (docs/performance.md).

/// Runs `op` on a worker of the global rayon pool (in place when already on a worker of any
/// pool, e.g. a sweep's own) and returns its result.
pub fn in_pool<R: Send>(op: impl FnOnce() -> R + Send) -> R {
    rayon::scope(|_| op())
}
