//! A Clamp holds its node's three coordinates and its vertex frame (moved to its `move_to`,
//! turned by its `rotate_by`); its reaction has a moment.

use super::{held_info, Builder, Marker, Reported, Site, SupportTag};
use crate::network::info::SupportInfo;
use crate::scene::types::Support;
use crate::scene::FieldError;

pub(super) const NAME: &str = "clamp";
pub(super) const REPORTED: Reported = Reported::Held;
pub(super) const MARKER: Marker = Marker::Square;

pub(super) fn add(b: &mut Builder, s: &Support, at: &Site) -> Result<SupportInfo, FieldError> {
    b.hold(s, at, &[0, 1, 2])?;
    // `network/build/frames.rs` gives every clamped vertex a frame.
    if let Some(f) = at.frame {
        b.hold_frame(s, at, f)?;
    }
    Ok(held_info(s, at, SupportTag::Clamp, at.frame))
}
