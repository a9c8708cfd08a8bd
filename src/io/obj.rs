//! OBJ export: one `o` per rod named after it, its nodes as `v` lines and the rod as one `l`
//! polyline (closed rods repeat their first vertex).

use std::fmt::Write;

use crate::io::results::Results;

pub fn to_obj(r: &Results) -> String {
    let mut s = String::from("# rodnet equilibrium\n");
    let mut base = 1;
    for rod in &r.rods {
        let _ = writeln!(s, "o {}", rod.name.replace(char::is_whitespace, "_"));
        for p in &rod.points {
            let _ = writeln!(s, "v {:.12e} {:.12e} {:.12e}", p[0], p[1], p[2]);
        }
        s.push('l');
        for k in 0..rod.points.len() {
            let _ = write!(s, " {}", base + k);
        }
        if rod.points.len() == rod.twist.len() {
            let _ = write!(s, " {base}");
        }
        s.push('\n');
        base += rod.points.len();
    }
    s
}
