//! The network as a [`NewtonProblem`](crate::solver::NewtonProblem), role by role: a thin
//! adapter that lends the solver a [`Model`] for one or several solves and keeps what those solves cache (the Hessian slot map, the length
//! projector) and the scratch copy used by trial evaluations.

use crate::network::assembly::{Assembly, HessianOut, HessianSlots};
use crate::network::model::Model;
use crate::network::projection::Projector;
use crate::network::{Network, RodInfo};
use crate::solver::linalg::SparseCholesky;
use crate::solver::problem::{
    Constraints, ContinuationPath, Core, Gauge, HessianPattern, LengthRepair, Mechanisms,
    NonConservative, Scales, Snapshots, Steps, SymmetryBreak,
};
use crate::solver::{NewtonReport, NewtonSettings, Ordering};
use crate::variables::{State, VarKind};

/// Most Gauss–Newton passes of the length projection after a secant prediction on a buckling
/// path. The passes go on while they reduce the largest relative length error, to round-off:
/// with EA/EI ≈ (L/r)², a length error the Newton iterations are left to absorb costs them more
/// than the passes (each a factorization of the edge–edge matrix AAᵀ, far smaller than H).
const PREDICTOR_PROJECTIONS: usize = 50;
/// Largest relative length error at which the predictor's projection stops.
const PREDICTOR_LENGTH_ERROR: f64 = 1e-12;
/// A prediction whose edges are all within this relative length of the target is left as it
/// is: Newton's first step removes so small a stretch error, and projecting it would only
/// change the rounding (small-displacement scenes then took one more iteration at the floor,
/// `star` and `euler_column` 1 → 2), and build the projector where nothing needs it.
const PREDICTION_STRAIN: f64 = 1e-6;
/// Fraction of the remaining path over which the mechanism test measures the load vector
/// (`mechanism`): dead loads are linear in λ, so any fraction gives their direction, and a
/// small one keeps prescribed ends from crossing their neighbours.
const MECHANISM_PROBE: f64 = 1e-3;

pub struct NetworkProblem<'m> {
    pub model: &'m mut Model,
    slots: HessianSlots,
    projector: Option<Projector>,
    /// Scratch copy of the variables for trial evaluations.
    saved_q: Vec<f64>,
    /// Scratch of `residual_floor`: the rounding noise and the gradient it causes.
    floor_scratch: (Vec<f64>, Vec<f64>),
    /// A temporary dead force on the free unknowns (energy −b·q), empty for none: the bias of
    /// `buckle_toward` (`network/symmetry_break.rs`).
    bias: Vec<f64>,
    /// The side a symmetric state should be left toward, for the saddle escape's sign.
    toward: Option<[f64; 3]>,
    /// The rods (to name a mechanism) and the gauge node of an unsupported structure.
    rods: &'m [RodInfo],
    gauge_node: Option<usize>,
    /// The load factors at continuation parameters 0 and 1 (default 0 and 1): a solve then
    /// goes from one load factor to another (`network/stability.rs` follows a path beyond 1).
    load_range: (f64, f64),
    /// The continuation parameter last set (`set_continuation`).
    lambda: f64,
    /// The factorization object of the last solve, for the next one while the model's Hessian
    /// pattern (its fingerprint) and the ordering asked for stay the same.
    kept: Option<Kept>,
}

struct Kept {
    fingerprint: [u64; 2],
    ordering: Ordering,
    chol: SparseCholesky,
}

impl<'m> NetworkProblem<'m> {
    pub fn new(model: &'m mut Model) -> Self {
        NetworkProblem {
            model,
            slots: HessianSlots::default(),
            projector: None,
            saved_q: Vec::new(),
            floor_scratch: (Vec::new(), Vec::new()),
            bias: Vec::new(),
            toward: None,
            rods: &[],
            gauge_node: None,
            load_range: (0.0, 1.0),
            lambda: 0.0,
            kept: None,
        }
    }

