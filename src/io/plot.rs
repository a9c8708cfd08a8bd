//! A picture of an equilibrium: three orthographic views and an axonometric one, rods coloured
//! by extreme-fibre bending stress, with a colour scale. Lines are drawn by plotters' in-memory
//! bitmap backend; labels use a built-in 5×7 bitmap font (plotters' text needs a font stack
//! and system fonts); the PNG is encoded here so that the caller can write it atomically.

use plotters::prelude::*;

use crate::io::results::{Results, RodJson};

/// One rod to draw.
#[derive(Debug, Clone, PartialEq)]
pub struct PlotRod {
    pub name: String,
    pub points: Vec<[f64; 3]>,
    /// Bending stress at each node, Pa (same length as `points`).
    pub stress: Vec<f64>,
    pub closed: bool,
}

/// Reads the rods of a results JSON through the results schema ([`Results`]): `points` per
/// rod, per-node `bending_stress` when present, else the rod's `max_bending_stress`, else zero.
/// Errors name the file (`file`), and the line, column and key of the offending value.
pub fn rods_from_json(file: &str, text: &str) -> Result<Vec<PlotRod>, String> {
    let de = &mut serde_json::Deserializer::from_str(text);
    let results: Results = serde_path_to_error::deserialize(de).map_err(|e| {
        let inner = e.inner();
        if e.path().iter().next().is_none() && inner.to_string().starts_with("missing field `rods`")
        {
            format!("{file}: no `rods` array: not a rodnet results JSON")
        } else {
            format!(
                "{file}:{}:{}: {}: {inner}",
                inner.line(),
                inner.column(),
                e.path()
            )
        }
    })?;
    if results.rods.is_empty() {
        return Err(format!("{file}: `rods` is empty: nothing to draw"));
    }
    results
        .rods
        .into_iter()
        .enumerate()
        .map(|(i, r)| plot_rod(i, r).map_err(|e| format!("{file}: {e}")))
        .collect()
}

fn plot_rod(i: usize, r: RodJson) -> Result<PlotRod, String> {
    let n = r.points.len();
    if n < 2 {
        return Err(format!("rods[{i}].points: needs at least 2 points"));
    }
    let stress = if r.bending_stress.is_empty() {
        vec![r.max_bending_stress; n]
    } else if r.bending_stress.len() != n {
        return Err(format!(
            "rods[{i}].bending_stress: {} values for {n} points",
            r.bending_stress.len()
        ));
    } else if let Some(k) = r.bending_stress.iter().position(|x| !x.is_finite()) {
        return Err(format!(
            "rods[{i}].bending_stress[{k}]: not a finite number"
        ));
    } else {
        r.bending_stress
    };
    Ok(PlotRod {
        name: r.name,
        // Closed rods have as many edges (twist angles) as nodes.
        closed: r.twist.len() == n,
        points: r.points,
        stress,
    })
}

/// Viridis, sampled at five stops.
const STOPS: [[f64; 3]; 5] = [
    [68.0, 1.0, 84.0],
    [59.0, 82.0, 139.0],
    [33.0, 145.0, 140.0],
    [94.0, 201.0, 98.0],
    [253.0, 231.0, 37.0],
];

pub fn colour(t: f64) -> [u8; 3] {
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let x = t * (STOPS.len() - 1) as f64;
    let k = (x.floor() as usize).min(STOPS.len() - 2);
    let f = x - k as f64;
    let c = |j: usize| (STOPS[k][j] + f * (STOPS[k + 1][j] - STOPS[k][j])).round() as u8;
    [c(0), c(1), c(2)]
}

type Projection = fn(&[f64; 3]) -> (f64, f64);

/// Views: name and projection to (right, up) screen coordinates.
const VIEWS: [(&str, Projection); 4] = [
    ("TOP (X RIGHT, Y UP)", |p| (p[0], p[1])),
    ("FRONT (X RIGHT, Z UP)", |p| (p[0], p[2])),
    ("SIDE (Y RIGHT, Z UP)", |p| (p[1], p[2])),
    // Seen from (1, -1, 1): right = (1, 1, 0)/√2, up = (-1, 1, 2)/√6.
    ("AXONOMETRIC", |p| {
        (
            (p[0] + p[1]) / std::f64::consts::SQRT_2,
            (-p[0] + p[1] + 2.0 * p[2]) / 6f64.sqrt(),
        )
    }),
];

const TITLE_H: u32 = 34;
/// Height of the colour-scale band at the bottom, pixels.
pub const LEGEND_H: u32 = 64;
const PAD: f64 = 26.0;
const TEXT: [u8; 3] = [30, 30, 30];

