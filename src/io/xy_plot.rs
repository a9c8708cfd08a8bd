//! Several named series on linear or logarithmic axes as a PNG, with a legend above the axes
//! (the indentation study's K against n and r/R, its force–depth curves; `rodnet indent
//! --plot` through [`crate::io::curve_plot`]): plotters' bitmap backend, the embedded font,
//! our PNG encoder.

use plotters::prelude::*;

use crate::io::plot::{draw_text, encode_png, fmt_sci, text_width};

/// How a series marks its points.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Marker {
    None,
    Dot,
    Ring,
}

#[derive(Debug, Clone)]
pub struct Series {
    pub name: String,
    pub colour: [u8; 3],
    pub points: Vec<(f64, f64)>,
    /// Join the points by a line (dashed when `dashed`).
    pub line: bool,
    pub dashed: bool,
    pub marker: Marker,
}

#[derive(Debug, Clone)]
pub struct Axis {
    pub label: String,
    pub log: bool,
    /// Tick values; None: decades (and 2, 5 times them over less than two decades) on a log
    /// axis, six even steps on a linear one.
    pub ticks: Option<Vec<f64>>,
}

const TEXT: [u8; 3] = [30, 30, 30];
const GRID: RGBColor = RGBColor(225, 225, 225);

/// Data range of one axis in plot coordinates (log10 on a log axis), padded by 4 %; a linear
/// axis includes 0 when its data are all of one sign and reach within a third of it.
fn range(v: &[f64], log: bool) -> Option<(f64, f64)> {
    let t: Vec<f64> = v
        .iter()
        .filter(|x| x.is_finite() && (!log || **x > 0.0))
        .map(|&x| if log { x.log10() } else { x })
        .collect();
    let lo = t.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = t.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    if !(lo.is_finite() && hi.is_finite()) {
        return None;
    }
    let (mut lo, mut hi) = (lo, hi);
    if !log && lo > 0.0 && lo < (hi - lo) / 2.0 {
        lo = 0.0;
    }
    if hi <= lo {
        (lo, hi) = (lo - 0.5, hi + 0.5);
    }
    let pad = 0.04 * (hi - lo);
    Some((if !log && lo == 0.0 { 0.0 } else { lo - pad }, hi + pad))
}

fn ticks(axis: &Axis, lo: f64, hi: f64) -> Vec<f64> {
    let inside = |t: f64| {
        let x = if axis.log { t.log10() } else { t };
        x >= lo - 1e-9 && x <= hi + 1e-9
    };
    if let Some(t) = &axis.ticks {
        return t.iter().copied().filter(|&t| inside(t)).collect();
    }
    if !axis.log {
        return (0..=5).map(|k| lo + (hi - lo) * k as f64 / 5.0).collect();
    }
    let mantissas: &[f64] = if hi - lo < 2.0 {
        &[1.0, 2.0, 5.0]
    } else {
        &[1.0]
    };
    (lo.floor() as i32..=hi.ceil() as i32)
        .flat_map(|k| mantissas.iter().map(move |m| m * 10f64.powi(k)))
        .filter(|&t| inside(t))
        .collect()
}