    /// The relative residual that rounding the free unknowns causes at the current state,
    /// whose gradient is `grad` (`Core::residual_floor`; `by_node`: see
    /// `Model::rounding_noise`).
    pub fn rounding_response(&mut self, grad: &[f64], by_node: bool) -> f64 {
        // Measured, not estimated from stiffnesses: the residual that rounding every free
        // variable to the nearest double causes. A finely subdivided rod's bending stencils turn a
        // coordinate's rounding εX into a force of order EI·εX/h³, which grows as N³ and exceeds
        // the stretch estimate EA·εX/h used before from a few hundred edges per metre on
        // (docs/design.md). Twice the measured value: one pattern of signs is typical, not worst.
        // The noise is applied 1024 times larger and the response scaled back (it is linear):
        // measured at its own size, the difference of two gradients would be as noisy as what it
        // measures, and decisions against the floor would depend on the last bits.
        const AMPLIFY: f64 = 1024.0;
        let n = self.model.n_free;
        let (mut noise, mut g1) = std::mem::take(&mut self.floor_scratch);
        noise.resize(n, 0.0);
        g1.resize(n, 0.0);
        self.model.rounding_noise(&mut noise, by_node);
        self.trial_gradient(&noise, AMPLIFY, &mut g1);
        g1.iter_mut().zip(grad).for_each(|(a, b)| *a -= b);
        let floor = 2.0 * self.model.relative_residual(&g1) / AMPLIFY;
        self.floor_scratch = (noise, g1);
        floor
    }

    /// The adapter of a whole network: mechanisms are then named by rod.
    pub fn of_network(net: &'m mut Network) -> Self {
        let Network {
            model, rods, gauge, ..
        } = net;
        let mut p = NetworkProblem::new(model);
        p.rods = rods;
        p.gauge_node = gauge.as_ref().map(|g| g.node);
        p
    }

    /// Leaves symmetric states toward `toward`, with the bias force `bias` on the free unknowns
    /// (empty: none) until it is removed.
    pub fn set_bias(&mut self, bias: Vec<f64>, toward: Option<[f64; 3]>) {
        self.bias = bias;
        self.toward = toward;
    }

    /// Maps the continuation parameter [0, 1] to the load factors [`from`, `to`].
    pub fn set_load_range(&mut self, from: f64, to: f64) {
        self.load_range = (from, to);
    }

    /// Solves for an equilibrium from the current state with the solver's Newton method.
    /// Successive solves of one problem (form finding's cap
    /// steps, `buckle_toward`'s two solves) share the Hessian's pattern analysis, slots and factor
    /// storage while the model's pattern does not change.
    pub fn solve(&mut self, settings: &NewtonSettings) -> NewtonReport {
        let fingerprint = self.model.pattern_fingerprint();
        let kept = self.kept.take().and_then(|k| {
            (k.fingerprint == fingerprint && k.ordering == settings.ordering).then_some(k.chol)
        });
        let analyses = self.model.analyses.clone();
        let (report, chol) = crate::solver::solve_with(self, settings, kept, &analyses);
        self.kept = Some(Kept {
            fingerprint,
            ordering: settings.ordering,
            chol,
        });
        report
    }

    /// Evaluates `f` at the current state displaced by `alpha · step`, then restores the state
    /// exactly; the saved copy reuses one buffer, so line searches do not allocate.
    fn displaced<R>(&mut self, step: &[f64], alpha: f64, f: impl FnOnce(&Model) -> R) -> R {
        let mut saved = std::mem::take(&mut self.saved_q);
        saved.clear();
        saved.extend_from_slice(&self.model.state.q);
        self.model.displace(step, alpha);
        let r = f(self.model);
        std::mem::swap(&mut self.model.state.q, &mut saved);
        self.saved_q = saved;
        r
    }
}

/// Solves `model` for an equilibrium (one adapter, dropped after the solve).
pub fn solve(model: &mut Model, settings: &NewtonSettings) -> NewtonReport {
    NetworkProblem::new(model).solve(settings)
}

/// Energy of the bias force b at the model's current state, −b·q over free unknowns.
fn bias_energy(m: &Model, b: &[f64]) -> f64 {
    if b.is_empty() {
        return 0.0;
    }
    let mut e = 0.0;
    for (v, &f) in m.free.iter().enumerate() {
        if f != crate::variables::FIXED {
            e -= b[f as usize] * m.state.q[v];
        }
    }
    e
}

fn subtract(grad: &mut [f64], b: &[f64]) {
    grad.iter_mut().zip(b).for_each(|(g, b)| *g -= b);
}

