//! The CPU image pipeline: from an RGBA8 frame to the target's centroid and maximal length in
//! pixels (3.1)-(3.7), with a status saying whether to trust them; plus the geometric ground
//! truth to compare with, and an overlay to look at.
//!
//! One frame, in order:
//! 1. `background`: a per-channel quadratic colour surface fitted robustly to the image border,
//!    and the background noise σ (uniform skies, gradients at any tilt, Gaussian noise).
//! 2. `segment`: candidates (colour distance to the background ≥ threshold), per-pixel coverage
//!    α ∈ [0, 1] for anti-aliased edges, binary mask (α ≥ 0.5 or interior).
//! 3. `components`: 8-connected blobs of the mask; [`BlobSelection`] picks one.
//! 4. `measure`: coverage-weighted centroid (ring of partly covered pixels included), and the
//!    maximum Feret diameter (`feret`: hull + rotating calipers) of sub-pixel outline points
//!    (`edge_points`: the straight edge each edge pixel's coverage implies, plus corners where
//!    straight edges meet).
//! 5. [`BlobStatus`]: `Ok`, `NotFound`, `Truncated` (touches the border), `TooSmall`.
//!
//! A tracking camera measures only a region of the image: [`TrackingWindow`] predicts it from
//! the last measurement and the follower's attitude, and [`VisionPipeline::measure_region`]
//! measures it, in the image's coordinates.
//!
//! Pixel conventions are those of [`crate::render::camera`]: pixel (i, j) covers
//! [i, i+1) x [j, j+1), u right, v down; [`BlobMeasurement::image_measurement`] converts to the
//! seed's (yI, zI, bI) (3.1).

mod background;
mod components;
mod config;
mod edge_points;
mod feret;
mod font;
mod image_measurement;
mod image_view;
mod measure;
pub mod overlay;
mod pipeline;
mod reference;
mod segment;
pub mod silhouette;
mod subpixel_edge;
#[cfg(test)]
mod synthetic;
mod target_colour;
#[cfg(test)]
mod tests;
pub mod tracking;
pub mod truth;

pub use components::{BlobSummary, PixelBox};
pub use config::{
    BackgroundSource, BlobSelection, DetectionThreshold, SegmentationConfig, TargetColour,
    VisionConfig, VisionConfigError,
};
pub use feret::{FeretDiameter, FeretFinder, PixelPoint, convex_hull_into, max_feret_diameter};
pub use image_measurement::ImageMeasurement;
pub use image_view::ImageSizeError;
pub use pipeline::{BlobMeasurement, BlobStatus, RegionMeasurement, VisionPipeline};
pub use reference::ViewGeometry;
pub use tracking::TrackingWindow;
pub use truth::{ImageTruth, TruthProjector, image_truth};
