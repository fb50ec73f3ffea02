//! The truth: the target's motion (or a relayed aircraft's), the 6-DOF aircraft's plant, and the air
//! it flies in.

pub mod aircraft;
pub mod atmosphere;
pub mod relay;
pub mod target;
pub mod trajectory;
