use super::{positive, MAX_MAGNITUDE};
use crate::scene::types::{Scene, Section};
use crate::scene::FieldError;

pub(super) fn materials(s: &Scene) -> Result<(), FieldError> {
    for (name, m) in &s.materials {
        let err = |f: &str, msg: String| Err(FieldError::keyed("materials", name, f, msg));
        if !positive(m.young_modulus) {
            return err(
                "young_modulus",
                format!(
                    "must be positive and finite (at most {MAX_MAGNITUDE:e}), got {:?}",
                    m.young_modulus
                ),
            );
        }
        match (m.poisson_ratio, m.shear_modulus) {
            (Some(_), Some(_)) => {
                return err(
                    "shear_modulus",
                    "give exactly one of `poisson_ratio` and `shear_modulus`, not both".into(),
                )
            }
            (None, None) => {
                return err(
                    "young_modulus",
                    "give exactly one of `poisson_ratio` and `shear_modulus`".into(),
                )
            }
            (Some(nu), None) => {
                if !(nu.is_finite() && nu > -1.0 && nu <= 0.5) {
                    return err(
                        "poisson_ratio",
                        format!("must lie in (-1, 0.5], got {nu:?}"),
                    );
                }
            }
            (None, Some(g)) => {
                if !positive(g) {
                    return err(
                        "shear_modulus",
                        format!(
                            "must be positive and finite (at most {MAX_MAGNITUDE:e}), got {g:?}"
                        ),
                    );
                }
            }
        }
        if !(m.density.is_finite() && (0.0..=MAX_MAGNITUDE).contains(&m.density)) {
            return err(
                "density",
                format!(
                    "must be non-negative and finite (at most {MAX_MAGNITUDE:e}), got {:?}",
                    m.density
                ),
            );
        }
        if let Some(y) = m.yield_strength {
            if !positive(y) {
                return err(
                    "yield_strength",
                    format!("must be positive and finite (at most {MAX_MAGNITUDE:e}), got {y:?}"),
                );
            }
        }
        let ok = match m.section {
            Section::Circle { radius } => positive(radius),
            Section::Ellipse { a, b } => positive(a) && positive(b),
            Section::Rectangle { width, height } => positive(width) && positive(height),
        };
        if !ok {
            return err(
                "section",
                format!(
                    "dimensions must be positive and finite (at most {MAX_MAGNITUDE:e}), got {:?}",
                    m.section
                ),
            );
        }
        // Rigidities go as E·r⁴: a tiny section or modulus underflows to zero stiffness.
        let k = m.section.stiffness(m.young_modulus, m.shear(), m.density);
        for (what, v) in [("EA", k.ea), ("EI1", k.ei1), ("EI2", k.ei2), ("GJ", k.gj)] {
            if !(v.is_normal() && v > 0.0 && v <= MAX_MAGNITUDE) {
                return err(
                    "section",
                    format!(
                        "with this section and modulus the rigidity {what} = {v:e} is not a \
                         usable number (it must lie between {:e} and {MAX_MAGNITUDE:e})",
                        f64::MIN_POSITIVE
                    ),
                );
            }
        }
    }
    Ok(())
}
