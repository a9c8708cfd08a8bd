//! Rollers with a general normal (a node on a slanted plane, or on the line where two planes
//! meet): the node keeps its three coordinates as unknowns, and the constraint is kept exactly by
//! projection instead of elimination. With U the orthonormal normals of the node's planes and
//! P = I − UUᵀ, every term's gradient and Hessian at the node is projected (g → Pg, H → PHP), a
//! normal stiffness s·UUᵀ is added by a spring to the plane (zero force on the plane), and every
//! state the solver makes is put back on the planes. Newton steps then have no normal component
//! (UᵀΔx = 0 exactly: the normal rows read s·UᵀΔx = −UᵀPg = 0), so the iteration is Newton's
//! on the constrained manifold, in world coordinates that every other part of the solver keeps
//! reading. Axis-aligned rollers are eliminated instead (`network/build/supports.rs`).

use crate::energy::registry::Terms;
use crate::energy::spring::Spring;
use crate::math::vec::{any_perpendicular, cross, dot, normalize, scalef, sub};
use crate::math::{D1, HD};

/// Marks variables that belong to no slanted roller.
const NONE: u32 = u32::MAX;

/// One node held on one or two planes.
#[derive(Debug, Clone)]
pub struct SlantedRoller {
    pub node: usize,
    /// The node's variables (x, y, z).
    pub vars: [usize; 3],
    /// Orthonormal normals of its planes (one or two).
    pub normals: Vec<[f64; 3]>,
    /// A point of the planes at load factor 0 and 1 (the rest position, the `move_to`).
    pub through: [[f64; 3]; 2],
    /// P = I − UUᵀ.
    pub projector: [[f64; 3]; 3],
}

impl SlantedRoller {
    pub fn new(
        node: usize,
        vars: [usize; 3],
        normals: Vec<[f64; 3]>,
        through: [[f64; 3]; 2],
    ) -> Self {
        let projector = std::array::from_fn(|i| {
            std::array::from_fn(|j| {
                let id = if i == j { 1.0 } else { 0.0 };
                id - normals.iter().map(|n| n[i] * n[j]).sum::<f64>()
            })
        });
        SlantedRoller {
            node,
            vars,
            normals,
            through,
            projector,
        }
    }

    fn point_at(&self, lambda: f64) -> [f64; 3] {
        let [a, b] = self.through;
        std::array::from_fn(|k| a[k] + lambda * (b[k] - a[k]))
    }

    /// The component of `v` along the planes' normals, U Uᵀ v.
    pub fn normal_part(&self, v: [f64; 3]) -> [f64; 3] {
        let mut out = [0.0; 3];
        for n in &self.normals {
            let d = n[0] * v[0] + n[1] * v[1] + n[2] * v[2];
            for k in 0..3 {
                out[k] += d * n[k];
            }
        }
        out
    }
}

/// The slanted rollers of a model and, per variable, which one holds it.
#[derive(Debug, Clone, Default)]
pub struct Rollers {
    pub list: Vec<SlantedRoller>,
    of_var: Vec<u32>,
}

impl Rollers {
    pub fn new(list: Vec<SlantedRoller>, n_vars: usize) -> Self {
        let mut of_var = Vec::new();
        if !list.is_empty() {
            of_var = vec![NONE; n_vars];
            for (i, r) in list.iter().enumerate() {
                for v in r.vars {
                    of_var[v] = i as u32;
                }
            }
        }
        Rollers { list, of_var }
    }

    pub fn is_empty(&self) -> bool {
        self.list.is_empty()
    }

    /// Puts every held node back on its planes at load factor `lambda`: x ← x − UUᵀ(x − p).
    pub fn snap(&self, q: &mut [f64], lambda: f64) {
        for r in &self.list {
            let p = r.point_at(lambda);
            let x: [f64; 3] = std::array::from_fn(|k| q[r.vars[k]]);
            let off = r.normal_part(std::array::from_fn(|k| x[k] - p[k]));
            for k in 0..3 {
                q[r.vars[k]] = x[k] - off[k];
            }
        }
    }

    /// Whether the planes move with the load factor.
    pub fn planes_move(&self) -> bool {
        self.list.iter().any(|r| {
            let d: [f64; 3] = std::array::from_fn(|k| r.through[1][k] - r.through[0][k]);
            r.normal_part(d) != [0.0; 3]
        })
    }

