//! Off-screen rendering of the target as the follower's camera sees it.
//!
//! [`gpu::GpuContext`] opens a headless wgpu device once; [`mesh::TargetMesh`] holds the
//! target's triangles (the seed aircraft is built by [`aircraft_mesh`] and committed as
//! `assets/target_aircraft.obj`).

pub mod aircraft_mesh;
pub mod camera;
pub mod gpu;
pub mod mesh;

pub use gpu::{GpuContext, GpuError};
pub use mesh::{MeshError, TargetMesh};
