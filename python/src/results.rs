//! `rodnet.Results`: a solve's results (the results JSON of docs/contract.md), with NumPy
//! arrays for the rods' points and twists.

use std::path::PathBuf;

use pyo3::exceptions::{PyIndexError, PyKeyError, PyOSError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyBytes;

use rodnet::io::results::{Results as ResultsJson, RodJson};
use rodnet::sweep::run::Solved;

/// The results of a solve: the content of the results JSON (`to_dict()`), with shortcuts.
/// Pickled as that JSON text (read back bit for bit), so that process pools and Dask can pass
/// results between processes.
#[pyclass(module = "rodnet", frozen)]
pub struct Results {
    solved: Solved,
    /// The `gridshell` block as JSON: the block's own type only serializes, and an unpickled
    /// Results has nothing else to build it from.
    gridshell: Option<serde_json::Value>,
}

/// A results block as a dict, or None where the results have none.
fn optional_block<'py, T: serde::Serialize>(
    py: Python<'py>,
    block: Option<&T>,
) -> PyResult<Option<Bound<'py, PyAny>>> {
    block
        .map(|b| crate::to_python(py, &serde_json::to_value(b).expect("serializes")))
        .transpose()
}

impl Results {
    pub fn new(solved: Solved) -> Results {
        let gridshell = solved
            .gridshell
            .as_ref()
            .map(|g| serde_json::to_value(g).expect("the gridshell block serializes"));
        let solved = Solved {
            results: solved.results,
            gridshell: None,
        };
        Results { solved, gridshell }
    }

    /// The results JSON (`Solved::to_json` with the block kept here).
    fn json(&self) -> serde_json::Value {
        let mut v = self.solved.to_json();
        if let (Some(g), serde_json::Value::Object(m)) = (&self.gridshell, &mut v) {
            m.insert("gridshell".into(), g.clone());
        }
        v
    }

    fn rod(&self, rod: &Bound<'_, PyAny>) -> PyResult<&RodJson> {
        let rods = &self.solved.results.rods;
        if let Ok(i) = rod.extract::<i64>() {
            let n = rods.len() as i64;
            let k = if i < 0 { i + n } else { i };
            return usize::try_from(k)
                .ok()
                .and_then(|k| rods.get(k))
                .ok_or_else(|| {
                    PyIndexError::new_err(format!("rod index {i} out of range ({n} rods)"))
                });
        }
        let name: String = rod.extract()?;
        rods.iter().find(|r| r.name == name).ok_or_else(|| {
            let names: Vec<&str> = rods.iter().map(|r| r.name.as_str()).collect();
            PyKeyError::new_err(format!(
                "no rod named {name:?} (rods: {})",
                names.join(", ")
            ))
        })
    }
}

/// A float64 NumPy array of `shape` from `values`.
fn array<'py>(py: Python<'py>, values: &[f64], shape: &[usize]) -> PyResult<Bound<'py, PyAny>> {
    let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_ne_bytes()).collect();
    let np = py.import("numpy")?;
    // frombuffer shares the immutable bytes; the copy makes an ordinary writable array.
    np.call_method1("frombuffer", (PyBytes::new(py, &bytes), "float64"))?
        .call_method1("reshape", (shape.to_vec(),))?
        .call_method0("copy")
}

