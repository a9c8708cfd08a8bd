//! OBJ export: one `o` per rod named after it, its nodes as `v` lines and the rod as one `l`
//! polyline (closed rods repeat their first vertex).

use std::fmt::Write;

use crate::io::results::Results;

pub fn to_obj(r: &Results) -> String {
    let mut s = String::from("# rodnet equilibrium\n");
    let mut base = 1;
    for rod in &r.rods {
        let _ = writeln!(s, "o {}", rod.name.replace(char::is_whitespace, "_"));
        base = polyline(
            &mut s,
            &rod.points,
            rod.points.len() == rod.twist.len(),
            base,
        );
    }
    s
}

/// Writes `points` as `v` lines and one `l` polyline through them (a closed one back to its
/// first vertex), numbered from `base`; returns the next free vertex number.
pub fn polyline(s: &mut String, points: &[[f64; 3]], closed: bool, base: usize) -> usize {
    for p in points {
        let _ = writeln!(s, "v {:.12e} {:.12e} {:.12e}", p[0], p[1], p[2]);
    }
    s.push('l');
    for k in 0..points.len() {
        let _ = write!(s, " {}", base + k);
    }
    if closed {
        let _ = write!(s, " {base}");
    }
    s.push('\n');
    base + points.len()
}
