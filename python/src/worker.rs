//! The threads Python's solves run on (`solve_released`), and fork safety.
//!
//! A solve runs on a thread of its own so that the calling thread can check for Ctrl-C while it
//! runs; starting a thread per call cost about 0.2 ms, so finished threads wait for the next
//! solve a while before they end.

use std::sync::mpsc::{self, RecvTimeoutError};
use std::sync::{Arc, Mutex, OnceLock};
use std::time::Duration;

/// Work for a solve thread.
pub(crate) type Task = Box<dyn FnOnce() + Send>;

/// Stack of a solve thread: the main thread's (8 MiB), which the solver has always run on.
const STACK: usize = 8 << 20;
/// How long a finished thread waits for another solve.
const IDLE_FOR: Duration = Duration::from_secs(30);

/// Threads waiting for a solve: (process id, thread number, where to send it). The process id
/// tells a forked child that the threads of its parent are not its own.
static IDLE: Mutex<Vec<(u32, u64, mpsc::Sender<Task>)>> = Mutex::new(Vec::new());
static NUMBER: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);

/// Runs `task` on a waiting solve thread, or on a new one.
pub(crate) fn run(task: Task) -> std::io::Result<()> {
    let pid = std::process::id();
    let mut task = task;
    loop {
        let idle = {
            let mut idle = IDLE.lock().unwrap_or_else(|p| p.into_inner());
            idle.retain(|(p, _, _)| *p == pid);
            idle.pop()
        };
        let Some((_, _, tx)) = idle else { break };
        match tx.send(task) {
            Ok(()) => return Ok(()),
            // That thread has ended: try the next.
            Err(mpsc::SendError(t)) => task = t,
        }
    }
    std::thread::Builder::new()
        .name("rodnet-solve".into())
        .stack_size(STACK)
        .spawn(move || serve(task))
        .map(|_| ())
}

fn serve(first: Task) {
    let pid = std::process::id();
    let me = NUMBER.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let mut task = first;
    loop {
        task();
        let (tx, rx) = mpsc::channel();
        IDLE.lock()
            .unwrap_or_else(|p| p.into_inner())
            .push((pid, me, tx));
        task = match rx.recv_timeout(IDLE_FOR) {
            Ok(t) => t,
            Err(RecvTimeoutError::Disconnected) => return,
            Err(RecvTimeoutError::Timeout) => {
                let mut idle = IDLE.lock().unwrap_or_else(|p| p.into_inner());
                if let Some(i) = idle.iter().position(|(_, n, _)| *n == me) {
                    idle.remove(i);
                    return;
                }
                drop(idle);
                // Taken off the list just now: its task is on the way.
                match rx.recv() {
                    Ok(t) => t,
                    Err(_) => return,
                }
            }
        };
    }
}

/// The process that imported the module: its solves use rayon's global pool.
static IMPORTED_IN: OnceLock<u32> = OnceLock::new();
/// A forked child's own pool, with the child's process id.
static CHILD_POOL: Mutex<Option<(u32, Arc<rayon::ThreadPool>)>> = Mutex::new(None);

/// Records the importing process (the module's init).
pub(crate) fn imported() {
    IMPORTED_IN.get_or_init(std::process::id);
}

/// Runs `f` where rayon can run it. A process forked after rayon's global pool started (a
/// `multiprocessing` or `ProcessPoolExecutor` worker of the "fork" start method) inherits that
/// pool without its threads, and the first parallel loop would wait for them forever; such a
/// child runs its work on a pool of its own instead.
pub(crate) fn fork_safe<R: Send>(f: impl FnOnce() -> R + Send) -> R {
    let pid = std::process::id();
    if IMPORTED_IN.get() == Some(&pid) {
        return f();
    }
    let pool = {
        let mut slot = CHILD_POOL.lock().unwrap_or_else(|p| p.into_inner());
        match &*slot {
            Some((owner, pool)) if *owner == pid => pool.clone(),
            _ => {
                let pool = Arc::new(
                    rayon::ThreadPoolBuilder::new()
                        .build()
                        .expect("a thread pool builds"),
                );
                *slot = Some((pid, pool.clone()));
                pool
            }
        }
    };
    pool.install(f)
}
