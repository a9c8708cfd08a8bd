//! The memory and work a scene will take, estimated before the solve allocates it, so that a
//! small input asking for more than the machine has is refused with a located message instead
//! of aborting in the allocator (docs/performance.md, "Memory", compares these estimates with
//! measured peaks).
//!
//! Two stages: [`lower_bound`] from the scene's sizes alone, before anything is built (the
//! model and the Hessian's pattern grow with the nodes whatever the ordering does), and
//! [`estimate`] from the built network, with the factor's non-zeros counted exactly by the
//! symbolic analysis the solver will run.

use super::model::{Model, FIXED};
use super::Network;
use crate::energy::registry::TermVisitor;
use crate::energy::Term;
use crate::scene::types::Scene;
use crate::scene::FieldError;
use crate::solver::linalg::{factor_cost, FactorCost};
use crate::solver::Ordering;

/// Resident bytes of the process before the scene: binary, allocator, thread pool.
const BASE_BYTES: u64 = 8 << 20;
/// Bytes per node that solving a network takes at least: measured 9–11 KB per node on
/// chains, the cheapest networks (docs/performance.md); [`lower_bound`] takes half of it.
pub const MIN_BYTES_PER_NODE: u64 = 8_000;
/// Vectors of the unknowns' length the Newton iteration, its line search and the results keep
/// (gradients, steps, scales, weights, snapshots).
const VECTORS_PER_UNKNOWN: u64 = 24;
/// Bytes per node of the equilibrium and results (positions, forces, stresses, JSON text).
const RESULT_BYTES_PER_NODE: u64 = 600;

/// How a refusal's message begins (commands that generate their scene rephrase it).
pub const REFUSAL: &str = "the scene is too large for the memory limit";

/// What solving a network will take.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Estimate {
    pub nodes: usize,
    pub factor: FactorCost,
    /// Energy terms, state and layout.
    pub model_bytes: u64,
    /// Estimated peak resident bytes of the whole solve.
    pub bytes: u64,
}

impl Estimate {
    /// One line for messages: sizes, the factor's fill and the peak.
    pub fn describe(&self) -> String {
        let f = &self.factor;
        if f.bytes == u64::MAX {
            // The symbolic analysis failed: no size can be given, and none is made up.
            return format!(
                "{} nodes, {} unknowns, {} Hessian non-zeros: the symbolic analysis of its \
                 Cholesky factor failed (its indices or its memory overflow), so no solve of \
                 this size can run",
                self.nodes, f.unknowns, f.hessian_nnz
            );
        }
        format!(
            "{} nodes, {} unknowns, {} Hessian non-zeros, {} non-zeros in the Cholesky factor \
             ({}, {:.1e} flops per factorization): about {} resident{}",
            self.nodes,
            f.unknowns,
            f.hessian_nnz,
            f.factor_nnz,
            match f.ordering {
                Ordering::NestedDissection => "nested dissection",
                _ => "AMD",
            },
            f.flops,
            bytes_text(self.bytes),
            if f.other_factor_nnz > 0 {
                format!(" (the other ordering: {} non-zeros)", f.other_factor_nnz)
            } else {
                String::new()
            }
        )
    }
}

/// Bytes in binary units for messages ("1.5 GiB").
pub fn bytes_text(b: u64) -> String {
    if b == u64::MAX {
        // A saturated count: a number would pretend to know it.
        return "more than 16 EiB".into();
    }
    const UNITS: [&str; 7] = ["B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"];
    let mut v = b as f64;
    let mut u = 0;
    while v >= 1024.0 && u + 1 < UNITS.len() {
        v /= 1024.0;
        u += 1;
    }
    if u == 0 {
        format!("{b} B")
    } else {
        format!("{v:.1} {}", UNITS[u])
    }
}

/// Nodes of a validated scene (each rod's segments times `subdivide`, plus its end node).
pub fn scene_nodes(scene: &Scene) -> usize {
    scene
        .rods
        .iter()
        .map(|r| {
            let segments = r.points.len().saturating_sub(usize::from(!r.closed));
            segments
                .saturating_mul(r.subdivide)
                .saturating_add(usize::from(!r.closed))
        })
        .fold(0, usize::saturating_add)
}

/// Bytes that solving the scene takes at least, from its nodes alone.
pub fn lower_bound(scene: &Scene) -> u64 {
    BASE_BYTES + (scene_nodes(scene) as u64).saturating_mul(MIN_BYTES_PER_NODE / 2)
}

/// Heap bytes of the model's terms and of the Hessian slot map the solve builds from them.
fn term_bytes(m: &Model) -> (u64, u64) {
    struct Sizes(u64, u64);
    impl TermVisitor for Sizes {
        fn visit<const N: usize, E: Term<N>>(&mut self, _: usize, terms: &[E]) {
            self.0 += std::mem::size_of_val(terms) as u64;
            self.1 += (4 * terms.len() * N * (N + 1) / 2) as u64;
        }
    }
    let mut s = Sizes(0, 0);
    m.terms.visit(&mut s);
    (s.0, s.1)
}

