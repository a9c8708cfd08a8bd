//! One discrete elastic rod: sections, frames and transport.
pub mod committed_frames;
pub mod frames;
pub mod section;
