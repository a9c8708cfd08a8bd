//! The variables of a network and the state that gives them meaning: the layout of `q`
//! ([`DofLayout`]), the state with DER's reference data ([`State`]) and the ports where rods meet
//! vertex frames ([`Port`]). Everything above (energy terms, the network, the solver adapter)
//! reads variables through these types; this layer imports only `math` and `rod`.

pub mod layout;
pub mod port;
pub mod state;

pub use layout::{DofLayout, Unknowns, VarKind, FIXED};
pub use port::Port;
pub use state::{FrameRef, State};
