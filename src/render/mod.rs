//! Off-screen rendering of the target as the follower's camera sees it.

pub mod camera;
