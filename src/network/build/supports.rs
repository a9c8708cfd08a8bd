//! Supports: each scene support placed on the built network and handed to its kind
//! (`network/support/`, one file per kind), which fixes or prescribes its variables or adds its
//! energy terms.

use super::geometry::Rest;
use super::nodes::Numbered;
use crate::network::joint::PortTable;
use crate::network::support::{Builder, Site, Supported};
use crate::scene::FieldError;
use crate::variables::DofLayout;

pub fn apply(
    rest: &Rest,
    net: &Numbered,
    table: &PortTable,
    layout: &DofLayout,
    fixed: &mut [bool],
) -> Result<Supported, FieldError> {
    let supports = &rest.scene.supports;
    let sites: Vec<Site> = supports
        .iter()
        .enumerate()
        .map(|(index, s)| {
            let (r, rnode) = rest.site(&s.rod, s.vertex);
            let node = net.rods[r].nodes[rnode];
            Site {
                index,
                node,
                rest_pos: net.rest_pos[node],
                frame: table
                    .port_of
                    .get(&(r, rnode))
                    .map(|&p| table.ports[p].frame),
            }
        })
        .collect();
    let mut builder = Builder::new(supports, &sites, layout, fixed);
    for (s, at) in supports.iter().zip(&sites) {
        builder.add(s, at)?;
    }
    Ok(builder.finish())
}
