//! A Roller keeps its node on a plane: with a normal along x, y or z it holds (and moves) that
//! one coordinate; with a general normal the node keeps its coordinates and all Rollers on it
//! hold it by projection (`network/roller.rs`).

use std::collections::HashSet;

use super::{held_info, Builder, Marker, Reported, Site, SupportTag};
use crate::network::info::SupportInfo;
use crate::scene::types::{Support, SupportKind};
use crate::scene::FieldError;

pub(super) const NAME: &str = "roller";
pub(super) const REPORTED: Reported = Reported::Held;
pub(super) const MARKER: Marker = Marker::OpenTriangle;

/// The nodes of Rollers with a general normal.
pub(super) fn slanted_nodes(supports: &[Support], sites: &[Site]) -> HashSet<usize> {
    supports
        .iter()
        .zip(sites)
        .filter(|(s, _)| {
            matches!(s.kind, SupportKind::Roller { .. }) && s.kind.roller_axis().is_none()
        })
        .map(|(_, at)| at.node)
        .collect()
}

pub(super) fn add(
    b: &mut Builder,
    s: &Support,
    at: &Site,
    normal: [f64; 3],
) -> Result<SupportInfo, FieldError> {
    if b.slanted_nodes.contains(&at.node) {
        let through = [at.rest_pos, s.move_to.unwrap_or(at.rest_pos)];
        match b.out.slanted.iter_mut().find(|e| e.0 == at.node) {
            Some(e) => e.1.push(normal),
            None => b.out.slanted.push((at.node, vec![normal], through)),
        }
    } else if let Some(k) = s.kind.roller_axis() {
        b.hold(s, at, &[k])?;
    }
    Ok(held_info(s, at, SupportTag::Roller, None))
}
