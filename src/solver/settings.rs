//! Newton solver settings and the report it returns.

use std::sync::Arc;
use std::time::{Duration, Instant};

use serde::Serialize;

/// Called after every iteration with (load step, iteration, relative residual, energy). A
/// closure, so that each caller keeps its own context (a progress bar, a log, a channel).
pub type Progress = Arc<dyn Fn(usize, usize, f64, f64) + Send + Sync>;

#[derive(Clone)]
pub struct NewtonSettings {
    /// Relative residual tolerance (see `NewtonProblem::relative_residual`).
    pub tolerance: f64,
    /// The tolerance was not asked for: a final state that round-off stalls below its floor
    /// but above `tolerance` has converged, to the floor (reported as the tolerance used).
    pub automatic_tolerance: bool,
    /// Newton iterations allowed per load step (its continuation sub-steps included).
    pub max_iterations: usize,
    /// Continuation steps from λ = 0 to 1.
    pub load_steps: usize,
    pub progress: Option<Progress>,
    /// Fill-reducing ordering of the factorization.
    pub ordering: super::Ordering,
    /// Seconds after which the solve stops with its last iterate (`stopped: "time limit"`).
    pub time_limit: Option<f64>,
    /// When the time limit runs out: set once, when the limit is (`time_limit`), so that every
    /// solve made with these settings or their clones (a restart and its solve from rest,
    /// stages, extrapolation levels) shares one budget instead of each starting its own.
    pub deadline: Option<Instant>,
    /// Bytes the solve may take (`u64::MAX`: none): its caller checks a scene against it before
    /// building (`pipeline::build_within_limit`); carried here so every build of one job sees
    /// the same limit.
    pub memory_limit: u64,
    /// Solve at the end of the path (λ = 1) from the current state, without a path.
    pub equilibrate_only: bool,
    /// How the path from λ = 0 to 1 is followed.
    pub continuation: Continuation,
    /// The solve's state only starts another solve (a form-finding path's earlier steps): it
    /// ends, like the path's own intermediate sub-steps, at a loose tolerance or once a full,
    /// unregularized Newton step as small as the next start needs has been taken.
    pub intermediate: bool,
}

/// How the path from λ = 0 to 1 is followed.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, serde::Deserialize)]
pub enum Continuation {
    /// Increments of λ (load control), adaptive: `continuation.rs`.
    #[default]
    Load,
    /// Pseudo-arclength: through limit points, `arc_length.rs`.
    ArcLength,
}

/// A limit point met on an arc-length path: λ there and the step after which it was seen.
#[derive(Debug, Clone, Copy, Serialize, serde::Deserialize, PartialEq)]
pub struct LimitPoint {
    pub load_factor: f64,
    pub step: usize,
}

impl Default for NewtonSettings {
    fn default() -> Self {
        NewtonSettings {
            tolerance: 1e-9,
            automatic_tolerance: false,
            max_iterations: 200,
            load_steps: 1,
            progress: None,
            ordering: super::Ordering::Auto,
            time_limit: None,
            deadline: None,
            memory_limit: u64::MAX,
            equilibrate_only: false,
            continuation: Continuation::Load,
            intermediate: false,
        }
    }
}

impl std::fmt::Debug for NewtonSettings {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("NewtonSettings")
            .field("tolerance", &self.tolerance)
            .field("automatic_tolerance", &self.automatic_tolerance)
            .field("max_iterations", &self.max_iterations)
            .field("load_steps", &self.load_steps)
            .field("progress", &self.progress.as_ref().map(|_| "closure"))
            .field("ordering", &self.ordering)
            .field("time_limit", &self.time_limit)
            .field("deadline", &self.deadline)
            .field("equilibrate_only", &self.equilibrate_only)
            .field("continuation", &self.continuation)
            .field("intermediate", &self.intermediate)
            .finish()
    }
}

impl NewtonSettings {
    /// Reports progress to `f` (see [`Progress`]).
    pub fn progress(mut self, f: impl Fn(usize, usize, f64, f64) + Send + Sync + 'static) -> Self {
        self.progress = Some(Arc::new(f));
        self
    }
    pub fn tolerance(mut self, t: f64) -> Self {
        self.tolerance = t;
        self
    }
    pub fn automatic_tolerance(mut self, on: bool) -> Self {
        self.automatic_tolerance = on;
        self
    }
    pub fn max_iterations(mut self, n: usize) -> Self {
        self.max_iterations = n;
        self
    }
    pub fn ordering(mut self, o: super::Ordering) -> Self {
        self.ordering = o;
        self
    }
    /// Sets the time limit, counted from now (see `deadline`).
    pub fn time_limit(mut self, seconds: Option<f64>) -> Self {
        self.time_limit = seconds;
        self.deadline =
            seconds.map(|t| Instant::now() + Duration::from_secs_f64(t.clamp(0.0, 1e9)));
        self
    }
    pub fn memory_limit(mut self, bytes: u64) -> Self {
        self.memory_limit = bytes;
        self
    }
    pub fn continuation(mut self, c: Continuation) -> Self {
        self.continuation = c;
        self
    }
    pub fn equilibrate_only(mut self, on: bool) -> Self {
        self.equilibrate_only = on;
        self
    }
    pub fn intermediate(mut self, on: bool) -> Self {
        self.intermediate = on;
        self
    }
    pub fn load_steps(mut self, n: usize) -> Self {
        self.load_steps = n;
        self
    }
}

