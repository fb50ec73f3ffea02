//! Off-screen rendering of the target as the follower's camera sees it.
//!
//! [`gpu::GpuContext`] opens a headless wgpu device once; [`mesh::TargetMesh`] holds the
//! target's triangles (the seed aircraft is built by [`aircraft_mesh`] and committed as
//! `assets/target_aircraft.obj`); [`renderer::Renderer`] draws it with the exact pinhole
//! projection of [`camera::CameraIntrinsics`] ([`projection`]) and reads back a
//! [`image::CameraImage`] of the whole image or of an [`region::ImageRegion`] of it.

pub mod aircraft_mesh;
pub mod camera;
pub mod diameter;
pub mod gpu;
pub mod image;
pub mod mesh;
pub mod noise;
mod passes;
mod pipelines;
pub mod projection;
mod readback;
pub mod region;
pub mod renderer;
pub mod scene;
pub mod settings;
mod targets;
mod uniforms;
mod vertices;
pub mod window;

pub use gpu::{GpuContext, GpuError};
pub use image::CameraImage;
pub use mesh::{MeshError, TargetMesh};
pub use readback::ReadbackError;
pub use region::ImageRegion;
pub use renderer::{RenderError, RenderTimings, Renderer};
pub use scene::{Backdrop, CameraInWorld, Clouds, Ground, Sun, WorldScene};
pub use settings::{Background, PixelNoise, RenderSettings, Sky, TargetShading};
