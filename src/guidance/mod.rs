//! Guidance: the adaptive laws that turn the scaled relative position r into a follower
//! command ([`law`] chooses between [`velocity`] and [`acceleration`]), with what they share:
//! the command frames ([`command`]), the shaping of the scaled command ([`shaping`]), the
//! intelligent excitation ([`excitation`]), the compensation for a follower that does not
//! realise the command ([`compensation`]) and the signals in and out ([`signals`]). The
//! projection bounds of the laws' estimates are [`crate::projection`]'s.

pub mod acceleration;
pub mod command;
pub mod compensation;
pub mod excitation;
pub mod law;
pub mod on_estimate;
pub mod shaping;
pub mod signals;
pub mod velocity;
pub mod velocity_estimator;

pub use signals::{FollowerCommand, GuidanceInput, GuidanceOutput};
