//! Energy, gradient and Hessian of a [`Model`] over its free unknowns, on a sparsity pattern
//! fixed for the model's lifetime. The Hessian's value array belongs to the linear solver; the
//! map from each term's local pairs to that array ([`HessianSlots`]) belongs to whoever owns the
//! array (the Newton adapter, a test, a benchmark).

use rayon::prelude::*;

use super::model::{Model, FIXED};
use super::roller::Rollers;
use super::scratch::Buffers;
use crate::energy::registry::{TermVisitor, Terms};
use crate::energy::Term;
use crate::math::{D1, HD};
use crate::variables::State;

/// For each term kind, for each term, for each local pair (i ≤ j): its index in the Hessian
/// values, or [`FIXED`].
#[derive(Debug, Clone, Default)]
pub struct HessianSlots(Vec<Vec<u32>>);

/// Where the Hessian goes: its values (by slot) and the slot map built on the same pattern.
pub struct HessianOut<'a> {
    pub values: &'a mut [f64],
    pub slots: &'a HessianSlots,
}

/// Output buffers of one assembly over free variables.
pub struct Assembly<'a> {
    pub grad: &'a mut [f64],
    /// Gradient over every variable (for support reactions), if wanted.
    pub full_grad: Option<&'a mut [f64]>,
    pub hess: Option<HessianOut<'a>>,
}

impl Model {
    /// Upper-triangle (row ≤ col) pairs of free variables coupled by some term, including every
    /// diagonal entry, in the order that [`Model::hessian_slots`] expects.
    pub fn hessian_pattern(&self) -> Vec<(usize, usize)> {
        struct Pattern<'a>(&'a [u32], Vec<(usize, usize)>);
        impl TermVisitor for Pattern<'_> {
            fn visit<const N: usize, E: Term<N>>(&mut self, _: usize, terms: &[E]) {
                let free = self.0;
                for t in terms {
                    let v = t.vars();
                    for i in 0..N {
                        for j in i + 1..N {
                            let (a, b) = (free[v[i]], free[v[j]]);
                            if a != FIXED && b != FIXED {
                                self.1.push((a.min(b) as usize, a.max(b) as usize));
                            }
                        }
                    }
                }
            }
        }
        let mut p = Pattern(&self.free, (0..self.n_free).map(|i| (i, i)).collect());
        self.terms.visit(&mut p);
        p.1
    }

    /// A hash of everything [`Model::hessian_pattern`] depends on: the free map and every
    /// term's variables, in visiting order. Two 64-bit multiplicative hashes with different
    /// constants and rotations, so that two different patterns are taken for the same only by
    /// a collision in both; it costs a small fraction of making the pattern (and no memory,
    /// where keeping the pattern to compare would cost 16 bytes per Hessian entry).
    pub fn pattern_fingerprint(&self) -> [u64; 2] {
        struct Hash([u64; 2]);
        impl Hash {
            fn mix(&mut self, w: u64) {
                let [a, b] = &mut self.0;
                *a = (a.rotate_left(5) ^ w).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95);
                *b = (b.rotate_left(23) ^ w).wrapping_mul(0x9e_37_79_b9_7f_4a_7c_15);
            }
        }
        impl TermVisitor for Hash {
            fn visit<const N: usize, E: Term<N>>(&mut self, _: usize, terms: &[E]) {
                self.mix(terms.len() as u64);
                for t in terms {
                    t.vars().iter().for_each(|&v| self.mix(v as u64));
                }
            }
        }
        let mut h = Hash([1, 2]);
        h.mix(self.n_free as u64);
        self.free.iter().for_each(|&f| h.mix(u64::from(f)));
        self.terms.visit(&mut h);
        h.0
    }

    /// The slot map from, for each pair of [`Model::hessian_pattern`], its index in the Hessian
    /// values.
    pub fn hessian_slots(&self, slot_of_pair: &[usize]) -> HessianSlots {
        struct Slots<'a> {
            free: &'a [u32],
            slot_of_pair: &'a [usize],
            at: usize,
            out: Vec<Vec<u32>>,
        }
        impl TermVisitor for Slots<'_> {
            fn visit<const N: usize, E: Term<N>>(&mut self, _: usize, terms: &[E]) {
                let mut out = Vec::with_capacity(terms.len() * N * (N + 1) / 2);
                for t in terms {
                    let v = t.vars();
                    for i in 0..N {
                        for j in i..N {
                            let (a, b) = (self.free[v[i]], self.free[v[j]]);
                            if a == FIXED || b == FIXED {
                                out.push(FIXED);
                            } else if i == j {
                                // Diagonal pairs come first in the pattern, one per free variable.
                                out.push(self.slot_of_pair[a as usize] as u32);
                            } else {
                                out.push(self.slot_of_pair[self.at] as u32);
                                self.at += 1;
                            }
                        }
                    }
                }
                self.out.push(out);
            }
        }
        let mut s = Slots {
            free: &self.free,
            slot_of_pair,
            at: self.n_free,
            out: Vec::with_capacity(Terms::KINDS),
        };
        self.terms.visit(&mut s);
        HessianSlots(s.out)
    }

    /// Energy, gradient and (optionally) Hessian at the current state.
    pub fn assemble(&self, out: &mut Assembly) -> f64 {
        out.grad.iter_mut().for_each(|g| *g = 0.0);
        if let Some(f) = out.full_grad.as_deref_mut() {
            f.iter_mut().for_each(|g| *g = 0.0);
        }
        if let Some(h) = out.hess.as_mut() {
            h.values.iter_mut().for_each(|g| *g = 0.0);
        }
        let mut held = self.scratch.lock();
        let mut fresh = Buffers::default();
        let mut a = Assemble {
            st: &self.state,
            free: &self.free,
            rollers: &self.rollers,
            out,
            buffers: held.as_deref_mut().unwrap_or(&mut fresh),
            energy: 0.0,
        };
        self.terms.visit(&mut a);
        a.energy
    }
}

