//! The frame-to-measurement pipeline: background model, segmentation, connected components,
//! blob selection, centroid and maximal length. [`VisionPipeline`] owns every scratch buffer,
//! so measuring frames of an unchanged size allocates nothing once the buffers have grown.
//!
//! [`VisionPipeline::measure_region`] measures the pixels of a region of the image only (a
//! tracking camera looks where the target is predicted to be), with the background
//! fitted on the region's border, and returns the measurement in the image's coordinates. It
//! equals the whole image's measurement when the region's border is background like the
//! image's (noise-free: the same colour surface) and no blob comes within
//! [`VisionPipeline::region_clearance_px`] of an edge of the region inside the image; when
//! one does, it says so, and the caller measures the whole image instead.

use super::ImageMeasurement;
use crate::render::camera::CameraIntrinsics;
use crate::render::region::ImageRegion;
use crate::scenario::BearingPoint;

use super::background::{BackgroundFitter, BackgroundModel, QUANTISATION_SIGMA};
use super::components::{BlobSummary, ComponentLabeller, PixelBox};
use super::config::{BlobSelection, VisionConfig, VisionConfigError};
use super::feret::FeretDiameter;
use super::image_view::{ImageSizeError, RgbaView};
use super::measure::{BlobGeometry, BlobMeasurer, BlobToMeasure};
use super::reference::{DEFAULT_RING_RADIUS_PX, MotionReference, ViewGeometry};
use super::segment::{CoverageModel, Segmenter};
use super::target_colour::LearnedColour;

/// The local colour model's ring radius per expected maximal length: beyond half the length,
/// with room for the target to grow or turn between frames.
const RING_PER_LENGTH: f64 = 0.65;
/// And beyond the anti-aliased edge, px.
const RING_MARGIN_PX: f64 = 4.0;
/// Edge points need a coverage of at least this many noise standard deviations of the coverage
/// (σ / contrast): the debiased coverage of a background pixel exceeds 3.6 σ/contrast with
/// probability 1e-3 (χ²(3) quantile 16.3, minus the 3 subtracted).
const EDGE_MIN_COVERAGE_SIGMAS: f64 = 4.0;
/// Bounds of the edge-point coverage cut: at least 0.1 (a pixel can be 10% covered by noise-free
/// rounding artefacts of the renderer), at most 0.5.
const EDGE_MIN_COVERAGE_RANGE: (f64, f64) = (0.1, 0.5);

/// How trustworthy a frame's measurement is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BlobStatus {
    /// A blob inside the image, at least `min_pixel_count` pixels.
    Ok,
    /// No target pixel at all (or an empty image).
    NotFound,
    /// The measured blob touches the image border: centroid and length are of the visible part.
    Truncated,
    /// Every blob is smaller than `min_pixel_count` (the largest is measured), or the one
    /// selected has no measurable length.
    TooSmall,
    /// The tracked target joined to another blob (a merge, `camera.merges = "bearing"`): the
    /// joined blob is measured; its centroid lies near the target's, its length is not the
    /// target's.
    Merged,
}

impl BlobStatus {
    /// Short upper-case name for logs and overlays: OK, LOST, TRUNC, SMALL, MERGE.
    pub fn label(&self) -> &'static str {
        match self {
            BlobStatus::Ok => "OK",
            BlobStatus::NotFound => "LOST",
            BlobStatus::Truncated => "TRUNC",
            BlobStatus::TooSmall => "SMALL",
            BlobStatus::Merged => "MERGE",
        }
    }
}

