//! `rodnet._rodnet`: the native part of the `rodnet` Python package (docs/python.md). The
//! package's Python files add the wrappers that are easier to write in Python (the executor
//! route of sweeps, the `gridshell` namespace).
//!
//! Every solve runs with the GIL released and inside `catch_unwind`: a panic becomes a
//! `SolveError`, never an abort of the interpreter.

mod results;
mod scene;
mod sweep;
mod worker;

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{self, RecvTimeoutError};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use rodnet::solver::Progress;
use rodnet::sweep::run::{panic_message, Failure, Solved};

pub(crate) use worker::fork_safe;

pyo3::create_exception!(
    rodnet,
    SceneError,
    PyValueError,
    "A scene (or sweep, or generator option) that rodnet refuses. Attributes: `path` (the file, \
     or None), `line` and `column` (1-based, or None), `field` (e.g. `rods[0].subdivide`, or \
     None) and `message`."
);
pyo3::create_exception!(
    rodnet,
    SolveError,
    PyRuntimeError,
    "A solve that produced no results: non-finite values, a failed eigen-analysis, an \
     internal error. A solve that only fails to converge returns Results with \
     `converged == False` instead."
);

/// A `SceneError` with its location attributes.
pub(crate) fn scene_error(
    py: Python<'_>,
    file: Option<&str>,
    line: Option<usize>,
    column: Option<usize>,
    field: Option<String>,
    message: &str,
) -> PyErr {
    let shown = match (file, line, column) {
        (Some(f), Some(l), Some(c)) => format!("{f}:{l}:{c}: {message}"),
        (Some(f), _, _) => format!("{f}: {message}"),
        (None, _, _) => message.to_string(),
    };
    let err = SceneError::new_err(shown);
    let v = err.value(py);
    let set = |k: &str, val: Bound<'_, PyAny>| {
        let _ = v.setattr(k, val);
    };
    set("path", file.into_pyobject(py).expect("str").into_any());
    set("line", line.into_pyobject(py).expect("int").into_any());
    set("column", column.into_pyobject(py).expect("int").into_any());
    set("field", field.into_pyobject(py).expect("str").into_any());
    set(
        "message",
        message.into_pyobject(py).expect("str").into_any(),
    );
    err
}

/// A located `rodnet::scene::SceneError` as a Python `SceneError` (the same message as the
/// command line's).
pub(crate) fn located(
    py: Python<'_>,
    e: &rodnet::scene::SceneError,
    field: Option<String>,
) -> PyErr {
    let file = (!e.file.is_empty()).then_some(e.file.as_str());
    scene_error(py, file, e.line, e.column, field, &e.message)
}

/// How often the calling thread looks for signals (Ctrl-C) while a solve runs.
const SIGNAL_POLL: Duration = Duration::from_millis(50);