    /// The first local index of each held node among a term's variables, with its roller.
    fn blocks<const N: usize>(&self, v: &[usize; N]) -> Vec<(usize, &SlantedRoller)> {
        (0..N)
            .filter_map(|i| {
                let r = self.of_var[v[i]];
                (r != NONE && self.list[r as usize].vars[0] == v[i]).then(|| {
                    debug_assert!(i + 2 < N && v[i + 1] == v[i] + 1 && v[i + 2] == v[i] + 2);
                    (i, &self.list[r as usize])
                })
            })
            .collect()
    }

    /// Whether a term with variables `v` touches a held node.
    pub fn touches<const N: usize>(&self, v: &[usize; N]) -> bool {
        !self.of_var.is_empty() && v.iter().any(|&x| self.of_var[x] != NONE)
    }

    /// A term's gradient with the held nodes' rows projected.
    pub fn project_gradient<const N: usize>(&self, v: &[usize; N], d: &D1<N>) -> [f64; N] {
        let mut g = d.g;
        for (i, r) in self.blocks(v) {
            let pg = apply(&r.projector, [g[i], g[i + 1], g[i + 2]]);
            g[i..i + 3].copy_from_slice(&pg);
        }
        g
    }

    /// A term's gradient and Hessian with the held nodes' rows and columns projected.
    pub fn project<const N: usize>(&self, v: &[usize; N], d: &HD<N>) -> HD<N> {
        // The hyper-duals keep the upper triangle only; projecting rows and columns needs both.
        let mut out = *d;
        out.h = d.hessian();
        for (i, r) in self.blocks(v) {
            let p = &r.projector;
            let pg = apply(p, [out.g[i], out.g[i + 1], out.g[i + 2]]);
            out.g[i..i + 3].copy_from_slice(&pg);
            for j in 0..N {
                let col = apply(p, [out.h[i][j], out.h[i + 1][j], out.h[i + 2][j]]);
                for k in 0..3 {
                    out.h[i + k][j] = col[k];
                }
            }
            for row in out.h.iter_mut() {
                let r3 = apply(p, [row[i], row[i + 1], row[i + 2]]);
                row[i..i + 3].copy_from_slice(&r3);
            }
        }
        out
    }
}

fn apply(p: &[[f64; 3]; 3], x: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| p[i][0] * x[0] + p[i][1] * x[1] + p[i][2] * x[2])
}

/// Orthonormal directions spanning `normals` (Gram–Schmidt), dropping those the earlier ones
/// already span: parallel normals through one node are one plane.
pub fn orthonormal(normals: &[[f64; 3]]) -> Vec<[f64; 3]> {
    let mut basis: Vec<[f64; 3]> = Vec::new();
    for n in normals {
        let mut u = normalize(*n);
        for b in &basis {
            u = sub(u, scalef(*b, dot(u, *b)));
        }
        if dot(u, u) > 1e-12 && basis.len() < 3 {
            basis.push(normalize(u));
        }
    }
    basis
}

/// The stiffness that holds slanted planes: the network's stiffest edge, EA/l (N/m). Stiff
/// enough that the held directions never show among the lowest modes, no stiffer, so that the
/// factorization's conditioning does not change.
pub fn holding_stiffness(terms: &Terms) -> f64 {
    terms
        .stretch
        .iter()
        .map(|s| s.ea / s.rest_length)
        .fold(0.0, f64::max)
}

/// The spring along a roller's normals (one or two; three hold the node entirely) that gives
/// the projected Hessian back its stiffness there; it pulls nothing on the planes.
pub fn holding_spring(r: &SlantedRoller, stiffness: f64) -> Spring {
    let u = &r.normals;
    let a = u[0];
    let b = u
        .get(1)
        .copied()
        .unwrap_or_else(|| normalize(any_perpendicular(a)));
    let k = |i: usize| if u.len() > i { stiffness } else { 0.0 };
    Spring {
        vars: r.vars,
        stiffness: [k(0), k(1), k(2)],
        axes: [a, b, cross(a, b)],
        anchor: r.through,
    }
}
