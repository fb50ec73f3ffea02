//! # wingman — vision-in-the-loop aerial tracking
//!
//! A follower aircraft keeps station on (or intercepts) an unknown, manoeuvring target using only
//! a monocular camera. One simulation tick: the target's pose comes from its motion model and the
//! follower's from its plant; on camera ticks an off-screen renderer draws the target as the
//! follower's camera sees it and the image pipeline measures its centroid and maximal length in
//! pixels; the sensing transform turns (yI, zI, bI) and the follower's attitude into the scaled
//! relative position r; the adaptive guidance law (with its estimator and excitation) turns r
//! into a velocity or acceleration command; the follower realises that command (kinematically,
//! or through a flight controller on a 6-DOF aircraft); the recorder logs every stage.
//!
//! Modules, in the order data flows: [`frames`], [`scenario`], [`world`], [`sensing`],
//! [`noisy_sensor`], [`sensor`], [`guidance`], [`control`], [`follower`], [`integrate`], [`sim`],
//! [`output`].
#![warn(missing_docs)]

pub mod control;
pub mod estimation;
pub mod follower;
pub mod frames;
pub mod guidance;
pub mod integrate;
pub mod linalg;
pub mod output;
pub mod render;
pub mod scenario;
pub mod sensing;
pub mod sim;
pub mod state_block;

pub mod vision;
pub mod world;
