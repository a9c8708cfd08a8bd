//! The compass construction of a Chebyshev net on a mesh, at one step h = a/m.
//!
//! Node (i, j) is the net point with parameters (i h, j h). The generators (j = 0 and i = 0)
//! are straightest curves from the origin along the two given directions, stepped with chord
//! h. Every other node closes a rhombus: it is at chord h from its two neighbours nearer the
//! generators, on the far side from the cell's fourth corner. Each quadrant is filled outward
//! from the generators. A node that cannot be placed (its cell closed below the locking angle,
//! no point of the surface at chord h, off the boundary, or a neighbour missing) records why,
//! and the rods stop before it.

use crate::math::vec::{cross, dot, norm, sub};
use crate::surface::steps::{compass_step, geodesic_step, NoStep};
use crate::surface::Surface;

/// What stands at one node of the fine grid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Node {
    At([f64; 3]),
    /// The cell closed: its angle fell below the locking angle (or the compass had no circle).
    Locked,
    /// No point of the surface at the step's distance near the expected place.
    NoRoot,
    /// The step left the surface across its boundary.
    OffSurface,
    /// A neighbour it is built from is missing.
    Missing,
}

impl Node {
    pub fn point(&self) -> Option<[f64; 3]> {
        match self {
            Node::At(p) => Some(*p),
            _ => None,
        }
    }
}

impl From<NoStep> for Node {
    fn from(e: NoStep) -> Node {
        match e {
            NoStep::Locked => Node::Locked,
            NoStep::NoRoot => Node::NoRoot,
            NoStep::OffSurface => Node::OffSurface,
        }
    }
}

/// The fine net: nodes (i, j) for i in −`reach[0]`..=`reach[1]`, j in −`reach[2]`..=`reach[3]`.
#[derive(Debug, Clone)]
pub struct FineNet {
    pub h: f64,
    /// Fine steps per net spacing.
    pub m: usize,
    /// Generator lengths in steps: −i, +i, −j, +j.
    pub reach: [usize; 4],
    nodes: Vec<Node>,
}

impl FineNet {
    fn slot(&self, i: i64, j: i64) -> Option<usize> {
        let (ii, jj) = (i + self.reach[0] as i64, j + self.reach[2] as i64);
        let (wi, wj) = self.dims();
        (ii >= 0 && jj >= 0 && (ii as usize) < wi && (jj as usize) < wj)
            .then(|| jj as usize * wi + ii as usize)
    }

    fn dims(&self) -> (usize, usize) {
        (
            self.reach[0] + self.reach[1] + 1,
            self.reach[2] + self.reach[3] + 1,
        )
    }

    /// The node (i, j); outside the grid, `Missing`.
    pub fn node(&self, i: i64, j: i64) -> Node {
        self.slot(i, j).map_or(Node::Missing, |s| self.nodes[s])
    }

    pub fn at(&self, i: i64, j: i64) -> Option<[f64; 3]> {
        self.node(i, j).point()
    }

    fn set(&mut self, i: i64, j: i64, n: Node) {
        let s = self.slot(i, j).expect("inside the grid");
        self.nodes[s] = n;
    }

    /// Nodes placed on the surface.
    pub fn placed(&self) -> usize {
        self.nodes.iter().filter(|n| n.point().is_some()).count()
    }
}

/// Where and how the net starts.
#[derive(Debug, Clone, Copy)]
pub struct Seed {
    /// On the surface.
    pub origin: [f64; 3],
    /// Unit tangents of the two generators at the origin.
    pub d1: [f64; 3],
    pub d2: [f64; 3],
    /// Cells whose angle is below this (or above π minus it) lock, rad.
    pub min_angle: f64,
}

