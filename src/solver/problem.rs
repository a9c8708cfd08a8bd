//! The one generic Newton problem: energy, gradient and Hessian over free unknowns, a way to
//! try and accept steps, and a continuation parameter. Rods, networks, joints and inequality
//! constraints all plug in through this interface.
//!
//! The interface is split by role into small traits; [`NewtonProblem`] is all of them, and any
//! type implementing every role is one. Roles a problem may lack (length repair, constraints,
//! gauge, mechanisms, symmetry breaking, non-conservative loads) have default methods that give
//! the neutral answer, so such a problem implements them with an empty `impl`. The solver's
//! functions ask for the narrowest roles they use where that is easy.

/// Rigid turns to second order (`Gauge::gauge_turns`): three first-order motions over
/// the free unknowns and the six second-order motions of their pairs (0,0), (0,1), (0,2), (1,1),
/// (1,2), (2,2).
pub struct TurnPaths {
    pub first: Vec<Vec<f64>>,
    pub second: Vec<Vec<f64>>,
}

/// Every role of a problem the solver drives: implemented for any type that has them all.
pub trait NewtonProblem:
    Core
    + HessianPattern
    + Scales
    + Steps
    + ContinuationPath
    + LengthRepair
    + Constraints
    + Gauge
    + Mechanisms
    + SymmetryBreak
    + NonConservative
{
}

impl<T> NewtonProblem for T where
    T: Core
        + HessianPattern
        + Scales
        + Steps
        + ContinuationPath
        + LengthRepair
        + Constraints
        + Gauge
        + Mechanisms
        + SymmetryBreak
        + NonConservative
{
}

/// The energy and its derivatives at the current iterate, and how far it is from equilibrium.
pub trait Core {
    fn num_free(&self) -> usize;
    /// Energy, gradient and optionally Hessian values (by slot) at the current iterate.
    fn assemble(&self, grad: &mut [f64], hess: Option<&mut [f64]>) -> f64;
    fn energy(&self) -> f64;
    /// Largest residual relative to the problem's force (and moment) scale.
    fn relative_residual(&self, grad: &[f64]) -> f64;
    /// Relative residual below which round-off dominates (see `relative_residual`).
    /// (`grad`: the gradient at the current iterate.)
    fn residual_floor(&mut self, grad: &[f64]) -> f64;
}

/// Where the Hessian's non-zeros are, for the symbolic analysis and its fill-reducing ordering.
pub trait HessianPattern {
    /// Upper-triangle (row ≤ col) pairs of the Hessian, every diagonal entry included.
    fn hessian_pattern(&self) -> Vec<(usize, usize)>;
    /// For each pair of `hessian_pattern`, its index in the Hessian value array.
    fn set_hessian_slots(&mut self, slots: &[usize]);
    /// A point in space for every free unknown (where its node, edge or joint is), for the
    /// geometric nested-dissection ordering; `None` if the problem has no geometry.
    fn unknown_positions(&self) -> Option<Vec<[f64; 3]>> {
        None
    }
}

/// The sizes of the unknowns and of small motions: what makes the solver's regularization and
/// perturbations independent of units.
pub trait Scales {
    /// Size of a perturbation along `direction` that is small for the problem's geometry.
    fn perturbation_size(&self, direction: &[f64]) -> f64;
    /// Characteristic size of each free unknown in its own unit (a length for positions, 1 for
    /// angles). The solver's Hessian regularization and its search for negative curvature act
    /// on the unknowns divided by these sizes, so that they do not depend on the units or the
    /// size of the problem. Default: all 1.
    fn unknown_scales(&self, scales: &mut [f64]) {
        scales.fill(1.0);
    }
}

