//! A Spring holds nothing: its node (and frame) stay free, tied to an anchor that moves with the
//! load factor from rest to `move_to` (turns to `rotate_by`) by translational (rotational)
//! springs, energy terms whose force (moment) is its reaction.

use super::{Builder, Marker, Reported, Site, SupportTag};
use crate::energy::rotational_spring::RotationalSpring;
use crate::energy::spring::Spring;
use crate::network::info::SupportInfo;
use crate::scene::types::Support;
use crate::scene::FieldError;

pub(super) const NAME: &str = "spring";
pub(super) const REPORTED: Reported = Reported::Elastic;
pub(super) const MARKER: Marker = Marker::Ring;

pub(super) fn add(
    b: &mut Builder,
    s: &Support,
    at: &Site,
    stiffness: [f64; 3],
) -> Result<SupportInfo, FieldError> {
    let axes = s.kind.spring_axes();
    let layout = b.layout;
    let out = &mut b.out;
    let spring = stiffness.iter().any(|k| *k != 0.0).then(|| {
        out.springs.push(Spring {
            vars: [0, 1, 2].map(|k| layout.node_coord(at.node, k)),
            stiffness,
            axes,
            anchor: [at.rest_pos, s.move_to.unwrap_or(at.rest_pos)],
        });
        out.springs.len() - 1
    });
    let rotational = s.kind.rotational_stiffness().map(|k| {
        // `network/build/frames.rs` gives the vertex of a rotational spring a frame.
        let frame = at.frame.expect("a rotational spring's vertex has a frame");
        out.rotational.push(RotationalSpring {
            vars: layout.frame(frame),
            frame,
            axes,
            stiffness: k,
            rotate_by: s.rotate_by.unwrap_or([0.0; 3]),
        });
        (out.rotational.len() - 1, frame)
    });
    Ok(SupportInfo {
        rod: s.rod.clone(),
        vertex: s.vertex,
        node: at.node,
        kind: SupportTag::Spring,
        frame: rotational.map(|(_, f)| f),
        spring,
        rotational: rotational.map(|(k, _)| k),
    })
}
