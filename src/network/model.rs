//! The Newton problem of a network and nothing else: the variable layout, the state, the energy
//! terms, which variables are free, the prescribed motions of the continuation, the scales that
//! make residuals relative, and the inequality constraints. Assembly is in
//! `assembly.rs`; caches of a solve live in the adapter (`problem.rs`).

use rayon::prelude::*;

use crate::energy::frame_bend::FrameBend;
use crate::energy::registry::{TermVisitor, Terms};
use crate::energy::{Category, Term};
use crate::math::vec::{norm, normalize, scalef, sub, transport};
use crate::network::contact::Contact;
use crate::network::roller::{Rollers, SlantedRoller};
use crate::network::scratch::{Scratch, MAX_CATEGORIES};
use crate::rod::frames::EdgeRef;
use crate::solver::linalg::AnalysisCache;
use crate::variables::{DofLayout, FrameRef, State, Unknowns, VarKind};

pub use crate::variables::FIXED;

/// Energy split by category, in joules.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct EnergyParts {
    pub stretch: f64,
    pub bend: f64,
    pub twist: f64,
    pub joints: f64,
    /// Elastic supports.
    pub supports: f64,
    pub external: f64,
}

impl EnergyParts {
    pub fn total(&self) -> f64 {
        self.stretch + self.bend + self.twist + self.joints + self.supports + self.external
    }
    /// Sums kinds by category, in the given order.
    pub fn of(kinds: &[KindEnergy]) -> EnergyParts {
        let mut parts = EnergyParts::default();
        for k in kinds {
            parts.add(k.category, k.energy);
        }
        parts
    }

    pub fn add(&mut self, c: Category, e: f64) {
        match c {
            Category::Stretch => self.stretch += e,
            Category::Bend => self.bend += e,
            Category::Twist => self.twist += e,
            Category::Joints => self.joints += e,
            Category::Supports => self.supports += e,
            Category::External => self.external += e,
        }
    }
}

/// The energy of one kind of term.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KindEnergy {
    pub name: &'static str,
    pub category: Category,
    pub energy: f64,
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

/// The values each load term starts and ends a load stage at: (from, to) per `terms.loads`
/// force and per `terms.torques` torque.
#[derive(Debug, Clone, Default)]
pub struct LoadRamp {
    pub loads: Vec<[[f64; 3]; 2]>,
    pub torques: Vec<[[f64; 3]; 2]>,
}

impl LoadRamp {
    fn at(ends: &[[f64; 3]; 2], lambda: f64) -> [f64; 3] {
        std::array::from_fn(|k| ends[0][k] + lambda * (ends[1][k] - ends[0][k]))
    }

    fn is_trivial(&self) -> bool {
        self.loads.iter().chain(&self.torques).all(|[a, b]| a == b)
    }
}

/// Which 2π branch of each reference twist `Model::store_reference_twists` keeps.
#[derive(Debug, Clone, Copy)]
enum TwistBranch {
    /// Unwrapped against the last accepted value (`Term::remembered`).
    Remembered,
    /// Within half a turn of rest in discrete twist (`Term::nearest_turn`).
    NearestTurn,
}

/// Characteristic length (m) and force (N) that make residuals relative.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scales {
    pub length: f64,
    pub force: f64,
}

#[derive(Debug, Clone)]
pub struct Model {
    pub layout: DofLayout,
    pub state: State,
    pub terms: Terms,
    /// Free index of each variable, or [`FIXED`].
    pub free: Vec<u32>,
    pub n_free: usize,
    pub prescribed: Vec<Prescribed>,
    pub prescribed_rotations: Vec<PrescribedRotation>,
    /// A second stage on top of the scene's full load (`network/indent.rs`): when not empty,
    /// the scene's loads and prescribed motions stay at λ = 1 and only these motions follow the
    /// continuation parameter.
    pub staged: Vec<Prescribed>,
    /// A load stage on top of an earlier stage's equilibrium (`network/stage.rs`): when set,
    /// the load terms go from that stage's values to their own with the continuation
    /// parameter, and the prescribed motions stay at λ = 1.
    pub ramp: Option<LoadRamp>,
    /// Global edges as (node a, node b).
    pub edge_nodes: Vec<[usize; 2]>,
    /// Rest length of each global edge.
    pub rest_lengths: Vec<f64>,
    /// Each edge's reference frame at rest: reported angles are measured against it
    /// (`rod::frames::canonical_angle`), and a restart rebuilds the frames from it.
    pub rest_edges: Vec<EdgeRef>,
    pub length_scale: f64,
    pub force_scale: f64,
    /// Contact and bound constraints, when the scene declares any.
    pub contact: Option<Contact>,
    /// Rollers with a general normal (`network/roller.rs`).
    pub rollers: Rollers,
    /// Buffers reused by every assembly and commit, so that Newton iterations do not allocate.
    pub scratch: Scratch,
    /// Where the origin of the coordinates the model is solved in lies in the scene's own:
    /// zero, or a point near the centre of a scene far from the origin (`scene::translate`).
    /// Positions in `q` are relative to it; results are given in the scene's coordinates.
    pub origin: [f64; 3],
    /// The analyses of the Hessian patterns factored for this model (its memory estimate, its
    /// solves and eigen-analyses), shared with its clones and freed with the last of them.
    pub analyses: AnalysisCache,
}