/// Trying a step without taking it, and taking it.
pub trait Steps {
    /// Energy at the current iterate moved by `alpha · step`, without accepting it.
    fn trial_energy(&mut self, step: &[f64], alpha: f64) -> f64;
    /// Gradient at the current iterate moved by `alpha · step`, without accepting it; returns
    /// the energy there.
    fn trial_gradient(&mut self, step: &[f64], alpha: f64, grad: &mut [f64]) -> f64;
    /// Largest admissible `alpha ≤ 1` for `step` (keeps the kinematics well defined).
    fn max_step(&self, step: &[f64]) -> f64;
    /// Moves by `alpha · step` and accepts the result as the new iterate.
    fn accept(&mut self, step: &[f64], alpha: f64);
}

/// Saved iterates, for retrying a continuation step and for secant prediction.
pub trait Snapshots {
    /// A saved iterate.
    type Snapshot: Clone;
    fn snapshot(&self) -> Self::Snapshot;
    fn restore(&mut self, s: &Self::Snapshot);
    /// Moves the free unknowns x to x + Σ wᵢ (xᵢ − x) over the snapshots xᵢ with weights wᵢ
    /// (`from`): the secant predictor through the current iterate and one earlier snapshot, or
    /// the quadratic one through two.
    fn extrapolate(&mut self, from: &[(&Self::Snapshot, f64)]);
}

/// The continuation parameter λ ∈ [0, 1] (load factor, prescribed motions) and the predictor
/// of a step along it.
pub trait ContinuationPath: Snapshots {
    /// Sets the continuation parameter (load factor, prescribed motions) in [0, 1].
    fn set_continuation(&mut self, lambda: f64);
    /// True when the continuation parameter changes nothing (no loads, no prescribed motion):
    /// the solve is then one equilibration, without a path.
    fn continuation_is_trivial(&self) -> bool {
        false
    }
    /// The predictor of a continuation sub-step: `extrapolate`, then the continuation parameter
    /// set to `lambda`. A problem may also restore what extrapolation breaks (the lengths of
    /// turning edges).
    fn predict(&mut self, from: &[(&Self::Snapshot, f64)], lambda: f64) {
        self.extrapolate(from);
        self.set_continuation(lambda);
    }
    /// Restores what the first (linear-response) prediction of a path breaks: the lengths of
    /// the edges at the snapshot `of` (the path's start). Default: nothing.
    fn keep_lengths(&mut self, _of: &Self::Snapshot) {}
}

/// Second-order corrections of a step for the length error of its stiff terms. Default none.
pub trait LengthRepair {
    /// A second-order correction c for the step (the line search then follows x + αd + α²c);
    /// false if none.
    fn step_correction(&mut self, _step: &[f64], _c: &mut [f64]) -> bool {
        false
    }
    /// The force that the higher-order length error of the trial step `trial` would create in
    /// the stiffest terms (stretch), measured against the lengths that the linearization of
    /// `linear` = (d, α), the step α·d, gives; returns its energy (0: nothing to correct). The
    /// solver corrects by c = −H⁻¹f: with `trial` = d, α = 1, the step's second-order
    /// correction; with a corrected trial point, that correction's remaining error.
    fn excess_force(&mut self, _trial: &[f64], _linear: (&[f64], f64), _f: &mut [f64]) -> f64 {
        0.0
    }
    /// Whether the line search may repair its trial points with `excess_force` passes
    /// (`solver/step.rs::repair_lengths`). Default false.
    fn repairs_lengths(&self) -> bool {
        false
    }
}

/// Inequality constraints c(x) ≥ 0 (contact, bounds). A problem without any keeps these
/// defaults; the solver then never builds a QP.
pub trait Constraints {
    /// Number of inequality constraints.
    fn num_constraints(&self) -> usize {
        0
    }
    /// Non-zeros (constraint, free unknown) of the Jacobian ∂c/∂x, grouped by constraint and
    /// fixed for the whole solve.
    fn constraint_pattern(&self) -> Vec<(usize, usize)> {
        Vec::new()
    }
    /// Constraint values c(x) and Jacobian values (in `constraint_pattern` order) at the
    /// current iterate.
    fn constraints(&self, _c: &mut [f64], _jac: &mut [f64]) {}
    /// Whether the current iterate moved by `step` satisfies every constraint (or violates none
    /// more than the current iterate does).
    fn feasible(&mut self, _step: &[f64]) -> bool {
        true
    }
    /// Limits a correction so that the corrected step stays admissible (contact).
    fn limit_correction(&self, _step: &[f64], _c: &mut [f64]) {}
}

