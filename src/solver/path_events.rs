//! Events on a load-controlled path: where it passed a bifurcation (the state turned unstable
//! and the saddle escape left it) or snapped (a limit point passed under load control: Newton
//! found the sub-step's equilibrium far from the path it was on, through unstable states).
//!
//! Judged once per converged sub-step from the sub-step's start, prediction and end
//! (`Judged`); a bifurcation is located between the sub-step's ends by the curvature of the
//! escape direction at both (`locate`).

use serde::{Deserialize, Serialize};

/// A snap: the end lies farther from the prediction than this many times the predicted motion…
const SNAP_MISS: f64 = 4.0;
/// … and farther than this share of the structure's size (bounding-box diagonal).
const SNAP_SIZE: f64 = 1e-2;

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum EventKind {
    /// The load factor stopped rising along an arc-length path.
    LimitPoint,
    /// The path's state turned unstable and the state left it along negative curvature.
    Bifurcation,
    /// Under load control, the state jumped to another branch past a limit point.
    Snap,
}

impl EventKind {
    pub fn name(self) -> &'static str {
        match self {
            EventKind::LimitPoint => "limit point",
            EventKind::Bifurcation => "bifurcation",
            EventKind::Snap => "snap",
        }
    }
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PathEvent {
    pub kind: EventKind,
    /// The load factor of the solve's loads where it happened (a stage's own loads in a stage).
    pub load_factor: f64,
    /// What happened, in words: the bracket, how far the state moved.
    pub detail: String,
}

/// One converged sub-step, for the judgement: load factors at its ends, positions of the free
/// unknowns at its start, its prediction and its end, and what its Newton iterations did.
pub struct Judged<'a> {
    pub from: f64,
    pub to: f64,
    pub start: &'a [[f64; 3]],
    pub predicted: &'a [[f64; 3]],
    pub end: &'a [[f64; 3]],
    /// Iterations on an indefinite Hessian and saddle escapes during the sub-step.
    pub regularized: usize,
    pub escapes: usize,
}

fn dist(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt()
}

fn largest_distance(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
    a.iter().zip(b).map(|(p, q)| dist(p, q)).fold(0.0, f64::max)
}

fn diagonal(points: &[[f64; 3]]) -> f64 {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in points {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    dist(&lo, &hi)
}

impl Judged<'_> {
    /// A snap: Newton reached the end only through indefinite Hessians, and the end lies far
    /// from the prediction, both against the predicted motion (a smooth branch's prediction
    /// errs by the square of the increment) and against the structure's size. Along a stable
    /// branch the Hessian stays positive definite, however far the state moves.
    pub fn snap(&self) -> Option<PathEvent> {
        let miss = largest_distance(self.end, self.predicted);
        let predicted = largest_distance(self.predicted, self.start);
        let size = diagonal(self.start).max(diagonal(self.end));
        (self.regularized > 0 && miss > SNAP_MISS * predicted && miss > SNAP_SIZE * size).then(
            || PathEvent {
                kind: EventKind::Snap,
                load_factor: self.to,
                detail: format!(
                    "between load factors {:.6} and {:.6} the state jumped {:.3e} m away from the \
                     path it followed ({:.3e} m predicted; structure size {:.3e} m): a limit \
                     point was passed under load control, and the structure snapped to another \
                     equilibrium branch (the results are that branch's state; arc-length \
                     continuation follows the path through the limit point)",
                    self.from, self.to, miss, predicted, size
                ),
            },
        )
    }
}

/// A bifurcation met in a sub-step from `from` to `to`: the escape direction's curvature was
/// `at_start` at the sub-step's start and `at_end` (negative) where it was left. Along the
/// path the tangent stiffness is near linear in the load factor (exactly, on a straight strut's
/// path), so the crossing of zero is interpolated between the two.
pub fn bifurcation(from: f64, to: f64, at_start: f64, at_end: f64) -> PathEvent {
    let at = if at_start > 0.0 && at_end < 0.0 {
        from + (to - from) * at_start / (at_start - at_end)
    } else {
        from
    };
    PathEvent {
        kind: EventKind::Bifurcation,
        load_factor: at,
        detail: format!(
            "between load factors {from:.6} and {to:.6} the path's state turned unstable and the \
             solver left it along negative curvature (crossing interpolated at {at:.6}); the \
             results are the branch it went to"
        ),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_far_end_reached_through_indefinite_steps_is_a_snap() {
        let start = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]];
        let predicted = [[0.0, 0.0, -0.01], [1.0, 0.0, 0.0]];
        let end = [[0.0, 0.0, -0.5], [1.0, 0.0, 0.0]];
        let mut j = Judged {
            from: 0.4,
            to: 0.5,
            start: &start,
            predicted: &predicted,
            end: &end,
            regularized: 3,
            escapes: 0,
        };
        assert_eq!(j.snap().map(|e| e.kind), Some(EventKind::Snap));
        // Through positive definite Hessians: a soft but stable branch.
        j.regularized = 0;
        assert!(j.snap().is_none());
        // Near the prediction: a converging sub-step.
        j.regularized = 3;
        let near = [[0.0, 0.0, -0.02], [1.0, 0.0, 0.0]];
        j.end = &near;
        assert!(j.snap().is_none());
    }

    #[test]
    fn a_linear_stiffness_is_interpolated_to_its_zero() {
        let e = bifurcation(0.0, 1.0, 3.0, -1.0);
        assert!((e.load_factor - 0.75).abs() < 1e-15);
        // Already unstable at the start: the bracket's start.
        assert_eq!(bifurcation(0.2, 0.4, -1.0, -2.0).load_factor, 0.2);
    }
}
