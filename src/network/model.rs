//! A built network: its state, its energy terms, the map from variables to free unknowns, and
//! assembly of energy, gradient and Hessian over a fixed sparsity pattern.

use rayon::prelude::*;

use crate::energy::{
    bend::Bend, frame_bend::FrameBend, frame_twist::FrameTwist, joint_rotation::JointRotation,
    joint_translation::JointTranslation, point_load::PointLoad, stretch::Stretch, torque::Torque,
    twist::Twist, Category, Term,
};
use crate::math::vec::{normalize, sub, transport};
#[allow(unused_imports)]
use crate::math::Real;
use crate::math::{D1, HD};
use crate::network::state::State;

/// Marks a fixed variable in [`Model::free`] and an unused Hessian slot.
pub const FIXED: u32 = u32::MAX;

/// All energy terms of a network, grouped by kind so that assembly is monomorphized.
#[derive(Debug, Clone, Default)]
pub struct Terms {
    pub stretch: Vec<Stretch>,
    pub bend: Vec<Bend>,
    pub twist: Vec<Twist>,
    pub frame_bend: Vec<FrameBend>,
    pub frame_twist: Vec<FrameTwist>,
    pub joint_rotation: Vec<JointRotation>,
    pub joint_translation: Vec<JointTranslation>,
    pub loads: Vec<PointLoad>,
    pub torques: Vec<Torque>,
}

/// Energy split by category, in joules.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct EnergyParts {
    pub stretch: f64,
    pub bend: f64,
    pub twist: f64,
    pub joints: f64,
    pub external: f64,
}

impl EnergyParts {
    pub fn total(&self) -> f64 {
        self.stretch + self.bend + self.twist + self.joints + self.external
    }
    fn add(&mut self, c: Category, e: f64) {
        match c {
            Category::Stretch => self.stretch += e,
            Category::Bend => self.bend += e,
            Category::Twist => self.twist += e,
            Category::Joints => self.joints += e,
            Category::External => self.external += e,
        }
    }
}

/// What a variable is, for step limits and residual scaling.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VarKind {
    Position,
    Angle,
}

/// A fixed vertex frame rotated by `λ · rotation` (rotation vector) over the load steps.
#[derive(Debug, Clone, Copy)]
pub struct PrescribedRotation {
    pub frame: usize,
    pub rotation: [f64; 3],
}

/// A variable moved from `start` to `end` over the load steps (`move_to`).
#[derive(Debug, Clone, Copy)]
pub struct Prescribed {
    pub var: usize,
    pub start: f64,
    pub end: f64,
}

#[derive(Debug, Clone)]
pub struct Model {
    pub state: State,
    pub terms: Terms,
    pub kinds: Vec<VarKind>,
    /// Free index of each variable, or [`FIXED`].
    pub free: Vec<u32>,
    pub n_free: usize,
    pub prescribed: Vec<Prescribed>,
    pub prescribed_rotations: Vec<PrescribedRotation>,
    /// Global edges as (node a, node b); node k's coordinates are variables 3k..3k+3.
    pub edge_nodes: Vec<[usize; 2]>,
    /// Rest length of each global edge.
    pub rest_lengths: Vec<f64>,
    /// Characteristic length (m) and force (N) used to make residuals relative.
    pub length_scale: f64,
    pub force_scale: f64,
    /// First ω variable of each vertex frame.
    pub frame_vars: Vec<usize>,
    /// Contact and bound constraints, when the scene declares any.
    pub contact: Option<crate::network::contact::Contact>,
    slots: Slots,
    pub(crate) projector: crate::network::projection::LazyProjector,
    /// Scratch copy of the variables for trial evaluations.
    saved_q: Vec<f64>,
}

#[derive(Debug, Clone, Default)]
struct Slots {
    stretch: Vec<u32>,
    bend: Vec<u32>,
    twist: Vec<u32>,
    frame_bend: Vec<u32>,
    frame_twist: Vec<u32>,
    joint_rotation: Vec<u32>,
    joint_translation: Vec<u32>,
    loads: Vec<u32>,
    torques: Vec<u32>,
}

/// Output buffers of one assembly over free variables.
pub struct Assembly<'a> {
    pub grad: &'a mut [f64],
    /// Gradient over every variable (for support reactions), if wanted.
    pub full_grad: Option<&'a mut [f64]>,
    /// Values of the sparse Hessian's upper triangle, indexed by the slots from `set_slots`.
    pub hess: Option<&'a mut [f64]>,
}