/// What the image pipeline measured in one frame, in pixel coordinates (u right, v down).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BlobMeasurement {
    /// Whether the numbers below can be trusted.
    pub status: BlobStatus,
    /// Coverage-weighted centroid, column, px (NaN when `NotFound`).
    pub centroid_u_px: f64,
    /// Coverage-weighted centroid, row, px (NaN when `NotFound`).
    pub centroid_v_px: f64,
    /// Maximal length (maximum Feret diameter of the sub-pixel edge), px (NaN when `NotFound`).
    pub max_length_px: f64,
    /// Silhouette area, the sum of coverage weights, px² (0 when `NotFound`).
    pub area_px: f64,
    /// Mask pixels in the measured blob.
    pub pixel_count: usize,
    /// Bounding box of the measured blob's mask pixels.
    pub bbox: Option<PixelBox>,
    /// Ends of the maximal length, for overlays.
    pub feret: Option<FeretDiameter>,
    /// Blobs found in the frame (all sizes).
    pub blob_count: usize,
    /// Estimated per-channel background noise, grey levels (NaN for an empty image).
    pub background_noise_sigma: f64,
}

impl BlobMeasurement {
    fn not_found(blob_count: usize, background_noise_sigma: f64) -> Self {
        Self {
            status: BlobStatus::NotFound,
            centroid_u_px: f64::NAN,
            centroid_v_px: f64::NAN,
            max_length_px: f64::NAN,
            area_px: 0.0,
            pixel_count: 0,
            bbox: None,
            feret: None,
            blob_count,
            background_noise_sigma,
        }
    }

    /// The unit direction of the maximal length in the seed's image coordinates (yI right,
    /// zI up), either sense; `None` without a maximal length of positive length.
    pub fn length_direction(&self) -> Option<[f64; 2]> {
        let feret = self.feret?;
        let (dy, dz) = (
            feret.end.u_px - feret.start.u_px,
            feret.start.v_px - feret.end.v_px,
        );
        let length = dy.hypot(dz);
        (length > 0.0).then(|| [dy / length, dz / length])
    }

    /// Centroid and maximal length in the seed's image coordinates (3.1) (yI right, zI up, relative to
    /// the principal point), whatever the status except `NotFound` (then `None`): check
    /// `status` before trusting a `Truncated` or `TooSmall` measurement.
    pub fn image_measurement(&self, camera: &CameraIntrinsics) -> Option<ImageMeasurement> {
        self.image_measurement_at(camera, BearingPoint::Centroid)
    }

    /// The measurement with the bearing and elevation taken to `point` of the silhouette.
    pub fn image_measurement_at(
        &self,
        camera: &CameraIntrinsics,
        point: BearingPoint,
    ) -> Option<ImageMeasurement> {
        if self.status == BlobStatus::NotFound {
            return None;
        }
        let (u_px, v_px) = match (point, self.feret) {
            (BearingPoint::LengthMidpoint, Some(f)) => f.midpoint_px(),
            _ => (self.centroid_u_px, self.centroid_v_px),
        };
        let (y_i_px, z_i_px) = camera.image_from_pixel(u_px, v_px);
        Some(ImageMeasurement {
            y_i_px,
            z_i_px,
            b_i_px: self.max_length_px,
        })
    }
}

/// A measurement of a region of the image, and whether to trust it as the whole image's.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RegionMeasurement {
    /// The measurement, in the image's coordinates (its `Truncated` status means the blob
    /// touches the region's border).
    pub blob: BlobMeasurement,
    /// A blob of at least `min_pixel_count` mask pixels comes within
    /// [`VisionPipeline::region_clearance_px`] of an edge of the region that is inside the
    /// image: the target may reach beyond the region, so the measurement may differ from the
    /// whole image's.
    pub reaches_inner_edge: bool,
}

/// Measures the target's centroid and maximal length in RGBA frames; reuse one per camera.
#[derive(Debug, Clone)]
pub struct VisionPipeline {
    config: VisionConfig,
    background: BackgroundFitter,
    segmenter: Segmenter,
    labeller: ComponentLabeller,
    measurer: BlobMeasurer,
    /// Per-pixel backgrounds, with `config.motion_reference`.
    motion: Option<MotionReference>,
    /// The target's colour, with `config.target_colour_tolerance_deg` > 0.
    colour: Option<LearnedColour>,
}