impl NetworkProblem<'_> {
    /// Whether predictions are projected onto edge lengths (`predict`, `keep_lengths`): not
    /// with contact off a buckling path, where contact's own projection of the prediction (in
    /// `extrapolate`) and the length projection undo each other (`rod_over_sphere` did not
    /// converge in 1000 iterations).
    fn projects_predictions(&self) -> bool {
        !self.bias.is_empty() || self.model.contact.is_none()
    }

    /// Moves the free nodes onto the edge lengths `lengths` (Gauss–Newton passes of the
    /// minimal-motion projection, to `PREDICTOR_LENGTH_ERROR`; passes that end worse than they
    /// started are undone), unless every edge is within `PREDICTION_STRAIN` of its length.
    fn project_lengths(&mut self, lengths: &[f64]) {
        let m = &*self.model;
        let worst = m
            .edge_lengths_of(&m.state.q)
            .iter()
            .zip(lengths)
            .map(|(l, t)| (l - t).abs() / l)
            .fold(0.0, f64::max);
        if worst <= PREDICTION_STRAIN {
            return;
        }
        let proj = self
            .projector
            .get_or_insert_with(|| Projector::new(m.unknowns(), &m.edge_nodes));
        let mut c = vec![0.0; m.n_free];
        let saved = self.model.state.q.clone();
        let mut first = None;
        for pass in 0..=PREDICTOR_PROJECTIONS {
            let m = &mut *self.model;
            let u = m.unknowns();
            let err = match proj.restore_lengths(u, &m.edge_nodes, &m.state.q, lengths, &mut c) {
                Some(err) if err > PREDICTOR_LENGTH_ERROR => err,
                _ => break,
            };
            // Far from the lengths (supports moved by a large fraction of an edge) the
            // linearized passes wander before they converge.
            let start = *first.get_or_insert(err);
            if pass == PREDICTOR_PROJECTIONS {
                if err > start {
                    m.state.q.copy_from_slice(&saved);
                }
                break;
            }
            m.displace(&c, 1.0);
        }
        // The reference frames are transported once, from the prediction to the projected
        // positions, not through every pass's intermediate positions: those are no states of
        // the rods, and a prediction's frames are a choice that Newton's twist angles correct.
        self.model.commit();
    }
}

impl Core for NetworkProblem<'_> {
    fn num_free(&self) -> usize {
        self.model.n_free
    }
    fn assemble(&self, grad: &mut [f64], hess: Option<&mut [f64]>) -> f64 {
        let e = self.model.assemble(&mut Assembly {
            grad,
            full_grad: None,
            hess: hess.map(|values| HessianOut {
                values,
                slots: &self.slots,
            }),
        });
        subtract(grad, &self.bias);
        e + bias_energy(self.model, &self.bias)
    }
    fn energy(&self) -> f64 {
        self.model.energy() + bias_energy(self.model, &self.bias)
    }
    fn relative_residual(&self, grad: &[f64]) -> f64 {
        self.model.relative_residual(grad)
    }
    fn residual_floor(&mut self, grad: &[f64]) -> f64 {
        self.rounding_response(grad, false)
    }
}

impl HessianPattern for NetworkProblem<'_> {
    fn hessian_pattern(&self) -> Vec<(usize, usize)> {
        self.model.hessian_pattern()
    }
    fn set_hessian_slots(&mut self, slots: &[usize]) {
        self.slots = self.model.hessian_slots(slots);
    }
    fn unknown_positions(&self) -> Option<Vec<[f64; 3]>> {
        Some(self.model.unknown_positions())
    }
}

impl Scales for NetworkProblem<'_> {
    fn perturbation_size(&self, direction: &[f64]) -> f64 {
        self.model.perturbation_size(direction)
    }
    fn unknown_scales(&self, scales: &mut [f64]) {
        self.model.unknown_scales(scales)
    }
}

impl Steps for NetworkProblem<'_> {
    fn trial_energy(&mut self, step: &[f64], alpha: f64) -> f64 {
        let b = std::mem::take(&mut self.bias);
        let e = self.displaced(step, alpha, |m| m.energy() + bias_energy(m, &b));
        self.bias = b;
        e
    }
    fn trial_gradient(&mut self, step: &[f64], alpha: f64, grad: &mut [f64]) -> f64 {
        let b = std::mem::take(&mut self.bias);
        let e = self.displaced(step, alpha, |m| {
            let e = m.assemble(&mut Assembly {
                grad,
                full_grad: None,
                hess: None,
            });
            e + bias_energy(m, &b)
        });
        subtract(grad, &b);
        self.bias = b;
        e
    }
    fn max_step(&self, step: &[f64]) -> f64 {
        self.model.max_step(step)
    }
    fn accept(&mut self, step: &[f64], alpha: f64) {
        self.model.displace(step, alpha);
        self.model.commit();
    }
}

