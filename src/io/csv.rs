//! CSV export: one row per node with position, the twist angle of the following edge, the
//! centreline curvature, and the bending strain and stress at the node's extreme fibre.

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

fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}
