//! A picture of an equilibrium: three orthographic views and an axonometric one, the rest shape
//! under the deformed one (displacements scaled by the deflection scale), the supports and the
//! point loads, rods coloured by a chosen quantity with a colour scale. Drawn by plotters'
//! in-memory bitmap backend with text in an embedded font ([`crate::io::text`]); the PNG is
//! encoded here so that the caller can write it atomically.

use plotters::prelude::*;

use crate::network::support::Marker;

pub use crate::io::plot_data::{read, Picture, PlotRod, Quantity};
pub use crate::io::text::{draw_text, text_width};

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
    ("Top (x right, y up)", |p| (p[0], p[1])),
    ("Front (x right, z up)", |p| (p[0], p[2])),
    ("Side (y right, z up)", |p| (p[1], p[2])),
    // Seen from (1, -1, 1): right = (1, 1, 0)/√2, up = (-1, 1, 2)/√6.
    ("Axonometric", |p| {
        (
            (p[0] + p[1]) / std::f64::consts::SQRT_2,
            (-p[0] + p[1] + 2.0 * p[2]) / 6f64.sqrt(),
        )
    }),
];

const TITLE_H: u32 = 34;
/// Height of the band at the bottom with the colour scale and the key, pixels.
pub const LEGEND_H: u32 = 88;
const PAD: f64 = 30.0;
const TEXT: [u8; 3] = [30, 30, 30];
/// The rest shape: a light blue-grey, unlike the colour scale and the (neutral) text.
pub const REST: [u8; 3] = [150, 170, 205];
/// Supports.
pub const SUPPORT: [u8; 3] = [0, 0, 0];
/// Point loads.
pub const LOAD: [u8; 3] = [215, 40, 40];

fn rgb(c: [u8; 3]) -> RGBColor {
    RGBColor(c[0], c[1], c[2])
}

/// A segment to draw: ends and colour parameter in [0, 1].
type Segment = ([f64; 3], [f64; 3], f64);

fn segments(p: &Picture) -> (Vec<Segment>, Vec<Segment>) {
    let (lo, hi) = p.range;
    let (mut drawn, mut rest) = (Vec::new(), Vec::new());
    for r in &p.rods {
        let n = r.points.len();
        for (k, v) in r.values.iter().enumerate() {
            let j = (k + 1) % n;
            let t = if hi > lo { (v - lo) / (hi - lo) } else { 0.0 };
            drawn.push((r.points[k], r.points[j], t));
            if let Some(q) = &r.rest {
                rest.push((q[k], q[j], 0.0));
            }
        }
    }
    // Low values first, so that peaks stay visible.
    drawn.sort_by(|a, b| a.2.total_cmp(&b.2));
    (drawn, rest)
}