impl VisionPipeline {
    /// A pipeline with `config`, after checking it.
    pub fn new(config: VisionConfig) -> Result<Self, VisionConfigError> {
        config.validate()?;
        Ok(Self {
            config,
            background: BackgroundFitter::default(),
            segmenter: Segmenter::default(),
            labeller: ComponentLabeller::default(),
            measurer: BlobMeasurer::default(),
            motion: config.motion_reference.then(MotionReference::default),
            colour: (config.target_colour_tolerance_deg > 0.0)
                .then(|| LearnedColour::new(config.target_colour_tolerance_deg)),
        })
    }

    /// The configuration in use.
    pub fn config(&self) -> &VisionConfig {
        &self.config
    }

    /// How the next frame measured looks into the world, for the previous frame to explain
    /// its background by (`motion_reference` only; None: not known).
    pub fn set_view_geometry(&mut self, geometry: Option<ViewGeometry>) {
        if let Some(motion) = &mut self.motion {
            motion.set_geometry(geometry);
        }
    }

    /// The target's expected maximal length in the next frame's pixels (`motion_reference`
    /// only; None: not known): the local colour model's ring lies beyond it, and never
    /// nearer than the default radius (a blob measured short must not shrink the ring onto
    /// the target itself).
    pub fn expect_length_px(&mut self, length_px: Option<f64>) {
        if let Some(motion) = &mut self.motion {
            let beyond = length_px.map_or(0.0, |l| RING_PER_LENGTH * l + RING_MARGIN_PX);
            motion.set_ring_radius(beyond.max(DEFAULT_RING_RADIUS_PX));
        }
    }

    /// Makes the frame measured last the one the next frame's background is explained by
    /// (`motion_reference` only): call once per frame, after its final measurement.
    pub fn commit_frame(&mut self) {
        if let Some(motion) = &mut self.motion {
            motion.commit();
        }
    }

    /// Every blob of the last measured frame (mask pixels, 8-connected), in raster order of
    /// their first pixel, in the coordinates of the pixels measured (a region's own, after
    /// [`Self::measure_region`]).
    pub fn blobs(&self) -> &[BlobSummary] {
        &self.labeller.blobs
    }

    /// Measures the blob chosen by `selection` in an RGBA8 frame (row-major, top row first,
    /// `width_px * 4` bytes per row). Errors only when the buffer length does not match.
    pub fn measure(
        &mut self,
        rgba: &[u8],
        width_px: u32,
        height_px: u32,
        selection: BlobSelection,
    ) -> Result<BlobMeasurement, ImageSizeError> {
        self.measure_view(&RgbaView::new(rgba, width_px, height_px)?, selection)
    }