/// Renders the rods into a PNG of `width` × `height` pixels.
pub fn render(rods: &[PlotRod], width: u32, height: u32, title: &str) -> Result<Vec<u8>, String> {
    if width < 200 || height < 200 {
        return Err(format!(
            "the picture must be at least 200 × 200 pixels, got {width} × {height}"
        ));
    }
    let smax = rods
        .iter()
        .flat_map(|r| r.stress.iter())
        .copied()
        .filter(|s| s.is_finite())
        .fold(0.0, f64::max);
    // Segments with their colour parameter, drawn low stress first so peaks stay visible.
    let mut segs: Vec<([f64; 3], [f64; 3], f64)> = Vec::new();
    for r in rods {
        let n = r.points.len();
        let m = if r.closed { n } else { n - 1 };
        for k in 0..m {
            let j = (k + 1) % n;
            // The larger end: node stresses are zero at rod ends, also at clamped ones, where
            // the moment is often largest.
            let s = r.stress[k].max(r.stress[j]);
            let t = if smax > 0.0 { s / smax } else { 0.0 };
            segs.push((r.points[k], r.points[j], t));
        }
    }
    segs.sort_by(|a, b| a.2.total_cmp(&b.2));

    let (w, h) = (width as usize, height as usize);
    let mut buf = vec![255u8; w * h * 3];
    let panel_w = width / 2;
    let panel_h = (height - TITLE_H - LEGEND_H) / 2;
    let origin = |v: usize| ((v % 2) as u32 * panel_w, TITLE_H + (v / 2) as u32 * panel_h);
    // One scale for the three orthographic views, so lengths compare across them.
    let fit = |proj: Projection| {
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for r in rods {
            for p in &r.points {
                let (u, v) = proj(p);
                lo = [lo[0].min(u), lo[1].min(v)];
                hi = [hi[0].max(u), hi[1].max(v)];
            }
        }
        let span = [(hi[0] - lo[0]).max(1e-300), (hi[1] - lo[1]).max(1e-300)];
        let su = (panel_w as f64 - 2.0 * PAD) / span[0];
        let sv = (panel_h as f64 - 2.0 * PAD - 12.0) / span[1];
        (su.min(sv), [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0])
    };
    let ortho = VIEWS[..3]
        .iter()
        .map(|(_, p)| fit(*p).0)
        .fold(f64::INFINITY, f64::min);
    let mut labels: Vec<(u32, u32, u32, String)> = Vec::new();
    {
        let root = BitMapBackend::with_buffer(&mut buf, (width, height)).into_drawing_area();
        let err = |e: DrawingAreaErrorKind<_>| format!("drawing failed: {e:?}");
        for (v, (name, proj)) in VIEWS.iter().enumerate() {
            let (x0, y0) = origin(v);
            let (s, centre) = fit(*proj);
            let scale = if v < 3 { ortho } else { s };
            let cx = x0 as f64 + panel_w as f64 / 2.0;
            let cy = y0 as f64 + 12.0 + panel_h as f64 / 2.0;
            let to_px = |p: &[f64; 3]| {
                let (u, w) = proj(p);
                (
                    (cx + (u - centre[0]) * scale).round() as i32,
                    (cy - (w - centre[1]) * scale).round() as i32,
                )
            };
            root.draw(&Rectangle::new(
                [
                    (x0 as i32 + 4, y0 as i32 + 4),
                    ((x0 + panel_w) as i32 - 4, (y0 + panel_h) as i32 - 4),
                ],
                RGBColor(200, 200, 200).stroke_width(1),
            ))
            .map_err(err)?;
            for (a, b, t) in &segs {
                let [r, g, bl] = colour(*t);
                root.draw(&PathElement::new(
                    vec![to_px(a), to_px(b)],
                    RGBColor(r, g, bl).stroke_width(3),
                ))
                .map_err(err)?;
            }
            labels.push((
                x0 + 12,
                y0 + 12,
                fitting(name, panel_w - 24),
                name.to_string(),
            ));
        }
        let (bx0, by0) = (width / 6, height - LEGEND_H + 14);
        let bw = width * 2 / 3;
        root.present().map_err(err)?;
        labels.push((bx0, by0 + 24, 2, "0 PA".into()));
        let max = format!("{} PA", fmt_sci(smax));
        labels.push((bx0 + bw - text_width(&max, 2), by0 + 24, 2, max.clone()));
        // The caption goes between the end labels, shortened or left out when they would touch.
        let free = (
            bx0 + text_width("0 PA", 2) + 12,
            bx0 + bw - text_width(&max, 2) - 12,
        );
        if let Some(c) = ["EXTREME-FIBRE BENDING STRESS", "BENDING STRESS"]
            .into_iter()
            .find(|c| text_width(c, 2) <= free.1.saturating_sub(free.0))
        {
            let x = (width / 2 - text_width(c, 2) / 2).clamp(free.0, free.1 - text_width(c, 2));
            labels.push((x, by0 + 24, 2, c.into()));
        }
    }
    // Colour scale under the views.
    let (bx0, by0, bw) = (w / 6, h - LEGEND_H as usize + 14, w * 2 / 3);
    for i in 0..bw {
        let c = colour(i as f64 / (bw - 1) as f64);
        for y in by0..by0 + 16 {
            let at = 3 * (y * w + bx0 + i);
            buf[at..at + 3].copy_from_slice(&c);
        }
    }
    for (x, y, scale, s) in &labels {
        draw_text(&mut buf, w, h, *x, *y, *scale, TEXT, s);
    }
    draw_text(
        &mut buf,
        w,
        h,
        12,
        10,
        fitting(title, width - 24),
        TEXT,
        title,
    );
    encode_png(&buf, width, height)
}

