//! Energy terms. Each term is a function of a few local variables behind one interface
//! ([`Term`]): its value comes from `eval::<f64>` and its exact gradient and Hessian from
//! `eval::<HD<N>>`.

pub mod bend;
pub mod bend_twist;
pub mod bend_twist_outer;
pub mod frame_bend;
pub mod frame_bend_twist;
pub mod frame_twist;
pub mod half_stencil;
pub mod joint_rotation;
pub mod joint_translation;
pub mod point_load;
pub mod registry;
pub mod rotational_spring;
pub mod spring;
pub mod stretch;
pub mod torque;
pub mod twist;

use crate::math::{Real, HD};
use crate::variables::State;

/// Where a term's energy is reported in the results.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Category {
    Stretch,
    Bend,
    Twist,
    Joints,
    /// Elastic supports (springs to the ground).
    Supports,
    External,
}

/// A local energy term in `N` variables (indices into [`State::q`]).
pub trait Term<const N: usize>: Sync + Send {
    const CATEGORY: Category;
    /// Where the energy is reported: one category per physical term. A fused kernel
    /// ([`frame_bend_twist`]) evaluates several terms at once and reports each under its own.
    const CATEGORIES: &'static [Category] = &[Self::CATEGORY];
    fn vars(&self) -> &[usize; N];
    fn eval<T: Real>(&self, st: &State, x: &[T; N]) -> T;

    /// Exact value, gradient and Hessian at `x` (default: hyper-dual evaluation in all N
    /// variables; [`Reduced`] terms use fewer).
    fn derivatives(&self, st: &State, x: &[f64; N]) -> HD<N> {
        self.eval(st, &HD::<N>::vars(x))
    }

    fn gather(&self, q: &[f64]) -> [f64; N] {
        let v = self.vars();
        std::array::from_fn(|i| q[v[i]])
    }

    fn energy(&self, st: &State) -> f64 {
        self.eval::<f64>(st, &self.gather(&st.q))
    }

    /// Adds the energy of each of [`Term::CATEGORIES`] to `out`, in that order.
    fn energies_by_category(&self, st: &State, out: &mut [f64]) {
        out[0] += self.energy(st);
    }

    /// The global edge whose rod this term's energy belongs to (per-rod energies), if any.
    fn edge(&self) -> Option<usize> {
        None
    }

    /// Reference data to keep from an accepted iterate: `(slot, value)` to store in
    /// [`State::twist_prev`] (twist terms unwrap their reference twist against it).
    fn remembered(&self, _st: &State) -> Option<(usize, f64)> {
        None
    }

    /// For a twist term, where the 2π branch of its reference twist is not known (a restart
    /// from results, which hold angles but no branches): `(slot, reference twist)` on the branch
    /// that puts its discrete twist within half a turn of its rest value.
    fn nearest_turn(&self, _st: &State) -> Option<(usize, f64)> {
        None
    }
}

/// The reference twist `reference` (with discrete twist `twist` and rest value `rest`) moved by
/// whole turns so that the discrete twist lies within half a turn of its rest value.
pub fn nearest_turn(reference: f64, twist: f64, rest: f64) -> f64 {
    let turns = ((twist - rest) / std::f64::consts::TAU).round();
    reference - turns * std::f64::consts::TAU
}

/// A term whose N variables enter only through M ≤ N linear combinations y = A x (edge vectors
/// x_b − x_a instead of both end points): differentiating in y costs (M/N)² of differentiating
/// in x, and the exact x-derivatives follow as ∇ₓ = Aᵀ∇ᵧ, Hₓ = AᵀHᵧA.
pub trait Reduced<const N: usize, const M: usize> {
    /// Row i of A: y_i = Σ c·x_j over its (j, c) entries (c = 0 entries are padding).
    const MAP: [[(usize, f64); 2]; M];
    fn eval_reduced<T: Real>(&self, st: &State, y: &[T; M]) -> T;
}

