//! The truth: the target's motion, the 6-DOF aircraft's plant, and the air it flies in.

pub mod aircraft;
pub mod atmosphere;
pub mod target;
pub mod trajectory;
