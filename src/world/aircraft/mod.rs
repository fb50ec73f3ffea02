//! The follower's 6-DOF plant (seed Chapter 7, (7.15)-(7.19)): aircraft data,
//! aerodynamics and thrust, actuators, equations of motion over a flat state, air data for the
//! flight controller, and trim.
//!
//! Use: load [`AircraftParams`] (e.g. [`AircraftParams::seed_follower`]), build an
//! [`Aircraft`], trim it with [`trim_level_flight`], pack the trimmed [`AircraftState`] into
//! the simulation's state vector, and each tick call [`Aircraft::derivative`] inside
//! [`crate::integrate::Rk4::step`] with the controller's [`Controls`] and the
//! [`crate::world::atmosphere::AtmosphereSample`] of that tick, then [`Aircraft::normalize`].

pub mod actuators;
pub mod aero;
pub mod air_data;
pub mod dynamics;
pub mod params;
pub mod state;
pub mod trim;

pub use actuators::{ActuatorLimits, Actuators};
pub use aero::{AirAngles, CoefficientValues, ControlEffectiveness, Loads};
pub use air_data::AirData;
pub use dynamics::Aircraft;
pub use params::{AircraftFileError, AircraftParams};
pub use state::{AircraftState, Controls, STATE_LEN};
pub use trim::{Trim, TrimError, TrimRequest, trim_level_flight};