/// Renders the picture into a PNG of `width` × `height` pixels.
pub fn render(p: &Picture, width: u32, height: u32, title: &str) -> Result<Vec<u8>, String> {
    if width < 200 || height < 200 {
        return Err(format!(
            "the picture must be at least 200 × 200 pixels, got {width} × {height}"
        ));
    }
    let (drawn, rest) = segments(p);
    let (w, h) = (width as usize, height as usize);
    let mut buf = vec![255u8; w * h * 3];
    let panel_w = width / 2;
    let panel_h = (height - TITLE_H - LEGEND_H) / 2;
    let origin = |v: usize| ((v % 2) as u32 * panel_w, TITLE_H + (v / 2) as u32 * panel_h);
    let all: Vec<[f64; 3]> = drawn
        .iter()
        .chain(&rest)
        .flat_map(|(a, b, _)| [*a, *b])
        .collect();
    // One scale for the three orthographic views, so lengths compare across them.
    let fit = |proj: Projection| {
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for q in &all {
            let (u, v) = proj(q);
            lo = [lo[0].min(u), lo[1].min(v)];
            hi = [hi[0].max(u), hi[1].max(v)];
        }
        let span = [(hi[0] - lo[0]).max(1e-300), (hi[1] - lo[1]).max(1e-300)];
        let su = (panel_w as f64 - 2.0 * PAD) / span[0];
        let sv = (panel_h as f64 - 2.0 * PAD - 12.0) / span[1];
        (su.min(sv), [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0])
    };
    let ortho = VIEWS[..3]
        .iter()
        .map(|(_, q)| fit(*q).0)
        .fold(f64::INFINITY, f64::min);
    let fmax = p.loads.iter().map(|l| norm(l.force)).fold(0.0, f64::max);
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
            let view = View {
                proj: *proj,
                to_px: &|u: f64, w: f64| {
                    (
                        (cx + (u - centre[0]) * scale).round() as i32,
                        (cy - (w - centre[1]) * scale).round() as i32,
                    )
                },
            };
            root.draw(&Rectangle::new(
                [
                    (x0 as i32 + 4, y0 as i32 + 4),
                    ((x0 + panel_w) as i32 - 4, (y0 + panel_h) as i32 - 4),
                ],
                RGBColor(200, 200, 200).stroke_width(1),
            ))
            .map_err(err)?;
            for (a, b, _) in &rest {
                root.draw(&PathElement::new(vec![view.px(a), view.px(b)], rgb(REST)))
                    .map_err(err)?;
            }
            for (a, b, t) in &drawn {
                let style = rgb(colour(*t)).stroke_width(3);
                root.draw(&PathElement::new(vec![view.px(a), view.px(b)], style))
                    .map_err(err)?;
            }
            for s in &p.supports {
                draw_support(&root, view.px(&s.at), s.kind.marker()).map_err(err)?;
            }
            for l in &p.loads {
                draw_load(&root, &view, l, fmax).map_err(err)?;
            }
            labels.push((
                x0 + 12,
                y0 + 10,
                fitting(name, panel_w - 24),
                name.to_string(),
            ));
        }
        root.present().map_err(err)?;
    }
    legend(&mut buf, p, width, height, &mut labels);
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

/// A view's projection and its map from projected coordinates to pixels.
struct View<'a> {
    proj: Projection,
    to_px: &'a dyn Fn(f64, f64) -> (i32, i32),
}

impl View<'_> {
    fn px(&self, p: &[f64; 3]) -> (i32, i32) {
        let (u, v) = (self.proj)(p);
        (self.to_px)(u, v)
    }

    /// Screen direction (right, down) of a vector, scaled as the view scales lengths.
    fn direction(&self, d: [f64; 3]) -> (f64, f64) {
        let (o, e) = ((self.proj)(&[0.0; 3]), (self.proj)(&d));
        (e.0 - o.0, -(e.1 - o.1))
    }
}

fn norm(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

type Area<'a> = DrawingArea<BitMapBackend<'a>, plotters::coord::Shift>;
type DrawResult<'a> =
    Result<(), DrawingAreaErrorKind<<BitMapBackend<'a> as DrawingBackend>::ErrorType>>;

/// A support's marker at its node (the triangles under it).
fn draw_support<'a>(root: &Area<'a>, (x, y): (i32, i32), marker: Marker) -> DrawResult<'a> {
    let c = rgb(SUPPORT);
    let tri = vec![(x, y), (x - 7, y + 12), (x + 7, y + 12), (x, y)];
    match marker {
        Marker::Square => root.draw(&Rectangle::new(
            [(x - 6, y - 6), (x + 6, y + 6)],
            c.filled(),
        )),
        Marker::OpenTriangle => root.draw(&PathElement::new(tri, c.stroke_width(2))),
        Marker::Ring => root.draw(&Circle::new((x, y), 6, c.stroke_width(2))),
        Marker::Triangle => root.draw(&Polygon::new(tri, c.filled())),
    }
}

