//! Frictionless contact with rigid obstacles and simple bounds on node coordinates, as inequality
//! constraints c(x) ≥ 0 on the free nodes (see docs/design.md, "Constraints").
//!
//! Contact is node-based: each free rod node keeps its centreline at least the rod's outer radius
//! away from each obstacle, so the rod's surface touches, not its centreline. Every gap function
//! below is convex in the node position (distance to a half-space, to a ball, to an infinite
//! cylinder; a coordinate), which is what makes the solver's linearized constraints safe: a step
//! that satisfies c(x) + ∇c·d ≥ 0 also satisfies c(x + αd) ≥ (1 − α)c(x) for α ∈ [0, 1].

use crate::math::vec::{dot, norm, scalef, sub};
use crate::network::info::RodInfo;
use crate::network::roller::SlantedRoller;
use crate::scene::types::{Obstacle, Scene};
use crate::scene::FieldError;
use crate::variables::{DofLayout, Unknowns};

/// An obstacle with unit directions.
#[derive(Debug, Clone, Copy)]
pub enum Shape {
    Plane {
        point: [f64; 3],
        normal: [f64; 3],
    },
    Sphere {
        center: [f64; 3],
        radius: f64,
    },
    Cylinder {
        point: [f64; 3],
        axis: [f64; 3],
        radius: f64,
    },
}

impl Shape {
    fn of(o: &Obstacle) -> Shape {
        let unit = |v: [f64; 3]| scalef(v, 1.0 / norm(v));
        match *o {
            Obstacle::Plane { point, normal } => Shape::Plane {
                point,
                normal: unit(normal),
            },
            Obstacle::Sphere { center, radius } => Shape::Sphere { center, radius },
            Obstacle::Cylinder {
                point,
                axis,
                radius,
            } => Shape::Cylinder {
                point,
                axis: unit(axis),
                radius,
            },
        }
    }

    /// Signed distance from `x` to the surface offset by `clearance`, and its (unit) gradient.
    fn gap(&self, x: [f64; 3], clearance: f64) -> (f64, [f64; 3]) {
        // At the centre of a ball or on a cylinder's axis the gradient is undefined; any unit
        // vector is a valid subgradient there, and such a node is deep inside anyway.
        let radial = |v: [f64; 3], r: f64| {
            let l = norm(v);
            if l > 0.0 {
                (l - r - clearance, scalef(v, 1.0 / l))
            } else {
                (-r - clearance, [0.0, 0.0, 1.0])
            }
        };
        match *self {
            Shape::Plane { point, normal } => (dot(normal, sub(x, point)) - clearance, normal),
            Shape::Sphere { center, radius } => radial(sub(x, center), radius),
            Shape::Cylinder {
                point,
                axis,
                radius,
            } => {
                let u = sub(x, point);
                radial(sub(u, scalef(axis, dot(u, axis))), radius)
            }
        }
    }
}

/// What a constraint row comes from, for results.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Source {
    Obstacle(usize),
    Bound(usize),
}

#[derive(Debug, Clone, Copy)]
enum Kind {
    /// Gap to shape `shape` minus the node's outer radius.
    Surface { shape: usize, clearance: f64 },
    /// x[axis] ≥ value.
    Lower { axis: usize, value: f64 },
    /// x[axis] ≤ value.
    Upper { axis: usize, value: f64 },
}

/// One inequality c(x_node) ≥ 0.
#[derive(Debug, Clone, Copy)]
pub struct Row {
    pub node: usize,
    pub source: Source,
    kind: Kind,
    /// What the node's supports leave of its motion: the free coordinates (a roller along x, y
    /// or z eliminates one), and for a slanted roller the projector P = I − UUᵀ onto its
    /// planes. The solver's unknowns move only there, so the row's Jacobian is P∇c over the free
    /// coordinates; the normal part of the contact force goes to the roller's reaction.
    held: Held,
}

#[derive(Debug, Clone, Copy)]
struct Held {
    free: [bool; 3],
    projector: Option<[[f64; 3]; 3]>,
}

