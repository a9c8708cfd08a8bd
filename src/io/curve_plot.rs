//! A force–depth curve on linear axes as a PNG (`rodnet indent --plot`): one series of
//! [`crate::io::xy_plot`], its limit points ringed.

use crate::io::xy_plot::{chart, Axis, Marker, Series};

/// Draws `points` (x, y) joined, `marks` as red rings, with axis labels and a title.
pub fn curve(
    points: &[(f64, f64)],
    marks: &[(f64, f64)],
    labels: (&str, &str),
    title: &str,
    size: (u32, u32),
) -> Result<Vec<u8>, String> {
    let mut series = vec![Series {
        name: "force".into(),
        colour: [31, 119, 180],
        points: points.to_vec(),
        line: true,
        dashed: false,
        marker: Marker::None,
    }];
    if !marks.is_empty() {
        series.push(Series {
            name: "limit point".into(),
            colour: [214, 39, 40],
            points: marks.to_vec(),
            line: false,
            dashed: false,
            marker: Marker::Ring,
        });
    }
    let axis = |label: &str| Axis {
        label: label.into(),
        log: false,
        ticks: None,
    };
    chart(&series, (&axis(labels.0), &axis(labels.1)), title, size)
}