/// A force as an arrow that ends at its node, longer for larger forces; a force along the
/// line of sight, or a torque, as a ring around the node.
fn draw_load<'a>(
    root: &Area<'a>,
    view: &View,
    l: &crate::io::plot_data::PointLoad,
    fmax: f64,
) -> DrawResult<'a> {
    let c = rgb(LOAD);
    let (x, y) = view.px(&l.at);
    let f = norm(l.force);
    if f > 0.0 {
        let (dx, dy) = view.direction(l.force.map(|v| v / f));
        let shown = (dx * dx + dy * dy).sqrt();
        if shown > 0.2 {
            let len = 18.0 + 32.0 * f / fmax;
            let (ux, uy) = (dx / shown, dy / shown);
            let tail = ((x as f64 - len * ux) as i32, (y as f64 - len * uy) as i32);
            root.draw(&PathElement::new(vec![tail, (x, y)], c.stroke_width(2)))?;
            for s in [-0.45f64, 0.45] {
                let (cs, sn) = (s.cos(), s.sin());
                let (bx, by) = (ux * cs - uy * sn, ux * sn + uy * cs);
                let end = ((x as f64 - 9.0 * bx) as i32, (y as f64 - 9.0 * by) as i32);
                root.draw(&PathElement::new(vec![end, (x, y)], c.stroke_width(2)))?;
            }
        } else {
            root.draw(&Circle::new((x, y), 5, c.stroke_width(2)))?;
        }
    }
    if norm(l.moment) > 0.0 {
        root.draw(&Circle::new((x, y), 9, c.stroke_width(2)))?;
    }
    Ok(())
}

/// The colour scale with its end values and caption, and the key to the other marks.
fn legend(
    buf: &mut [u8],
    p: &Picture,
    width: u32,
    height: u32,
    labels: &mut Vec<(u32, u32, u32, String)>,
) {
    let w = width as usize;
    let (bx0, by0, bw) = (width / 6, height - LEGEND_H + 8, width * 2 / 3);
    for i in 0..bw as usize {
        let c = colour(i as f64 / (bw - 1) as f64);
        for y in by0 as usize..by0 as usize + 14 {
            let at = 3 * (y * w + bx0 as usize + i);
            buf[at..at + 3].copy_from_slice(&c);
        }
    }
    let (caption, unit) = p.quantity.caption();
    let value = |x: f64| format!("{} {unit}", fmt_sci(x)).trim_end().to_string();
    let (lo, hi) = (value(p.range.0), value(p.range.1));
    let y = by0 + 20;
    labels.push((bx0, y, 2, lo.clone()));
    labels.push((bx0 + bw - text_width(&hi, 2), y, 2, hi.clone()));
    // The caption goes between the end labels, left out when it would touch them.
    let free = (
        bx0 + text_width(&lo, 2) + 12,
        bx0 + bw - text_width(&hi, 2) - 12,
    );
    let cw = text_width(caption, 2);
    if cw <= free.1.saturating_sub(free.0) {
        let x = (width / 2 - cw / 2).clamp(free.0, free.1 - cw);
        labels.push((x, y, 2, caption.into()));
    }
    let key = key(p);
    if !key.is_empty() {
        let scale = fitting(&key, width - 24);
        let x = (width / 2)
            .saturating_sub(text_width(&key, scale) / 2)
            .max(12);
        labels.push((x, y + 26, scale, key));
    }
}

/// What the marks mean, for those the picture has.
fn key(p: &Picture) -> String {
    let mut parts = Vec::new();
    if p.rods.iter().any(|r| r.rest.is_some()) {
        parts.push(format!(
            "blue-grey: undeformed; deformed shape drawn with displacements × {}",
            p.deflection_scale
        ));
    }
    // One entry per kind, in the order of their names.
    let mut kinds: Vec<_> = p.supports.iter().map(|s| &s.kind).collect();
    kinds.sort_unstable_by_key(|k| k.name());
    kinds.dedup_by_key(|k| k.name());
    let marks: Vec<String> = kinds
        .iter()
        .map(|k| format!("{} {}", k.marker().glyph(), k.name()))
        .collect();
    if !marks.is_empty() {
        parts.push(marks.join("  "));
    }
    let fmax = p.loads.iter().map(|l| norm(l.force)).fold(0.0, f64::max);
    if fmax > 0.0 {
        parts.push(format!(
            "red arrows: point loads (largest {} N)",
            fmt_sci(fmax)
        ));
    }
    if p.loads.iter().any(|l| norm(l.moment) > 0.0) {
        parts.push("red rings: torques".into());
    }
    parts.join("   ·   ")
}

/// The text scale, 2 or 1, at which `s` fits in `room` pixels (too long text is clipped).
fn fitting(s: &str, room: u32) -> u32 {
    if text_width(s, 2) <= room {
        2
    } else {
        1
    }
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
}
