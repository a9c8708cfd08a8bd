//! Linear statics of straight rods and frames: uniform torsion, and the L-frame whose tip
//! deflection couples bending and torsion.

/// Tip deflection of an L-shaped frame under a small out-of-plane tip force.
///
/// Arm 1 runs from the clamp at the origin along `x` (length `a`); a rigid corner joins it
/// to arm 2 along `y` (length `b`); the force `P` acts along `z` at the free end of arm 2.
/// Both arms have bending stiffness `EI` for out-of-plane bending and torsional stiffness
/// `GJ`.
///
/// Internal forces: arm 2 bends under `M = P η` (`η` the distance from the tip) and is not
/// twisted; arm 1 bends under `M = P ξ` (`ξ` from the corner) and carries the constant
/// torque `T = P b`. The complementary energy is
/// `U = P² b³/(6EI) + P² a³/(6EI) + P² b² a/(2GJ)`, and Castigliano's theorem gives
///
/// `δ = ∂U/∂P = P (a³ + b³)/(3 EI) + P a b² / GJ`.
///
/// Geometrically: arm 2 as a cantilever (`P b³/3EI`), the corner deflection of arm 1
/// (`P a³/3EI`), and the twist `P b a/GJ` of arm 1 rotating arm 2 rigidly (`× b`). The slope
/// of arm 1 at the corner is a rotation about `y`, along arm 2, so it moves the tip not at all.
#[must_use]
pub fn l_frame_tip_deflection(a: f64, b: f64, ei: f64, gj: f64, p: f64) -> f64 {
    p * (a.powi(3) + b.powi(3)) / (3.0 * ei) + p * a * b * b / gj
}

/// Torque needed to twist a straight rod uniformly by a total angle `phi` over length `l`:
/// `GJ φ / L` (Saint-Venant torsion, uniform twist rate `φ/L`).
#[must_use]
pub fn uniform_twist_torque(gj: f64, phi: f64, l: f64) -> f64 {
    gj * phi / l
}
