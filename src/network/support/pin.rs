//! A Pin holds its node's three coordinates (moved to its `move_to`); rotations stay free.

use super::{held_info, Builder, Marker, Reported, Site, SupportTag};
use crate::network::info::SupportInfo;
use crate::scene::types::Support;
use crate::scene::FieldError;

pub(super) const NAME: &str = "pin";
pub(super) const REPORTED: Reported = Reported::Held;
pub(super) const MARKER: Marker = Marker::Triangle;

pub(super) fn add(b: &mut Builder, s: &Support, at: &Site) -> Result<SupportInfo, FieldError> {
    b.hold(s, at, &[0, 1, 2])?;
    Ok(held_info(s, at, SupportTag::Pin, None))
}
