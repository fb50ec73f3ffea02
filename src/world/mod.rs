//! The truth: the target's motion and the follower's plant.

pub mod aircraft;
pub mod atmosphere;
pub mod target;
