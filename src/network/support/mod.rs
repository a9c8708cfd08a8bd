//! Support kinds, one file each: what a kind fixes or prescribes when the network is built, how
//! its reaction is reported at equilibrium, and the marker a picture draws for it. The scene's
//! [`SupportKind`] (RON data) becomes a [`SupportTag`] here; everything downstream (equilibrium,
//! results, pictures) knows a support's kind only as that tag, and the results JSON only by
//! [`SupportTag::name`].

mod clamp;
mod pin;
mod roller;
mod spring;

use std::collections::{HashMap, HashSet};

use crate::energy::rotational_spring::RotationalSpring;
use crate::energy::spring::Spring;
use crate::network::info::SupportInfo;
pub use crate::network::info::SupportTag;
use crate::network::model::{Prescribed, PrescribedRotation};
use crate::scene::types::{Support, SupportKind};
use crate::scene::FieldError;
use crate::variables::DofLayout;

/// How a kind's reaction is reported.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Reported {
    /// The gradient at the variables it fixes (the first support on a node takes its force, the
    /// first on a frame its moment).
    Held,
    /// Its energy terms' own force and moment; it fixes nothing.
    Elastic,
}

/// What a picture draws at a support's node.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Marker {
    /// A filled square on the node.
    Square,
    /// A filled triangle under the node (also for supports whose kind the results do not say).
    Triangle,
    /// An open triangle under the node.
    OpenTriangle,
    /// A ring around the node.
    Ring,
}

impl Marker {
    /// The legend's symbol for this marker.
    pub fn glyph(self) -> &'static str {
        match self {
            Marker::Square => "■",
            Marker::Triangle => "▲",
            Marker::OpenTriangle => "△",
            Marker::Ring => "○",
        }
    }
}

impl SupportTag {
    pub const ALL: [SupportTag; 4] = [
        SupportTag::Pin,
        SupportTag::Clamp,
        SupportTag::Roller,
        SupportTag::Spring,
    ];

    pub fn of(kind: &SupportKind) -> SupportTag {
        match kind {
            SupportKind::Pin => SupportTag::Pin,
            SupportKind::Clamp => SupportTag::Clamp,
            SupportKind::Roller { .. } => SupportTag::Roller,
            SupportKind::Spring { .. } => SupportTag::Spring,
        }
    }

    /// The kind's name in the results JSON (contract: never renamed).
    pub fn name(self) -> &'static str {
        match self {
            SupportTag::Pin => pin::NAME,
            SupportTag::Clamp => clamp::NAME,
            SupportTag::Roller => roller::NAME,
            SupportTag::Spring => spring::NAME,
        }
    }

    /// The kind a results JSON names, if this build knows it.
    pub fn from_name(name: &str) -> Option<SupportTag> {
        SupportTag::ALL.into_iter().find(|t| t.name() == name)
    }

    pub fn reported(self) -> Reported {
        match self {
            SupportTag::Pin => pin::REPORTED,
            SupportTag::Clamp => clamp::REPORTED,
            SupportTag::Roller => roller::REPORTED,
            SupportTag::Spring => spring::REPORTED,
        }
    }

    pub fn marker(self) -> Marker {
        match self {
            SupportTag::Pin => pin::MARKER,
            SupportTag::Clamp => clamp::MARKER,
            SupportTag::Roller => roller::MARKER,
            SupportTag::Spring => spring::MARKER,
        }
    }
}

/// The Rollers with a general normal on one node: (node, their normals, a point of their
/// planes at λ = 0 and 1).
pub type Slanted = (usize, Vec<[f64; 3]>, [[f64; 3]; 2]);

/// What the supports add to the model.
pub struct Supported {
    pub prescribed: Vec<Prescribed>,
    /// Elastic supports: their energy terms.
    pub springs: Vec<Spring>,
    pub rotational: Vec<RotationalSpring>,
    /// Rollers with a general normal, by node.
    pub slanted: Vec<Slanted>,
    pub rotations: Vec<PrescribedRotation>,
    pub infos: Vec<SupportInfo>,
}

/// Where a scene support sits in the built network.
#[derive(Debug, Clone, Copy)]
pub struct Site {
    /// Its index in the scene's supports.
    pub index: usize,
    pub node: usize,
    pub rest_pos: [f64; 3],
    /// The vertex frame at its rod vertex, if the vertex has one.
    pub frame: Option<usize>,
}

/// The supports' build, one support after another; it keeps what several supports on one node
/// or frame must agree on.
pub struct Builder<'a> {
    out: Supported,
    layout: &'a DofLayout,
    fixed: &'a mut [bool],
    /// Nodes that a Roller with a general normal holds: all Rollers there hold by projection.
    slanted_nodes: HashSet<usize>,
    moved: HashMap<usize, [f64; 3]>,
    turned: HashMap<usize, (usize, Option<[f64; 3]>)>,
}