#[derive(Debug, Clone)]
pub struct Contact {
    pub shapes: Vec<Shape>,
    pub rows: Vec<Row>,
    /// Length scale of the scene (m), for round-off tolerances.
    length_scale: f64,
    layout: DofLayout,
}

/// Largest penetration (relative to the length scale) that the rest shape may have; larger
/// ones are input errors, smaller ones are round-off in the scene's coordinates and are removed
/// by the first Newton step.
pub const REST_TOLERANCE: f64 = 1e-9;

impl Row {
    /// Value and gradient with respect to the node's position.
    fn eval(&self, shapes: &[Shape], x: [f64; 3]) -> (f64, [f64; 3]) {
        match self.kind {
            Kind::Surface { shape, clearance } => shapes[shape].gap(x, clearance),
            Kind::Lower { axis, value } => {
                let mut g = [0.0; 3];
                g[axis] = 1.0;
                (x[axis] - value, g)
            }
            Kind::Upper { axis, value } => {
                let mut g = [0.0; 3];
                g[axis] = -1.0;
                (value - x[axis], g)
            }
        }
    }

    /// Node coordinates the row depends on (its Jacobian's non-zeros).
    fn axes(&self) -> std::ops::Range<usize> {
        match self.kind {
            Kind::Surface { .. } => 0..3,
            Kind::Lower { axis, .. } | Kind::Upper { axis, .. } => axis..axis + 1,
        }
    }

    /// Value and gradient at positions `q`.
    pub fn at(&self, c: &Contact, q: &[f64]) -> (f64, [f64; 3]) {
        self.eval(&c.shapes, c.layout.position(q, self.node))
    }

    /// Value and Jacobian at positions `q` with respect to the node's unknowns: the gradient
    /// projected onto the node's roller planes, zero on coordinates that supports eliminate.
    pub fn linearized(&self, c: &Contact, q: &[f64]) -> (f64, [f64; 3]) {
        let (v, g) = self.at(c, q);
        let g = match self.held.projector {
            Some(p) => std::array::from_fn(|i| dot(p[i], g)),
            None => g,
        };
        (
            v,
            std::array::from_fn(|k| if self.held.free[k] { g[k] } else { 0.0 }),
        )
    }

    /// Whether no motion that the node's supports allow changes the row: a plane or bound
    /// along the normal of the node's roller. Such a row is met at rest and stays met (its
    /// roller holds the node); kept, its zero Jacobian would make the step QP's active-set
    /// system singular wherever it touches (a beam lying on a floor at its roller).
    fn is_constant(&self, shapes: &[Shape]) -> bool {
        let normal = match self.kind {
            Kind::Surface { shape, .. } => match shapes[shape] {
                Shape::Plane { normal, .. } => normal,
                Shape::Sphere { .. } | Shape::Cylinder { .. } => return false,
            },
            Kind::Lower { axis, .. } | Kind::Upper { axis, .. } => {
                std::array::from_fn(|k| f64::from(k == axis))
            }
        };
        let g = match self.held.projector {
            Some(p) => std::array::from_fn(|i| dot(p[i], normal)),
            None => normal,
        };
        (0..3).all(|k| !self.held.free[k] || g[k].abs() <= 1e-12)
    }

    /// The free node coordinates the row's Jacobian has entries for.
    fn free_axes(&self) -> impl Iterator<Item = usize> + '_ {
        self.axes().filter(|&k| self.held.free[k])
    }

    /// The row's curvature at positions `q`, for rows on curved surfaces: ∇²c = (I − nnᵀ)/d on
    /// a ball, (I − nnᵀ − aaᵀ)/d on a cylinder of axis a, with d the node's distance from the
    /// centre (axis). `(d, a)`; None where ∇²c = 0 (planes, bounds).
    pub fn curvature(&self, c: &Contact, q: &[f64]) -> Option<(f64, Option<[f64; 3]>)> {
        let Kind::Surface { shape, .. } = self.kind else {
            return None;
        };
        let x = c.layout.position(q, self.node);
        match c.shapes[shape] {
            Shape::Plane { .. } => None,
            Shape::Sphere { center, .. } => Some((norm(sub(x, center)), None)),
            Shape::Cylinder { point, axis, .. } => {
                let u = sub(x, point);
                Some((norm(sub(u, scalef(axis, dot(u, axis)))), Some(axis)))
            }
        }
    }
}