/// `1.23E+08`-style numbers for the labels.
pub fn fmt_sci(x: f64) -> String {
    if x == 0.0 {
        return "0".into();
    }
    let s = format!("{x:.3e}");
    match s.split_once('e') {
        Some((m, e)) => {
            let e: i32 = e.parse().unwrap_or(0);
            format!("{m}E{}{:02}", if e < 0 { '-' } else { '+' }, e.abs())
        }
        None => s,
    }
}

pub(crate) fn encode_png(rgb: &[u8], width: u32, height: u32) -> Result<Vec<u8>, String> {
    let mut out = Vec::new();
    let mut enc = png::Encoder::new(&mut out, width, height);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    let mut wr = enc
        .write_header()
        .map_err(|e| format!("PNG encoding failed: {e}"))?;
    wr.write_image_data(rgb)
        .map_err(|e| format!("PNG encoding failed: {e}"))?;
    wr.finish()
        .map_err(|e| format!("PNG encoding failed: {e}"))?;
    Ok(out)
}

/// 5×7 glyphs, one byte per row, high bit on the left of five.
const FONT: &[(char, [u8; 7])] = &[
    ('A', [0x0E, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11]),
    ('B', [0x1E, 0x11, 0x11, 0x1E, 0x11, 0x11, 0x1E]),
    ('C', [0x0E, 0x11, 0x10, 0x10, 0x10, 0x11, 0x0E]),
    ('D', [0x1E, 0x11, 0x11, 0x11, 0x11, 0x11, 0x1E]),
    ('E', [0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x1F]),
    ('F', [0x1F, 0x10, 0x10, 0x1E, 0x10, 0x10, 0x10]),
    ('G', [0x0E, 0x11, 0x10, 0x17, 0x11, 0x11, 0x0F]),
    ('H', [0x11, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11]),
    ('I', [0x0E, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E]),
    ('J', [0x07, 0x02, 0x02, 0x02, 0x02, 0x12, 0x0C]),
    ('K', [0x11, 0x12, 0x14, 0x18, 0x14, 0x12, 0x11]),
    ('L', [0x10, 0x10, 0x10, 0x10, 0x10, 0x10, 0x1F]),
    ('M', [0x11, 0x1B, 0x15, 0x15, 0x11, 0x11, 0x11]),
    ('N', [0x11, 0x11, 0x19, 0x15, 0x13, 0x11, 0x11]),
    ('O', [0x0E, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E]),
    ('P', [0x1E, 0x11, 0x11, 0x1E, 0x10, 0x10, 0x10]),
    ('Q', [0x0E, 0x11, 0x11, 0x11, 0x15, 0x12, 0x0D]),
    ('R', [0x1E, 0x11, 0x11, 0x1E, 0x14, 0x12, 0x11]),
    ('S', [0x0F, 0x10, 0x10, 0x0E, 0x01, 0x01, 0x1E]),
    ('T', [0x1F, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04]),
    ('U', [0x11, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0E]),
    ('V', [0x11, 0x11, 0x11, 0x11, 0x11, 0x0A, 0x04]),
    ('W', [0x11, 0x11, 0x11, 0x15, 0x15, 0x15, 0x0A]),
    ('X', [0x11, 0x11, 0x0A, 0x04, 0x0A, 0x11, 0x11]),
    ('Y', [0x11, 0x11, 0x0A, 0x04, 0x04, 0x04, 0x04]),
    ('Z', [0x1F, 0x01, 0x02, 0x04, 0x08, 0x10, 0x1F]),
    ('0', [0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E]),
    ('1', [0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E]),
    ('2', [0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F]),
    ('3', [0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E]),
    ('4', [0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02]),
    ('5', [0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E]),
    ('6', [0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E]),
    ('7', [0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08]),
    ('8', [0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E]),
    ('9', [0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C]),
    (' ', [0x00; 7]),
    ('.', [0x00, 0x00, 0x00, 0x00, 0x00, 0x0C, 0x0C]),
    (',', [0x00, 0x00, 0x00, 0x00, 0x0C, 0x04, 0x08]),
    ('-', [0x00, 0x00, 0x00, 0x1F, 0x00, 0x00, 0x00]),
    ('+', [0x00, 0x04, 0x04, 0x1F, 0x04, 0x04, 0x00]),
    (':', [0x00, 0x0C, 0x0C, 0x00, 0x0C, 0x0C, 0x00]),
    ('(', [0x02, 0x04, 0x08, 0x08, 0x08, 0x04, 0x02]),
    (')', [0x08, 0x04, 0x02, 0x02, 0x02, 0x04, 0x08]),
    ('/', [0x00, 0x01, 0x02, 0x04, 0x08, 0x10, 0x00]),
    ('_', [0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x1F]),
    ('=', [0x00, 0x00, 0x1F, 0x00, 0x1F, 0x00, 0x00]),
    ('%', [0x18, 0x19, 0x02, 0x04, 0x08, 0x13, 0x03]),
    ('?', [0x0E, 0x11, 0x01, 0x02, 0x04, 0x00, 0x04]),
];

