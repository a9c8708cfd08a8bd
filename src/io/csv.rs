//! CSV exports: one row per node with position, the twist angle of the following edge, the
//! centreline curvature, and the bending strain and stress at the node's extreme fibre
//! (`--csv`); one row per edge with its internal forces (`--forces-csv`).

use std::fmt::Write;

use crate::network::equilibrium::Equilibrium;

pub fn to_csv(eq: &Equilibrium) -> String {
    let mut s = String::from("rod,index,x,y,z,twist,curvature,bending_strain,bending_stress\n");
    for rod in &eq.rods {
        let bend = &rod.bending;
        for (k, p) in rod.points.iter().enumerate() {
            let tw = rod
                .twist
                .get(k)
                .or(rod.twist.last())
                .copied()
                .unwrap_or(0.0);
            let b = bend[k];
            let _ = writeln!(
                s,
                "{},{k},{:.12e},{:.12e},{:.12e},{:.12e},{:.12e},{:.12e},{:.12e}",
                csv_field(&rod.name),
                p[0],
                p[1],
                p[2],
                tw,
                b.curvature,
                b.strain,
                b.stress
            );
        }
    }
    s
}

/// Header of [`to_forces_csv`], units after the underscore.
pub const FORCES_HEADER: &str = "rod,edge,s_m,axial_N,shear1_N,shear2_N,moment1_Nm,moment2_Nm,\
torsion_Nm,von_mises_Pa,utilization";

/// One row per edge: the arc length of its midpoint along the deformed rod, its internal forces
/// in its material frame (docs/internal-forces.md), the largest von Mises stress over its two
/// end sections and, when the material has a yield strength, the utilization (else empty).
pub fn to_forces_csv(eq: &Equilibrium) -> String {
    let mut s = format!("{FORCES_HEADER}\n");
    for rod in &eq.rods {
        let mut along = 0.0;
        for (k, f) in rod.forces.iter().enumerate() {
            let (a, b) = (rod.points[k], rod.points[(k + 1) % rod.points.len()]);
            let half = 0.5 * crate::math::vec::dist(&a, &b);
            let u = f
                .utilization
                .map(|u| format!("{u:.12e}"))
                .unwrap_or_default();
            let _ = writeln!(
                s,
                "{},{k},{:.12e},{:.12e},{:.12e},{:.12e},{:.12e},{:.12e},{:.12e},{:.12e},{u}",
                csv_field(&rod.name),
                along + half,
                f.axial,
                f.shear[0],
                f.shear[1],
                f.moment[0],
                f.moment[1],
                f.torsion,
                f.von_mises,
            );
            along += 2.0 * half;
        }
    }
    s
}

fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}
