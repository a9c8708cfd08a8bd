//! Elastic gridshells: the Chebyshev net on the sphere and (later) the hemisphere form-finding job.
pub mod chebyshev;