struct Assemble<'a, 'b> {
    st: &'a State,
    free: &'a [u32],
    rollers: &'a Rollers,
    out: &'a mut Assembly<'b>,
    buffers: &'a mut Buffers,
    energy: f64,
}

impl TermVisitor for Assemble<'_, '_> {
    fn visit<const N: usize, E: Term<N>>(&mut self, kind: usize, terms: &[E]) {
        let slots: Option<&HessianSlots> = self.out.hess.as_ref().map(|h| h.slots);
        // Slanted rollers project every term at their nodes but their own normal springs.
        let rollers = (!self.rollers.is_empty() && Terms::NAMES[kind] != "roller_normals")
            .then_some(self.rollers);
        let (st, free, out) = (self.st, self.free, &mut *self.out);
        self.energy += match slots {
            None => {
                let local = self.buffers.results(2 * kind);
                gradient_kind(terms, st, free, rollers, out, local)
            }
            Some(s) => {
                let local = self.buffers.results::<Vec<HD<N>>>(2 * kind + 1);
                local.resize_with(2, Vec::new);
                let (a, b) = local.split_at_mut(1);
                let kind = (terms, &s.0[kind][..]);
                hessian_kind(kind, st, free, rollers, out, (&mut a[0], &mut b[0]))
            }
        };
    }
}

/// Terms are differentiated in parallel blocks; each block's local results are scattered
/// serially, which keeps the sum deterministic.
const BLOCK: usize = 1024;

/// Evaluates `eval` on every term of `block` into `local`, in parallel for large blocks.
fn evaluate<E: Sync, R: Send>(
    block: &[E],
    local: &mut Vec<R>,
    eval: impl Fn(&E) -> R + Sync + Send,
) {
    if block.len() > 64 {
        block.par_iter().map(eval).collect_into_vec(local);
    } else {
        local.clear();
        local.extend(block.iter().map(eval));
    }
}