impl Model {
    /// Assembles parts from already-built pieces; `slots` come later from the linear solver.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        state: State,
        terms: Terms,
        kinds: Vec<VarKind>,
        fixed: &[bool],
        prescribed: Vec<Prescribed>,
        edge_nodes: Vec<[usize; 2]>,
        rest_lengths: Vec<f64>,
        length_scale: f64,
        force_scale: f64,
        frame_vars: Vec<usize>,
    ) -> Model {
        let mut free = vec![FIXED; fixed.len()];
        let mut n_free = 0;
        for (i, f) in fixed.iter().enumerate() {
            if !f {
                free[i] = n_free as u32;
                n_free += 1;
            }
        }
        Model {
            state,
            terms,
            kinds,
            free,
            n_free,
            prescribed,
            prescribed_rotations: Vec::new(),
            edge_nodes,
            rest_lengths,
            length_scale,
            force_scale,
            frame_vars,
            contact: None,
            slots: Slots::default(),
            projector: Default::default(),
            saved_q: Vec::new(),
        }
    }

    /// Upper-triangle (row ≤ col) pairs of free variables coupled by some term, including every
    /// diagonal entry, in the order that [`Model::set_slots`] expects.
    pub fn hessian_pattern(&self) -> Vec<(usize, usize)> {
        let mut pairs: Vec<(usize, usize)> = (0..self.n_free).map(|i| (i, i)).collect();
        let t = &self.terms;
        pattern_of(&t.stretch, &self.free, &mut pairs);
        pattern_of(&t.bend, &self.free, &mut pairs);
        pattern_of(&t.twist, &self.free, &mut pairs);
        pattern_of(&t.frame_bend, &self.free, &mut pairs);
        pattern_of(&t.frame_twist, &self.free, &mut pairs);
        pattern_of(&t.joint_rotation, &self.free, &mut pairs);
        pattern_of(&t.joint_translation, &self.free, &mut pairs);
        pattern_of(&t.loads, &self.free, &mut pairs);
        pattern_of(&t.torques, &self.free, &mut pairs);
        pairs
    }

    /// Receives, for each pair of [`Model::hessian_pattern`], its index in the Hessian values.
    pub fn set_slots(&mut self, slot_of_pair: &[usize]) {
        let mut at = self.n_free;
        let t = &self.terms;
        let free = &self.free;
        self.slots = Slots {
            stretch: slots_of(&t.stretch, free, slot_of_pair, &mut at),
            bend: slots_of(&t.bend, free, slot_of_pair, &mut at),
            twist: slots_of(&t.twist, free, slot_of_pair, &mut at),
            frame_bend: slots_of(&t.frame_bend, free, slot_of_pair, &mut at),
            frame_twist: slots_of(&t.frame_twist, free, slot_of_pair, &mut at),
            joint_rotation: slots_of(&t.joint_rotation, free, slot_of_pair, &mut at),
            joint_translation: slots_of(&t.joint_translation, free, slot_of_pair, &mut at),
            loads: slots_of(&t.loads, free, slot_of_pair, &mut at),
            torques: slots_of(&t.torques, free, slot_of_pair, &mut at),
        };
    }

    /// Energy of the current state, by category.
    pub fn energy_parts(&self) -> EnergyParts {
        let mut parts = EnergyParts::default();
        let st = &self.state;
        let t = &self.terms;
        parts.add(Category::Stretch, sum_energy(&t.stretch, st));
        parts.add(Category::Bend, sum_energy(&t.bend, st));
        parts.add(Category::Twist, sum_energy(&t.twist, st));
        parts.add(Category::Bend, sum_energy(&t.frame_bend, st));
        parts.add(Category::Twist, sum_energy(&t.frame_twist, st));
        parts.add(Category::Joints, sum_energy(&t.joint_rotation, st));
        parts.add(Category::Joints, sum_energy(&t.joint_translation, st));
        parts.add(Category::External, sum_energy(&t.loads, st));
        parts.add(Category::External, sum_energy(&t.torques, st));
        parts
    }

    pub fn energy(&self) -> f64 {
        self.energy_parts().total()
    }

    /// Energy, gradient and (optionally) Hessian at the current state.
    pub fn assemble(&self, out: &mut Assembly) -> f64 {
        out.grad.iter_mut().for_each(|g| *g = 0.0);
        if let Some(f) = out.full_grad.as_deref_mut() {
            f.iter_mut().for_each(|g| *g = 0.0);
        }
        if let Some(h) = out.hess.as_deref_mut() {
            h.iter_mut().for_each(|g| *g = 0.0);
        }
        let (st, t, s) = (&self.state, &self.terms, &self.slots);
        let mut e = 0.0;
        e += assemble_kind(&t.stretch, &s.stretch, st, &self.free, out);
        e += assemble_kind(&t.bend, &s.bend, st, &self.free, out);
        e += assemble_kind(&t.twist, &s.twist, st, &self.free, out);
        e += assemble_kind(&t.frame_bend, &s.frame_bend, st, &self.free, out);
        e += assemble_kind(&t.frame_twist, &s.frame_twist, st, &self.free, out);
        e += assemble_kind(&t.joint_rotation, &s.joint_rotation, st, &self.free, out);
        e += assemble_kind(
            &t.joint_translation,
            &s.joint_translation,
            st,
            &self.free,
            out,
        );
        e += assemble_kind(&t.loads, &s.loads, st, &self.free, out);
        e += assemble_kind(&t.torques, &s.torques, st, &self.free, out);
        e
    }

    /// Applies `alpha · step` (over free variables) to the variables, without committing.
    pub fn displace(&mut self, step: &[f64], alpha: f64) {
        for (v, &f) in self.free.iter().enumerate() {
            if f != FIXED {
                self.state.q[v] += alpha * step[f as usize];
            }
        }
    }

    /// Gradient (over free variables) at the current state displaced by `alpha · step`,
    /// without committing; returns the energy there.
    pub fn trial_gradient(&mut self, step: &[f64], alpha: f64, grad: &mut [f64]) -> f64 {
        self.displaced(step, alpha, |m| {
            m.assemble(&mut Assembly {
                grad,
                full_grad: None,
                hess: None,
            })
        })
    }

    /// Energy at the current state displaced by `alpha · step`, using the current reference
    /// frames (time-parallel transport from the last accepted iterate).
    pub fn trial_energy(&mut self, step: &[f64], alpha: f64) -> f64 {
        self.displaced(step, alpha, |m| m.energy())
    }

    /// Evaluates `f` at the current state displaced by `alpha · step`, then restores the state
    /// exactly; the saved copy reuses one buffer, so line searches do not allocate.
    fn displaced<R>(&mut self, step: &[f64], alpha: f64, f: impl FnOnce(&Self) -> R) -> R {
        let mut saved = std::mem::take(&mut self.saved_q);
        saved.clear();
        saved.extend_from_slice(&self.state.q);
        self.displace(step, alpha);
        let r = f(self);
        std::mem::swap(&mut self.state.q, &mut saved);
        self.saved_q = saved;
        r
    }

    /// Accepts the current variables as the new iterate: edge reference frames are transported
    /// in time to the new tangents, reference twists are unwrapped and stored, and frame rotation
    /// increments are folded into the frames' reference rotations.
    pub fn commit(&mut self) {
        let q = &self.state.q;
        for (e, [a, b]) in self.edge_nodes.iter().enumerate() {
            let xa = [q[3 * a], q[3 * a + 1], q[3 * a + 2]];
            let xb = [q[3 * b], q[3 * b + 1], q[3 * b + 2]];
            let t = normalize(sub(xb, xa));
            let r = &mut self.state.edges[e];
            r.u = normalize(transport(r.t, t, r.u));
            r.t = t;
        }
        // Reference twists must be recomputed with the new edge references, which give the same
        // angles as before (transport composes), then stored for unwrapping.
        let prev: Vec<(usize, f64)> = self
            .terms
            .twist
            .iter()
            .map(|tw| {
                (
                    tw.slot,
                    tw.reference_twist::<f64>(&self.state, &Twist::reduced(&tw.gather(q))),
                )
            })
            .chain(self.terms.frame_twist.iter().map(|tw| {
                (
                    tw.slot,
                    tw.reference_twist::<f64>(&self.state, &FrameTwist::reduced(&tw.gather(q))),
                )
            }))
            .collect();
        // Frame twists depend on ω, so fold ω only after their values are taken.
        for (slot, v) in prev {
            self.state.twist_prev[slot] = v;
        }
        let nf = self.state.frames.len();
        for f in 0..nf {
            if let Some(base) = self.frame_var(f) {
                let w = [
                    self.state.q[base],
                    self.state.q[base + 1],
                    self.state.q[base + 2],
                ];
                self.state.frames[f].commit(w);
                for k in 0..3 {
                    self.state.q[base + k] = 0.0;
                }
            }
        }
    }

    /// First ω variable of frame `f`.
    pub fn frame_var(&self, f: usize) -> Option<usize> {
        self.frame_vars.get(f).copied()
    }

    /// Sets the load factor and the prescribed variables for continuation parameter `lambda`.
    pub fn set_load(&mut self, lambda: f64) {
        self.state.load_factor = lambda;
        for p in &self.prescribed {
            self.state.q[p.var] = p.start + lambda * (p.end - p.start);
        }
        for p in &self.prescribed_rotations {
            let w = crate::math::vec::scalef(p.rotation, lambda);
            let mut f = crate::network::state::FrameRef::identity();
            f.commit(w);
            self.state.frames[p.frame] = f;
        }
    }

    /// Largest fraction of `step` that keeps every edge from turning or stretching too far in one
    /// iteration (keeps time-parallel transport away from its antipodal singularity) and every
    /// rotation increment below 1 rad.
    pub fn max_step(&self, step: &[f64]) -> f64 {
        let q = &self.state.q;
        let d = |v: usize| {
            let f = self.free[v];
            if f == FIXED {
                0.0
            } else {
                step[f as usize]
            }
        };
        let mut alpha: f64 = 1.0;
        for (e, [a, b]) in self.edge_nodes.iter().enumerate() {
            let mut de2 = 0.0;
            let mut l2 = 0.0;
            for k in 0..3 {
                let dd = d(3 * b + k) - d(3 * a + k);
                let l = q[3 * b + k] - q[3 * a + k];
                de2 += dd * dd;
                l2 += l * l;
            }
            let lim = 0.5 * l2.sqrt().max(0.1 * self.rest_lengths[e]);
            if de2 > lim * lim {
                alpha = alpha.min(lim / de2.sqrt());
            }
        }
        for (v, k) in self.kinds.iter().enumerate() {
            if *k == VarKind::Angle {
                let s = d(v).abs();
                if s > 1.0 {
                    alpha = alpha.min(1.0 / s);
                }
            }
        }
        alpha
    }

    /// Relative residual that round-off alone produces: a coordinate X carries an absolute error
    /// of about ε·X, so an edge of rest length l̄ and rigidity EA carries a force error of about
    /// 2ε·EA·X/l̄. Stiff, finely subdivided rods cannot be converged below this. A node sums
    /// the errors of its two edges (more at a joint) and of its bending stencils: with 2ε the
    /// estimate was exceeded (an L-frame under 1e-5 N at 160 edges per rod stalled at 1.07× it
    /// and wandered off), so it carries a factor 4.
    pub fn residual_floor(&self) -> f64 {
        let q = &self.state.q;
        let x = (0..q.len())
            .filter(|&v| self.kinds[v] == VarKind::Position)
            .map(|v| q[v].abs())
            .fold(self.length_scale, f64::max);
        let worst = self
            .terms
            .stretch
            .iter()
            .map(|s| s.ea / s.rest_length)
            .fold(0.0, f64::max);
        8.0 * f64::EPSILON * worst * x / self.force_scale
    }

    /// Largest residual over free variables, relative: forces over the force scale and moments
    /// over force scale × length scale.
    pub fn relative_residual(&self, grad: &[f64]) -> f64 {
        let mut r: f64 = 0.0;
        for (v, &f) in self.free.iter().enumerate() {
            if f == FIXED {
                continue;
            }
            let g = grad[f as usize].abs();
            let s = match self.kinds[v] {
                VarKind::Position => self.force_scale,
                VarKind::Angle => self.force_scale * self.length_scale,
            };
            r = r.max(g / s);
        }
        r
    }
}

