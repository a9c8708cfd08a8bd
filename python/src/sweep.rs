//! The hemisphere generator and sweeps, natively: `rodnet.gridshell.hemisphere` and
//! `rodnet.sweep` (whose executor route is written in Python) call these.

use std::path::PathBuf;

use pyo3::exceptions::{PyIndexError, PyOSError};
use pyo3::prelude::*;

use rodnet::scene::SceneError as RustSceneError;
use rodnet::sweep::generator;
use rodnet::sweep::run::{self, Failure};
use rodnet::sweep::{table, Job, OrderedMap, Value};

use crate::results::Results;
use crate::{located, scene_error, solve_released, SolveError};

fn value(py: Python<'_>, name: &str, v: &Bound<'_, PyAny>) -> PyResult<Value> {
    let j = crate::from_python(v, name)?;
    Value::from_json(&j).ok_or_else(|| {
        scene_error(
            py,
            None,
            None,
            None,
            Some(name.to_string()),
            &format!("expected a number, a string or a bool, got {j}"),
        )
    })
}

/// Form-finds the hemispherical gridshell of the given options (those of `rodnet gridshell
/// hemisphere`, as (name, value) pairs) with the GIL released.
#[pyfunction]
#[pyo3(signature = (options, progress=None))]
pub fn hemisphere(
    py: Python<'_>,
    options: Vec<(String, Bound<'_, PyAny>)>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Results> {
    let mut o = OrderedMap::default();
    for (k, v) in &options {
        o.0.push((k.clone(), value(py, k, v)?));
    }
    let h = generator::hemisphere(&o)
        .map_err(|(name, m)| scene_error(py, None, None, None, Some(name), &m))?;
    let job = Job::Hemisphere(Box::new(h));
    let outcome = solve_released(py, progress, move |hook| {
        run::solve(&job, None, hook, &rodnet::pipeline::Limits::machine())
    })?;
    results_of(py, outcome)
}

/// A generator's solve as `Results`, or the exception its failure raises: a scene error names
/// the generated scene's field, a failed solve is a `SolveError`.
fn results_of(py: Python<'_>, outcome: Result<run::Solved, Failure>) -> PyResult<Results> {
    match outcome {
        Ok(s) => Ok(Results::new(s)),
        Err(Failure::Scene(e)) => Err(scene_error(
            py,
            None,
            None,
            None,
            Some(e.path()),
            &e.message,
        )),
        Err(Failure::Solve(m)) => Err(SolveError::new_err(m)),
    }
}

/// The hemisphere generator's option names.
#[pyfunction]
pub fn hemisphere_options() -> Vec<String> {
    generator::option_names()
}

fn sweep_error(py: Python<'_>, e: &RustSceneError) -> PyErr {
    // Parameter errors start "parameter `path` ...": that path is the field.
    let field = e
        .message
        .strip_prefix("parameter `")
        .and_then(|m| m.split('`').next())
        .map(String::from);
    let file = (!e.file.is_empty()).then_some(e.file.as_str());
    scene_error(py, file, e.line, e.column, field, &e.message)
}

/// A checked sweep (native side of `rodnet.sweep`).
#[pyclass(module = "rodnet", frozen)]
pub struct Sweep {
    sweep: rodnet::sweep::Sweep,
    default_output: Option<String>,
}

#[pymethods]
impl Sweep {
    /// Reads and checks a sweep file (RON).
    #[staticmethod]
    fn load(py: Python<'_>, path: PathBuf) -> PyResult<Sweep> {
        let mut sweep = rodnet::sweep::Sweep::load(&path).map_err(|e| sweep_error(py, &e))?;
        sweep.limits = rodnet::pipeline::Limits::machine();
        Ok(Sweep {
            sweep,
            default_output: path.file_stem().map(|s| s.to_string_lossy().into_owned()),
        })
    }

    /// Parses and checks a sweep from RON or JSON text; relative paths from `base_dir`.
    #[staticmethod]
    #[pyo3(signature = (text, file, base_dir, default_output=None))]
    fn parse(
        py: Python<'_>,
        text: &str,
        file: &str,
        base_dir: PathBuf,
        default_output: Option<String>,
    ) -> PyResult<Sweep> {
        let mut sweep = rodnet::sweep::Sweep::parse(
            file,
            text,
            &base_dir,
            default_output.clone().map(PathBuf::from),
        )
        .map_err(|e| sweep_error(py, &e))?;
        sweep.limits = rodnet::pipeline::Limits::machine();
        Ok(Sweep {
            sweep,
            default_output,
        })
    }

    /// What re-creates this sweep elsewhere: (text, file, base_dir, default_output).
    #[getter]
    fn source(&self) -> (String, String, PathBuf, Option<String>) {
        let s = &self.sweep;
        (
            s.source.clone(),
            s.file.clone(),
            s.base_dir.clone(),
            self.default_output.clone(),
        )
    }

    #[getter]
    fn output(&self) -> PathBuf {
        self.sweep.output.clone()
    }

    #[getter]
    fn parameters(&self) -> Vec<String> {
        self.sweep.parameters.clone()
    }

    #[getter]
    fn quantities(&self) -> Vec<String> {
        self.sweep.quantities.clone()
    }

    fn __len__(&self) -> usize {
        self.sweep.points.len()
    }

    /// Indices of the points without finished results.
    fn pending(&self) -> Vec<usize> {
        (0..self.sweep.points.len())
            .filter(|&i| self.sweep.finished_point(i).is_none())
            .collect()
    }

    fn write_manifest(&self, py: Python<'_>) -> PyResult<()> {
        self.sweep
            .write_manifest()
            .map_err(|e| located(py, &e, None))
    }

    /// Solves point `i` (unless its results exist) with the GIL released; returns its record.
    fn run_point<'py>(&self, py: Python<'py>, i: usize) -> PyResult<Bound<'py, PyAny>> {
        if i >= self.sweep.points.len() {
            return Err(PyIndexError::new_err(format!(
                "point {i} of {}",
                self.sweep.points.len()
            )));
        }
        let r = py.detach(|| crate::fork_safe(|| self.sweep.run_point(i)));
        let o = r.map_err(PyOSError::new_err)?;
        crate::to_python(py, &o.record)
    }

    /// Solves every pending point on `jobs` threads with the GIL released.
    fn run(&self, py: Python<'_>, jobs: usize) -> PyResult<()> {
        let out = py.detach(|| self.sweep.run(jobs, &|_| {}));
        match out.into_iter().find_map(Result::err) {
            Some(e) => Err(PyOSError::new_err(e)),
            None => Ok(()),
        }
    }

    /// Writes sweep.csv from the finished points; returns (its path, missing points, rows as
    /// dicts: point, the parameters, converged, iterations, seconds, the quantities, message).
    fn merge<'py>(&self, py: Python<'py>) -> PyResult<(PathBuf, Vec<usize>, Bound<'py, PyAny>)> {
        let (p, missing) = table::merge(&self.sweep.output).map_err(PyOSError::new_err)?;
        let m = table::Manifest::read(&self.sweep.output).map_err(PyOSError::new_err)?;
        let rows: Vec<serde_json::Value> = table::rows(&m)
            .into_iter()
            .map(|r| {
                let mut row = serde_json::Map::new();
                row.insert("point".into(), r.index.into());
                row.extend(r.parameters);
                let rec = r.record.unwrap_or(serde_json::Value::Null);
                row.insert(
                    "converged".into(),
                    rec.get("converged").cloned().unwrap_or_default(),
                );
                row.insert(
                    "iterations".into(),
                    rec.get("iterations").cloned().unwrap_or_default(),
                );
                row.insert(
                    "seconds".into(),
                    rec.pointer("/sweep/seconds").cloned().unwrap_or_default(),
                );
                for q in &m.quantities {
                    let v = rodnet::sweep::path::get(&rec, q)
                        .cloned()
                        .unwrap_or_default();
                    row.insert(q.clone(), v);
                }
                row.insert("message".into(), table::message(&rec).into());
                serde_json::Value::Object(row)
            })
            .collect();
        Ok((
            p,
            missing,
            crate::to_python(py, &serde_json::Value::Array(rows))?,
        ))
    }
}