impl<'a> Builder<'a> {
    /// `sites` in the order of `supports`; `fixed` receives the variables the supports hold.
    pub fn new(
        supports: &[Support],
        sites: &[Site],
        layout: &'a DofLayout,
        fixed: &'a mut [bool],
    ) -> Builder<'a> {
        Builder {
            out: Supported {
                prescribed: Vec::new(),
                springs: Vec::new(),
                rotational: Vec::new(),
                slanted: Vec::new(),
                rotations: Vec::new(),
                infos: Vec::new(),
            },
            layout,
            fixed,
            slanted_nodes: roller::slanted_nodes(supports, sites),
            moved: HashMap::new(),
            turned: HashMap::new(),
        }
    }

    /// Adds one support, by its kind.
    pub fn add(&mut self, s: &Support, at: &Site) -> Result<(), FieldError> {
        let info = match s.kind {
            SupportKind::Pin => pin::add(self, s, at)?,
            SupportKind::Clamp => clamp::add(self, s, at)?,
            SupportKind::Roller { normal } => roller::add(self, s, at, normal)?,
            SupportKind::Spring { stiffness, .. } => spring::add(self, s, at, stiffness)?,
        };
        self.out.infos.push(info);
        Ok(())
    }

    pub fn finish(self) -> Supported {
        self.out
    }

    /// Holds coordinates `coords` of the support's node, moved to its `move_to` if it has one.
    fn hold(&mut self, s: &Support, at: &Site, coords: &[usize]) -> Result<(), FieldError> {
        for &k in coords {
            self.fixed[self.layout.node_coord(at.node, k)] = true;
        }
        let Some(target) = s.move_to.filter(|_| !coords.is_empty()) else {
            return Ok(());
        };
        match self.moved.insert(at.node, target) {
            Some(prev) if prev != target => Err(FieldError::new(
                "supports",
                at.index,
                "move_to",
                "this node already has a different `move_to` from another support".into(),
            )),
            Some(_) => Ok(()),
            None => {
                let (layout, rest_pos) = (self.layout, at.rest_pos);
                self.out
                    .prescribed
                    .extend(coords.iter().map(|&k| Prescribed {
                        var: layout.node_coord(at.node, k),
                        start: rest_pos[k],
                        end: target[k],
                    }));
                Ok(())
            }
        }
    }

    /// Holds vertex frame `f`, turned by the support's `rotate_by` if it has one. Clamps on one
    /// frame (one rod vertex twice, or rods of one Rigid or Hinge joint) must agree on how it
    /// turns: held, or rotated by the same rotation vector.
    fn hold_frame(&mut self, s: &Support, at: &Site, f: usize) -> Result<(), FieldError> {
        match self.turned.insert(f, (at.index, s.rotate_by)) {
            Some((k, prev)) if prev != s.rotate_by => {
                let field = if s.rotate_by.is_some() {
                    "rotate_by"
                } else {
                    "kind"
                };
                Err(FieldError::new(
                    "supports",
                    at.index,
                    field,
                    frame_contradiction(k, prev, s.rotate_by),
                ))
            }
            Some(_) => Ok(()),
            None => {
                if let Some(rotation) = s.rotate_by {
                    self.out
                        .rotations
                        .push(PrescribedRotation { frame: f, rotation });
                }
                Ok(())
            }
        }
    }
}

/// The record of a support that holds variables (its reaction is the gradient there).
fn held_info(s: &Support, at: &Site, kind: SupportTag, frame: Option<usize>) -> SupportInfo {
    SupportInfo {
        rod: s.rod.clone(),
        vertex: s.vertex,
        node: at.node,
        kind,
        frame,
        spring: None,
        rotational: None,
    }
}

/// Why a clamp that turns its frame by `now` (or holds it) contradicts supports[`k`], which
/// clamps the same frame and turns it by `prev` (or holds it).
fn frame_contradiction(k: usize, prev: Option<[f64; 3]>, now: Option<[f64; 3]>) -> String {
    let what = match (prev, now) {
        (Some(a), Some(b)) => format!("rotates it by {a:?}, not {b:?}"),
        (Some(a), None) => {
            format!("rotates it by {a:?}, but this clamp holds it; give both the same `rotate_by`")
        }
        (None, Some(_)) => {
            "holds it, but this clamp rotates it; give both the same `rotate_by`".into()
        }
        (None, None) => unreachable!("equal motions do not contradict"),
    };
    format!("supports[{k}] clamps the same vertex frame (one joint or vertex) and {what}")
}
