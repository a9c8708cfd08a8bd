//! Error against solve time on log–log axes, as a PNG, with the bitmap font and PNG encoder of
//! [`crate::io::plot`] (no font stack).

use plotters::prelude::*;

use crate::io::plot::{draw_text, encode_png, text_width};
use crate::study::convergence::{Measure, Study};

/// One curve: (level, seconds, error, converged) per point; not converged points are crosses.
#[derive(Debug, Clone)]
pub struct Series {
    pub name: String,
    pub colour: [u8; 3],
    pub points: Vec<(usize, f64, f64, bool)>,
    /// Write the level next to each point (one series is enough: they share the times).
    pub labelled: bool,
}

const BLUE: [u8; 3] = [31, 119, 180];
const GREEN: [u8; 3] = [44, 160, 44];
const ORANGE: [u8; 3] = [230, 120, 20];
const TEXT: [u8; 3] = [30, 30, 30];
const GRID: RGBColor = RGBColor(225, 225, 225);

/// The curves of a study: the primary error, the Richardson error when the primary one is the
/// reference's, and the deviation from the target sphere.
pub fn series_of(study: &Study) -> Vec<Series> {
    let pick = |f: &dyn Fn(&crate::study::convergence::Level) -> Option<f64>| {
        study
            .levels
            .iter()
            .filter_map(|l| f(l).map(|e| (l.level, l.seconds, e, l.converged)))
            .collect::<Vec<_>>()
    };
    let mut out = Vec::new();
    let richardson = Series {
        name: "ERROR AGAINST THE RICHARDSON EXTRAPOLATE".into(),
        colour: GREEN,
        points: pick(&|l| l.richardson_error),
        labelled: study.measure == Measure::Richardson,
    };
    if study.measure == Measure::Reference {
        out.push(Series {
            name: "ERROR AGAINST THE ANALYTIC REFERENCE".into(),
            colour: BLUE,
            points: pick(&|l| l.reference_error),
            labelled: true,
        });
    }
    out.push(richardson);
    out.push(Series {
        name: "MAX RADIAL DEVIATION FROM THE SPHERE".into(),
        colour: ORANGE,
        points: pick(&|l| l.sphere_deviation),
        labelled: false,
    });
    out.retain(|s| !s.points.is_empty());
    out
}

/// The decade range [lo, hi] (log10) covering `v`, padded, at least one decade wide.
fn log_range(v: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    let (lo, hi) = v.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
        (a.min(x.log10()), b.max(x.log10()))
    });
    if !(lo.is_finite() && hi.is_finite()) {
        return None;
    }
    let (mut lo, mut hi) = (lo - 0.12, hi + 0.12);
    if hi - lo < 1.0 {
        let mid = 0.5 * (lo + hi);
        (lo, hi) = (mid - 0.5, mid + 0.5);
    }
    Some((lo, hi))
}

/// Tick positions (log10) and labels: every decade, and 2 and 5 times each when the range
/// holds fewer than two decades.
fn ticks(lo: f64, hi: f64) -> Vec<(f64, String)> {
    let decades = (lo.ceil() as i32..=hi.floor() as i32).count();
    let mantissas: &[f64] = if decades < 2 {
        &[1.0, 2.0, 5.0]
    } else {
        &[1.0]
    };
    let mut out = Vec::new();
    for k in (lo.floor() as i32)..=(hi.ceil() as i32) {
        for &m in mantissas {
            let x = m.log10() + k as f64;
            if (lo..=hi).contains(&x) {
                out.push((x, format!("{m}E{k:+03}")));
            }
        }
    }
    out
}