/// The pieces a [`Model`] is made of (everything but the free map, which follows from `fixed`).
pub struct ModelParts {
    pub layout: DofLayout,
    pub state: State,
    pub terms: Terms,
    pub fixed: Vec<bool>,
    pub prescribed: Vec<Prescribed>,
    pub prescribed_rotations: Vec<PrescribedRotation>,
    pub edge_nodes: Vec<[usize; 2]>,
    pub rest_lengths: Vec<f64>,
    pub scales: Scales,
    pub contact: Option<Contact>,
    pub rollers: Vec<SlantedRoller>,
}

impl Model {
    pub fn new(p: ModelParts) -> Model {
        debug_assert_eq!(p.fixed.len(), p.layout.len());
        let mut free = vec![FIXED; p.fixed.len()];
        let mut n_free = 0;
        for (i, f) in p.fixed.iter().enumerate() {
            if !f {
                free[i] = n_free as u32;
                n_free += 1;
            }
        }
        Model {
            layout: p.layout,
            rest_edges: p.state.edges.clone(),
            state: p.state,
            terms: p.terms,
            free,
            n_free,
            prescribed: p.prescribed,
            prescribed_rotations: p.prescribed_rotations,
            staged: Vec::new(),
            ramp: None,
            edge_nodes: p.edge_nodes,
            rest_lengths: p.rest_lengths,
            length_scale: p.scales.length,
            force_scale: p.scales.force,
            contact: p.contact,
            rollers: Rollers::new(p.rollers, p.layout.len()),
            scratch: Scratch::default(),
            origin: [0.0; 3],
            analyses: AnalysisCache::default(),
        }
    }

    /// Holds variable `v` where it is (a support on one coordinate, as an axis Roller is),
    /// renumbering the free unknowns; `staged` may then move it.
    pub fn hold(&mut self, v: usize) {
        self.free[v] = FIXED;
        let mut n = 0;
        for f in self.free.iter_mut().filter(|f| **f != FIXED) {
            *f = n;
            n += 1;
        }
        self.n_free = n as usize;
    }

