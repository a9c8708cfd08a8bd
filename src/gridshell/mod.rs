//! Elastic gridshells: the Chebyshev net on the sphere, the flat footprint of the hemispherical
//! gridshell as a scene, its form finding, and its comparison with the analytic shapes.
pub mod chebyshev;
pub mod fit;
pub mod footprint;
pub mod formfind;
pub mod job;
pub mod options;
pub mod report;