/// Renders the study's error against solve time into a PNG of `width` × `height` pixels.
pub fn error_vs_time(
    series: &[Series],
    title: &str,
    width: u32,
    height: u32,
) -> Result<Vec<u8>, String> {
    let points = || series.iter().flat_map(|s| s.points.iter());
    let usable = |p: &&(usize, f64, f64, bool)| p.1 > 0.0 && p.2 > 0.0;
    let (xlo, xhi) = log_range(points().filter(usable).map(|p| p.1))
        .ok_or("no level has a positive error to plot")?;
    let (ylo, yhi) = log_range(points().filter(usable).map(|p| p.2)).expect("same points");
    let (w, h) = (width as usize, height as usize);
    // The legend goes above the axes, where it cannot hide a point.
    let top = 44.0 + 22.0 * series.len() as f64;
    let (left, right, bottom) = (100.0, 24.0, 64.0);
    let (pw, ph) = (width as f64 - left - right, height as f64 - top - bottom);
    let px = |t: f64| (left + (t.log10() - xlo) / (xhi - xlo) * pw).round() as i32;
    let py = |e: f64| (top + (yhi - e.log10()) / (yhi - ylo) * ph).round() as i32;
    let mut buf = vec![255u8; w * h * 3];
    let mut labels: Vec<(i32, i32, [u8; 3], String)> = Vec::new();
    {
        let root = BitMapBackend::with_buffer(&mut buf, (width, height)).into_drawing_area();
        let err = |e: DrawingAreaErrorKind<_>| format!("drawing failed: {e:?}");
        let (x0, x1) = (left as i32, (left + pw) as i32);
        let (y0, y1) = (top as i32, (top + ph) as i32);
        for (x, label) in ticks(xlo, xhi) {
            let at = px(10f64.powf(x));
            root.draw(&PathElement::new(vec![(at, y0), (at, y1)], GRID))
                .map_err(err)?;
            let tw = text_width(&label, 2) as i32;
            labels.push((at - tw / 2, y1 + 10, TEXT, label));
        }
        for (y, label) in ticks(ylo, yhi) {
            let at = py(10f64.powf(y));
            root.draw(&PathElement::new(vec![(x0, at), (x1, at)], GRID))
                .map_err(err)?;
            let tw = text_width(&label, 2) as i32;
            labels.push((x0 - tw - 8, at - 7, TEXT, label));
        }
        root.draw(&Rectangle::new(
            [(x0, y0), (x1, y1)],
            RGBColor(120, 120, 120).stroke_width(1),
        ))
        .map_err(err)?;
        // The labelled (primary) curve is drawn last, on top, as filled dots; the others as
        // rings around them, so that curves that coincide stay visible.
        for s in series.iter().rev() {
            let c = RGBColor(s.colour[0], s.colour[1], s.colour[2]);
            let pts: Vec<_> = s.points.iter().filter(|p| usable(p)).collect();
            let line: Vec<(i32, i32)> = pts
                .iter()
                .filter(|p| p.3)
                .map(|p| (px(p.1), py(p.2)))
                .collect();
            let width = if s.labelled { 2 } else { 1 };
            root.draw(&PathElement::new(line, c.stroke_width(width)))
                .map_err(err)?;
            for p in pts {
                let at = (px(p.1), py(p.2));
                if !p.3 {
                    // Not converged: a cross, not joined to the curve.
                    for (dx, dy) in [(6, 6), (6, -6)] {
                        root.draw(&PathElement::new(
                            vec![(at.0 - dx, at.1 - dy), (at.0 + dx, at.1 + dy)],
                            c.stroke_width(2),
                        ))
                        .map_err(err)?;
                    }
                } else if s.labelled {
                    root.draw(&Circle::new(at, 5, c.filled())).map_err(err)?;
                } else {
                    root.draw(&Circle::new(at, 8, c.stroke_width(2)))
                        .map_err(err)?;
                }
                if s.labelled {
                    let text = if p.3 {
                        format!("L{}", p.0)
                    } else {
                        format!("L{} NOT CONVERGED", p.0)
                    };
                    // Left of the point when it would run past the axes.
                    let tw = text_width(&text, 2) as i32;
                    let x = if at.0 + 10 + tw > x1 {
                        at.0 - 10 - tw
                    } else {
                        at.0 + 10
                    };
                    labels.push((x, at.1 - 18, s.colour, text));
                }
            }
        }
        for (k, s) in series.iter().enumerate() {
            let y = 34 + 22 * k as i32;
            let x = x1 - text_width(&s.name, 2) as i32;
            let c = RGBColor(s.colour[0], s.colour[1], s.colour[2]);
            let marker = if s.labelled {
                Circle::new((x - 16, y + 6), 5, c.filled())
            } else {
                Circle::new((x - 16, y + 6), 7, c.stroke_width(2))
            };
            root.draw(&marker).map_err(err)?;
            labels.push((x, y, s.colour, s.name.clone()));
        }
        root.present().map_err(err)?;
    }
    for (x, y, c, s) in &labels {
        let (x, y) = ((*x).max(0) as u32, (*y).max(0) as u32);
        draw_text(&mut buf, w, h, x, y, 2, *c, s);
    }
    draw_text(&mut buf, w, h, 12, 10, 2, TEXT, title);
    draw_text(&mut buf, w, h, 12, top as u32 - 22, 2, TEXT, "ERROR (LOG)");
    let xl = "WALL TIME OF THE SOLVE, S (LOG)";
    let xw = text_width(xl, 2);
    draw_text(
        &mut buf,
        w,
        h,
        (left as u32 + (pw as u32).saturating_sub(xw) / 2).min(width.saturating_sub(xw)),
        height - 26,
        2,
        TEXT,
        xl,
    );
    encode_png(&buf, width, height)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_cover_the_range_with_readable_labels() {
        let t = ticks(-3.2, -0.1);
        let labels: Vec<&str> = t.iter().map(|(_, l)| l.as_str()).collect();
        assert_eq!(labels, ["1E-03", "1E-02", "1E-01"]);
        // Less than two decades: 2 and 5 fill in.
        let t = ticks(-2.3, -1.4);
        let labels: Vec<&str> = t.iter().map(|(_, l)| l.as_str()).collect();
        assert_eq!(labels, ["1E-02", "2E-02"]);
    }

    #[test]
    fn ranges_are_at_least_a_decade() {
        let (lo, hi) = log_range([0.01, 0.012].into_iter()).unwrap();
        assert!((hi - lo - 1.0).abs() < 1e-12);
        assert!(lo < -2.0 && hi > 0.012f64.log10());
        assert!(log_range(std::iter::empty()).is_none());
    }
}