/// Runs a solve with the GIL released, its progress reported to `callback` between
/// iterations; a callback's exception stops the solve and is raised, a panic becomes a
/// `SolveError`.
///
/// The solve runs on a thread of its own (`worker`, which keeps finished threads for the next
/// solve) while the calling thread waits for it and checks for signals every `SIGNAL_POLL`:
/// Python runs its signal handlers only on the main thread, and a solve spends whole seconds
/// outside its iterations (building the network, measuring its round-off floor, the
/// eigen-analysis, the results), where a check in the progress hook would not come. On Ctrl-C
/// (`KeyboardInterrupt`, or any exception a handler raises) the call returns at once; the
/// solve's thread is told to stop and does at its next iteration, its results discarded.
pub(crate) fn solve_released<F>(
    py: Python<'_>,
    callback: Option<Py<PyAny>>,
    solve: F,
) -> PyResult<Result<Solved, Failure>>
where
    F: FnOnce(Option<Progress>) -> Result<Solved, Failure> + Send + 'static,
{
    /// Unwinds out of the solver when the callback or an interrupt asks to stop.
    struct Stop;
    let raised: Arc<Mutex<Option<PyErr>>> = Arc::new(Mutex::new(None));
    let cancelled = Arc::new(AtomicBool::new(false));
    let (slot, stop) = (raised.clone(), cancelled.clone());
    let hook: Progress = Arc::new(move |step, iteration, residual, energy| {
        // Checked first: an abandoned solve must not call into an interpreter that may be
        // shutting down.
        if stop.load(Ordering::Relaxed) {
            std::panic::resume_unwind(Box::new(Stop));
        }
        let failed = callback.as_ref().and_then(|cb| {
            Python::attach(|py| cb.call1(py, (step, iteration, residual, energy)).err())
        });
        if let Some(e) = failed {
            *slot.lock().unwrap_or_else(|p| p.into_inner()) = Some(e);
            // resume_unwind skips the panic hook: nothing is printed for a requested stop.
            std::panic::resume_unwind(Box::new(Stop));
        }
    });
    let (tx, rx) = mpsc::channel();
    worker::run(Box::new(move || {
        let out = fork_safe(|| {
            std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| solve(Some(hook))))
        });
        let _ = tx.send(out);
    }))
    .map_err(|e| SolveError::new_err(format!("cannot start the solve's thread: {e}")))?;
    let mut rx = rx;
    let outcome = loop {
        // The receiver goes into the GIL-free closure and back (it is not `Sync`).
        let (got, back) = py.detach(move || (rx.recv_timeout(SIGNAL_POLL), rx));
        rx = back;
        match got {
            Ok(out) => break out,
            Err(RecvTimeoutError::Timeout) => {
                if let Err(e) = py.check_signals() {
                    cancelled.store(true, Ordering::Relaxed);
                    return Err(e);
                }
            }
            Err(RecvTimeoutError::Disconnected) => {
                return Err(SolveError::new_err(
                    "internal error (please report): the solve's thread ended without a result",
                ))
            }
        }
    };
    match outcome {
        Ok(r) => Ok(r),
        Err(p) => {
            if let Some(e) = raised.lock().unwrap_or_else(|p| p.into_inner()).take() {
                return Err(e);
            }
            Err(SolveError::new_err(format!(
                "internal error (please report): {}",
                panic_message(&*p)
            )))
        }
    }
}

/// JSON text to Python objects (through the json module, which is as fast as any).
pub(crate) fn to_python<'py>(
    py: Python<'py>,
    v: &serde_json::Value,
) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(v).map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
    py.import("json")?.call_method1("loads", (text,))
}

/// Python objects to JSON (dicts, lists, numbers, strings; NumPy scalars and arrays through
/// their `tolist`). A value JSON cannot carry (NaN, infinity, another type) is a `SceneError`
/// whose `field` names it: `root` followed by its place inside `obj` (`rods[0].points[1][2]`).
pub(crate) fn from_python(obj: &Bound<'_, PyAny>, root: &str) -> PyResult<serde_json::Value> {
    let py = obj.py();
    let convert = py.import("rodnet._convert")?;
    let kwargs = PyDict::new(py);
    kwargs.set_item("default", convert.getattr("plain")?)?;
    // Python's json writes NaN as `NaN`, which no JSON reader takes: refuse it here, where
    // the value's place is still known.
    kwargs.set_item("allow_nan", false)?;
    let text: String = match py
        .import("json")?
        .call_method("dumps", (obj,), Some(&kwargs))
    {
        Ok(t) => t.extract()?,
        Err(e) => {
            // Only a failed conversion walks the data, so a good scene costs one dumps.
            let found = convert.call_method1("locate", (obj,))?;
            if found.is_none() {
                return Err(e);
            }
            let (at, message): (String, String) = found.extract()?;
            let field = match (root.is_empty(), at.is_empty()) {
                (true, _) => at,
                (false, true) => root.to_string(),
                (false, false) if at.starts_with('[') => format!("{root}{at}"),
                (false, false) => format!("{root}.{at}"),
            };
            let shown = if field.is_empty() {
                message
            } else {
                format!("{field}: {message}")
            };
            let field = (!field.is_empty()).then_some(field);
            return Err(scene_error(py, None, None, None, field, &shown));
        }
    };
    serde_json::from_str(&text).map_err(|e| PyValueError::new_err(e.to_string()))
}

#[pymodule]
fn _rodnet(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    worker::imported();
    m.add("SceneError", py.get_type::<SceneError>())?;
    m.add("SolveError", py.get_type::<SolveError>())?;
    m.add_class::<scene::Scene>()?;
    m.add_class::<results::Results>()?;
    m.add_class::<sweep::Sweep>()?;
    m.add_function(wrap_pyfunction!(scene::load_scene, m)?)?;
    m.add_function(wrap_pyfunction!(scene::_bench_solve, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::hemisphere, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::fit, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::hemisphere_options, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
