//! A force–depth curve on linear axes as a PNG (`rodnet indent --plot`), with the bitmap font
//! and PNG encoder of [`crate::io::plot`].

use plotters::prelude::*;

use crate::io::plot::{draw_text, encode_png, fmt_sci, text_width};

const LINE: RGBColor = RGBColor(31, 119, 180);
const MARK: RGBColor = RGBColor(214, 39, 40);
const TEXT: [u8; 3] = [30, 30, 30];
const GRID: RGBColor = RGBColor(225, 225, 225);

/// Draws `points` (x, y) joined, `marks` as red rings, with axis labels and a title.
pub fn curve(
    points: &[(f64, f64)],
    marks: &[(f64, f64)],
    labels: (&str, &str),
    title: &str,
    (width, height): (u32, u32),
) -> Result<Vec<u8>, String> {
    let range = |f: &dyn Fn(&(f64, f64)) -> f64| {
        let lo = points.iter().map(f).fold(0.0, f64::min);
        let hi = points.iter().map(f).fold(0.0, f64::max);
        if hi > lo {
            (lo, hi)
        } else {
            (lo - 1.0, lo + 1.0)
        }
    };
    let (xlo, xhi) = range(&|p| p.0);
    let (ylo, yhi) = range(&|p| p.1);
    let (left, right, top, bottom) = (110.0, 70.0, 64.0, 64.0);
    let (pw, ph) = (width as f64 - left - right, height as f64 - top - bottom);
    let px = |x: f64| (left + (x - xlo) / (xhi - xlo) * pw).round() as i32;
    let py = |y: f64| (top + (yhi - y) / (yhi - ylo) * ph).round() as i32;
    let (w, h) = (width as usize, height as usize);
    let mut buf = vec![255u8; w * h * 3];
    let mut text: Vec<(i32, i32, String)> = Vec::new();
    {
        let root = BitMapBackend::with_buffer(&mut buf, (width, height)).into_drawing_area();
        let err = |e: DrawingAreaErrorKind<_>| format!("drawing failed: {e:?}");
        let (x0, x1, y0, y1) = (
            left as i32,
            (left + pw) as i32,
            top as i32,
            (top + ph) as i32,
        );
        for k in 0..=5 {
            let (x, y) = (
                xlo + (xhi - xlo) * k as f64 / 5.0,
                ylo + (yhi - ylo) * k as f64 / 5.0,
            );
            root.draw(&PathElement::new(vec![(px(x), y0), (px(x), y1)], GRID))
                .map_err(err)?;
            root.draw(&PathElement::new(vec![(x0, py(y)), (x1, py(y))], GRID))
                .map_err(err)?;
            let (lx, ly) = (fmt_sci(x), fmt_sci(y));
            text.push((px(x) - text_width(&lx, 2) as i32 / 2, y1 + 10, lx));
            text.push((x0 - text_width(&ly, 2) as i32 - 8, py(y) - 7, ly));
        }
        root.draw(&Rectangle::new(
            [(x0, y0), (x1, y1)],
            RGBColor(120, 120, 120).stroke_width(1),
        ))
        .map_err(err)?;
        let line: Vec<(i32, i32)> = points.iter().map(|&(x, y)| (px(x), py(y))).collect();
        root.draw(&PathElement::new(line, LINE.stroke_width(2)))
            .map_err(err)?;
        for &(x, y) in marks {
            root.draw(&Circle::new((px(x), py(y)), 7, MARK.stroke_width(2)))
                .map_err(err)?;
        }
        root.present().map_err(err)?;
    }
    for (x, y, s) in &text {
        draw_text(
            &mut buf,
            w,
            h,
            (*x).max(0) as u32,
            (*y).max(0) as u32,
            2,
            TEXT,
            s,
        );
    }
    draw_text(&mut buf, w, h, 12, 10, 2, TEXT, title);
    draw_text(&mut buf, w, h, 12, top as u32 - 34, 2, TEXT, labels.1);
    let xw = text_width(labels.0, 2);
    draw_text(
        &mut buf,
        w,
        h,
        (left as u32 + (pw as u32).saturating_sub(xw) / 2).min(width.saturating_sub(xw)),
        height - 26,
        2,
        TEXT,
        labels.0,
    );
    encode_png(&buf, width, height)
}
