//! One discrete elastic rod: sections, frames and transport.
pub mod frames;
pub mod section;