fn pattern_of<const N: usize, E: Term<N>>(
    terms: &[E],
    free: &[u32],
    pairs: &mut Vec<(usize, usize)>,
) {
    for t in terms {
        let v = t.vars();
        for i in 0..N {
            for j in i..N {
                let (a, b) = (free[v[i]], free[v[j]]);
                if i != j && a != FIXED && b != FIXED {
                    let (a, b) = (a.min(b) as usize, a.max(b) as usize);
                    pairs.push((a, b));
                }
            }
        }
    }
}

fn slots_of<const N: usize, E: Term<N>>(
    terms: &[E],
    free: &[u32],
    slot_of_pair: &[usize],
    at: &mut usize,
) -> Vec<u32> {
    let mut out = Vec::with_capacity(terms.len() * N * (N + 1) / 2);
    for t in terms {
        let v = t.vars();
        for i in 0..N {
            for j in i..N {
                let (a, b) = (free[v[i]], free[v[j]]);
                if a == FIXED || b == FIXED {
                    out.push(FIXED);
                } else if i == j {
                    // Diagonal pairs come first in the pattern, one per free variable.
                    out.push(slot_of_pair[a as usize] as u32);
                } else {
                    out.push(slot_of_pair[*at] as u32);
                    *at += 1;
                }
            }
        }
    }
    out
}

