//! Eigenmodes at a solved equilibrium (`rodnet solve --modes`) and mode shapes as OBJ.

use crate::network::Network;
use crate::pipeline::Solution;

/// The lowest `k` eigenmodes at a solved equilibrium (`rodnet solve --modes K`): sets the
/// results' `stability` block and returns the analysis (for mode shapes).
pub fn analyse_modes(
    sol: &mut Solution,
    k: usize,
) -> Result<crate::network::stability::Stability, String> {
    let st = match (&sol.network.model.contact, &sol.equilibrium.constraints) {
        // The modes of the structure with its active set fixed.
        (Some(_), Some(forces)) => {
            let (mut held, _) = crate::network::active_set::hold_active(&sol.network, forces);
            crate::network::stability::analyse(&mut held, k)?
        }
        _ => crate::network::stability::analyse(&mut sol.network, k)?,
    };
    if !st.converged {
        eprintln!(
            "warning: the {k} lowest eigenvalues did not settle within {} rounds (largest \
             relative residual {:.3e}); stability.converged is false",
            st.rounds, st.residual
        );
    }
    sol.results.stability = Some((&st).into());
    Ok(st)
}

/// Mode shapes as OBJ, one object per mode, each displaced by a tenth of the structure's size.
pub fn modes_obj(network: &Network, labels: &[String], modes: &[Vec<f64>]) -> String {
    let shapes: Vec<(String, crate::network::stability::Shape)> = labels
        .iter()
        .zip(modes)
        .map(|(l, m)| {
            (
                l.clone(),
                crate::network::stability::mode_shape(network, m, MODE_AMPLITUDE),
            )
        })
        .collect();
    crate::io::stability::modes_obj("mode shapes", &shapes)
}

/// Largest node motion of a drawn mode shape, over the bounding-box diagonal.
pub const MODE_AMPLITUDE: f64 = 0.1;
