//! Guidance: the adaptive laws that turn the scaled relative position r into a follower
//! command, with their projection bounds and the intelligent excitation.

pub mod acceleration;
pub mod command;
pub mod excitation;
pub mod law;
pub mod projection;
pub mod velocity;