    /// Measures `frame` (a whole image, or a region of one): centroid and outline in image
    /// coordinates, blob boxes in the frame's own pixels.
    fn measure_view(
        &mut self,
        frame: &RgbaView<'_>,
        selection: BlobSelection,
    ) -> Result<BlobMeasurement, ImageSizeError> {
        let frame = *frame;
        if frame.pixel_count() == 0 {
            self.labeller.label(&[], 0, 0);
            return Ok(BlobMeasurement::not_found(0, f64::NAN));
        }
        let seg = &self.config.segmentation;
        let gate = self.colour.and_then(|c| c.gate());
        let (background, reference) = match &mut self.motion {
            Some(motion) if !motion.has_previous() => {
                // A first frame only sets up the next frame's background: without one, the
                // local colour model alone takes every unexplained texture for target.
                self.labeller.label(&[], frame.width, frame.height);
                motion.keep(&frame, expected_box(selection));
                return Ok(BlobMeasurement::not_found(0, QUANTISATION_SIGMA));
            }
            Some(motion) => {
                // The reference replaces the border-fitted surface: only its noise σ is used.
                let mut model = BackgroundModel::constant(frame.width, frame.height, [0.0; 3]);
                motion.set_colour_gate(gate);
                model.noise_sigma = motion.build(&frame, QUANTISATION_SIGMA);
                (model, Some(motion.reference.as_slice()))
            }
            None => (self.background.fit(&frame, seg.background), None),
        };
        let sigma = background.noise_sigma;
        let target_rgb = gate.map(|g| g.target_rgb);
        let segmented = self
            .segmenter
            .segment(&frame, background, reference, seg, target_rgb);
        let Some(coverage) = segmented else {
            self.labeller.label(&[], frame.width, frame.height);
            self.keep_frame(&frame, None, selection);
            return Ok(BlobMeasurement::not_found(0, sigma));
        };
        self.labeller.label_linked(
            &self.segmenter.mask,
            frame.width,
            frame.height,
            self.config.link_radius_px,
        );
        let blobs = &self.labeller.blobs;
        let Some((index, pick)) = select_blob(blobs, self.config.min_pixel_count, selection) else {
            self.keep_frame(&frame, None, selection);
            return Ok(BlobMeasurement::not_found(0, sigma));
        };
        let summary = blobs[index];
        let blob_count = blobs.len();
        let noise = CoverageNoise::at(&coverage, &summary);
        let geometry = self.measurer.measure(
            &frame,
            &BlobToMeasure {
                labels: &self.labeller.labels,
                label: index as u32 + 1,
                bbox: summary.bbox,
                coverage: &coverage,
                edge_min_coverage: noise.edge_min_coverage(),
                corner_tolerance: noise.corner_tolerance(),
            },
        );
        let measurement = blob_measurement(&summary, &geometry, pick, blob_count, sigma);
        let target = (measurement.status == BlobStatus::Ok).then_some(index as u32 + 1);
        if let (Some(colour), Some(label)) = (&mut self.colour, target) {
            let labels = &self.labeller.labels;
            let pixels =
                (self.segmenter.mask.iter().map(|&i| i as usize)).filter(|&i| labels[i] == label);
            colour.learn_from_blob(&frame, &coverage, pixels);
        }
        self.keep_frame(&frame, target, selection);
        Ok(measurement)
    }
}

/// The measurement of the blob `summary` whose moments and outline are `geometry`
/// (`pick`: as [`select_blob`] picked it), among `blob_count` blobs, the background's noise
/// `sigma`.
fn blob_measurement(
    summary: &BlobSummary,
    geometry: &BlobGeometry,
    pick: Pick,
    blob_count: usize,
    sigma: f64,
) -> BlobMeasurement {
    // A blob without a measurable length (no edge points) gives no range.
    let too_small = pick == Pick::TooSmall || geometry.feret.is_none();
    let status = match (too_small, pick, geometry.truncated) {
        (true, _, _) => BlobStatus::TooSmall,
        (false, Pick::Joined, _) => BlobStatus::Merged,
        (false, _, true) => BlobStatus::Truncated,
        (false, _, false) => BlobStatus::Ok,
    };
    BlobMeasurement {
        status,
        centroid_u_px: geometry.centroid_u_px,
        centroid_v_px: geometry.centroid_v_px,
        max_length_px: geometry.feret.map_or(0.0, |f| f.length_px),
        area_px: geometry.area_px,
        pixel_count: summary.pixel_count,
        bbox: Some(summary.bbox),
        feret: geometry.feret,
        blob_count,
        background_noise_sigma: sigma,
    }
}

impl VisionPipeline {
    /// Keeps `frame` for the next frame's background (`motion_reference` only), the pixels
    /// around the mask of blob `label` (the target measured `Ok`) and the gate of a
    /// `NearestWithin` selection (where the target was expected) kept out and that mask
    /// marked for the next frame's ring; without one, the gate alone kept out.
    fn keep_frame(&mut self, frame: &RgbaView<'_>, label: Option<u32>, selection: BlobSelection) {
        let Some(motion) = &mut self.motion else {
            return;
        };
        let Some(label) = label else {
            return motion.keep(frame, expected_box(selection));
        };
        let labels = &self.labeller.labels;
        let target =
            || (self.segmenter.mask.iter().map(|&i| i as usize)).filter(|&i| labels[i] == label);
        // A blob that was a part of the target (a wing tip, the fuselage) says less of where
        // the rest of it lies than the prediction does: both are kept out.
        let measured = motion.exclusion_about(target(), frame.width);
        motion.keep(frame, covering(measured, expected_box(selection)));
        motion.mark_target(target());
    }

