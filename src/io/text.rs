//! Text in the pictures: DejaVu Sans (compiled in from the `dejavu` crate, so no system font
//! is needed) drawn anti-aliased by plotters' `ab_glyph` backend.

use std::sync::Once;

use plotters::prelude::*;
use plotters::style::{register_font, FontStyle};

/// The name the font is registered under.
const FAMILY: &str = "rodnet-sans";

fn font(size: u32) -> FontDesc<'static> {
    static REGISTER: Once = Once::new();
    REGISTER.call_once(|| {
        // The font is a fixed, valid file; a failure would show as missing text, which the
        // picture tests catch.
        let _ = register_font(FAMILY, FontStyle::Normal, dejavu::sans::regular());
    });
    (FAMILY, size as f64).into_font()
}

/// Font size in pixels of text at `scale` 1 (small) or 2 (normal).
pub fn size(scale: u32) -> u32 {
    4 + 7 * scale
}

/// Width in pixels of `s` at `scale`.
pub fn text_width(s: &str, scale: u32) -> u32 {
    font(size(scale)).box_size(s).map_or(0, |(w, _)| w)
}

/// Draws `s` in an RGB buffer of `w` × `h` pixels with the top of its capitals near `y`.
#[allow(clippy::too_many_arguments)]
pub fn draw_text(
    buf: &mut [u8],
    w: usize,
    h: usize,
    x: u32,
    y: u32,
    scale: u32,
    rgb: [u8; 3],
    s: &str,
) {
    let px = size(scale);
    // plotters' ab_glyph backend puts the baseline half a size below the given point; capitals
    // rise about 0.73 of a size above the baseline.
    let y = y as i32 + (0.23 * px as f64).round() as i32;
    let root = BitMapBackend::with_buffer(buf, (w as u32, h as u32)).into_drawing_area();
    let style = font(px).color(&RGBColor(rgb[0], rgb[1], rgb[2]));
    let _ = root.draw(&Text::new(s.to_string(), (x as i32, y), style));
    let _ = root.present();
}
