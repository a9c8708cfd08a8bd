//! `rodnet.Scene` and `rodnet.load_scene`: scenes from RON text, files or Python data, written
//! back as RON, changed by parameter path, and solved.

use std::path::PathBuf;

use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use rodnet::jobs::{BuckleError, IndentError};
use rodnet::scene::{self as rscene, FieldError};
use rodnet::sweep::run::{self, Failure};
use rodnet::sweep::{path, Job};

use crate::results::Results;
use crate::{located, scene_error, solve_released, SolveError};

/// What a pickled scene holds: its text and file (`Scene::__reduce__`).
type SceneState = (String, Option<String>);

/// A validated scene (the RON scene format of docs/scene-format.md).
///
/// Build one with `rodnet.load_scene(path)`, `Scene.from_ron(text)`, `Scene.from_dict(data)`
/// or `Scene(**data)` (data shaped as the RON text: `{"materials": {...}, "rods": [...]}`,
/// enum values as `{"Circle": {"radius": 0.01}}` or a plain string for unit variants).
#[pyclass(module = "rodnet", frozen)]
pub struct Scene {
    pub(crate) scene: rscene::Scene,
    /// Where it came from, for errors: the file (or None) and its text.
    file: Option<String>,
    src: String,
}

/// A scene's validation error as `SceneError`, located in its text when it has one.
fn invalid(py: Python<'_>, file: Option<&str>, src: &str, e: &FieldError) -> PyErr {
    // The message is the command line's: `field: message`.
    let at = rscene::SceneError::from_field(file.unwrap_or(""), src, e);
    scene_error(py, file, at.line, at.column, Some(e.path()), &at.message)
}

/// The field a scene's text fails validation at, when the text itself parses (the command
/// line's message names it; Python's `SceneError.field` holds it apart).
fn validation_field(src: &str) -> Option<String> {
    // The options of `rodnet::scene::parse`.
    let options =
        ron::Options::default().with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME);
    let scene: rscene::Scene = options.from_str(src).ok()?;
    rscene::validate::validate(&scene).err().map(|e| e.path())
}

impl Scene {
    fn parse(py: Python<'_>, file: Option<String>, src: String) -> PyResult<Scene> {
        let label = file.clone().unwrap_or_else(|| "<string>".into());
        let scene = rscene::parse(&label, &src).map_err(|e| {
            let file = file.as_ref().map(|_| e.file.as_str());
            scene_error(
                py,
                file,
                e.line,
                e.column,
                validation_field(&src),
                &e.message,
            )
        })?;
        Ok(Scene { scene, file, src })
    }

    /// A scene from its JSON form, checked field by field and validated.
    pub(crate) fn from_json(py: Python<'_>, v: serde_json::Value) -> PyResult<Scene> {
        let scene: rscene::Scene = serde_path_to_error::deserialize(v).map_err(|e| {
            let field = e.path().to_string();
            scene_error(
                py,
                None,
                None,
                None,
                Some(field.clone()),
                &format!("{field}: {}", e.inner()),
            )
        })?;
        rscene::validate::validate(&scene).map_err(|e| invalid(py, None, "", &e))?;
        let src = rodnet::gridshell::footprint::to_ron(&scene);
        Ok(Scene {
            scene,
            file: None,
            src,
        })
    }

    fn json(&self) -> serde_json::Value {
        serde_json::to_value(&self.scene).expect("a scene serializes")
    }
}

/// Reads, parses and validates a scene file (RON). Raises `SceneError` with the file, line,
/// column and field of the first problem.
#[pyfunction]
pub fn load_scene(py: Python<'_>, path: PathBuf) -> PyResult<Scene> {
    let file = path.display().to_string();
    let src = rscene::read_text(&path, "scene", rscene::validate::MAX_SCENE_BYTES)
        .map_err(|e| located(py, &e, None))?;
    Scene::parse(py, Some(file), src)
}

#[pymethods]
impl Scene {
    #[new]
    #[pyo3(signature = (**data))]
    fn new(py: Python<'_>, data: Option<&Bound<'_, PyDict>>) -> PyResult<Scene> {
        match data {
            Some(d) => Scene::from_json(py, crate::from_python(d.as_any(), "")?),
            None => Scene::from_json(py, serde_json::json!({})),
        }
    }

    /// Parses and validates RON text; `path` names it in errors.
    #[staticmethod]
    #[pyo3(signature = (text, path=None))]
    fn from_ron(py: Python<'_>, text: String, path: Option<String>) -> PyResult<Scene> {
        Scene::parse(py, path, text)
    }

    /// A scene from Python data shaped as the RON text (dicts, lists, numbers, strings).
    #[staticmethod]
    fn from_dict(py: Python<'_>, data: &Bound<'_, PyAny>) -> PyResult<Scene> {
        Scene::from_json(py, crate::from_python(data, "")?)
    }

    /// The scene as RON text (what `load_scene` reads back).
    fn to_ron(&self) -> String {
        rodnet::gridshell::footprint::to_ron(&self.scene)
    }

