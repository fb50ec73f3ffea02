//! Flight control of the 6-DOF follower (seed Chapter 7; docs/equations.md, The 6-DOF follower
//! (Chapter 7)): the guidance velocity V_F becomes airspeed and attitude references
//! ([`reference`](mod@reference)), smoothed by prefilters that also give their derivatives
//! ([`prefilter`]); an adaptive backstepping controller with RBF corrections ([`rbf`]) turns
//! them into throttle and surface commands ([`autopilot`], whose steps live in the modules
//! named in its docs).
//!
//! Use: build an [`Autopilot`] from the aircraft data and an
//! [`crate::scenario::AutopilotSection`], start its state with [`Autopilot::initial_state`],
//! and each tick, inside [`crate::integrate::Rk4::step`] over the joint state
//! `[plant | autopilot]`, compute the plant's air data, call [`Autopilot::derivative`] for the
//! controller's slice and feed its [`AutopilotOutput::controls`] to
//! [`crate::world::aircraft::Aircraft::derivative`]; after the step call
//! [`Autopilot::enforce_bounds`] (and the plant's `normalize`).

mod adaptation;
mod attitude;
pub mod autopilot;
mod control_law;
mod energy;
mod inversion;
mod nominal_model;
pub mod prefilter;
mod rate_loop;
pub mod rbf;
pub mod reference;
mod signals;
mod state;
mod velocity_command;
mod wind;

pub use autopilot::Autopilot;
pub use prefilter::{
    FilteredCommand, IntegralPrefilter, SecondOrderFilter, SmoothIntegralPrefilter,
};
pub use rbf::{RBF_CENTRES, RBF_INPUTS, RbfBasis, RbfInput};
pub use reference::VelocityReference;
pub use signals::{AutopilotInput, AutopilotOutput, Saturation, SlotAxis};
pub use state::{AUTOPILOT_STATE_LEN, AutopilotState, autopilot_state_names};
pub use velocity_command::{WeaveGeometry, slot_weave_side, weave_side};
