//! Results, exports and file writing.
pub mod atomic;
pub mod csv;
pub mod curve_plot;
pub mod footprint;
pub mod formats;
pub mod indent;
pub mod initial;
pub mod obj;
pub mod plot;
pub mod plot_data;
pub mod results;
pub mod stability;
pub mod states;
pub mod text;
pub mod vtk;
pub mod xy_plot;