/// Builds the net with step `a / m`, going no further than `max_steps` along each generator,
/// on a grid of at most `max_nodes` nodes: a larger grid is refused before it is allocated
/// or filled, with the number of nodes it would have had (at least).
pub fn build(
    s: &Surface,
    seed: &Seed,
    a: f64,
    m: usize,
    max_steps: usize,
    max_nodes: usize,
) -> Result<FineNet, usize> {
    let h = a / m as f64;
    // The grid's width is one more than the first generators' steps: the second pair is held
    // to what the grid allows beside them, so that no generator walks on past the limit.
    let first = max_steps.min(max_nodes);
    let g0 = generator(s, seed.origin, seed.d1, -1.0, h, first);
    let g1 = generator(s, seed.origin, seed.d1, 1.0, h, first);
    let second = max_steps.min(max_nodes / (g0.len() + g1.len() + 1));
    let g2 = generator(s, seed.origin, seed.d2, -1.0, h, second);
    let g3 = generator(s, seed.origin, seed.d2, 1.0, h, second);
    // A generator stopped by the grid's limit (not by `max_steps` or the boundary).
    let cut = |g: &Vec<[f64; 3]>, limit: usize| limit < max_steps && g.len() >= limit;
    let gens = [g0, g1, g2, g3];
    let reach = [0, 1, 2, 3].map(|k| gens[k].len());
    let (w, hgt) = (reach[0] + reach[1] + 1, reach[2] + reach[3] + 1);
    let nodes = w.saturating_mul(hgt);
    if nodes > max_nodes || cut(&gens[0], first) || cut(&gens[1], first) {
        return Err(nodes.max(max_nodes.saturating_add(1)));
    }
    if cut(&gens[2], second) || cut(&gens[3], second) {
        return Err(max_nodes.saturating_add(1));
    }
    let mut net = FineNet {
        h,
        m,
        reach,
        nodes: vec![Node::Missing; w * hgt],
    };
    net.set(0, 0, Node::At(seed.origin));
    for (k, points) in gens.iter().enumerate() {
        let sign = if k % 2 == 0 { -1 } else { 1 };
        for (t, p) in points.iter().enumerate() {
            let step = sign * (t as i64 + 1);
            let (i, j) = if k < 2 { (step, 0) } else { (0, step) };
            net.set(i, j, Node::At(*p));
        }
    }
    let cos_lock = seed.min_angle.cos();
    for (si, sj) in [(1i64, 1i64), (-1, 1), (-1, -1), (1, -1)] {
        let ni = reach[if si > 0 { 1 } else { 0 }] as i64;
        let nj = reach[if sj > 0 { 3 } else { 2 }] as i64;
        for b in 1..=nj {
            for a_ in 1..=ni {
                let (i, j) = (si * a_, sj * b);
                let node = match (net.at(i - si, j), net.at(i, j - sj), net.at(i - si, j - sj)) {
                    (Some(pa), Some(pb), Some(pp)) => match compass_step(s, pa, pb, pp, h) {
                        Ok(c) if locked(c, pa, pb, cos_lock) => Node::Locked,
                        Ok(c) => Node::At(c),
                        Err(e) => e.into(),
                    },
                    _ => Node::Missing,
                };
                net.set(i, j, node);
            }
        }
    }
    Ok(net)
}

/// The rhombus's angle at its new corner `c` is outside [θ, π − θ].
fn locked(c: [f64; 3], a: [f64; 3], b: [f64; 3], cos_lock: f64) -> bool {
    let (u, v) = (sub(a, c), sub(b, c));
    let cos = dot(u, v) / (norm(u) * norm(v));
    cos.abs() > cos_lock || norm(cross(u, v)) == 0.0
}

/// Steps a straightest curve from `origin` along `sign · d` until it leaves the surface; its
/// points, not the origin. The rods on it end by the same boundary search as every rod.
fn generator(
    s: &Surface,
    origin: [f64; 3],
    d: [f64; 3],
    sign: f64,
    h: f64,
    max_steps: usize,
) -> Vec<[f64; 3]> {
    let mut points = Vec::new();
    let mut here = origin;
    let mut dir = d.map(|x| sign * x);
    while points.len() < max_steps {
        match geodesic_step(s, here, dir, h) {
            Ok(next) => {
                dir = sub(next, here);
                here = next;
                points.push(next);
            }
            Err(_) => break,
        }
    }
    points
}