fn sum_energy<const N: usize, E: Term<N>>(terms: &[E], st: &State) -> f64 {
    if terms.len() > 2048 {
        terms.par_iter().map(|t| t.energy(st)).sum()
    } else {
        terms.iter().map(|t| t.energy(st)).sum()
    }
}

/// Terms are differentiated in parallel blocks; each block's local results are scattered
/// serially, which keeps the sum deterministic.
const BLOCK: usize = 1024;

fn gradient_kind<const N: usize, E: Term<N>>(
    terms: &[E],
    st: &State,
    free: &[u32],
    out: &mut Assembly,
) -> f64 {
    let mut energy = 0.0;
    let mut local: Vec<D1<N>> = Vec::new();
    for block in terms.chunks(BLOCK) {
        let eval = |t: &E| {
            let x = D1::<N>::vars(&t.gather(&st.q));
            t.eval(st, &x)
        };
        if block.len() > 64 {
            block.par_iter().map(eval).collect_into_vec(&mut local);
        } else {
            local.clear();
            local.extend(block.iter().map(eval));
        }
        for (t, r) in block.iter().zip(&local) {
            energy += r.v;
            let v = t.vars();
            for i in 0..N {
                let f = free[v[i]];
                if f != FIXED {
                    out.grad[f as usize] += r.g[i];
                }
            }
            if let Some(fg) = out.full_grad.as_deref_mut() {
                for i in 0..N {
                    fg[v[i]] += r.g[i];
                }
            }
        }
    }
    energy
}