/// One surface row per obstacle and free rod node (in rod order), with the node's clearance.
fn obstacle_rows(
    obstacles: usize,
    order: &[usize],
    radius: &[f64],
    held: impl Fn(usize) -> Option<Held>,
) -> Vec<Row> {
    let mut rows = Vec::new();
    for i in 0..obstacles {
        for (n, held) in order.iter().filter_map(|&n| held(n).map(|h| (n, h))) {
            rows.push(Row {
                node: n,
                source: Source::Obstacle(i),
                kind: Kind::Surface {
                    shape: i,
                    clearance: radius[n],
                },
                held,
            });
        }
    }
    rows
}

/// One row per bound, bounded axis and free node it applies to.
fn bound_rows(
    scene: &Scene,
    rods: &[RodInfo],
    order: &[usize],
    held: impl Fn(usize) -> Option<Held>,
) -> Vec<Row> {
    let mut rows = Vec::new();
    for (i, b) in scene.bounds.iter().enumerate() {
        let rod_named = |name: &String| {
            rods.iter()
                .find(|r| &r.name == name)
                .expect("validated rod")
        };
        let mut nodes: Vec<usize> = match (&b.rod, &b.vertices) {
            (Some(name), Some(vs)) => {
                let rod = rod_named(name);
                vs.iter()
                    .map(|&v| rod.vertex_node(v).expect("validated vertex"))
                    .collect()
            }
            (Some(name), None) => rod_named(name).nodes.clone(),
            _ => order.to_vec(),
        };
        let mut seen = std::collections::HashSet::new();
        nodes.retain(|&n| held(n).is_some() && seen.insert(n));
        for axis in 0..3 {
            for &n in &nodes {
                let held = held(n).expect("retained");
                if let Some(value) = b.min[axis] {
                    rows.push(Row {
                        node: n,
                        source: Source::Bound(i),
                        kind: Kind::Lower { axis, value },
                        held,
                    });
                }
                if let Some(value) = b.max[axis] {
                    rows.push(Row {
                        node: n,
                        source: Source::Bound(i),
                        kind: Kind::Upper { axis, value },
                        held,
                    });
                }
            }
        }
    }
    rows
}

impl Contact {
    /// The constraints a scene declares, over the free nodes of the built rods; `None` when it
    /// declares none. Pinned and clamped nodes are fixed and carry no constraint; a roller's
    /// node does, in the directions its planes leave free (`slanted`: the rollers held by
    /// projection). A rest shape that violates a constraint is an input error.
    pub fn build(
        scene: &Scene,
        rods: &[RodInfo],
        (unknowns, slanted): (Unknowns, &[SlantedRoller]),
        q: &[f64],
        length_scale: f64,
    ) -> Result<Option<Contact>, FieldError> {
        if scene.obstacles.is_empty() && scene.bounds.is_empty() {
            return Ok(None);
        }
        let layout = *unknowns.layout;
        let n_nodes = layout.n_nodes();
        // A node shared by rods of different sections keeps the largest clearance.
        let mut radius = vec![0.0f64; n_nodes];
        let mut owner: Vec<Option<(usize, usize)>> = vec![None; n_nodes];
        let mut order = Vec::new();
        for (r, rod) in rods.iter().enumerate() {
            for (k, &n) in rod.nodes.iter().enumerate() {
                if owner[n].is_none() {
                    owner[n] = Some((r, k));
                    order.push(n);
                }
                radius[n] = radius[n].max(rod.stiffness.outer_radius);
            }
        }
        let held = |n: usize| {
            let free: [bool; 3] = std::array::from_fn(|k| unknowns.of_node(n, k).is_some());
            let projector = slanted.iter().find(|r| r.node == n).map(|r| r.projector);
            free.contains(&true).then_some(Held { free, projector })
        };
        let shapes: Vec<Shape> = scene.obstacles.iter().map(Shape::of).collect();
        let mut rows = obstacle_rows(shapes.len(), &order, &radius, held);
        rows.extend(bound_rows(scene, rods, &order, held));
        let contact = Contact {
            shapes,
            rows,
            length_scale,
            layout,
        };
        contact.check_rest(rods, &owner, &radius, q)?;
        let mut contact = contact;
        let shapes = std::mem::take(&mut contact.shapes);
        contact.rows.retain(|r| !r.is_constant(&shapes));
        contact.shapes = shapes;
        Ok(Some(contact))
    }