/// Short tick labels: plain decimals from 0.001 to 1e5 (three decimals at most), `2E-07`
/// otherwise.
fn label(t: f64) -> String {
    if t == 0.0 || (1e-3..1e5).contains(&t.abs()) {
        let s = format!("{t:.3}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        let s = fmt_sci(t);
        // fmt_sci writes three decimals; ticks need at most two significant digits.
        match s.split_once('E') {
            Some((m, e)) => {
                let m: f64 = m.parse().unwrap_or(0.0);
                let m = format!("{m:.1}");
                format!("{}E{e}", m.trim_end_matches(".0"))
            }
            None => s,
        }
    }
}

/// Renders `series` on axes `x` and `y` with `title` into a PNG of `width` × `height` pixels.
pub fn chart(
    series: &[Series],
    (x, y): (&Axis, &Axis),
    title: &str,
    (width, height): (u32, u32),
) -> Result<Vec<u8>, String> {
    let xs: Vec<f64> = series
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.0))
        .collect();
    let ys: Vec<f64> = series
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.1))
        .collect();
    let (xlo, xhi) = range(&xs, x.log).ok_or("no point to plot")?;
    let (ylo, yhi) = range(&ys, y.log).ok_or("no point to plot")?;
    // Two legend entries per row above the axes.
    let rows = series.len().div_ceil(2) as f64;
    let (left, right, top, bottom) = (100.0, 28.0, 56.0 + 22.0 * rows, 64.0);
    let (pw, ph) = (width as f64 - left - right, height as f64 - top - bottom);
    let tx = |v: f64| if x.log { v.log10() } else { v };
    let ty = |v: f64| if y.log { v.log10() } else { v };
    let px = |v: f64| (left + (tx(v) - xlo) / (xhi - xlo) * pw).round() as i32;
    let py = |v: f64| (top + (yhi - ty(v)) / (yhi - ylo) * ph).round() as i32;
    let usable = |p: &&(f64, f64)| {
        p.0.is_finite() && p.1.is_finite() && (!x.log || p.0 > 0.0) && (!y.log || p.1 > 0.0)
    };
    let (w, h) = (width as usize, height as usize);
    let mut buf = vec![255u8; w * h * 3];
    let mut text: Vec<(i32, i32, [u8; 3], String)> = Vec::new();
    {
        let root = BitMapBackend::with_buffer(&mut buf, (width, height)).into_drawing_area();
        let err = |e: DrawingAreaErrorKind<_>| format!("drawing failed: {e:?}");
        let (x0, x1, y0, y1) = (
            left as i32,
            (left + pw) as i32,
            top as i32,
            (top + ph) as i32,
        );
        for t in ticks(x, xlo, xhi) {
            root.draw(&PathElement::new(vec![(px(t), y0), (px(t), y1)], GRID))
                .map_err(err)?;
            let s = label(t);
            text.push((px(t) - text_width(&s, 2) as i32 / 2, y1 + 10, TEXT, s));
        }
        for t in ticks(y, ylo, yhi) {
            root.draw(&PathElement::new(vec![(x0, py(t)), (x1, py(t))], GRID))
                .map_err(err)?;
            let s = label(t);
            text.push((x0 - text_width(&s, 2) as i32 - 8, py(t) - 7, TEXT, s));
        }
        root.draw(&Rectangle::new(
            [(x0, y0), (x1, y1)],
            RGBColor(120, 120, 120).stroke_width(1),
        ))
        .map_err(err)?;
        for s in series {
            let c = RGBColor(s.colour[0], s.colour[1], s.colour[2]);
            let pts: Vec<(i32, i32)> = s
                .points
                .iter()
                .filter(usable)
                .map(|&(a, b)| (px(a), py(b)))
                .collect();
            if s.line && s.dashed {
                for seg in pts.windows(2) {
                    dashed(&root, seg[0], seg[1], c).map_err(err)?;
                }
            } else if s.line {
                root.draw(&PathElement::new(pts.clone(), c.stroke_width(2)))
                    .map_err(err)?;
            }
            for &at in &pts {
                match s.marker {
                    Marker::None => {}
                    Marker::Dot => root.draw(&Circle::new(at, 5, c.filled())).map_err(err)?,
                    Marker::Ring => root
                        .draw(&Circle::new(at, 6, c.stroke_width(2)))
                        .map_err(err)?,
                }
            }
        }
        // Unnamed series continue a named one (its later runs): one legend entry each.
        for (k, s) in series.iter().filter(|s| !s.name.is_empty()).enumerate() {
            let col = x0 + (k % 2) as i32 * (pw as i32 / 2);
            let row = 40 + 22 * (k / 2) as i32;
            let c = RGBColor(s.colour[0], s.colour[1], s.colour[2]);
            if s.line && s.dashed {
                dashed(&root, (col, row + 6), (col + 28, row + 6), c).map_err(err)?;
            } else if s.line {
                root.draw(&PathElement::new(
                    vec![(col, row + 6), (col + 28, row + 6)],
                    c.stroke_width(2),
                ))
                .map_err(err)?;
            }
            match s.marker {
                Marker::None => {}
                Marker::Dot => root
                    .draw(&Circle::new((col + 14, row + 6), 5, c.filled()))
                    .map_err(err)?,
                Marker::Ring => root
                    .draw(&Circle::new((col + 14, row + 6), 6, c.stroke_width(2)))
                    .map_err(err)?,
            }
            text.push((col + 36, row, s.colour, s.name.clone()));
        }
        root.present().map_err(err)?;
    }
    for (a, b, c, s) in &text {
        draw_text(
            &mut buf,
            w,
            h,
            (*a).max(0) as u32,
            (*b).max(0) as u32,
            2,
            *c,
            s,
        );
    }
    draw_text(&mut buf, w, h, 12, 10, 2, TEXT, title);
    draw_text(&mut buf, w, h, 12, top as u32 - 24, 2, TEXT, &y.label);
    let xw = text_width(&x.label, 2);
    draw_text(
        &mut buf,
        w,
        h,
        (left as u32 + (pw as u32).saturating_sub(xw) / 2).min(width.saturating_sub(xw)),
        height - 26,
        2,
        TEXT,
        &x.label,
    );
    encode_png(&buf, width, height)
}

/// A dashed segment: 8 pixels on, 6 off.
fn dashed<DB: DrawingBackend>(
    root: &DrawingArea<DB, plotters::coord::Shift>,
    a: (i32, i32),
    b: (i32, i32),
    c: RGBColor,
) -> Result<(), DrawingAreaErrorKind<DB::ErrorType>> {
    let (dx, dy) = ((b.0 - a.0) as f64, (b.1 - a.1) as f64);
    let len = (dx * dx + dy * dy).sqrt();
    let at = |s: f64| {
        let f = (s / len.max(1e-9)).min(1.0);
        (a.0 + (f * dx).round() as i32, a.1 + (f * dy).round() as i32)
    };
    let mut s = 0.0;
    while s < len {
        root.draw(&PathElement::new(
            vec![at(s), at((s + 8.0).min(len))],
            c.stroke_width(2),
        ))?;
        s += 14.0;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn log_ticks_and_labels() {
        let a = Axis {
            label: String::new(),
            log: true,
            ticks: None,
        };
        let t = ticks(&a, -3.1, -1.9);
        assert_eq!(t.len(), 4);
        assert_eq!(label(t[0]), "0.001");
        assert_eq!(label(2e-7), "2E-07");
        assert_eq!(label(12.0), "12");
        assert_eq!(label(0.05), "0.05");
    }

    #[test]
    fn a_chart_is_a_png() {
        let s = Series {
            name: "a".into(),
            colour: [200, 0, 0],
            points: vec![(8.0, 1e-7), (24.0, 1e-6)],
            line: true,
            dashed: true,
            marker: Marker::Ring,
        };
        let ax = Axis {
            label: "n".into(),
            log: true,
            ticks: Some(vec![8.0, 12.0, 16.0, 24.0]),
        };
        let png = chart(&[s], (&ax, &ax), "t", (400, 300)).unwrap();
        assert_eq!(&png[1..4], b"PNG");
    }
}