impl Snapshots for NetworkProblem<'_> {
    type Snapshot = State;
    fn snapshot(&self) -> State {
        self.model.state.clone()
    }
    fn restore(&mut self, s: &State) {
        self.model.state.clone_from(s);
    }
    fn extrapolate(&mut self, from: &[(&State, f64)]) {
        // Positions only: edge angles are relative to reference frames that differ between the
        // iterates, and frame increments are zero after every commit.
        let m = &mut *self.model;
        for (v, &f) in m.free.iter().enumerate() {
            if f != crate::variables::FIXED && m.layout.kind(v) == VarKind::Position {
                let x = m.state.q[v];
                m.state.q[v] += from.iter().map(|(s, w)| w * (s.q[v] - x)).sum::<f64>();
            }
        }
        if let Some(c) = &m.contact {
            // The predictor must not start a sub-step inside an obstacle.
            c.project(&mut m.state.q);
        }
        m.rollers.snap(&mut m.state.q, m.state.load_factor);
        m.commit();
    }
}

impl ContinuationPath for NetworkProblem<'_> {
    fn set_continuation(&mut self, lambda: f64) {
        let (a, b) = self.load_range;
        self.lambda = lambda;
        self.model.set_load(a + lambda * (b - a));
        // Prescribed variables moved: reference frames must follow before the next assembly.
        self.model.commit();
    }
    fn continuation_is_trivial(&self) -> bool {
        self.model.continuation_is_trivial()
    }
    fn predict(&mut self, from: &[(&State, f64)], lambda: f64) {
        if !self.projects_predictions() {
            self.extrapolate(from);
            self.set_continuation(lambda);
            return;
        }
        // Edges turn far more than they stretch (on a buckling path and on any large-deflection
        // path of slender rods), and a linearly extrapolated turn lengthens an edge to second
        // order, which the stiff stretch terms punish: the prediction is projected back onto
        // lengths extrapolated like the positions (kept by an inextensible structure, followed
        // by a stretching one).
        let mut lengths = self.model.edge_lengths_of(&self.model.state.q);
        let now = lengths.clone();
        for (s, w) in from {
            let before = self.model.edge_lengths_of(&s.q);
            for ((l, n), b) in lengths.iter_mut().zip(&now).zip(&before) {
                *l += w * (b - n);
            }
        }
        self.extrapolate(from);
        self.set_continuation(lambda);
        self.project_lengths(&lengths);
    }
    fn keep_lengths(&mut self, of: &State) {
        if self.projects_predictions() {
            let lengths = self.model.edge_lengths_of(&of.q);
            self.project_lengths(&lengths);
        }
    }
}

impl LengthRepair for NetworkProblem<'_> {
    fn step_correction(&mut self, step: &[f64], c: &mut [f64]) -> bool {
        let m = &*self.model;
        let proj = self
            .projector
            .get_or_insert_with(|| Projector::new(m.unknowns(), &m.edge_nodes));
        let r = proj.correction(m.unknowns(), &m.edge_nodes, &m.state.q, step, c);
        if let (true, Some(contact)) = (r, &m.contact) {
            contact.limit_correction(&m.state.q, m.unknowns(), step, c);
        }
        r
    }
    fn excess_force(&mut self, trial: &[f64], linear: (&[f64], f64), f: &mut [f64]) -> f64 {
        let m = &*self.model;
        let k = m
            .terms
            .stretch
            .iter()
            .map(|s| (s.edge, s.ea / s.rest_length));
        let u = m.unknowns();
        crate::network::projection::excess_force(u, &m.edge_nodes, k, &m.state.q, trial, linear, f)
    }
    fn repairs_lengths(&self) -> bool {
        // Not against obstacles: contact limits every correction of a step
        // (`limit_correction`), the repair's passes have no such limit, and the comparison with
        // the plain point then leads rods sliding over a surface astray (`rod_over_sphere`: 54
        // iterations instead of 49; `lifted_wire` took 23 instead of 33). Bounds keep it: a
        // bound that is never active must change nothing (tests/contact_validation.rs).
        self.model
            .contact
            .as_ref()
            .is_none_or(|c| c.shapes.is_empty())
    }
}

