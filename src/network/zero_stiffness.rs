//! The stiffness scale below which a deforming mode counts as zero: a negligible share of the
//! softest bending stiffness a rod of the structure can have (the zero band of the eigen-solves
//! and the mechanism test), and the mean rest edge that turns edge angles into lengths.

use crate::math::vec::{norm, sub};

/// Fraction of the softest physical stiffness below which a deforming mode's eigenvalue that
/// residuals or round-off leave unresolved counts as zero. A rod's softest bending mode is
/// about 12 EI ē³/L⁴: three decades under EI ē³/L⁴ leave room for modes softer than one rod's
/// (a chain or coil of rods ten times longer than the structure's span: 12/10⁴), while a
/// mode that is zero only to round-off (a bifurcation point) stays zero up to 10⁻³ of it.
const NEGLIGIBLE: f64 = 1e-3;

/// An eigenvalue (J, in the solver's metric W, for a W-unit mode) negligible against the
/// softest bending stiffness a rod of the structure can have: NEGLIGIBLE · EI_min ē³ / L⁴,
/// EI_min the smallest principal bending stiffness of the rods and L the larger of the
/// longest rod and the structure's diagonal. A rod's softest bending mode w(s) has
/// λ = ∫EI w''² / ∫w² ≥ (1.875/L)⁴ EI ≈ 12 EI/L⁴ per unit length (the clamped–free one); its
/// nodes, ē apart, carry ∫w²/ē of the discrete norm and W counts lengths in units of ē, so
/// in W it is about 12 EI ē³/L⁴, falling as 1/n³ with refinement as the physical floor does.
/// Infinite without rods (no physical scale: the band's other caps apply).
pub fn zero_stiffness(m: &crate::network::Model, rods: &[crate::network::info::RodInfo]) -> f64 {
    let ei = rods
        .iter()
        .map(|r| r.stiffness.ei1.min(r.stiffness.ei2))
        .fold(f64::INFINITY, f64::min);
    let longest = rods
        .iter()
        .map(|r| r.edges.iter().map(|&e| m.rest_lengths[e]).sum::<f64>())
        .fold(0.0, f64::max);
    let (lo, hi) = (0..m.layout.n_nodes()).fold(
        ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]),
        |(lo, hi), n| {
            let x = m.position(n);
            (
                std::array::from_fn(|k| lo[k].min(x[k])),
                std::array::from_fn(|k| hi[k].max(x[k])),
            )
        },
    );
    let span = longest.max(norm(sub(hi, lo)));
    let ebar = mean_edge(m);
    let k = NEGLIGIBLE * ei * ebar.powi(3) / span.powi(4);
    if k.is_finite() && k > 0.0 {
        k
    } else {
        f64::INFINITY
    }
}

/// The mean rest edge length: the unit that turns edge angles into lengths (1 m without edges).
pub fn mean_edge(m: &crate::network::Model) -> f64 {
    match m.mean_edge() {
        l if l > 0.0 => l,
        _ => 1.0,
    }
}