    /// The scene as Python data (what `from_dict` reads back).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        crate::to_python(py, &self.json())
    }

    /// Writes the scene as RON to `path` (atomically).
    fn write_ron(&self, path: PathBuf) -> PyResult<()> {
        rodnet::io::atomic::write(&path, self.to_ron().as_bytes())
            .map_err(|e| pyo3::exceptions::PyOSError::new_err(format!("{}: {e}", path.display())))
    }

    /// A copy with the value at a parameter path replaced, e.g.
    /// `scene.set("materials.steel.young_modulus", 70e9)` or `scene.set("rods[0].subdivide", 8)`
    /// (paths as in sweeps, docs/sweep.md); the copy is validated.
    fn set(&self, py: Python<'_>, path: &str, value: &Bound<'_, PyAny>) -> PyResult<Scene> {
        let mut v = self.json();
        let new = crate::from_python(value, path)?;
        path::set(&mut v, path, new).map_err(|m| {
            scene_error(
                py,
                None,
                None,
                None,
                Some(path.to_string()),
                &format!("{path}: {m}"),
            )
        })?;
        let mut s = Scene::from_json(py, v)?;
        s.file = None;
        Ok(s)
    }

    /// Names of the rods, in order.
    #[getter]
    fn rods(&self) -> Vec<String> {
        self.scene.rods.iter().map(|r| r.name.clone()).collect()
    }

    /// Names of the materials.
    #[getter]
    fn materials(&self) -> Vec<String> {
        self.scene.materials.keys().cloned().collect()
    }

    /// The file the scene was read from, or None.
    #[getter]
    fn path(&self) -> Option<String> {
        self.file.clone()
    }

    /// The scene from its text and file (what unpickling calls): parsed and validated again,
    /// so that it is the scene that was pickled.
    #[staticmethod]
    #[pyo3(signature = (text, path=None))]
    fn _from_state(py: Python<'_>, text: String, path: Option<String>) -> PyResult<Scene> {
        Scene::parse(py, path, text)
    }

    /// Pickled as its text (RON, whose numbers read back bit for bit) and file, so that
    /// process pools and Dask can pass scenes between processes.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<(Bound<'py, PyAny>, SceneState)> {
        let ctor = slf.get_type().getattr("_from_state")?;
        let s = slf.get();
        Ok((ctor, (s.src.clone(), s.file.clone())))
    }

    fn __repr__(&self) -> String {
        format!(
            "Scene({} rods, {} joints, {} supports, {} loads{})",
            self.scene.rods.len(),
            self.scene.joints.len(),
            self.scene.supports.len(),
            self.scene.loads.len(),
            self.file
                .as_ref()
                .map_or(String::new(), |f| format!(", from {f}"))
        )
    }

    /// Linear buckling about the rest state, as `rodnet buckle`, with the GIL released: the
    /// `modes` lowest critical load factors (by which the loads and prescribed motions can be
    /// multiplied before the structure buckles) and their modes, and unless `linear_only` the
    /// first factor checked along the nonlinear load path. Returns the dict `rodnet buckle
    /// --json` writes (`critical_load_factors`, `modes`, `converged`, `path`, ...).
    #[pyo3(signature = (modes=4, *, linear_only=false))]
    fn buckle<'py>(
        &self,
        py: Python<'py>,
        modes: usize,
        linear_only: bool,
    ) -> PyResult<Bound<'py, PyAny>> {
        if !(1..=100).contains(&modes) {
            return Err(PyValueError::new_err(format!(
                "modes must be in 1..=100, got {modes}"
            )));
        }
        let scene = &self.scene;
        let out = py.detach(|| {
            crate::fork_safe(|| {
                std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                    rodnet::jobs::buckle(
                        scene,
                        modes,
                        linear_only,
                        None,
                        &rodnet::pipeline::Limits::machine(),
                    )
                    .map(|b| b.json)
                }))
            })
        });
        match out {
            Ok(Ok(json)) => crate::to_python(py, &serde_json::to_value(json).expect("serializes")),
            Ok(Err(BuckleError::Scene(e))) => Err(invalid(py, self.file.as_deref(), &self.src, &e)),
            Ok(Err(BuckleError::Analysis(m))) => Err(SolveError::new_err(m)),
            Err(p) => Err(SolveError::new_err(format!(
                "internal error (please report): {}",
                run::panic_message(&*p)
            ))),
        }
    }

    /// Indentation, as `rodnet indent`, with the GIL released: solves the scene, then pushes
    /// the point `at` (a joint's name, "ROD:VERTEX" or "apex") by `depth` m along
    /// `direction` in `steps` displacement-controlled steps. Returns the dict `rodnet indent
    /// --json` writes (`linear_stiffness` N/m, `curve` [[depth m, force N], ...],
    /// `limit_points`, `complete`, ...).
    #[pyo3(signature = (at, depth, *, direction=(0.0, 0.0, -1.0), steps=20))]
    fn indent<'py>(
        &self,
        py: Python<'py>,
        at: &str,
        depth: f64,
        direction: (f64, f64, f64),
        steps: usize,
    ) -> PyResult<Bound<'py, PyAny>> {
        let scene = &self.scene;
        let d = [direction.0, direction.1, direction.2];
        let out = py.detach(|| {
            crate::fork_safe(|| {
                std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                    rodnet::jobs::indent(
                        scene,
                        at,
                        d,
                        depth,
                        steps,
                        &rodnet::pipeline::Limits::machine(),
                    )
                    .map(|i| i.json)
                }))
            })
        });
        match out {
            Ok(Ok(json)) => crate::to_python(py, &serde_json::to_value(json).expect("serializes")),
            Ok(Err(IndentError::Scene(e))) => Err(invalid(py, self.file.as_deref(), &self.src, &e)),
            Ok(Err(IndentError::At(m))) => Err(PyValueError::new_err(m)),
            Ok(Err(IndentError::NotConverged(m))) => Err(SolveError::new_err(format!(
                "the scene itself did not converge ({m}); nothing pushed"
            ))),
            Ok(Err(IndentError::Push(m))) => Err(SolveError::new_err(m)),
            Err(p) => Err(SolveError::new_err(format!(
                "internal error (please report): {}",
                run::panic_message(&*p)
            ))),
        }
    }

    /// Solves the scene for its static equilibrium, with the GIL released.
    ///
    /// Settings override the scene's `solver` block: `tolerance`, `max_iterations`,
    /// `load_steps`, `time_limit` (s), `continuation` ("load" or "arc_length"); `modes=K` adds
    /// the K lowest eigenvalues (`results.stability`); `extrapolate=2` or `3` also solves at
    /// twice (and four times) every rod's subdivision and adds the Richardson extrapolate
    /// (`results.extrapolation`, as `rodnet solve --extrapolate --levels`; the
    /// other results are the finest solve's); `progress(step, iteration, residual,
    /// energy)` is called after every Newton iteration (an exception it raises stops the solve
    /// and is re-raised). Returns `Results` (also when the solve does not converge: see
    /// `converged`); raises `SceneError` for settings or a scene the builder refuses and
    /// `SolveError` when there are no results.
    #[pyo3(signature = (*, tolerance=None, max_iterations=None, load_steps=None, time_limit=None, continuation=None, modes=None, progress=None, extrapolate=None))]
    #[allow(clippy::too_many_arguments)]
    fn solve(
        &self,
        py: Python<'_>,
        tolerance: Option<f64>,
        max_iterations: Option<usize>,
        load_steps: Option<usize>,
        time_limit: Option<f64>,
        continuation: Option<&str>,
        modes: Option<usize>,
        progress: Option<Py<PyAny>>,
        extrapolate: Option<usize>,
    ) -> PyResult<Results> {
        if extrapolate.is_some_and(|l| !(2..=3).contains(&l)) {
            return Err(PyValueError::new_err(format!(
                "extrapolate takes 2 or 3 levels, got {}",
                extrapolate.unwrap_or(0)
            )));
        }
        let mut sc = self.scene.clone();
        let s = &mut sc.solver;
        s.tolerance = tolerance.or(s.tolerance);
        s.max_iterations = max_iterations.unwrap_or(s.max_iterations);
        s.load_steps = load_steps.unwrap_or(s.load_steps);
        s.time_limit = time_limit.or(s.time_limit);
        if let Some(c) = continuation {
            s.continuation = match c {
                "load" => rscene::types::Continuation::Load,
                "arc_length" => rscene::types::Continuation::ArcLength,
                other => {
                    return Err(PyValueError::new_err(format!(
                        "continuation must be \"load\" or \"arc_length\", got {other:?}"
                    )))
                }
            }
        }
        if modes == Some(0) {
            return Err(PyValueError::new_err("modes must be at least 1"));
        }
        if progress.as_ref().is_some_and(|p| !p.bind(py).is_callable()) {
            return Err(PyTypeError::new_err("progress must be callable"));
        }
        rscene::validate::validate(&sc).map_err(|e| invalid(py, None, "", &e))?;
        let job = Job::Scene(Box::new(sc));
        let outcome = solve_released(py, progress, move |hook| match extrapolate {
            Some(levels) => run::solve_extrapolated(
                &job,
                levels,
                modes,
                hook,
                &rodnet::pipeline::Limits::machine(),
            ),
            None => run::solve(&job, modes, hook, &rodnet::pipeline::Limits::machine()),
        })?;
        match outcome {
            Ok(solved) => Ok(Results::new(solved)),
            Err(Failure::Scene(e)) => Err(invalid(py, self.file.as_deref(), &self.src, &e)),
            Err(Failure::Solve(m)) => Err(SolveError::new_err(m)),
        }
    }
}

/// Benchmark helper (python/bench/overhead.py): mean seconds of `repeat` solves of the scene
/// entirely in Rust, to set against `Scene.solve` called from Python.
#[pyfunction]
pub fn _bench_solve(py: Python<'_>, scene: &Scene, repeat: usize) -> f64 {
    let job = Job::Scene(Box::new(scene.scene.clone()));
    py.detach(|| {
        let t0 = std::time::Instant::now();
        for _ in 0..repeat {
            let _ = run::solve(&job, None, None, &rodnet::pipeline::Limits::machine());
        }
        t0.elapsed().as_secs_f64() / repeat.max(1) as f64
    })
}
