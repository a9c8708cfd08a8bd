//! The configuration of a network: every variable plus the reference data that DER keeps from
//! the last accepted iterate (edge reference frames, joint-frame rotations, unwrapped twists).

use crate::math::vec::{frame_orthonormalize, frame_rotate, Frame};
use crate::rod::frames::EdgeRef;

/// Rotation reference of a vertex frame (joint, clamp or loaded vertex). The frame's current
/// rotation is exp(ω̂)·`rotation`, with ω the frame's three variables (zero after each commit).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrameRef {
    pub rotation: Frame,
    /// Sum of all committed increments ω: the frame's accumulated rotation vector, the conjugate
    /// of a dead torque (exact for rotations about a fixed axis).
    pub accumulated: [f64; 3],
}

impl FrameRef {
    pub fn identity() -> Self {
        FrameRef {
            rotation: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            accumulated: [0.0; 3],
        }
    }

    /// Folds an increment ω into the reference rotation.
    pub fn commit(&mut self, w: [f64; 3]) {
        self.rotation = frame_orthonormalize(&frame_rotate(w, &self.rotation));
        for k in 0..3 {
            self.accumulated[k] += w[k];
        }
    }
}

#[derive(Debug, Clone)]
pub struct State {
    /// Every variable: node coordinates, edge twist angles, frame rotation increments, hinge
    /// angles, and one always-zero variable.
    pub q: Vec<f64>,
    pub edges: Vec<EdgeRef>,
    pub frames: Vec<FrameRef>,
    /// Last accepted (unwrapped) reference twist of each twist term, for 2π unwrapping.
    pub twist_prev: Vec<f64>,
    /// Fraction of the external loads applied (load stepping).
    pub load_factor: f64,
}