    /// A rest shape that violates a constraint beyond round-off is an input error.
    fn check_rest(
        &self,
        rods: &[RodInfo],
        owner: &[Option<(usize, usize)>],
        radius: &[f64],
        q: &[f64],
    ) -> Result<(), FieldError> {
        let (contact, layout, length_scale) = (self, self.layout, self.length_scale);
        for row in &contact.rows {
            let (c, _) = row.at(contact, q);
            if c < -REST_TOLERANCE * length_scale {
                let (r, k) = owner[row.node].expect("rod node");
                let at = format!(
                    "node {k} of rod \"{}\" at {:?}",
                    rods[r].name,
                    layout.position(q, row.node)
                );
                return Err(match (row.source, row.kind) {
                    (Source::Obstacle(i), _) => FieldError::new(
                        "obstacles",
                        i,
                        "",
                        format!(
                            "the rest shape penetrates this obstacle by {:.3e} m at {at}; rods \
                             must start outside obstacles with their surface, which is the \
                             section's outer radius ({:.3e} m) from the centreline",
                            -c, radius[row.node]
                        ),
                    ),
                    (Source::Bound(i), Kind::Lower { axis, value }) => FieldError::new(
                        "bounds",
                        i,
                        "min",
                        format!("{at} is below min[{axis}] = {value} in the rest shape"),
                    ),
                    (Source::Bound(i), Kind::Upper { axis, value }) => FieldError::new(
                        "bounds",
                        i,
                        "max",
                        format!("{at} is above max[{axis}] = {value} in the rest shape"),
                    ),
                    (Source::Bound(i), Kind::Surface { .. }) => {
                        unreachable!("bound {i} built as a surface row")
                    }
                });
            }
        }
        Ok(())
    }

    pub fn len(&self) -> usize {
        self.rows.len()
    }

