//! The network as a [`NewtonProblem`].

use crate::network::model::{Assembly, Model, VarKind, FIXED};
use crate::network::state::State;
use crate::solver::NewtonProblem;

impl NewtonProblem for Model {
    type Snapshot = State;
    fn snapshot(&self) -> State {
        self.state.clone()
    }
    fn restore(&mut self, s: &State) {
        self.state.clone_from(s);
    }
    fn extrapolate(&mut self, from: &State, factor: f64) {
        // Positions only: edge angles are relative to reference frames that differ between the
        // two iterates, and frame increments are zero after every commit.
        for (v, &f) in self.free.iter().enumerate() {
            if f != FIXED && self.kinds[v] == VarKind::Position {
                self.state.q[v] += factor * (self.state.q[v] - from.q[v]);
            }
        }
        if let Some(c) = &self.contact {
            // The predictor must not start a sub-step inside an obstacle.
            c.project(&mut self.state.q);
        }
        self.commit();
    }
    fn residual_floor(&self) -> f64 {
        Model::residual_floor(self)
    }
    fn num_free(&self) -> usize {
        self.n_free
    }
    fn hessian_pattern(&self) -> Vec<(usize, usize)> {
        Model::hessian_pattern(self)
    }
    fn set_hessian_slots(&mut self, slots: &[usize]) {
        self.set_slots(slots)
    }
    fn assemble(&self, grad: &mut [f64], hess: Option<&mut [f64]>) -> f64 {
        Model::assemble(
            self,
            &mut Assembly {
                grad,
                full_grad: None,
                hess,
            },
        )
    }
    fn energy(&self) -> f64 {
        Model::energy(self)
    }
    fn trial_energy(&mut self, step: &[f64], alpha: f64) -> f64 {
        Model::trial_energy(self, step, alpha)
    }
    fn trial_gradient(&mut self, step: &[f64], alpha: f64, grad: &mut [f64]) -> f64 {
        Model::trial_gradient(self, step, alpha, grad)
    }
    fn step_correction(&mut self, step: &[f64], c: &mut [f64]) -> bool {
        let mut proj = self
            .projector
            .0
            .take()
            .unwrap_or_else(|| crate::network::projection::Projector::new(self));
        let r = proj.correction(self, step, c);
        self.projector.0 = Some(proj);
        if let (true, Some(contact)) = (r, &self.contact) {
            contact.limit_correction(&self.state.q, &self.free, step, c);
        }
        r
    }
    fn max_step(&self, step: &[f64]) -> f64 {
        Model::max_step(self, step)
    }
    fn accept(&mut self, step: &[f64], alpha: f64) {
        self.displace(step, alpha);
        self.commit();
    }
    fn relative_residual(&self, grad: &[f64]) -> f64 {
        Model::relative_residual(self, grad)
    }
    fn unknown_positions(&self) -> Option<Vec<[f64; 3]>> {
        Some(Model::unknown_positions(self))
    }
    fn continuation_is_trivial(&self) -> bool {
        self.terms.loads.is_empty()
            && self.terms.torques.is_empty()
            && self.prescribed.iter().all(|p| p.start == p.end)
            && self
                .prescribed_rotations
                .iter()
                .all(|p| p.rotation == [0.0; 3])
    }
    fn set_continuation(&mut self, lambda: f64) {
        self.set_load(lambda);
        // Prescribed variables moved: reference frames must follow before the next assembly.
        self.commit();
    }
    fn perturbation_size(&self, direction: &[f64]) -> f64 {
        // Largest node displacement 1 % of the length scale, or largest rotation 0.01 rad.
        let mut dx: f64 = 0.0;
        let mut da: f64 = 0.0;
        for (v, &f) in self.free.iter().enumerate() {
            if f == FIXED {
                continue;
            }
            let d = direction[f as usize].abs();
            match self.kinds[v] {
                VarKind::Position => dx = dx.max(d),
                VarKind::Angle => da = da.max(d),
            }
        }
        let sx = if dx > 0.0 {
            1e-2 * self.length_scale / dx
        } else {
            f64::INFINITY
        };
        let sa = if da > 0.0 { 1e-2 / da } else { f64::INFINITY };
        sx.min(sa)
    }
    fn unknown_scales(&self, scales: &mut [f64]) {
        // Positions in units of the mean rest edge length, angles in radians: turning an edge
        // by one radian moves its end by about that length, so a unit dimensionless step is
        // the same size for both. (The bounding box's diagonal, the other natural length,
        // damped the angles of the hemisphere's form finding (diagonal 4.4 R, edges 0.06 R)
        // 5000 times more and took 282 Newton iterations instead of 165.)
        let n = self.rest_lengths.len().max(1) as f64;
        let edge = self.rest_lengths.iter().sum::<f64>() / n;
        for (v, &f) in self.free.iter().enumerate() {
            if f != FIXED {
                scales[f as usize] = match self.kinds[v] {
                    VarKind::Position => edge,
                    VarKind::Angle => 1.0,
                };
            }
        }
    }
    fn num_constraints(&self) -> usize {
        self.contact.as_ref().map_or(0, |c| c.len())
    }
    fn constraint_pattern(&self) -> Vec<(usize, usize)> {
        self.contact
            .as_ref()
            .map_or_else(Vec::new, |c| c.pattern(&self.free))
    }
    fn constraints(&self, c: &mut [f64], jac: &mut [f64]) {
        if let Some(contact) = &self.contact {
            contact.values(&self.state.q, c, jac);
        }
    }
    fn feasible(&mut self, step: &[f64]) -> bool {
        let Some(contact) = self.contact.take() else {
            return true;
        };
        let current = self.state.q.clone();
        self.displace(step, 1.0);
        let ok = contact.admits(&current, &self.state.q);
        self.state.q = current;
        self.contact = Some(contact);
        ok
    }
}