#[derive(Debug, Clone, Default, Serialize)]
pub struct NewtonReport {
    pub converged: bool,
    /// Newton iterations summed over load steps.
    pub iterations: usize,
    pub load_steps: usize,
    /// Relative residual at the end.
    pub residual: f64,
    pub energy: f64,
    pub seconds: f64,
    pub factorizations: usize,
    /// Iterations whose Hessian needed a diagonal shift to be positive definite.
    pub regularized_iterations: usize,
    /// Steps taken along a direction of negative curvature to leave a saddle.
    pub saddle_escapes: usize,
    /// The Hessian at the final state, restricted to the free unknowns, is positive definite
    /// (up to gauge modes of an unsupported structure): a strict local minimum. False for a
    /// saddle and for a neutral state (`zero_modes` > 0).
    pub stable: bool,
    /// Seconds spent in numeric factorization and solves.
    pub factor_seconds: f64,
    /// Why the solve stopped when it did not converge.
    pub message: Option<String>,
    /// The solve stopped below the round-off floor with the residual above the tolerance:
    /// converged to the floor (`verdict.rs`).
    pub stopped_at_floor: bool,
    /// What stopped an unconverged solve early: "time limit".
    pub stopped: Option<String>,
    /// A zero-stiffness mode of the structure that its loads excite (the solve stopped there).
    pub mechanism: Option<String>,
    /// Zero-stiffness modes of the final state that are not gauge modes (up to 4 counted): with
    /// no negative curvature, the state is neutrally stable (`stable` is false).
    pub zero_modes: usize,
    /// Why `stable` is false without a saddle or zero mode found: the energy could not judge.
    pub stability_note: Option<String>,
    /// Bifurcations and snaps met along a load-controlled path (`path_events.rs`).
    pub path_events: Vec<super::path_events::PathEvent>,
    /// Arc-length continuation only: its steps and the limit points met.
    pub arc_length_steps: usize,
    pub limit_points: Vec<LimitPoint>,
    /// Iterations of a path followed under a temporary bias (`buckle_toward`), included in
    /// `iterations`.
    pub biased_iterations: usize,
    /// Continuation sub-steps taken (at least `load_steps`).
    pub substeps: usize,
    /// Sub-steps retried with a smaller increment.
    pub retries: usize,
    /// Relative residual that round-off alone produces (below it, the solve stops once round-off
    /// stalls Newton).
    pub residual_floor: f64,
    /// Iterations per load step.
    pub step_iterations: Vec<usize>,
    /// The tolerance the solve used.
    pub tolerance: f64,
    /// Constrained problems only: the last step QP's multipliers and its cost.
    pub constraints: Option<ConstraintReport>,
}

impl NewtonReport {
    /// Adds the work of an earlier solve of the same problem (counts and times); the state
    /// fields (residual, verdict) stay this report's.
    pub fn add_work(&mut self, earlier: &NewtonReport) {
        self.iterations += earlier.iterations;
        self.factorizations += earlier.factorizations;
        self.regularized_iterations += earlier.regularized_iterations;
        self.saddle_escapes += earlier.saddle_escapes;
        self.substeps += earlier.substeps;
        self.retries += earlier.retries;
        self.seconds += earlier.seconds;
        self.factor_seconds += earlier.factor_seconds;
    }

    /// No direction of negative curvature, but zero-stiffness modes (a rigid turn the loads
    /// leave alone, a continuous family of equal-energy states): neither stable nor unstable.
    pub fn neutral(&self) -> bool {
        !self.stable && self.zero_modes > 0
    }
}

#[derive(Debug, Clone, Default, Serialize)]
pub struct ConstraintReport {
    /// Multiplier of each constraint at the last QP (N for contact and bounds).
    pub multipliers: Vec<f64>,
    pub qp_solves: usize,
    /// QPs that stopped short of full accuracy (their steps still pass the line search).
    pub inexact_qps: usize,
    /// QPs whose solution was refined to the exact one on its active set.
    pub polished_qps: usize,
    /// Newton steps whose unconstrained step already satisfied the linearized constraints.
    pub steps_without_qp: usize,
    /// Interior-point iterations summed over the QPs.
    pub qp_iterations: usize,
    /// Seconds in Clarabel (setup, updates and solves).
    pub qp_seconds: f64,
}
