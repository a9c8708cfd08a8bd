//! The path between two equilibria under displacement control of one coordinate (`rodnet
//! states`' search for the saddle between two minima; the "drag method").
//!
//! One node coordinate, the one that differs most between the two states, is held and moved
//! from its value in the first to its value in the second; everything else is free and settled
//! by Newton at every step (which leaves saddles, so the path stays on states that are stable
//! with that coordinate held). The force holding the coordinate is the gradient there: where it
//! changes sign between two steps, the free structure is near an equilibrium. On the path
//! between two minima that is the barrier between them, an index-1 saddle whose unstable
//! direction moves the held coordinate (a shallow arch's S-shaped state on its way through:
//! the held crown leaves the antisymmetric mode free). Residual Newton from there finds it.
//! What it cannot see: equilibria where the path jumps (a fold in the held coordinate).

use crate::network::assembly::Assembly;
use crate::network::model::Prescribed;
use crate::network::problem::NetworkProblem;
use crate::network::Network;
use crate::solver::problem::ContinuationPath;
use crate::solver::NewtonSettings;
use crate::variables::{State, FIXED};

/// Steps of the displacement-controlled path between two states.
pub const STEPS: usize = 24;

/// A start for an equilibrium search on the path from `a` to `b` where the holding force
/// changes sign, with the held coordinate's value there (m).
pub struct Crossing {
    pub state: State,
    pub at: f64,
}

/// The held coordinate: the free coordinate of a node with all three free (not on a support
/// or roller) that differs most between `a` and `b`.
pub fn coordinate(net: &Network, a: &State, b: &State) -> Option<usize> {
    let m = &net.model;
    (0..m.layout.n_nodes())
        .filter(|&n| {
            let v = m.layout.node(n);
            v.iter().all(|&x| m.free[x] != FIXED) && !m.rollers.touches(&v)
        })
        .flat_map(|n| m.layout.node(n))
        .map(|v| (v, (b.q[v] - a.q[v]).abs()))
        .filter(|&(_, d)| d > 0.0)
        .max_by(|x, y| x.1.total_cmp(&y.1))
        .map(|(v, _)| v)
}

/// Times the first or last step of a path is followed again in [`STEPS`] finer steps when the
/// barrier lies inside it (the path's resolution is then 1/STEPS³ of the way).
const REFINEMENTS: usize = 2;

/// Follows the path from `a` to `b` with `var` held and moved in [`STEPS`] steps; returns the
/// starts where its holding force changes sign, each the nearer state of its step with its
/// positions interpolated linearly to the force's zero.
///
/// Near a minimum the holding force pulls back to it, so it starts with the sign of the motion
/// (σ) and ends with the opposite one: the barrier is where it turns. When it turns within the
/// first step, or within the last (the barrier close to `b`, as an arch's S-shaped saddle is to
/// its inverted state), that step is followed again in finer steps.
pub fn crossings(
    net: &Network,
    a: &State,
    b: &State,
    var: usize,
    settings: &NewtonSettings,
) -> Vec<Crossing> {
    let mut held = net.clone();
    held.model.hold(var);
    held.model.staged = vec![Prescribed {
        var,
        start: a.q[var],
        end: b.q[var],
    }];
    let mut path = Path {
        p: NetworkProblem::of_network(&mut held),
        var,
        settings,
        sigma: (b.q[var] - a.q[var]).signum(),
        out: Vec::new(),
    };
    path.scan((a.clone(), 0.0), b.q[var], REFINEMENTS, true);
    path.out
}

struct Path<'a, 'm> {
    p: NetworkProblem<'m>,
    var: usize,
    settings: &'a NewtonSettings,
    sigma: f64,
    out: Vec<Crossing>,
}

impl Path<'_, '_> {
    /// From `from` (a state and its holding force; zero at the first minimum) to `to` in
    /// [`STEPS`] steps; `to_minimum`: the end is the second minimum.
    fn scan(&mut self, from: (State, f64), to: f64, depth: usize, to_minimum: bool) {
        let samples = self.follow(&from.0, to);
        let largest = samples.iter().map(|s| s.1.abs()).fold(0.0, f64::max);
        // A force this small is the round-off of an equilibrium reached (the second minimum at
        // the end), not a side of a crossing.
        let zero = 1e-6 * largest;
        let mut last = &from;
        // A step that lands on the barrier itself (a path symmetric about it) has a round-off
        // force of either sign: the crossing is then that step, if the sign changes across it.
        let mut on_barrier: Option<&(State, f64)> = None;
        for s in &samples {
            if s.1.abs() <= zero {
                on_barrier.get_or_insert(s);
                continue;
            }
            if last.1 * s.1 < 0.0 {
                let start = match on_barrier {
                    Some(b) => b.0.clone(),
                    None => self.interpolated(last, s),
                };
                let at = start.q[self.var];
                self.out.push(Crossing { state: start, at });
            }
            on_barrier = None;
            last = s;
        }
        if depth == 0 || samples.is_empty() {
            return;
        }
        if from.1 == 0.0 && samples[0].1 * self.sigma < 0.0 {
            self.scan(from.clone(), samples[0].0.q[self.var], depth - 1, false);
        }
        let n = samples.len();
        let reached = n == STEPS && samples[n - 1].1.abs() <= zero;
        if to_minimum && reached && n >= 2 && samples[n - 2].1 * self.sigma > 0.0 {
            self.scan(samples[n - 2].clone(), to, depth - 1, true);
        }
    }

    /// The nearer of two steps whose forces have opposite signs, with its positions
    /// interpolated linearly to the force's zero.
    fn interpolated(&self, a: &(State, f64), b: &(State, f64)) -> State {
        let t = a.1 / (a.1 - b.1);
        let mut start = if t < 0.5 { a.0.clone() } else { b.0.clone() };
        for v in self.p.model.layout.positions() {
            start.q[v] = a.0.q[v] + t * (b.0.q[v] - a.0.q[v]);
        }
        start
    }

    /// The states and holding forces of the steps from `from` to `to` (up to the first that
    /// does not converge).
    fn follow(&mut self, from: &State, to: f64) -> Vec<(State, f64)> {
        let var = self.var;
        self.p.model.state = from.clone();
        self.p.model.staged[0].start = from.q[var];
        self.p.model.staged[0].end = to;
        self.p.set_load_range(0.0, 0.0);
        self.p.set_continuation(0.0);
        let mut out = Vec::new();
        for i in 1..=STEPS {
            self.p
                .set_load_range((i - 1) as f64 / STEPS as f64, i as f64 / STEPS as f64);
            if !self.p.solve(self.settings).converged {
                break;
            }
            let f = holding_force(self.p.model, var);
            out.push((self.p.model.state.clone(), f));
        }
        out
    }
}

/// The energy's gradient at the held variable: minus the force the holding support applies.
fn holding_force(m: &crate::network::Model, var: usize) -> f64 {
    let mut grad = vec![0.0; m.n_free];
    let mut full = vec![0.0; m.state.q.len()];
    m.assemble(&mut Assembly {
        grad: &mut grad,
        full_grad: Some(&mut full),
        hess: None,
    });
    full[var]
}
