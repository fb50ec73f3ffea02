//! The truth: the target's motion, the follower's plant, and the air it flies in.

pub mod aircraft;
pub mod atmosphere;
pub mod kinematic;
pub mod target;
