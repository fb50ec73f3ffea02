//! Trajectory sources for the target (docs/equations.md, Trajectory sources for the target):
//! waypoints and seeded random manoeuvres, flown by a kinematic point mass inside the
//! `[target]` limits, and recorded tracks played back from CSV files. Each gives a
//! [`SampledTrack`]: knots of position, velocity and acceleration interpolated by quintic
//! Hermite polynomials, which the simulation uses as its [`crate::world::target::TargetModel`].

mod point_mass;
mod random;
mod recorded;
mod sampled;
mod waypoints;

pub use random::{RANDOM_TRACK_SEED_SALT, random_track};
pub use recorded::{TrackError, read_track};
pub use sampled::{Knot, SampledTrack};
pub use waypoints::{reach_radius_ft, waypoint_track};
