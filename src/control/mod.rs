//! Flight control of the 6-DOF follower (seed Chapter 7; SPEC §7): the guidance velocity V_F
//! becomes airspeed and attitude references ([`reference`](mod@reference)), smoothed by
//! prefilters that also give their derivatives ([`prefilter`]); RBF networks ([`rbf`]) carry
//! the adaptive corrections.

pub mod prefilter;
pub mod rbf;
pub mod reference;

pub use prefilter::{
    FilteredCommand, IntegralPrefilter, SecondOrderFilter, SmoothIntegralPrefilter,
};
pub use rbf::{RBF_CENTRES, RBF_INPUTS, RbfBasis, RbfInput};
pub use reference::VelocityReference;
