//! # wingman — vision-in-the-loop aerial tracking
//!
//! A follower aircraft keeps station on (or intercepts) an unknown, manoeuvring target using only
//! a monocular camera.
//!
//! ## The loop and its seams
//!
//! Five stages, each a plain struct that owns its slice of the simulation's state and gets its
//! own configuration; [`sim::Simulation`] builds them, decides every mode that spans stages
//! (which command the follower flies, whether the laws compensate for a follower that does
//! not realise it, where the guidance's measurement comes from) and wires one tick:
//!
//! 1. **sensor** ([`sensing`]): `perfect` r = R/b, `noisy` r*, or the `camera`: an off-screen
//!    renderer ([`render`]) draws the target as the follower's camera sees it and the image
//!    pipeline ([`vision`]) measures its centroid and maximal length; the sensing transform
//!    turns (yI, zI, bI) and the follower's attitude into r*.
//! 2. **estimator** ([`estimation`]): what the guidance is given: the continuous measurement,
//!    or the camera's latest frame held and brought forward by the follower's own motion.
//! 3. **guidance** ([`guidance`]): the velocity or acceleration law turns r (with its own
//!    adaptive estimates, the command frame, the shaping filter and the excitation) into a
//!    [`guidance::FollowerCommand`].
//! 4. **follower** ([`follower`]): realises the command exactly (kinematic), or flies it with
//!    the Chapter 7 flight controller ([`control`]) on the 6-DOF aircraft of [`world`].
//! 5. **recorder** ([`output`]): telemetry, summary, frames and plots.
//!
//! Every continuous state is integrated by one RK4 ([`integrate`]) over one vector; each stage
//! reads and writes its slice through a typed block ([`state_block`]).
//!
//! Modules, in the order data flows (each imports only those before it): [`frames`],
//! [`state_block`], [`linalg`], [`integrate`], [`projection`], [`scenario`], [`world`],
//! [`navigation`], [`render`], [`vision`], [`sensing`], [`estimation`], [`guidance`],
//! [`control`], [`follower`], [`target_aircraft`], [`sim`], [`output`], [`study`].
//!
//! [`projection`] is the seed's projection operator, which the adaptive laws of the guidance
//! and of the flight controller share; [`study`] runs sweeps of many runs (`wingman sweep`).
#![warn(missing_docs)]

pub mod control;
pub mod estimation;
pub mod follower;
pub mod frames;
pub mod guidance;
pub mod integrate;
pub mod linalg;
pub mod navigation;
pub mod output;
pub mod projection;
pub mod render;
pub mod scenario;
pub mod sensing;
pub mod sim;
pub mod state_block;
pub mod study;
pub mod target_aircraft;

pub mod vision;
pub mod world;