    /// How close to an inner edge of a region a blob may come, px, before the region's
    /// measurement may differ from the whole image's: a blob takes in mask pixels up to
    /// `link_radius_px` away, and its measurement reads the coverage of pixels up to 2 px
    /// beyond its mask (the ring and the gradient stencil), plus one for a core pixel's
    /// neighbours. Smaller blobs (below `min_pixel_count`: noise, or a sliver of target whose
    /// link to the measured blob would pass outside the region, which the measured blob's
    /// own clearance rules out) are not measured and do not count.
    pub fn region_clearance_px(&self) -> u32 {
        self.config.link_radius_px as u32 + 3
    }

    /// Measures `rgba`, the pixels of `region` of an image of `intrinsics`' size (row-major,
    /// `region.width_px * 4` bytes per row), as [`Self::measure`] does, the background fitted
    /// on the region's border; `selection` and the result are in the image's coordinates.
    pub fn measure_region(
        &mut self,
        rgba: &[u8],
        region: &ImageRegion,
        intrinsics: &CameraIntrinsics,
        selection: BlobSelection,
    ) -> Result<RegionMeasurement, ImageSizeError> {
        let local_selection =
            selection.in_pixels(f64::from(region.u0_px), f64::from(region.v0_px), 1.0);
        let frame = RgbaView::new(rgba, region.width_px, region.height_px)?
            .at_origin(region.u0_px, region.v0_px);
        let mut blob = self.measure_view(&frame, local_selection)?;
        blob.bbox = blob.bbox.map(|b| PixelBox {
            min_u: b.min_u + region.u0_px,
            min_v: b.min_v + region.v0_px,
            max_u: b.max_u + region.u0_px,
            max_v: b.max_v + region.v0_px,
        });
        let [left, top, right, bottom] = region.inner_edges(intrinsics);
        let clearance = self.region_clearance_px() as usize;
        let (w, h) = (region.width_px as usize, region.height_px as usize);
        let reaches_inner_edge = self
            .labeller
            .blobs
            .iter()
            .filter(|b| b.pixel_count >= self.config.min_pixel_count)
            .any(|b| {
                let (u0, v0) = (b.bbox.min_u as usize, b.bbox.min_v as usize);
                let (u1, v1) = (b.bbox.max_u as usize, b.bbox.max_v as usize);
                (left && u0 < clearance)
                    || (top && v0 < clearance)
                    || (right && u1 + clearance >= w)
                    || (bottom && v1 + clearance >= h)
            });
        Ok(RegionMeasurement {
            blob,
            reaches_inner_edge,
        })
    }
}

/// A selection's point and gate, read once: the point a blob is judged against (none for
/// `Largest`), the gate's radius (infinite for `NearestTo`), and the expected length and
/// size weights of `NearestWithin` (0 for the others).
struct SelectionGate {
    point: Option<(f64, f64)>,
    radius_px: f64,
    length_px: f64,
    length_ratio: f64,
    fragment_fraction: f64,
    merge_ratio: f64,
    merges_measured: bool,
}

impl SelectionGate {
    fn of(selection: BlobSelection) -> Self {
        let ungated = |point| Self {
            point,
            radius_px: f64::INFINITY,
            length_px: 0.0,
            length_ratio: 0.0,
            fragment_fraction: 0.0,
            merge_ratio: 0.0,
            merges_measured: false,
        };
        match selection {
            BlobSelection::NearestTo { u_px, v_px } if u_px.is_finite() && v_px.is_finite() => {
                ungated(Some((u_px, v_px)))
            }
            BlobSelection::NearestWithin {
                u_px,
                v_px,
                radius_px,
                length_px,
                length_ratio,
                fragment_fraction,
                merge_ratio,
                merges_measured,
            } => Self {
                point: Some((u_px, v_px)),
                radius_px,
                length_px,
                length_ratio,
                fragment_fraction,
                merge_ratio,
                merges_measured,
            },
            _ => ungated(None),
        }
    }