/// Adds a term's gradient over its variables `v` to the free gradient (`g`, projected at slanted
/// rollers) and, if wanted, to the full gradient (`full`, as it is: reactions need the normal
/// parts).
fn scatter_gradient<const N: usize>(
    v: &[usize; N],
    g: &[f64; N],
    full: &[f64; N],
    free: &[u32],
    out: &mut Assembly,
) {
    for i in 0..N {
        let f = free[v[i]];
        if f != FIXED {
            out.grad[f as usize] += g[i];
        }
    }
    if let Some(fg) = out.full_grad.as_deref_mut() {
        for i in 0..N {
            fg[v[i]] += full[i];
        }
    }
}

fn gradient_kind<const N: usize, E: Term<N>>(
    terms: &[E],
    st: &State,
    free: &[u32],
    rollers: Option<&Rollers>,
    out: &mut Assembly,
    local: &mut Vec<D1<N>>,
) -> f64 {
    let mut energy = 0.0;
    for block in terms.chunks(BLOCK) {
        evaluate(block, local, |t: &E| {
            let x = D1::<N>::vars(&t.gather(&st.q));
            t.eval(st, &x)
        });
        for (t, r) in block.iter().zip(local.iter()) {
            energy += r.v;
            let v = t.vars();
            match rollers.filter(|p| p.touches(v)) {
                Some(p) => scatter_gradient(v, &p.project_gradient(v, r), &r.g, free, out),
                None => scatter_gradient(v, &r.g, &r.g, free, out),
            }
        }
    }
    energy
}

/// The Hessian of one term kind (`slots`: its part of the slot map). Each block's scatter
/// runs beside the next block's derivatives (`rayon::join`; `cur` and `next` hold the two
/// blocks' results): the scatter is serial, to keep every sum in one order, and on two threads
/// it would otherwise leave one idle.
fn hessian_kind<const N: usize, E: Term<N>>(
    (terms, slots): (&[E], &[u32]),
    st: &State,
    free: &[u32],
    rollers: Option<&Rollers>,
    out: &mut Assembly,
    (mut cur, mut next): (&mut Vec<HD<N>>, &mut Vec<HD<N>>),
) -> f64 {
    let np = N * (N + 1) / 2;
    let eval = |t: &E| t.derivatives(st, &t.gather(&st.q));
    let mut blocks = terms.chunks(BLOCK).enumerate().peekable();
    if let Some(&(_, first)) = blocks.peek() {
        evaluate(first, cur, eval);
    }
    let mut energy = 0.0;
    while let Some((b, block)) = blocks.next() {
        let following = blocks.peek().map(|&(_, f)| f);
        let s = &slots[b * BLOCK * np..(b * BLOCK + block.len()) * np];
        let local = &*cur;
        let energy = &mut energy;
        let mut scatter = || scatter_hessian(block, local, s, free, rollers, (out, energy));
        match following {
            Some(f) => {
                rayon::join(scatter, || evaluate(f, next, eval));
            }
            None => scatter(),
        }
        std::mem::swap(&mut cur, &mut next);
    }
    energy
}

/// Adds one block's energies, gradients and Hessians (`local`, in the order of `block`) to the
/// output.
fn scatter_hessian<const N: usize, E: Term<N>>(
    block: &[E],
    local: &[HD<N>],
    slots: &[u32],
    free: &[u32],
    rollers: Option<&Rollers>,
    (out, energy): (&mut Assembly, &mut f64),
) {
    let np = N * (N + 1) / 2;
    for (k, (t, full)) in block.iter().zip(local).enumerate() {
        *energy += full.v;
        let v = t.vars();
        let projected = rollers.filter(|p| p.touches(v)).map(|p| p.project(v, full));
        let r = projected.as_ref().unwrap_or(full);
        scatter_gradient(v, &r.g, &full.g, free, out);
        let h = &mut out.hess.as_mut().expect("Hessian output").values;
        let s = &slots[k * np..(k + 1) * np];
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
