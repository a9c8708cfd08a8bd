//! The commands' jobs beyond a plain solve: each runs the pipeline's flow (`crate::pipeline`:
//! build within limits → solve → equilibrium → results) and adds its own analysis on top:
//! linear buckling (`rodnet buckle`), the states pushes reach (`rodnet states`), indentation
//! (`rodnet indent`) and the eigenmodes at an equilibrium (`rodnet solve --modes`).

pub mod buckle;
pub mod indent;
pub mod modes;
pub mod states;

pub use buckle::{buckle, BuckleError, Buckling};
pub use indent::{indent, IndentError, Indentation};
pub use modes::{analyse_modes, modes_obj, MODE_AMPLITUDE};
pub use states::states;