/// The estimate for solving `net` with `ordering` (symbolic analyses included: linear in the
/// network's size, and what the solver runs first anyway).
pub fn estimate(net: &Network, ordering: Ordering) -> Estimate {
    let m = &net.model;
    let pairs = m.hessian_pattern();
    let factor = factor_cost(
        m.n_free,
        &pairs,
        || Some(m.unknown_positions()),
        ordering,
        &m.analyses,
    );
    drop(pairs);
    let (terms, slots) = term_bytes(m);
    let vars = m.state.q.len() as u64;
    let nodes = net.n_nodes();
    let model_bytes = terms + 8 * vars * 8;
    let n = factor.unknowns as u64;
    // While the solve runs: the model, the pattern's pairs (kept for the solve), the slot map,
    // the factorization objects, and the Newton vectors; then the results.
    let bytes = BASE_BYTES
        .saturating_add(model_bytes)
        .saturating_add(16 * factor.pairs as u64 + slots)
        .saturating_add(factor.bytes)
        .saturating_add(8 * VECTORS_PER_UNKNOWN * n)
        .saturating_add(RESULT_BYTES_PER_NODE * nodes as u64);
    Estimate {
        nodes,
        factor,
        model_bytes,
        bytes,
    }
}

/// The field that drives a scene's size, to name in a refusal: the `subdivide` of the rod with
/// the most nodes (or its `points` where it is not subdivided).
pub fn driving_field(scene: &Scene) -> (usize, &'static str) {
    let (i, r) = scene
        .rods
        .iter()
        .enumerate()
        .max_by_key(|(_, r)| r.points.len().saturating_mul(r.subdivide))
        .expect("a validated scene has rods");
    (
        i,
        if r.subdivide > 1 {
            "subdivide"
        } else {
            "points"
        },
    )
}

/// The refusal of a scene whose estimate (or lower bound) is above `limit` bytes.
pub fn refusal(scene: &Scene, what: &str, limit: u64) -> FieldError {
    let (i, field) = driving_field(scene);
    FieldError::new(
        "rods",
        i,
        field,
        format!(
            "{REFUSAL}: {what}, above --max-memory {} \
             (this rod has the most nodes; reduce its `{field}`, or raise --max-memory)",
            bytes_text(limit)
        ),
    )
}

/// Checks a scene against `limit` bytes before building it (from its sizes).
pub fn check_scene(scene: &Scene, limit: u64) -> Result<(), FieldError> {
    let low = lower_bound(scene);
    if low > limit {
        let what = format!(
            "{} nodes need at least {}",
            scene_nodes(scene),
            bytes_text(low)
        );
        return Err(refusal(scene, &what, limit));
    }
    Ok(())
}

/// Checks a built network against `limit` bytes before solving it.
pub fn check_network(
    scene: &Scene,
    net: &Network,
    limit: u64,
    ordering: Ordering,
) -> Result<Estimate, FieldError> {
    let e = estimate(net, ordering);
    // How docs/performance.md compares the estimate with measured peaks.
    if std::env::var_os("RODNET_ESTIMATE").is_some() {
        eprintln!("estimate: {}", e.describe());
    }
    if e.bytes > limit {
        return Err(refusal(scene, &e.describe(), limit));
    }
    check_slot_range(scene, e.factor.hessian_nnz)?;
    Ok(e)
}

/// Refuses a Hessian with more non-zeros than the slot map's 32-bit indices hold
/// (`assembly::HessianSlots`, [`FIXED`] reserved): they would wrap silently, whatever memory
/// the machine allows.
fn check_slot_range(scene: &Scene, hessian_nnz: usize) -> Result<(), FieldError> {
    if hessian_nnz < FIXED as usize {
        return Ok(());
    }
    let (i, field) = driving_field(scene);
    Err(FieldError::new(
        "rods",
        i,
        field,
        format!(
            "the scene is too large for rodnet: {hessian_nnz} Hessian non-zeros, its slot map \
             indexes fewer than {FIXED} (this rod has the most nodes; reduce its `{field}`)"
        ),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A failed symbolic analysis (saturated to u64::MAX bytes) is described as such, never as
    /// "16777216 TiB"; large counts take EiB.
    #[test]
    fn a_saturated_estimate_is_not_printed_as_a_size() {
        assert_eq!(bytes_text(u64::MAX), "more than 16 EiB");
        assert_eq!(bytes_text(3 << 60), "3.0 EiB");
        assert_eq!(bytes_text(1536), "1.5 KiB");
        let e = Estimate {
            nodes: 2_000_000,
            factor: FactorCost {
                unknowns: 8_000_000,
                pairs: 90_000_000,
                hessian_nnz: 90_000_000,
                factor_nnz: usize::MAX,
                flops: f64::INFINITY,
                bytes: u64::MAX,
                other_factor_nnz: 0,
                ordering: Ordering::Auto,
            },
            model_bytes: 0,
            bytes: u64::MAX,
        };
        let text = e.describe();
        assert!(
            text.contains("symbolic analysis") && !text.contains("TiB"),
            "{text}"
        );
        let scene =
            crate::scene::parse("c.ron", include_str!("../../networks/cantilever.ron")).unwrap();
        let refusal = format!("{:?}", refusal(&scene, &text, 4 << 30));
        assert!(!refusal.contains("16777216"), "{refusal}");
    }

    /// A Hessian past the slot map's indices is refused at the rod that drives the size, one
    /// below them is not.
    #[test]
    fn a_hessian_past_the_slot_indices_is_refused() {
        let text = include_str!("../../networks/extreme/nitinol_cross.ron");
        let scene = crate::scene::parse("nitinol_cross.ron", text).unwrap();
        assert!(check_slot_range(&scene, FIXED as usize - 1).is_ok());
        let e = check_slot_range(&scene, FIXED as usize).unwrap_err();
        let text = format!("{e:?}");
        assert!(
            text.contains("slot map") && text.contains("subdivide"),
            "{text}"
        );
    }
}
