//! Flight control of the 6-DOF follower (seed Chapter 7; SPEC §7): the guidance velocity V_F
//! becomes airspeed and attitude references ([`reference`](mod@reference)), smoothed by
//! prefilters that also give their derivatives ([`prefilter`]); an adaptive backstepping
//! controller with RBF corrections ([`rbf`]) turns them into throttle and surface commands
//! ([`autopilot`]).
//!
//! Use: build an [`Autopilot`] from the aircraft data and an
//! [`crate::scenario::AutopilotSection`], start its state with [`Autopilot::initial_state`],
//! and each tick, inside [`crate::integrate::Rk4::step`] over the joint state
//! `[plant | autopilot]`, compute the plant's air data, call [`Autopilot::derivative`] for the
//! controller's slice and feed its [`AutopilotOutput::controls`] to
//! [`crate::world::aircraft::Aircraft::derivative`]; after the step call
//! [`Autopilot::enforce_bounds`] (and the plant's `normalize`).

pub mod autopilot;
pub mod prefilter;
pub mod rbf;
pub mod reference;

pub use autopilot::{
    AUTOPILOT_STATE_LEN, Autopilot, AutopilotInput, AutopilotOutput, AutopilotState, Saturation,
    weave_side,
};
pub use prefilter::{
    FilteredCommand, IntegralPrefilter, SecondOrderFilter, SmoothIntegralPrefilter,
};
pub use rbf::{RBF_CENTRES, RBF_INPUTS, RbfBasis, RbfInput};
pub use reference::VelocityReference;