    fn distance(&self, b: &BlobSummary) -> f64 {
        self.point.map_or(0.0, |(u_px, v_px)| {
            (b.mean_u_px - u_px).hypot(b.mean_v_px - v_px)
        })
    }

    /// How unlike the prediction a blob is: its distance, and with an expected length the
    /// ratio of its box's longer side to it, a fragment's at the fragment fraction (see
    /// `BlobSelection::NearestWithin`).
    fn unlikeness(&self, b: &BlobSummary) -> f64 {
        if self.length_px <= 0.0 || self.length_ratio <= 1.0 || !self.radius_px.is_finite() {
            return self.distance(b);
        }
        let size = (extent_px(b) / self.length_px).max(self.fragment_fraction);
        (self.distance(b) / self.radius_px).powi(2) + (size.ln() / self.length_ratio.ln()).powi(2)
    }

    /// Longer than the target alone can be: the box's longer side over `merge_ratio` times
    /// the expected length.
    fn too_long(&self, b: &BlobSummary) -> bool {
        self.merge_ratio > 1.0
            && self.length_px > 0.0
            && extent_px(b) > self.merge_ratio * self.length_px
    }

    /// Inside the gate: the blob's centre within its radius, the whole blob within its
    /// square, and no longer than the target can be (a blob reaching beyond where the target
    /// can be, or longer than it, is not the target alone).
    fn inside(&self, b: &BlobSummary) -> bool {
        let r = self.radius_px;
        let Some((u_px, v_px)) = self.point.filter(|_| r.is_finite()) else {
            return true;
        };
        if self.too_long(b) {
            return false;
        }
        let (u0, v0) = (f64::from(b.bbox.min_u), f64::from(b.bbox.min_v));
        let (u1, v1) = (f64::from(b.bbox.max_u) + 1.0, f64::from(b.bbox.max_v) + 1.0);
        self.distance(b) <= r
            && u0 >= u_px - r
            && u1 <= u_px + r
            && v0 >= v_px - r
            && v1 <= v_px + r
    }

    /// Centred in the gate but reaching beyond its square or longer than the target: the
    /// tracked aircraft joined to another, or moved further than the gate allows.
    fn reaching(&self, b: &BlobSummary) -> bool {
        !self.inside(b) && self.distance(b) <= self.radius_px
    }
}

/// Index of the blob to measure and whether it is below `min_pixel_count` (then it is the
/// largest blob, because no blob is big enough); `None` when there are no blobs, none inside
/// a `NearestWithin` gate (its centre within the radius, its box within the gate's square and
/// no longer than the merge ratio allows), or a merge (a blob centred in the gate, reaching
/// beyond its square or longer than the target, more like the prediction than every blob
/// inside: the aircraft is there, not in a lesser blob; the joined blob is picked when
/// merges are measured, and then also when it is alone in the gate). A non-finite
/// `NearestTo` point falls back to `Largest`.
fn select_blob(
    blobs: &[BlobSummary],
    min_pixel_count: usize,
    selection: BlobSelection,
) -> Option<(usize, Pick)> {
    let gate = SelectionGate::of(selection);
    let largest = |eligible: &dyn Fn(&BlobSummary) -> bool| {
        blobs
            .iter()
            .enumerate()
            .filter(|(_, b)| eligible(b) && gate.inside(b))
            .max_by_key(|(i, b)| (b.pixel_count, std::cmp::Reverse(*i)))
            .map(|(i, _)| i)
    };
    let big_enough = |b: &BlobSummary| b.pixel_count >= min_pixel_count;
    // The eligible blob most like the prediction, and its unlikeness.
    let most_like = |eligible: &dyn Fn(&BlobSummary) -> bool| {
        blobs
            .iter()
            .enumerate()
            .filter(|(_, b)| big_enough(b) && eligible(b))
            .map(|(i, b)| (i, gate.unlikeness(b)))
            .min_by(|(_, a), (_, b)| a.total_cmp(b))
    };
    let chosen = match gate.point {
        Some(_) => match (
            most_like(&|b| gate.inside(b)),
            most_like(&|b| gate.reaching(b)),
        ) {
            (Some((_, best)), Some((j, beyond))) if beyond < best => {
                return gate.merges_measured.then_some((j, Pick::Joined));
            }
            (None, Some((j, _))) if gate.merges_measured => return Some((j, Pick::Joined)),
            (best, _) => best.map(|(i, _)| i),
        },
        None => largest(&big_enough),
    };
    match chosen {
        Some(i) => Some((i, Pick::Whole)),
        None => largest(&|_| true).map(|i| (i, Pick::TooSmall)),
    }
}

