//! Gridshells fitted to a target mesh (`rodnet gridshell fit`): the Chebyshev net on the
//! surface by the compass construction (`compass`, `net`), the flat footprint that builds it
//! (`footprint`), its form finding and comparison with the target (`job`).
pub mod compass;
pub mod footprint;
pub mod job;
pub mod net;
pub mod report;
pub mod size;