/// y = A x.
#[inline]
pub fn reduce<T: Real, const N: usize, const M: usize>(
    map: &[[(usize, f64); 2]; M],
    x: &[T; N],
) -> [T; M] {
    std::array::from_fn(|i| {
        let mut y = T::cst(0.0);
        for &(j, c) in &map[i] {
            if c != 0.0 {
                y += x[j] * c;
            }
        }
        y
    })
}

/// Derivatives in x from derivatives in y = A x.
#[inline(always)]
pub fn expand<const N: usize, const M: usize>(map: &[[(usize, f64); 2]; M], r: &HD<M>) -> HD<N> {
    let mut out = HD::<N>::cst(r.v);
    let hy = r.hessian();
    let mut hx = [[0.0; N]; N];
    for i in 0..M {
        for &(j, c) in &map[i] {
            if c == 0.0 {
                continue;
            }
            out.g[j] += c * r.g[i];
            for k in 0..M {
                for &(l, d) in &map[k] {
                    if d != 0.0 {
                        hx[j][l] += c * d * hy[i][k];
                    }
                }
            }
        }
    }
    for i in 0..N {
        for j in i..N {
            out.h[i][j] = hx[i][j];
        }
    }
    out
}

/// Implements `eval` and `derivatives` of a [`Term`] through its [`Reduced`] form.
macro_rules! reduced_term {
    ($n:literal, $m:literal) => {
        fn eval<T: Real>(&self, st: &State, x: &[T; $n]) -> T {
            <Self as super::Reduced<$n, $m>>::eval_reduced(
                self,
                st,
                &super::reduce(&<Self as super::Reduced<$n, $m>>::MAP, x),
            )
        }
        fn derivatives(&self, st: &State, x: &[f64; $n]) -> crate::math::HD<$n> {
            let map = &<Self as super::Reduced<$n, $m>>::MAP;
            let y = super::reduce(map, x);
            let r = <Self as super::Reduced<$n, $m>>::eval_reduced(
                self,
                st,
                &crate::math::HD::<$m>::vars(&y),
            );
            super::expand(map, &r)
        }
    };
}
pub(crate) use reduced_term;

/// The [`Term`] items shared by the fused bend + twist terms (fields `bend` and `twist`, and
/// `energies` returning [bend, twist]): vars and categories, the remembered reference twist,
/// and the energy reported by category.
macro_rules! bend_twist_items {
    () => {
        /// The category of the first part; see [`Term::CATEGORIES`].
        const CATEGORY: Category = Category::Bend;
        const CATEGORIES: &'static [Category] = &[Category::Bend, Category::Twist];
        fn vars(&self) -> &[usize; 11] {
            &self.bend.vars
        }
        fn remembered(&self, st: &State) -> Option<(usize, f64)> {
            self.twist.remembered(st)
        }
        fn nearest_turn(&self, st: &State) -> Option<(usize, f64)> {
            self.twist.nearest_turn(st)
        }
        fn eval<T: Real>(&self, st: &State, x: &[T; 11]) -> T {
            let [b, t] = self.energies(st, x);
            b + t
        }
        fn energies_by_category(&self, st: &State, out: &mut [f64]) {
            let [b, t] = self.energies::<f64>(st, &self.gather(&st.q));
            out[0] += b;
            out[1] += t;
        }
    };
}
pub(crate) use bend_twist_items;

/// Map rows for "x[b..b+3] − x[a..a+3]" (edge vectors).
pub(crate) const fn diff3(a: usize, b: usize) -> [[(usize, f64); 2]; 3] {
    [
        [(b, 1.0), (a, -1.0)],
        [(b + 1, 1.0), (a + 1, -1.0)],
        [(b + 2, 1.0), (a + 2, -1.0)],
    ]
}

/// Map row for "x[j]".
pub(crate) const fn same(j: usize) -> [(usize, f64); 2] {
    [(j, 1.0), (0, 0.0)]
}