fn glyph(c: char) -> [u8; 7] {
    let c = c.to_ascii_uppercase();
    FONT.iter()
        .find(|(g, _)| *g == c)
        .or_else(|| FONT.iter().find(|(g, _)| *g == '?'))
        .map(|(_, rows)| *rows)
        .unwrap_or([0; 7])
}

/// The text scale, 2 or 1, at which `s` fits in `room` pixels (too long text is clipped).
fn fitting(s: &str, room: u32) -> u32 {
    if text_width(s, 2) <= room {
        2
    } else {
        1
    }
}

/// Width in pixels of `s` at `scale` (6 columns per glyph, the last one blank).
pub fn text_width(s: &str, scale: u32) -> u32 {
    6 * scale * s.chars().count() as u32
}

#[allow(clippy::too_many_arguments)]
pub(crate) fn draw_text(
    buf: &mut [u8],
    w: usize,
    h: usize,
    x: u32,
    y: u32,
    scale: u32,
    rgb: [u8; 3],
    s: &str,
) {
    for (i, c) in s.chars().enumerate() {
        let rows = glyph(c);
        let gx = x as usize + i * 6 * scale as usize;
        for (r, bits) in rows.iter().enumerate() {
            for col in 0..5 {
                if bits & (0x10 >> col) == 0 {
                    continue;
                }
                for dy in 0..scale as usize {
                    for dx in 0..scale as usize {
                        let px = gx + col * scale as usize + dx;
                        let py = y as usize + r * scale as usize + dy;
                        if px < w && py < h {
                            buf[3 * (py * w + px)..3 * (py * w + px) + 3].copy_from_slice(&rgb);
                        }
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colour_scale_runs_from_dark_to_bright() {
        assert_eq!(colour(0.0), [68, 1, 84]);
        assert_eq!(colour(1.0), [253, 231, 37]);
        assert_eq!(colour(f64::NAN), colour(0.0));
        let lum = |c: [u8; 3]| c.iter().map(|&x| x as u32).sum::<u32>();
        for k in 0..10 {
            assert!(lum(colour(k as f64 / 10.0)) < lum(colour((k + 1) as f64 / 10.0)));
        }
    }

    #[test]
    fn labels_format_like_engineering_output() {
        assert_eq!(fmt_sci(0.0), "0");
        assert_eq!(fmt_sci(123456789.0), "1.235E+08");
        assert_eq!(fmt_sci(0.00125), "1.250E-03");
    }

    #[test]
    fn every_label_character_has_a_glyph() {
        let q = glyph('?');
        for c in "0123456789 .-+:()/ABCDEFGHIJKLMNOPQRSTUVWXYZ".chars() {
            assert!(c == '?' || glyph(c) != q, "{c}");
        }
        assert_eq!(glyph('a'), glyph('A'));
        assert_eq!(glyph('é'), q);
    }
}
