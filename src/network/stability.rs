//! Stability of a solved network (`rodnet solve --modes K`) and its linear buckling factors
//! (`rodnet buckle`), in SI units, with mode shapes as displaced copies of the rods.
//!
//! Eigenvalues are those of H u = λ M u over the free unknowns, M = diag(1 for coordinates,
//! ē² for edge angles), ē the mean rest edge length: a mode's stiffness in N/m against a unit
//! motion, an edge's turn θ counted as the motion ē·θ of its end. The solver's own metric is
//! W = M/ē², so λ_M = λ_W/ē².

use std::time::Instant;

use crate::math::vec::{norm, sub};
use crate::network::problem::NetworkProblem;
use crate::network::zero_stiffness::mean_edge;
use crate::network::Network;
use crate::solver::spectrum::{self, Spectrum};
use crate::solver::Ordering;

/// Rods of a displaced structure: (rod name, points, closed).
pub type Shape = Vec<(String, Vec<[f64; 3]>, bool)>;

/// What the lowest modes say about the state.
#[derive(Debug, Clone)]
pub struct Stability {
    /// No negative eigenvalue and no zero one but the gauge's.
    pub stable: bool,
    /// The lowest eigenvalues, N/m, ascending.
    pub eigenvalues: Vec<f64>,
    /// Negative eigenvalues among them (a lower bound when all are negative:
    /// `negative_at_least`).
    pub negative: usize,
    pub negative_at_least: bool,
    /// Zero eigenvalues (not resolved from zero and negligible against the structure's
    /// softest physical stiffness, `zero_stiffness`) and what they are.
    pub zero_modes: usize,
    pub zero_kind: Option<String>,
    /// Largest relative residual of the eigenpairs, subspace rounds, seconds.
    pub residual: f64,
    pub rounds: usize,
    /// The eigenvalues settled within the iteration limit.
    pub converged: bool,
    pub seconds: f64,
    /// Mode shapes, W-normalized, over the free unknowns (for `--modes-obj`).
    pub modes: Vec<Vec<f64>>,
}

/// The lowest `k` eigenmodes of the network at its current state.
pub fn analyse(net: &mut Network, k: usize) -> Result<Stability, String> {
    analyse_problem(&mut NetworkProblem::of_network(net), k)
}

/// [`analyse`] of a network already lent to the solver (a push's held network, step by step).
pub fn analyse_problem(p: &mut NetworkProblem, k: usize) -> Result<Stability, String> {
    let t0 = Instant::now();
    let ebar = mean_edge(p.model);
    let analyses = p.model.analyses.clone();
    let sp = spectrum::lowest_modes(p, k, Ordering::Auto, &analyses)?;
    let zero: Vec<Vec<f64>> = zero_vectors(&sp);
    let gauge = !zero.is_empty() && crate::solver::problem::Gauge::gauge_only(p, &zero);
    let negative = (0..sp.values.len())
        .filter(|&i| sp.values[i] < 0.0 && !sp.is_zero(i))
        .count();
    let zero_kind = (!zero.is_empty()).then(|| {
        if gauge {
            "gauge: rigid turns of an unsupported structure".to_string()
        } else {
            "neutral: motions that cost no energy (a mechanism the loads leave alone)".to_string()
        }
    });
    Ok(Stability {
        stable: negative == 0 && (zero.is_empty() || gauge),
        eigenvalues: sp.values.iter().map(|l| l / (ebar * ebar)).collect(),
        negative,
        negative_at_least: negative > 0 && negative == sp.values.len(),
        zero_modes: zero.len(),
        zero_kind,
        residual: sp.residual,
        rounds: sp.rounds,
        converged: sp.converged,
        seconds: t0.elapsed().as_secs_f64(),
        modes: sp.vectors,
    })
}

fn zero_vectors(sp: &Spectrum) -> Vec<Vec<f64>> {
    (0..sp.values.len())
        .filter(|&i| sp.is_zero(i))
        .map(|i| sp.vectors[i].clone())
        .collect()
}

/// Linear buckling about the network's start.
#[derive(Debug, Clone)]
pub struct LinearBuckling {
    /// The factors by which the scene's loads (and prescribed motions) can be multiplied before
    /// the structure buckles, ascending.
    pub factors: Vec<f64>,
    pub modes: Vec<Vec<f64>>,
    pub rounds: usize,
    pub converged: bool,
    pub seconds: f64,
}

/// The `k` smallest positive critical load factors of the network about its rest state.
pub fn buckling(net: &mut Network, k: usize) -> Result<LinearBuckling, String> {
    let t0 = Instant::now();
    let mut p = NetworkProblem::of_network(net);
    let analyses = p.model.analyses.clone();
    let b = spectrum::linear_buckling(&mut p, k, Ordering::Auto, &analyses)?;
    Ok(LinearBuckling {
        factors: b.factors,
        modes: b.modes,
        rounds: b.rounds,
        converged: b.converged,
        seconds: t0.elapsed().as_secs_f64(),
    })
}

/// Each rod's points displaced along `mode` so that the largest node motion is `fraction` of
/// the structure's bounding-box diagonal, the largest motion pointing along +x, +y or +z.
pub fn mode_shape(net: &Network, mode: &[f64], fraction: f64) -> Shape {
    let m = &net.model;
    let u = m.unknowns();
    let motion = |n: usize| -> [f64; 3] {
        std::array::from_fn(|k| u.of_node(n, k).map_or(0.0, |f| mode[f]))
    };
    let nodes = 0..m.layout.n_nodes();
    let largest = nodes
        .clone()
        .map(&motion)
        .max_by(|a, b| norm(*a).total_cmp(&norm(*b)))
        .unwrap_or([0.0; 3]);
    let size = norm(largest);
    if size == 0.0 {
        return rods_at(net, |n| m.world_position(n));
    }
    let (lo, hi) = nodes.fold(
        ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]),
        |(lo, hi), n| {
            let x = m.position(n);
            (
                std::array::from_fn(|k| lo[k].min(x[k])),
                std::array::from_fn(|k| hi[k].max(x[k])),
            )
        },
    );
    let diagonal = norm(sub(hi, lo)).max(mean_edge(&net.model));
    let dominant = largest
        .iter()
        .copied()
        .max_by(|a, b| a.abs().total_cmp(&b.abs()))
        .unwrap_or(1.0);
    let a = fraction * diagonal / size * dominant.signum();
    rods_at(net, |n| {
        let (x, d) = (m.world_position(n), motion(n));
        std::array::from_fn(|k| x[k] + a * d[k])
    })
}

/// Each rod's points at the network's current state.
pub fn rods_now(net: &Network) -> Shape {
    rods_at(net, |n| net.model.world_position(n))
}

fn rods_at(net: &Network, at: impl Fn(usize) -> [f64; 3]) -> Shape {
    net.rods
        .iter()
        .map(|r| {
            (
                r.name.clone(),
                r.nodes.iter().map(|&n| at(n)).collect(),
                r.closed,
            )
        })
        .collect()
}
