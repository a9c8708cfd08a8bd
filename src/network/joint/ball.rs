//! Ball joint (the joint model of Baek et al. 2018 gridshells): the sites share one node and
//! nothing else. No frame is created: a rod passing through the vertex keeps its own bending and
//! twisting stencil there (it stays continuous), and a rod ending there has a free end rotation.
//! Node sharing itself is done by the builder for every kind except translationally elastic
//! joints.

use super::Site;

/// Ball joints add no frames or terms; they exist for the node merge only.
pub fn add(_sites: &[Site]) {}