/// What [`select_blob`] picked.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Pick {
    /// A blob that may be the target alone.
    Whole,
    /// The largest blob, as none has `min_pixel_count` pixels.
    TooSmall,
    /// The target joined to another: a merge, measured for its bearing.
    Joined,
}

/// The longer side of a blob's box, px.
fn extent_px(b: &BlobSummary) -> f64 {
    f64::from((b.bbox.max_u - b.bbox.min_u).max(b.bbox.max_v - b.bbox.min_v) + 1)
}

/// The box [u0, v0, u1, v1] (pixels, inclusive) of a `NearestWithin` selection's gate.
fn expected_box(selection: BlobSelection) -> Option<[usize; 4]> {
    let BlobSelection::NearestWithin {
        u_px,
        v_px,
        radius_px,
        ..
    } = selection
    else {
        return None;
    };
    let (u0, u1) = (u_px - radius_px, u_px + radius_px);
    let (v0, v1) = (v_px - radius_px, v_px + radius_px);
    (u1 >= 0.0 && v1 >= 0.0 && u0.is_finite() && v0.is_finite())
        .then(|| [u0, v0, u1, v1].map(|x| x.max(0.0) as usize))
}

/// The smallest box [u0, v0, u1, v1] covering both boxes (either alone when the other is
/// None).
fn covering(a: Option<[usize; 4]>, b: Option<[usize; 4]>) -> Option<[usize; 4]> {
    match (a, b) {
        (Some(a), Some(b)) => Some([
            a[0].min(b[0]),
            a[1].min(b[1]),
            a[2].max(b[2]),
            a[3].max(b[3]),
        ]),
        (a, b) => a.or(b),
    }
}

/// How noisy coverage is near a blob: σ of the background over the target's contrast there.
#[derive(Debug, Clone, Copy)]
struct CoverageNoise {
    sigma: f64,
}

impl CoverageNoise {
    fn at(coverage: &CoverageModel, blob: &BlobSummary) -> Self {
        let b = coverage.background_near(blob.mean_u_px, blob.mean_v_px);
        let contrast = (0..3)
            .map(|c| (coverage.target_rgb[c] - b[c]).powi(2))
            .sum::<f64>()
            .sqrt()
            .max(coverage.threshold);
        Self {
            sigma: coverage.background.noise_sigma / contrast,
        }
    }

    /// Coverage below which an edge pixel is indistinguishable from background noise.
    fn edge_min_coverage(&self) -> f64 {
        let (lo, hi) = EDGE_MIN_COVERAGE_RANGE;
        (EDGE_MIN_COVERAGE_SIGMAS * self.sigma).clamp(lo, hi)
    }

    /// Largest difference between a corner model's predicted coverage of a pixel and the
    /// measured one: 0.05 (the supersampled or multisampled coverage of a pixel cut by a
    /// slightly curved edge, and line-offset errors of ~0.03 px) plus 3σ of the noise.
    fn corner_tolerance(&self) -> f64 {
        0.05 + 3.0 * self.sigma
    }
}