/// The motions the problem leaves free on purpose (rigid motions of an unsupported structure).
/// Default none.
pub trait Gauge {
    /// The problem's gauge modes (W-orthonormal over the free unknowns, W = diag(1/s²) of
    /// `unknown_scales`): motions it leaves free on purpose. Default none.
    fn gauge_modes(&mut self) -> Vec<Vec<f64>> {
        Vec::new()
    }
    /// The rigid turns the gauge leaves free, to second order: three first-order motions and
    /// the six second-order ones of their pairs (see `network::mechanism::turn_paths`). None
    /// when the problem has no gauge turns.
    fn gauge_turns(&mut self) -> Option<TurnPaths> {
        None
    }
    /// Whether the given zero-stiffness modes are all gauge modes (rigid motions the problem
    /// leaves free on purpose), so that the state is stable on the complement.
    fn gauge_only(&mut self, _modes: &[Vec<f64>]) -> bool {
        false
    }
}

/// What a zero-stiffness mode is physically: a mechanism the loads excite, a deformation, or
/// round-off against the softest physical stiffness.
pub trait Mechanisms {
    /// Given zero-stiffness modes of the start (W-orthonormal vectors over the free unknowns),
    /// describes the mechanism they contain that the loads or prescribed motions excite, or
    /// None (no such mode: gauge modes, modes the loads do not touch).
    fn mechanism(&mut self, _modes: &[Vec<f64>]) -> Option<String> {
        None
    }
    /// Whether `mode` deforms the structure (some part that moves in it does not move
    /// rigidly): then it is no symmetry's zero mode. Default false (unknown).
    fn deforms(&mut self, _mode: &[f64]) -> bool {
        false
    }
    /// An eigenvalue (J, for a W-unit mode) negligible against the softest stiffness that a
    /// mode deforming the problem's structure can physically have: the widest band around
    /// zero for such a mode (`spectrum::mode_band`). Default infinite (no physical scale
    /// known: the band's other caps apply).
    fn zero_stiffness(&mut self) -> f64 {
        f64::INFINITY
    }
}

/// Leaving a symmetric state toward a chosen side (`network/symmetry_break.rs`). Default: no
/// side, no bias.
pub trait SymmetryBreak {
    /// Which way `direction` leaves a symmetric state relative to the side the problem prefers
    /// (positive: toward it); 0 when it has none. Signs the escape from saddles.
    fn orientation(&self, _direction: &[f64]) -> f64 {
        0.0
    }
    /// The temporary bias force of `solve_toward` over the free unknowns (empty: none). A
    /// problem with one is followed as a buckling path (`continuation.rs`, `step.rs`).
    fn bias(&self) -> &[f64] {
        &[]
    }
}

/// Loads whose tangent is not symmetric (dead moments under 3-D rotations). Default
/// conservative.
pub trait NonConservative {
    /// The norm of the loads' non-symmetric stiffness in the unknowns divided by their scales
    /// (`unknown_scales`): 0 for conservative loads. Dead moments are not conservative for 3-D
    /// rotations; the energy's Hessian is the symmetric part of their tangent, and this bounds
    /// how far the rest can move its eigenvalues (`Newton::escape_saddle`).
    fn skew_stiffness(&self) -> f64 {
        0.0
    }
    /// The image S·v of a direction `v` of the free unknowns under that skew stiffness, in
    /// `out` (zero for conservative loads).
    fn skew_image(&self, _v: &[f64], out: &mut [f64]) {
        out.fill(0.0);
    }
}