impl Constraints for NetworkProblem<'_> {
    fn num_constraints(&self) -> usize {
        self.model.contact.as_ref().map_or(0, |c| c.len())
    }
    fn constraint_pattern(&self) -> Vec<(usize, usize)> {
        let m = &*self.model;
        m.contact
            .as_ref()
            .map_or_else(Vec::new, |c| c.pattern(m.unknowns()))
    }
    fn constraints(&self, c: &mut [f64], jac: &mut [f64]) {
        if let Some(contact) = &self.model.contact {
            contact.values(&self.model.state.q, c, jac);
        }
    }
    fn feasible(&mut self, step: &[f64]) -> bool {
        let m = &mut *self.model;
        let Some(contact) = m.contact.take() else {
            return true;
        };
        let current = m.state.q.clone();
        m.displace(step, 1.0);
        let ok = contact.admits(&current, &m.state.q);
        m.state.q = current;
        m.contact = Some(contact);
        ok
    }
    fn limit_correction(&self, step: &[f64], c: &mut [f64]) {
        let m = &*self.model;
        if let Some(contact) = &m.contact {
            contact.limit_correction(&m.state.q, m.unknowns(), step, c);
        }
    }
}

impl Gauge for NetworkProblem<'_> {
    fn gauge_modes(&mut self) -> Vec<Vec<f64>> {
        crate::network::mechanism::gauge_modes(self.model, self.gauge_node)
    }
    fn gauge_turns(&mut self) -> Option<crate::solver::problem::TurnPaths> {
        crate::network::mechanism::turn_paths(self.model, self.gauge_node)
    }
    fn gauge_only(&mut self, modes: &[Vec<f64>]) -> bool {
        crate::network::mechanism::gauge_only(self.model, self.gauge_node, modes)
    }
}

impl Mechanisms for NetworkProblem<'_> {
    fn mechanism(&mut self, modes: &[Vec<f64>]) -> Option<String> {
        // The load vector: the rate at which the load factor changes the gradient at the
        // current state (dead loads, and the pull of prescribed motions on the free unknowns),
        // measured over a small increment towards λ = 1. Jumping to λ = 1 moved a prescribed
        // end past its neighbours (a slack wire's pin moved by 5 edges): the reversed edges'
        // frames were committed as NaN and poisoned every later attempt. The state is restored
        // from a snapshot, not by setting λ back (which commits the frames once more).
        let saved = self.model.state.clone();
        let lam = self.lambda;
        let probe = lam + MECHANISM_PROBE * (1.0 - lam);
        let n = self.model.n_free;
        let (mut g0, mut g1) = (vec![0.0; n], vec![0.0; n]);
        self.assemble(&mut g0, None);
        self.set_continuation(probe);
        self.assemble(&mut g1, None);
        self.model.state.clone_from(&saved);
        self.lambda = lam;
        g1.iter_mut().zip(&g0).for_each(|(a, b)| *a -= b);
        crate::network::mechanism::describe(self.model, self.rods, self.gauge_node, modes, &g1)
    }
    fn deforms(&mut self, mode: &[f64]) -> bool {
        crate::network::mechanism::deforms(self.model, self.rods, mode)
    }
    fn zero_stiffness(&mut self) -> f64 {
        crate::network::zero_stiffness::zero_stiffness(self.model, self.rods)
    }
}

impl SymmetryBreak for NetworkProblem<'_> {
    fn orientation(&self, direction: &[f64]) -> f64 {
        let Some(t) = self.toward else { return 0.0 };
        let m = &*self.model;
        (0..m.layout.n_nodes())
            .map(|n| {
                (0..3)
                    .map(|k| {
                        m.unknowns()
                            .of_node(n, k)
                            .map_or(0.0, |f| direction[f] * t[k])
                    })
                    .sum::<f64>()
            })
            .sum()
    }
    fn bias(&self) -> &[f64] {
        &self.bias
    }
}

impl NonConservative for NetworkProblem<'_> {
    fn skew_stiffness(&self) -> f64 {
        self.model.dead_torque_skew()
    }
    fn skew_image(&self, v: &[f64], out: &mut [f64]) {
        self.model.dead_torque_image(v, out)
    }
}
