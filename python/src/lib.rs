//! `rodnet._rodnet`: the native part of the `rodnet` Python package (docs/python.md). The
//! package's Python files add the wrappers that are easier to write in Python (the executor
//! route of sweeps, the `gridshell` namespace).
//!
//! Every solve runs with the GIL released and inside `catch_unwind`: a panic becomes a
//! `SolveError`, never an abort of the interpreter.

mod results;
mod scene;
mod sweep;

use std::sync::{Arc, Mutex};

use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use rodnet::solver::Progress;
use rodnet::sweep::run::{panic_message, Failure, Solved};

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

/// Runs a solve with the GIL released, its progress reported to `callback` (and Ctrl-C
/// honoured) between iterations; a callback's exception or an interrupt stops the solve and is
/// raised, a panic becomes a `SolveError`.
pub(crate) fn solve_released(
    py: Python<'_>,
    callback: Option<Py<PyAny>>,
    solve: impl FnOnce(Option<Progress>) -> Result<Solved, Failure> + Send,
) -> PyResult<Result<Solved, Failure>> {
    /// Unwinds out of the solver when the callback asks to stop.
    struct Stop;
    let raised: Arc<Mutex<Option<PyErr>>> = Arc::new(Mutex::new(None));
    let slot = raised.clone();
    let hook: Progress = Arc::new(move |step, iteration, residual, energy| {
        let failed = Python::attach(|py| {
            py.check_signals().err().or_else(|| {
                callback
                    .as_ref()
                    .and_then(|cb| cb.call1(py, (step, iteration, residual, energy)).err())
            })
        });
        if let Some(e) = failed {
            *slot.lock().unwrap_or_else(|p| p.into_inner()) = Some(e);
            // resume_unwind skips the panic hook: nothing is printed for a requested stop.
            std::panic::resume_unwind(Box::new(Stop));
        }
    });
    let outcome =
        py.detach(|| std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| solve(Some(hook)))));
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
/// their `tolist`).
pub(crate) fn from_python(obj: &Bound<'_, PyAny>) -> PyResult<serde_json::Value> {
    let py = obj.py();
    let kwargs = PyDict::new(py);
    kwargs.set_item("default", py.import("rodnet._convert")?.getattr("plain")?)?;
    let text: String = py
        .import("json")?
        .call_method("dumps", (obj,), Some(&kwargs))?
        .extract()?;
    serde_json::from_str(&text).map_err(|e| PyValueError::new_err(e.to_string()))
}

#[pymodule]
fn _rodnet(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
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