    pub fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }

    /// Jacobian non-zeros as (row, free unknown), in the order [`Contact::values`] fills them.
    pub fn pattern(&self, unknowns: Unknowns) -> Vec<(usize, usize)> {
        let mut out = Vec::new();
        for (j, row) in self.rows.iter().enumerate() {
            for k in row.free_axes() {
                out.push((j, unknowns.of_node(row.node, k).expect("free coordinate")));
            }
        }
        out
    }

    /// Constraint values and Jacobian values (pattern order) at positions `q`.
    pub fn values(&self, q: &[f64], c: &mut [f64], jac: &mut [f64]) {
        let mut at = 0;
        for (j, row) in self.rows.iter().enumerate() {
            let (v, g) = row.linearized(self, q);
            c[j] = v;
            for k in row.free_axes() {
                jac[at] = g[k];
                at += 1;
            }
        }
    }

    /// Round-off allowance of a gap (m): coordinates of size X carry errors of ε·X.
    fn slack(&self, q: &[f64]) -> f64 {
        let x = self
            .rows
            .iter()
            .map(|r| norm(self.layout.position(q, r.node)))
            .fold(self.length_scale, f64::max);
        16.0 * f64::EPSILON * x
    }

    /// Whether positions `trial` keep every constraint satisfied, or no more violated than at
    /// `current` (the rest shape may violate by round-off).
    pub fn admits(&self, current: &[f64], trial: &[f64]) -> bool {
        let slack = self.slack(trial);
        self.rows.iter().all(|r| {
            let now = r.at(self, current).0;
            let then = r.at(self, trial).0;
            then >= now.min(0.0) - slack
        })
    }

    /// Moves every violating node back onto the constraint's surface (closest point, within
    /// what its supports leave free), e.g. after an extrapolated predictor. Two sweeps settle
    /// nodes with two active constraints that do not interfere (a floor and a side bound);
    /// anything else is left to the Newton steps.
    pub fn project(&self, q: &mut [f64]) {
        for _ in 0..2 {
            for r in &self.rows {
                let (c, g) = r.linearized(self, q);
                let gg = dot(g, g);
                if c < 0.0 && gg > 0.0 {
                    for (k, v) in self.layout.node(r.node).into_iter().enumerate() {
                        q[v] -= c * g[k] / gg;
                    }
                }
            }
        }
    }

    /// Limits a second-order step correction `corr` (over free unknowns) so that the curve
    /// x + αd + α²·corr satisfies every linearized constraint at α = 1 whenever x + d does. With
    /// convex gaps that keeps the whole curve feasible for α ∈ [0, 1]: the linearized gap
    /// a + αb + α²e is ≥ (1 − α)a when e ≥ 0, and concave with non-negative ends when e < 0.
    pub fn limit_correction(&self, q: &[f64], unknowns: Unknowns, d: &[f64], corr: &mut [f64]) {
        for r in &self.rows {
            let (c, g) = r.linearized(self, q);
            let gg: f64 = r.free_axes().map(|k| g[k] * g[k]).sum();
            let fi = |k: usize| unknowns.of_node(r.node, k).expect("free coordinate");
            let along = |v: &[f64]| r.free_axes().map(|k| g[k] * v[fi(k)]).sum::<f64>();
            let e = along(corr);
            let total = c + along(d) + e;
            if total < 0.0 && e < 0.0 && gg > 0.0 {
                // Remove just enough of the correction's inward part.
                let cut = (-total).min(-e) / gg;
                for k in r.free_axes() {
                    corr[fi(k)] += cut * g[k];
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The constraint gradients that the QP linearizes against central differences of the gap
    /// (step 1e-6, error O(h²)), and the gaps against their closed forms, for every shape.
    #[test]
    fn gap_gradients_match_finite_differences() {
        let shapes = [
            Shape::of(&Obstacle::Plane {
                point: [0.1, -0.2, 0.3],
                normal: [0.3, 0.4, 1.2],
            }),
            Shape::of(&Obstacle::Sphere {
                center: [0.5, 0.1, -0.4],
                radius: 0.7,
            }),
            Shape::of(&Obstacle::Cylinder {
                point: [0.0, 0.2, 0.1],
                axis: [1.0, -2.0, 0.5],
                radius: 0.3,
            }),
        ];
        let points = [
            [1.3, -0.7, 0.9],
            [0.2, 0.35, 0.4],
            [-0.6, 1.1, 0.05],
            [0.51, 0.12, 0.31],
        ];
        let h = 1e-6;
        for s in &shapes {
            for x in points {
                let (c, g) = s.gap(x, 0.01);
                for k in 0..3 {
                    let (mut xp, mut xm) = (x, x);
                    xp[k] += h;
                    xm[k] -= h;
                    let fd = (s.gap(xp, 0.01).0 - s.gap(xm, 0.01).0) / (2.0 * h);
                    assert!((fd - g[k]).abs() < 1e-8, "{s:?} at {x:?}: {fd} vs {}", g[k]);
                }
                assert!((norm(g) - 1.0).abs() < 1e-14);
                let exact = match *s {
                    Shape::Plane { point, normal } => dot(normal, sub(x, point)),
                    Shape::Sphere { center, radius } => norm(sub(x, center)) - radius,
                    Shape::Cylinder {
                        point,
                        axis,
                        radius,
                    } => {
                        let u = sub(x, point);
                        (norm(u).powi(2) - dot(u, axis).powi(2)).sqrt() - radius
                    }
                };
                assert!((c - (exact - 0.01)).abs() < 1e-14, "{s:?}: {c} vs {exact}");
            }
        }
    }
}