#[pymethods]
impl Results {
    /// Whether the solve reached its tolerance.
    #[getter]
    fn converged(&self) -> bool {
        self.solved.results.converged
    }
    /// Newton iterations over all load steps.
    #[getter]
    fn iterations(&self) -> usize {
        self.solved.results.iterations
    }
    /// Final relative residual.
    #[getter]
    fn residual(&self) -> f64 {
        self.solved.results.residual
    }
    /// Total energy at the equilibrium, J (the parts are in `to_dict()["energy"]`).
    #[getter]
    fn energy(&self) -> f64 {
        self.solved.results.energy.total
    }
    /// Solve time, s.
    #[getter]
    fn seconds(&self) -> f64 {
        self.solved.results.seconds
    }
    /// Whether the equilibrium is stable (Hessian positive definite).
    #[getter]
    fn stable(&self) -> bool {
        self.solved.results.solver.stable
    }
    /// The solver's message (why it stopped, when it did not converge), or None.
    #[getter]
    fn message(&self) -> Option<String> {
        self.solved.results.solver.message.clone()
    }
    /// Rod names, in order.
    #[getter]
    fn rods(&self) -> Vec<String> {
        self.solved
            .results
            .rods
            .iter()
            .map(|r| r.name.clone())
            .collect()
    }
    /// Support reactions: dicts with `rod`, `vertex`, `force` (N) and `moment` (N·m).
    #[getter]
    fn reactions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let v = serde_json::to_value(&self.solved.results.reactions).expect("serializes");
        crate::to_python(py, &v)
    }
    /// The shape metrics against the scene's (or the gridshell's) target, or None.
    #[getter]
    fn target<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        optional_block(py, self.solved.results.target.as_ref())
    }
    /// The eigen-analysis (`modes=K`), or None.
    #[getter]
    fn stability<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        optional_block(py, self.solved.results.stability.as_ref())
    }
    /// The Richardson extrapolation (`extrapolate=2` or `3`), or None.
    #[getter]
    fn extrapolation<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        optional_block(py, self.solved.results.extrapolation.as_ref())
    }
    /// The generated gridshell's block (options, sizes, shape metrics), or None.
    #[getter]
    fn gridshell<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        optional_block(py, self.gridshell.as_ref())
    }

    /// Node positions of a rod (by name or index), m: an (n, 3) array.
    fn points<'py>(&self, py: Python<'py>, rod: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
        let r = self.rod(rod)?;
        let flat: Vec<f64> = r.points.iter().flatten().copied().collect();
        array(py, &flat, &[r.points.len(), 3])
    }

    /// Material-frame angle of each edge of a rod (by name or index), rad: an (n - 1,) array.
    fn twist<'py>(&self, py: Python<'py>, rod: &Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>> {
        let r = self.rod(rod)?;
        array(py, &r.twist, &[r.twist.len()])
    }

    /// The results JSON as Python data.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        crate::to_python(py, &self.json())
    }

    /// The results JSON text.
    fn to_json(&self) -> String {
        serde_json::to_string_pretty(&self.json()).expect("serializes")
    }

    /// Writes the results JSON (as `rodnet solve --json`), atomically.
    fn write_json(&self, path: PathBuf) -> PyResult<()> {
        write(&path, self.to_json().as_bytes())
    }

    /// Writes the equilibrium as OBJ polylines (as `rodnet solve --obj`), atomically.
    fn write_obj(&self, path: PathBuf) -> PyResult<()> {
        self.write_format("obj", &path)
    }

    /// Writes the equilibrium as VTK XML (as `rodnet solve --vtk`): `.vtp` PolyData or `.vtu`
    /// UnstructuredGrid (meshio reads the latter), atomically.
    fn write_vtk(&self, path: PathBuf) -> PyResult<()> {
        let vtk = rodnet::io::formats::named("vtk").expect("vtk is a format");
        if let Some(check) = vtk.check {
            check(&path).map_err(PyValueError::new_err)?;
        }
        if !self.solved.results.all_finite() {
            return Err(PyValueError::new_err(
                "the results hold non-finite values (the solve diverged); no VTK file written",
            ));
        }
        self.write_format("vtk", &path)
    }

    /// Results from the text `to_json()` wrote (what unpickling calls).
    #[staticmethod]
    fn _from_json(text: &str) -> PyResult<Results> {
        let mut v: serde_json::Value =
            serde_json::from_str(text).map_err(|e| PyValueError::new_err(e.to_string()))?;
        let gridshell = v.as_object_mut().and_then(|m| m.remove("gridshell"));
        let results: ResultsJson =
            serde_json::from_value(v).map_err(|e| PyValueError::new_err(e.to_string()))?;
        Ok(Results {
            solved: Solved {
                results,
                gridshell: None,
            },
            gridshell,
        })
    }

    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<(Bound<'py, PyAny>, (String,))> {
        let ctor = slf.get_type().getattr("_from_json")?;
        Ok((ctor, (slf.get().to_json(),)))
    }

    fn __repr__(&self) -> String {
        let r = &self.solved.results;
        format!(
            "Results({}, {} iterations, residual {:.2e}, energy {:.6e} J, {} rods)",
            if r.converged {
                "converged"
            } else {
                "NOT converged"
            },
            r.iterations,
            r.residual,
            r.energy.total,
            r.rods.len()
        )
    }
}

impl Results {
    /// Writes one of `rodnet::io::formats::FORMATS` (made from the results alone), as the
    /// commands write it.
    fn write_format(&self, name: &str, path: &std::path::Path) -> PyResult<()> {
        let format = rodnet::io::formats::named(name).expect("a format");
        let solved = rodnet::io::formats::Solved {
            results: &self.solved.results,
            equilibrium: None,
            json: None,
        };
        let bytes = (format.bytes)(path, &solved).map_err(PyValueError::new_err)?;
        write(path, &bytes)
    }
}

fn write(path: &std::path::Path, bytes: &[u8]) -> PyResult<()> {
    rodnet::io::atomic::write(path, bytes)
        .map_err(|e| PyOSError::new_err(format!("cannot write {}: {e}", path.display())))
}