/// Fits a Chebyshev-net gridshell to the OBJ mesh `target` and form-finds it, as `rodnet
/// gridshell fit` does, with the GIL released.
#[pyfunction]
#[pyo3(signature = (target, spacing, *, origin=None, directions=None, layout="on", min_angle=None,
    subdivide=4, joint="ball", section_radius=None, young_modulus=1e9, poisson_ratio=0.3,
    tolerance=None, progress=None))]
#[allow(clippy::too_many_arguments)]
pub fn fit(
    py: Python<'_>,
    target: PathBuf,
    spacing: f64,
    origin: Option<[f64; 3]>,
    directions: Option<([f64; 3], [f64; 3])>,
    layout: &str,
    min_angle: Option<f64>,
    subdivide: usize,
    joint: &str,
    section_radius: Option<f64>,
    young_modulus: f64,
    poisson_ratio: f64,
    tolerance: Option<f64>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Results> {
    use rodnet::gridshell::fit::{footprint as fp, job, net::Layout};
    use rodnet::gridshell::footprint::JointChoice;
    let option = |name: &str, m: String| scene_error(py, None, None, None, Some(name.into()), &m);
    let layout = match layout {
        "on" => Layout::On,
        "between" => Layout::Between,
        other => {
            return Err(option(
                "layout",
                format!("must be \"on\" or \"between\", got {other:?}"),
            ))
        }
    };
    let Some(joint) = JointChoice::from_name(joint) else {
        return Err(option(
            "joint",
            format!("must be ball, hinge, rigid or elastic, got {joint:?}"),
        ));
    };
    let spec = fp::FitSpec {
        spacing,
        origin,
        directions,
        layout,
        min_angle_deg: min_angle.unwrap_or(fp::DEFAULT_MIN_ANGLE_DEG),
        subdivide,
        joint,
        section: rodnet::scene::types::Section::Circle {
            radius: section_radius.unwrap_or(spacing / 50.0),
        },
        young_modulus,
        poisson_ratio,
        tolerance,
        max_iterations: rodnet::scene::types::Solver::default().max_iterations,
    };
    spec.check()
        .map_err(|(name, m)| option(&name.replace('-', "_"), format!("{name} {m}")))?;
    let surface =
        rodnet::surface::Surface::load(&target, rodnet::scene::MAX_MESH_BYTES).map_err(|e| {
            scene_error(
                py,
                Some(&e.file),
                e.line,
                e.line.map(|_| 1),
                None,
                &e.message,
            )
        })?;
    let surface = std::sync::Arc::new(surface);
    let mesh = std::fs::canonicalize(&target)
        .unwrap_or(target)
        .display()
        .to_string();
    let outcome = solve_released(py, progress, move |hook| {
        match job::run(
            &surface,
            &mesh,
            &spec,
            hook,
            &rodnet::pipeline::Limits::machine(),
        ) {
            Ok(r) => Ok(run::Solved {
                results: r.results,
                gridshell: None,
            }),
            Err(job::FitError::Net(m)) => Err(Failure::Solve(m)),
            Err(job::FitError::Scene(e)) => Err(Failure::Scene(e)),
        }
    })?;
    results_of(py, outcome)
}
