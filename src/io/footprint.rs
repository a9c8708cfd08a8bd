//! Fabrication outputs of a fitted gridshell: the cut list (CSV) and the footprint to scale
//! (SVG). Pure formatting of the rods as the footprint lays them out.

use std::fmt::Write;

/// One rod of the footprint, m.
#[derive(Debug, Clone)]
pub struct FootprintRod {
    pub name: String,
    /// "u" or "v".
    pub family: &'static str,
    /// Offset of the rod's line in the footprint.
    pub offset: f64,
    /// Footprint coordinates of its two ends.
    pub ends: [[f64; 2]; 2],
    /// Its crossings: joint name and arc length from the rod's start.
    pub crossings: Vec<(String, f64)>,
}

impl FootprintRod {
    pub fn length(&self) -> f64 {
        let [a, b] = self.ends;
        (b[0] - a[0]).hypot(b[1] - a[1])
    }
}

/// One row per rod: family, offset, length, and the crossings' positions along it.
pub fn cut_list_csv(rods: &[FootprintRod]) -> String {
    let mut s = String::from("rod,family,offset_m,length_m,crossings,crossing_positions_m\n");
    for r in rods {
        let positions: Vec<String> = r.crossings.iter().map(|c| format!("{:.6}", c.1)).collect();
        let _ = writeln!(
            s,
            "{},{},{:.6},{:.6},{},{}",
            r.name,
            r.family,
            r.offset,
            r.length(),
            r.crossings.len(),
            positions.join(";")
        );
    }
    s
}

/// The footprint drawn to scale in millimetres: rods as lines labelled at their start, joints
/// as dots labelled with their names.
pub fn footprint_svg(rods: &[FootprintRod]) -> String {
    let pts = rods.iter().flat_map(|r| r.ends.iter());
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in pts {
        for k in 0..2 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let size = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(1e-9);
    let margin = 0.05 * size;
    let mm = |x: f64| x * 1000.0;
    // y grows downward in SVG: flip it so the drawing reads like the footprint's plan.
    let xy = |p: [f64; 2]| (mm(p[0] - lo[0] + margin), mm(hi[1] - p[1] + margin));
    let (w, h) = (
        mm(hi[0] - lo[0] + 2.0 * margin),
        mm(hi[1] - lo[1] + 2.0 * margin),
    );
    let stroke = mm(size) / 800.0;
    let font = mm(size) / 120.0;
    let mut s = String::new();
    let _ = writeln!(
        s,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w:.3}mm\" height=\"{h:.3}mm\" \
         viewBox=\"0 0 {w:.3} {h:.3}\">"
    );
    let _ = writeln!(
        s,
        "<!-- rodnet gridshell fit footprint, 1:1, units mm; u rods blue, v rods red -->"
    );
    for r in rods {
        let (a, b) = (xy(r.ends[0]), xy(r.ends[1]));
        let colour = if r.family == "u" {
            "#1f4e9c"
        } else {
            "#b0302a"
        };
        let _ = writeln!(
            s,
            "<line x1=\"{:.3}\" y1=\"{:.3}\" x2=\"{:.3}\" y2=\"{:.3}\" stroke=\"{colour}\" \
             stroke-width=\"{stroke:.3}\"/>",
            a.0, a.1, b.0, b.1
        );
        let _ = writeln!(
            s,
            "<text x=\"{:.3}\" y=\"{:.3}\" font-size=\"{font:.3}\" fill=\"{colour}\">{}</text>",
            a.0, a.1, r.name
        );
        if r.family == "u" {
            let len = r.length().max(1e-300);
            for (name, t) in &r.crossings {
                let f = t / len;
                let p = [
                    r.ends[0][0] + f * (r.ends[1][0] - r.ends[0][0]),
                    r.ends[0][1] + f * (r.ends[1][1] - r.ends[0][1]),
                ];
                let c = xy(p);
                let _ = writeln!(
                    s,
                    "<circle cx=\"{:.3}\" cy=\"{:.3}\" r=\"{:.3}\" fill=\"black\"/>\
                     <text x=\"{:.3}\" y=\"{:.3}\" font-size=\"{:.3}\">{name}</text>",
                    c.0,
                    c.1,
                    2.0 * stroke,
                    c.0 + 2.0 * stroke,
                    c.1 - 2.0 * stroke,
                    0.6 * font
                );
            }
        }
    }
    s.push_str("</svg>\n");
    s
}