fn assemble_kind<const N: usize, E: Term<N>>(
    terms: &[E],
    slots: &[u32],
    st: &State,
    free: &[u32],
    out: &mut Assembly,
) -> f64 {
    let np = N * (N + 1) / 2;
    let want_h = out.hess.is_some();
    if !want_h {
        return gradient_kind(terms, st, free, out);
    }
    let mut energy = 0.0;
    let mut local: Vec<HD<N>> = Vec::new();
    for (b, block) in terms.chunks(BLOCK).enumerate() {
        let eval = |t: &E| t.derivatives(st, &t.gather(&st.q));
        if block.len() > 64 {
            block.par_iter().map(eval).collect_into_vec(&mut local);
        } else {
            local.clear();
            local.extend(block.iter().map(eval));
        }
        for (k, (t, r)) in block.iter().zip(&local).enumerate() {
            energy += r.v;
            let v = t.vars();
            for i in 0..N {
                let f = free[v[i]];
                if f != FIXED {
                    out.grad[f as usize] += r.g[i];
                }
            }
            if let Some(fg) = out.full_grad.as_deref_mut() {
                for i in 0..N {
                    fg[v[i]] += r.g[i];
                }
            }
            if want_h {
                let h = out.hess.as_deref_mut().unwrap();
                let s = &slots[(b * BLOCK + k) * np..(b * BLOCK + k + 1) * np];
                let mut p = 0;
                for i in 0..N {
                    for j in i..N {
                        let slot = s[p];
                        p += 1;
                        if slot != FIXED {
                            let mut val = r.h[i][j];
                            // The same free variable twice in one term: (i,j) and (j,i) both land
                            // on the diagonal.
                            if i != j && free[v[i]] == free[v[j]] {
                                val *= 2.0;
                            }
                            h[slot as usize] += val;
                        }
                    }
                }
            }
        }
    }
    energy
}