    /// The free unknowns, for code that needs the free map but not the model.
    pub fn unknowns(&self) -> Unknowns<'_> {
        Unknowns {
            layout: &self.layout,
            free: &self.free,
        }
    }

    /// What variable `v` is.
    #[inline]
    pub fn kind(&self, v: usize) -> VarKind {
        self.layout.kind(v)
    }

    /// Position of node `n`, in the coordinates the model is solved in (`origin`).
    pub fn position(&self, n: usize) -> [f64; 3] {
        self.layout.position(&self.state.q, n)
    }

    /// Position of node `n` in the scene's coordinates: what results and restarts hold.
    pub fn world_position(&self, n: usize) -> [f64; 3] {
        let p = self.position(n);
        [0, 1, 2].map(|k| p[k] + self.origin[k])
    }

    /// Places node `n` at `p`, given in the scene's coordinates.
    pub fn set_world_position(&mut self, n: usize, p: [f64; 3]) {
        let o = self.origin;
        self.layout
            .set_position(&mut self.state.q, n, [0, 1, 2].map(|k| p[k] - o[k]));
    }

    /// Every node position in the scene's coordinates.
    pub fn world_positions(&self) -> Vec<[f64; 3]> {
        (0..self.layout.n_nodes())
            .map(|n| self.world_position(n))
            .collect()
    }

    /// Calls `f(kind, category, energy)` for every term kind at the current state, in the order
    /// of [`Terms::NAMES`], once per category of the kind ([`Term::CATEGORIES`]).
    fn each_kind_energy(&self, f: impl FnMut(usize, Category, f64)) {
        struct Each<'a, F>(&'a State, F, &'a mut Vec<[f64; MAX_CATEGORIES]>);
        impl<F: FnMut(usize, Category, f64)> TermVisitor for Each<'_, F> {
            fn visit<const N: usize, E: Term<N>>(&mut self, kind: usize, terms: &[E]) {
                let e = sum_energy(terms, self.0, self.2);
                for (&c, &e) in E::CATEGORIES.iter().zip(&e) {
                    (self.1)(kind, c, e);
                }
            }
        }
        let mut held = self.scratch.lock();
        let mut fresh = Vec::new();
        let blocks = held
            .as_deref_mut()
            .map_or(&mut fresh, |b| &mut b.energy_blocks);
        self.terms.visit(&mut Each(&self.state, f, blocks));
    }

    /// Energy of each term kind at the current state, J.
    pub fn energy_by_kind(&self) -> Vec<KindEnergy> {
        let mut out = Vec::with_capacity(Terms::KINDS);
        self.each_kind_energy(|kind, category, energy| {
            out.push(KindEnergy {
                name: Terms::NAMES[kind],
                category,
                energy,
            })
        });
        out
    }

    /// Energy of the current state, by category (no allocation: line searches call this).
    pub fn energy_parts(&self) -> EnergyParts {
        let mut parts = EnergyParts::default();
        self.each_kind_energy(|_, category, energy| parts.add(category, energy));
        parts
    }

    pub fn energy(&self) -> f64 {
        self.energy_parts().total()
    }

    /// Applies `alpha · step` (over free variables) to the variables, without committing.
    pub fn displace(&mut self, step: &[f64], alpha: f64) {
        for (v, &f) in self.free.iter().enumerate() {
            if f != FIXED {
                self.state.q[v] += alpha * step[f as usize];
            }
        }
        // Steps are tangent to slanted rollers' planes up to round-off; corrections may not be.
        self.rollers.snap(&mut self.state.q, self.state.load_factor);
    }

    /// Length of every global edge for the variables `q`.
    pub fn edge_lengths_of(&self, q: &[f64]) -> Vec<f64> {
        let layout = &self.layout;
        self.edge_nodes
            .iter()
            .map(|&[a, b]| norm(sub(layout.position(q, b), layout.position(q, a))))
            .collect()
    }

    /// Accepts the current variables as the new iterate: edge reference frames are transported
    /// in time to the new tangents, reference twists are unwrapped and stored, and frame rotation
    /// increments are folded into the frames' reference rotations.
    pub fn commit(&mut self) {
        let (layout, q) = (&self.layout, &self.state.q);
        let advance = |(r, [a, b]): (&mut EdgeRef, &[usize; 2])| {
            let t = normalize(sub(layout.position(q, *b), layout.position(q, *a)));
            r.u = normalize(transport(r.t, t, r.u));
            r.t = t;
        };
        let edges = &mut self.state.edges;
        if edges.len() > PARALLEL_BLOCK {
            edges.par_iter_mut().zip(&self.edge_nodes).for_each(advance);
        } else {
            edges.iter_mut().zip(&self.edge_nodes).for_each(advance);
        }
        // Reference twists must be recomputed with the new edge references, which give the same
        // angles as before (transport composes), then stored for unwrapping. Frame twists depend
        // on ω, so fold ω only after their values are taken.
        let buffer = std::mem::take(&mut self.scratch.get().remembered);
        let remembered = self.store_reference_twists(TwistBranch::Remembered, buffer);
        self.scratch.get().remembered = remembered;
        for f in 0..self.layout.n_frames() {
            let vars = self.layout.frame(f);
            let w = vars.map(|v| self.state.q[v]);
            self.state.frames[f].commit(w);
            for v in vars {
                self.state.q[v] = 0.0;
            }
        }
    }

    /// Puts every reference twist on the 2π branch that brings its discrete twist within half a
    /// turn of its rest value (`Term::nearest_turn`): a state placed from results (which hold
    /// angles, not branches) then keeps the turns its angles carry, e.g. a rod twisted by ten
    /// turns at a clamp, instead of unwinding them at the frames.
    pub fn nearest_turns(&mut self) {
        self.store_reference_twists(TwistBranch::NearestTurn, Vec::new());
    }

    /// Stores every twist term's reference twist on the branch `which` picks in
    /// `State::twist_prev`, collecting them in `buffer` (returned for reuse).
    fn store_reference_twists(
        &mut self,
        which: TwistBranch,
        mut buffer: Vec<(usize, f64)>,
    ) -> Vec<(usize, f64)> {
        struct Collect<'a>(&'a State, TwistBranch, Vec<(usize, f64)>);
        impl TermVisitor for Collect<'_> {
            fn visit<const N: usize, E: Term<N>>(&mut self, _: usize, terms: &[E]) {
                let (st, which) = (self.0, self.1);
                let value = |t: &E| match which {
                    TwistBranch::Remembered => t.remembered(st),
                    TwistBranch::NearestTurn => t.nearest_turn(st),
                };
                // In term order either way: each term writes its own slot.
                if terms.len() > PARALLEL_BLOCK {
                    self.2.par_extend(terms.par_iter().filter_map(value));
                } else {
                    self.2.extend(terms.iter().filter_map(value));
                }
            }
        }
        buffer.clear();
        let mut collect = Collect(&self.state, which, buffer);
        self.terms.visit(&mut collect);
        let values = collect.2;
        for &(slot, v) in &values {
            self.state.twist_prev[slot] = v;
        }
        values
    }

    /// Sets the load factor and the prescribed variables for continuation parameter `lambda`.
    pub fn set_load(&mut self, lambda: f64) {
        let held = !self.staged.is_empty() || self.ramp.is_some();
        let scene = if held { 1.0 } else { lambda };
        self.state.load_factor = scene;
        if let Some(r) = &self.ramp {
            for (l, ends) in self.terms.loads.iter_mut().zip(&r.loads) {
                l.force = LoadRamp::at(ends, lambda);
            }
            for (t, ends) in self.terms.torques.iter_mut().zip(&r.torques) {
                t.torque = LoadRamp::at(ends, lambda);
            }
        }
        for p in &self.prescribed {
            self.state.q[p.var] = p.start + scene * (p.end - p.start);
        }
        for p in &self.staged {
            self.state.q[p.var] = p.start + lambda * (p.end - p.start);
        }
        self.rollers.snap(&mut self.state.q, scene);
        for p in &self.prescribed_rotations {
            let w = scalef(p.rotation, scene);
            let mut f = FrameRef::identity();
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
                let (vb, va) = (self.layout.node_coord(*b, k), self.layout.node_coord(*a, k));
                let dd = d(vb) - d(va);
                let l = q[vb] - q[va];
                de2 += dd * dd;
                l2 += l * l;
            }
            let lim = 0.5 * l2.sqrt().max(0.1 * self.rest_lengths[e]);
            if de2 > lim * lim {
                alpha = alpha.min(lim / de2.sqrt());
            }
        }
        for v in 0..self.free.len() {
            if self.kind(v) == VarKind::Angle {
                let s = d(v).abs();
                if s > 1.0 {
                    alpha = alpha.min(1.0 / s);
                }
            }
        }
        alpha
    }

    /// The rounding error of each free variable (half an ulp of its value, with a fixed
    /// pseudo-random sign): the residual that this perturbation causes is what round-off alone
    /// produces at the current state (`NetworkProblem::residual_floor`). With `by_node`, each
    /// coordinate of a node is rounded at the size of the node's largest coordinate: a rod lying
    /// along an axis has exact zeros there now, but not once it moves (`network::floor`).
    pub fn rounding_noise(&self, out: &mut [f64], by_node: bool) {
        for (v, &f) in self.free.iter().enumerate() {
            if f != FIXED {
                let sign = if (v.wrapping_mul(2654435761) >> 13) & 1 == 0 {
                    1.0
                } else {
                    -1.0
                };
                // An angle is an increment on a stored frame, itself rounded to ε radians.
                let size = match self.kind(v) {
                    VarKind::Position if by_node => {
                        let n = self
                            .layout
                            .node_of(v)
                            .expect("a position belongs to a node");
                        self.position(n).iter().fold(0.0_f64, |a, x| a.max(x.abs()))
                    }
                    VarKind::Position => self.state.q[v].abs(),
                    VarKind::Angle => self.state.q[v].abs().max(1.0),
                };
                out[f as usize] = sign * 0.5 * f64::EPSILON * size;
            }
        }
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
            let s = match self.kind(v) {
                VarKind::Position => self.force_scale,
                VarKind::Angle => self.force_scale * self.length_scale,
            };
            r = r.max(g / s);
        }
        r
    }

    /// Turns every free vertex frame (Rigid and Hinge joints, torqued and spring-held
    /// vertices) once, by the rotation vector `rotation` gives for the first frame-bend term of
    /// that frame: how a new starting state (a net, an earlier result) carries the frames along
    /// with the nodes. Clamped frames keep the orientation their supports prescribe.
    pub fn turn_frames(&mut self, rotation: impl Fn(&Model, &FrameBend) -> [f64; 3]) {
        let mut turned = vec![false; self.state.frames.len()];
        for k in 0..self.terms.frame_bend_twist.len() {
            let fb = &self.terms.frame_bend_twist[k].bend;
            let f = fb.port.frame;
            let held = self.free[self.layout.frame(f)[0]] == FIXED;
            if !std::mem::replace(&mut turned[f], true) && !held {
                let w = rotation(self, fb);
                self.state.frames[f].commit(w);
            }
        }
    }

    /// True when the continuation parameter changes nothing: no external load and no
    /// prescribed motion.
    pub fn continuation_is_trivial(&self) -> bool {
        if !self.staged.is_empty() {
            return self.staged.iter().all(|p| p.start == p.end);
        }
        if let Some(r) = &self.ramp {
            return r.is_trivial();
        }
        let external = self.count_of(Category::External);
        external == 0
            && self.prescribed.iter().all(|p| p.start == p.end)
            && !self.rollers.planes_move()
            && self
                .terms
                .springs
                .iter()
                .all(|s| s.anchor[0] == s.anchor[1])
            && self
                .terms
                .rotational_springs
                .iter()
                .all(|s| s.rotate_by == [0.0; 3])
            && self
                .prescribed_rotations
                .iter()
                .all(|p| p.rotation == [0.0; 3])
    }

    /// Number of terms of category `c`.
    fn count_of(&self, c: Category) -> usize {
        struct Count(Category, usize);
        impl TermVisitor for Count {
            fn visit<const N: usize, E: Term<N>>(&mut self, _: usize, terms: &[E]) {
                if E::CATEGORIES.contains(&self.0) {
                    self.1 += terms.len();
                }
            }
        }
        let mut count = Count(c, 0);
        self.terms.visit(&mut count);
        count.1
    }

    /// Step along `direction` (over free unknowns) whose largest node displacement is 1 % of
    /// the length scale or whose largest rotation is 0.01 rad, whichever is smaller.
    pub fn perturbation_size(&self, direction: &[f64]) -> f64 {
        let mut dx: f64 = 0.0;
        let mut da: f64 = 0.0;
        for (v, &f) in self.free.iter().enumerate() {
            if f == FIXED {
                continue;
            }
            let d = direction[f as usize].abs();
            match self.kind(v) {
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

    /// The mean rest edge length (0 without edges): the length unit of the unknowns' scales.
    pub fn mean_edge(&self) -> f64 {
        let n = self.rest_lengths.len().max(1) as f64;
        self.rest_lengths.iter().sum::<f64>() / n
    }

    /// Characteristic size of each free unknown: positions in units of the mean rest edge
    /// length, angles in radians. Turning an edge by one radian moves its end by about that
    /// length, so a unit dimensionless step is the same size for both; the bounding box's
    /// diagonal, the other natural length, damps the angles by (diagonal / edge)² relative to the
    /// positions (docs/design.md).
    pub fn unknown_scales(&self, scales: &mut [f64]) {
        let edge = self.mean_edge();
        for (v, &f) in self.free.iter().enumerate() {
            if f != FIXED {
                scales[f as usize] = match self.kind(v) {
                    VarKind::Position => edge,
                    VarKind::Angle => 1.0,
                };
            }
        }
    }
}

/// Terms (or edges) per block of a parallel sweep: energies are summed per block in parallel
/// and the blocks' sums added in order, so the total does not depend on the number of threads;
/// fewer than this stay on the calling thread.
const PARALLEL_BLOCK: usize = 256;

/// Sum of the energies of `terms`, by category of their kind; `blocks` is scratch for the
/// blocks' sums.
fn sum_energy<const N: usize, E: Term<N>>(
    terms: &[E],
    st: &State,
    blocks: &mut Vec<[f64; MAX_CATEGORIES]>,
) -> [f64; MAX_CATEGORIES] {
    let one = |t: &E| {
        let mut e = [0.0; MAX_CATEGORIES];
        t.energies_by_category(st, &mut e[..E::CATEGORIES.len()]);
        e
    };
    let plus = |a: [f64; MAX_CATEGORIES], b: [f64; MAX_CATEGORIES]| [a[0] + b[0], a[1] + b[1]];
    let block = |b: &[E]| b.iter().map(one).fold([0.0; MAX_CATEGORIES], plus);
    if terms.len() <= PARALLEL_BLOCK {
        return block(terms);
    }
    terms
        .par_chunks(PARALLEL_BLOCK)
        .map(block)
        .collect_into_vec(blocks);
    blocks.iter().copied().fold([0.0; MAX_CATEGORIES], plus)
}
