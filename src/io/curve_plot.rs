//! A force–depth curve on linear axes as a PNG (`rodnet indent --plot`): series of
//! [`crate::io::xy_plot`], solid where the state is stable and dashed where it is not, its
//! limit points ringed.

use crate::io::xy_plot::{chart, Axis, Marker, Series};

/// Draws `points` (x, y) joined, `marks` as red rings, with axis labels and a title. With
/// `stable` (one flag per point) a segment between two stable points is solid and any other
/// dashed, each kind named once in the legend; without it (empty) the curve is one series.
pub fn curve(
    points: &[(f64, f64)],
    stable: &[bool],
    marks: &[(f64, f64)],
    labels: (&str, &str),
    title: &str,
    size: (u32, u32),
) -> Result<Vec<u8>, String> {
    let mut series = runs(points, stable);
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

/// The curve as runs of stable (solid) and unstable (dashed) segments.
fn runs(points: &[(f64, f64)], stable: &[bool]) -> Vec<Series> {
    let line = |name: &str, dashed: bool, points: Vec<(f64, f64)>| Series {
        name: name.into(),
        colour: [31, 119, 180],
        points,
        line: true,
        dashed,
        marker: Marker::None,
    };
    if stable.len() != points.len() || stable.iter().all(|&s| s) {
        return vec![line("force", false, points.to_vec())];
    }
    let mut out: Vec<Series> = Vec::new();
    let (mut named_stable, mut named_unstable) = (false, false);
    for k in 1..points.len() {
        let solid = stable[k - 1] && stable[k];
        match out.last_mut() {
            Some(s) if s.dashed != solid => s.points.push(points[k]),
            _ => {
                let named = if solid {
                    &mut named_stable
                } else {
                    &mut named_unstable
                };
                let name = match (std::mem::replace(named, true), solid) {
                    (true, _) => "",
                    (false, true) => "force, stable",
                    (false, false) => "force, unstable",
                };
                out.push(line(name, !solid, vec![points[k - 1], points[k]]));
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stable_runs_are_solid_and_unstable_ones_dashed_named_once() {
        let p: Vec<(f64, f64)> = (0..6).map(|k| (k as f64, k as f64)).collect();
        let s = runs(&p, &[true, true, false, false, true, true]);
        let kinds: Vec<(bool, usize, &str)> = s
            .iter()
            .map(|s| (s.dashed, s.points.len(), s.name.as_str()))
            .collect();
        assert_eq!(
            kinds,
            [
                (false, 2, "force, stable"),
                (true, 4, "force, unstable"),
                (false, 2, "")
            ]
        );
        // Unknown or all stable: one series, as before.
        assert_eq!(runs(&p, &[]).len(), 1);
        assert_eq!(runs(&p, &[true; 6])[0].name, "force");
    }
}
