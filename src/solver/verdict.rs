//! The verdict: whether a solve's final state is an equilibrium a user may act on, and what the
//! report says when it is not (docs/design.md, "The convergence verdict").
//!
//! `converged` means the state is as accurate as the tolerance asked, or as accurate as doubles
//! allow when the tolerance asked is below the round-off floor (`stopped_at_floor`), and in
//! either case out of balance by at most `MEANINGFUL_RESIDUAL` of the force scale beyond
//! rounding, with a floor of at most `MEANINGFUL_FLOOR`.

use super::newton::{Newton, Outcome};
use super::settings::{NewtonReport, NewtonSettings};

/// The largest relative residual of a state called converged, where the residual is above the
/// round-off floor (a real imbalance, not rounding): 1e-3 of the largest load out of balance is
/// as much as a reaction may miss a hand calculation by; an explicit tolerance above it is not
/// an answer either.
pub const MEANINGFUL_RESIDUAL: f64 = 1e-3;

/// The largest round-off floor of a state called converged. Rounding the state to doubles moves
/// it by ε|x|, which is harmless for displacements, but reactions and internal forces are read
/// off its strains: a floor f leaves nodal forces of up to about f/2 × the force scale
/// unresolved (the floor is twice the largest a typical rounding pattern makes). Above 0.1 a
/// reaction may be off by 5 % of the largest load, and the states this must catch lie far
/// beyond: a 10⁵-edge cantilever (floor 0.7–1.3), a modulus of 1e19 under 1 mN (809), springs
/// of 1e60 (1e40). Tiny check loads on stiff rods, whose displacements are exact, stay well
/// inside: the hairpin of tests/stiff.rs under 1 µN (1.1e-2 at 20 edges, 2e-2 at 40, its tip
/// within Castigliano's), the small-load cantilever of tests/rod_validation.rs (1.4e-3).
pub const MEANINGFUL_FLOOR: f64 = 0.1;

/// Sets the report's verdict from the outcome that ended the solve: `(k, steps)` the load step
/// it ended in, `its` the iterations spent in that step.
pub(super) fn finish(
    st: &mut Newton,
    o: Outcome,
    (k, steps): (usize, usize),
    its: usize,
    s: &NewtonSettings,
) {
    let r = &mut st.report;
    let at = format!("load step {k}/{steps}");
    match o {
        Outcome::Converged => r.converged = true,
        Outcome::AtFloor => at_floor(r, s),
        Outcome::Budget(msg) => {
            if msg.starts_with("time limit") {
                r.stopped = Some("time limit".into());
            }
            r.message = Some(format!(
                "no convergence at {at} within its budget of {} Newton iterations \
                 ({its} used in this load step, {} in all): {msg}",
                s.max_iterations, r.iterations
            ));
        }
        Outcome::Mechanism(msg) => {
            r.message = Some(format!("mechanism: {msg}"));
            r.mechanism = Some(msg);
        }
        Outcome::Failed(msg) => {
            r.message = Some(format!(
                "no convergence at {at} ({its} Newton iterations in this load step, {} in all, \
                 tolerance {:.1e}): {msg}",
                r.iterations, s.tolerance
            ));
        }
    }
    if !s.intermediate {
        meaningful(r);
    }
}

/// Round-off stalled Newton below the floor: the state is as close to equilibrium as doubles
/// allow. Converged to the floor; when the tolerance was the user's, the report says so.
fn at_floor(r: &mut NewtonReport, s: &NewtonSettings) {
    r.stopped_at_floor = true;
    r.converged = true;
    // Past the meaningful floor `meaningful` takes the verdict back, and the tolerance reported
    // stays the one used.
    if r.residual_floor > MEANINGFUL_FLOOR {
        return;
    }
    if s.automatic_tolerance {
        r.tolerance = r.residual_floor;
    } else {
        r.message = Some(format!(
            "converged to the round-off floor: relative residual {:.3e} is above the tolerance \
             {:.1e} asked but below the floor {:.3e} that rounding the unknowns to doubles \
             causes, where round-off stalls Newton; no state in doubles is closer to \
             equilibrium",
            r.residual, s.tolerance, r.residual_floor
        ));
    }
}

/// Takes back a converged verdict whose floor is too large for its forces to mean anything
/// (`MEANINGFUL_FLOOR`), or whose residual is a real imbalance above `MEANINGFUL_RESIDUAL`.
pub fn meaningful(r: &mut NewtonReport) {
    if !r.converged {
        return;
    }
    if r.residual_floor > MEANINGFUL_FLOOR {
        r.converged = false;
        r.message = Some(format!(
            "not an answer: the round-off floor {:.3e} (relative residual {:.3e}) is above \
             {MEANINGFUL_FLOOR:.0e} of the force scale, so rounding the state to doubles alone \
             leaves forces that large unresolved; stiffnesses, subdivision or coordinates too far \
             apart for double precision (docs/design.md, \"The convergence verdict\")",
            r.residual_floor, r.residual
        ));
    } else if r.residual > MEANINGFUL_RESIDUAL.max(r.residual_floor) {
        r.converged = false;
        r.message = Some(format!(
            "not an answer: relative residual {:.3e} meets the tolerance {:.1e} but is above \
             {MEANINGFUL_RESIDUAL:.0e} of the force scale, the largest imbalance that rodnet \
             calls converged (docs/design.md, \"The convergence verdict\")",
            r.residual, r.tolerance
        ));
    }
}
