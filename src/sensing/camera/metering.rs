//! How a read-back frame is measured: the image pipeline in the frame's tracking window
//! (binned or not, its measurement carried back to the image's pixels) or over the whole
//! image, which blob it follows, and the image measurement (yI, zI, bI) it gives.

use super::CameraTimings;
use super::drawing::DrawnFrame;
use super::setup::SensorError;
use crate::frames::{Mat3, Vec3};
use crate::render::camera::CameraIntrinsics;
use crate::scenario::{
    BearingPoint, BlobChoice, CameraSection, LengthExpectation, MergeMeasurement, SegmentationKind,
};
use crate::sensing::TargetExpectation;
use crate::sensing::binning::{binned_selection, unbinned_measurement};
use crate::vision::{
    BlobMeasurement, BlobSelection, BlobStatus, ImageMeasurement, ViewGeometry, VisionConfig,
    VisionPipeline,
};
use std::time::Instant;

/// A frame taken in a region: whether its measurement stands or the frame must be measured
/// whole.
#[derive(Debug, Clone, Copy)]
pub(super) enum RegionOutcome {
    /// The measurement (of the whole image, or of a region, in image coordinates).
    Measured(BlobMeasurement),
    /// The region's measurement cannot stand for the whole image's.
    NeedsWholeImage,
}

/// The image pipeline and what it remembers between frames.
pub(super) struct Metering {
    vision: VisionPipeline,
    selection: BlobChoice,
    bearing_point: BearingPoint,
    /// The last `Ok` frame's centroid, px (the blob `nearest` follows).
    previous_centroid_px: Option<(f64, f64)>,
    /// The camera's orientation by navigation for the frame being measured (L_CB L_BE).
    camera_from_ned: Option<Mat3>,
    /// The camera's position by navigation for the frame being measured, NED, ft.
    camera_position_ned_ft: Vec3,
    /// The flat ground's NED down coordinate, ft, when the scene has ground: the motion
    /// segmentation maps the ground between frames through it. The follower knows it as the
    /// terrain's elevation from a map (flat ground: one number); its height above the ground
    /// is that less its navigated altitude, so the navigation's vertical error enters.
    ground_down_ft: Option<f64>,
    /// The last `Ok` frame's maximal length, px (kept through frames without the target).
    previous_length_px: Option<f64>,
    /// The camera's orientation by navigation when the last frame was measured.
    previous_camera_from_ned: Option<Mat3>,
    /// Whether the last centroid is followed turned by the camera's rotation since
    /// (segmentation `motion`, or selection `predicted`).
    turns_centroid: bool,
    /// Where the follower expects the target in the frame being measured, and how large (the
    /// estimator's prediction, or the cue before the target is first seen).
    expected: Option<TargetExpectation>,
    /// `camera.expected_length`.
    length_expectation: LengthExpectation,
    /// `predicted` selection's gate beyond half the last maximal length, rad.
    gate_rad: f64,
    /// `camera.selection_length_ratio`.
    length_ratio: f64,
    /// `camera.selection_fragment_fraction`.
    fragment_fraction: f64,
    /// `camera.selection_merge_ratio`.
    merge_ratio: f64,
    /// `camera.merges`.
    merges: MergeMeasurement,
}

impl Metering {
    /// The image pipeline a `[camera]` section describes, over ground at NED down
    /// `ground_down_ft` when there is any.
    pub fn new(camera: &CameraSection, ground_down_ft: Option<f64>) -> Result<Self, SensorError> {
        let mut vision_config = VisionConfig {
            min_pixel_count: camera.min_pixel_count as usize,
            ..VisionConfig::default()
        };
        vision_config.segmentation.mask_coverage = camera.mask_coverage;
        vision_config.link_radius_px = camera.link_radius_px as usize;
        vision_config.motion_reference = camera.segmentation == SegmentationKind::Motion;
        vision_config.target_colour_tolerance_deg = camera.target_colour_tolerance_deg;
        Ok(Self {
            vision: VisionPipeline::new(vision_config)?,
            selection: camera.selection,
            bearing_point: camera.bearing_point,
            previous_centroid_px: None,
            camera_from_ned: None,
            camera_position_ned_ft: Vec3::zeros(),
            ground_down_ft,
            previous_length_px: None,
            previous_camera_from_ned: None,
            turns_centroid: camera.segmentation == SegmentationKind::Motion
                || camera.selection == BlobChoice::Predicted,
            expected: None,
            length_expectation: camera.expected_length,
            gate_rad: camera.selection_gate_deg.to_radians(),
            length_ratio: camera.selection_length_ratio,
            fragment_fraction: camera.selection_fragment_fraction,
            merge_ratio: camera.selection_merge_ratio,
            merges: camera.merges,
        })
    }

    /// The clearance the pipeline needs around the target in a window, px.
    pub fn region_clearance_px(&self) -> u32 {
        self.vision.region_clearance_px()
    }

    /// Sets the camera's orientation and position by navigation, L_CB L_BE and NED ft, and
    /// where the follower expects the target (if it has an expectation), for the frames
    /// measured next.
    pub fn orient(
        &mut self,
        camera_from_ned: Mat3,
        camera_position_ned_ft: Vec3,
        expected: Option<TargetExpectation>,
    ) {
        self.camera_from_ned = Some(camera_from_ned);
        self.camera_position_ned_ft = camera_position_ned_ft;
        self.expected = expected;
    }

    /// The target's expected maximal length in the image's pixels, its focal length
    /// `focal_px` (`camera.expected_length`): the last `Ok` length, or with `estimated` the
    /// larger of it and the estimator's span at its predicted range (either alone when the
    /// other is unknown).
    fn expected_length_px(&self, focal_px: f64) -> Option<f64> {
        let estimated = match self.length_expectation {
            LengthExpectation::LastMeasured => None,
            LengthExpectation::Estimated => self
                .expected
                .and_then(|e| e.span_rad)
                .map(|span_rad| 2.0 * focal_px * (0.5 * span_rad).tan()),
        };
        [estimated, self.previous_length_px]
            .into_iter()
            .flatten()
            .reduce(f64::max)
    }

    /// Tells the image pipeline how `frame`'s pixels look into the world.
    fn set_view(&mut self, frame: &DrawnFrame) {
        let geometry = self.camera_from_ned.map(|camera_from_ned| ViewGeometry {
            intrinsics: frame.intrinsics,
            camera_from_ned,
            position_ned_ft: self.camera_position_ned_ft,
            ground_down_ft: self.ground_down_ft,
        });
        self.vision.set_view_geometry(geometry);
        let factor = f64::from(frame.factor);
        let length_px = self.expected_length_px(frame.intrinsics.focal_px * factor);
        self.vision.expect_length_px(length_px.map(|l| l / factor));
    }

    /// The blob to measure in the next frame: the largest, the one nearest the last measured
    /// centroid (`camera.selection = "nearest"`; with `camera.segmentation = "motion"` the
    /// last centroid turned by the camera's rotation since, K R K⁻¹ of the camera of
    /// `intrinsics` with the orientations by navigation, where a target at rest against the
    /// world is now), or the one nearest where the target is expected inside a gate
    /// (`"predicted"`, see [`BlobChoice::Predicted`]).
    pub fn selection(&self, intrinsics: &CameraIntrinsics) -> BlobSelection {
        let last = self
            .previous_centroid_px
            .map(|(u_px, v_px)| self.turned(intrinsics, u_px, v_px).unwrap_or((u_px, v_px)));
        match self.selection {
            BlobChoice::Largest => BlobSelection::Largest,
            BlobChoice::Nearest => last.map_or(BlobSelection::Largest, |(u_px, v_px)| {
                BlobSelection::NearestTo { u_px, v_px }
            }),
            BlobChoice::Predicted => match self.expected_pixel(intrinsics).or(last) {
                Some((u_px, v_px)) => {
                    let length_px = self.expected_length_px(intrinsics.focal_px).unwrap_or(0.0);
                    BlobSelection::NearestWithin {
                        u_px,
                        v_px,
                        radius_px: intrinsics.focal_px * self.gate_rad.tan() + 0.5 * length_px,
                        length_px,
                        length_ratio: self.length_ratio,
                        fragment_fraction: self.fragment_fraction,
                        merge_ratio: self.merge_ratio,
                        merges_measured: self.merges == MergeMeasurement::Bearing,
                    }
                }
                None => BlobSelection::Largest,
            },
        }
    }

    /// Pixel of the expected line of sight in the frame being measured.
    fn expected_pixel(&self, intrinsics: &CameraIntrinsics) -> Option<(f64, f64)> {
        let (camera_from_ned, expected) = (self.camera_from_ned?, self.expected?);
        intrinsics.pixel_of_direction(&(camera_from_ned * expected.los_ned))
    }

    /// Pixel (u, v) of the last frame turned into the frame being measured.
    fn turned(&self, intrinsics: &CameraIntrinsics, u_px: f64, v_px: f64) -> Option<(f64, f64)> {
        let (before, now) = (self.previous_camera_from_ned?, self.camera_from_ned?);
        if !self.turns_centroid {
            return None;
        }
        let direction = intrinsics.direction_of_pixel(u_px, v_px);
        intrinsics.pixel_of_direction(&(now * before.transpose() * direction))
    }

    /// Measures a read-back frame: in its tracking window (binned or not), or the whole image;
    /// the measurement is in the image's pixels (`intrinsics`). A window's measurement that
    /// cannot stand asks for the frame to be drawn whole.
    pub fn measure(
        &mut self,
        frame: &DrawnFrame,
        selection: BlobSelection,
        timings: &mut CameraTimings,
    ) -> Result<RegionOutcome, SensorError> {
        let Some(window) = frame.window else {
            return Ok(RegionOutcome::Measured(
                self.measure_whole(frame, selection, timings)?,
            ));
        };
        let vision_started = Instant::now();
        self.set_view(frame);
        let measured = self.vision.measure_region(
            &frame.pixels.rgba,
            &window,
            &frame.intrinsics,
            binned_selection(selection, frame.factor),
        )?;
        timings.vision += vision_started.elapsed();
        if !measured.reaches_inner_edge && measured.blob.status == BlobStatus::Ok {
            Ok(RegionOutcome::Measured(unbinned_measurement(
                &measured.blob,
                frame.factor,
            )))
        } else {
            Ok(RegionOutcome::NeedsWholeImage)
        }
    }

    /// Measures the pixels of a frame, a whole image.
    pub fn measure_whole(
        &mut self,
        frame: &DrawnFrame,
        selection: BlobSelection,
        timings: &mut CameraTimings,
    ) -> Result<BlobMeasurement, SensorError> {
        let vision_started = Instant::now();
        self.set_view(frame);
        let image = frame.pixels;
        let blob = self
            .vision
            .measure(&image.rgba, image.width_px, image.height_px, selection)?;
        timings.vision += vision_started.elapsed();
        Ok(blob)
    }

    /// The image measurement of a blob at the camera's bearing point (None when nothing was
    /// found).
    pub fn image_measurement(
        &self,
        blob: &BlobMeasurement,
        intrinsics: &CameraIntrinsics,
    ) -> Option<ImageMeasurement> {
        blob.image_measurement_at(intrinsics, self.bearing_point)
    }

    /// Remembers a measured frame's blob for the next frame's selection.
    pub fn remember(&mut self, blob: &BlobMeasurement) {
        let ok = blob.status == BlobStatus::Ok;
        self.vision.commit_frame();
        if ok {
            self.previous_length_px = Some(blob.max_length_px);
        }
        self.previous_camera_from_ned = self.camera_from_ned;
        self.previous_centroid_px = ok.then_some((blob.centroid_u_px, blob.centroid_v_px));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vision::PixelBox;

    /// A blob measured `Ok`, `length_px` long, centred on the image.
    fn measured(length_px: f64) -> BlobMeasurement {
        BlobMeasurement {
            status: BlobStatus::Ok,
            centroid_u_px: 320.0,
            centroid_v_px: 240.0,
            max_length_px: length_px,
            area_px: length_px,
            pixel_count: length_px as usize,
            bbox: Some(PixelBox {
                min_u: 300,
                min_v: 239,
                max_u: 340,
                max_v: 241,
            }),
            feret: None,
            blob_count: 1,
            background_noise_sigma: 0.3,
        }
    }

    /// The gate's radius and expected length of a `predicted` selection after a fragment
    /// `fragment_px` long was measured, the estimator predicting the span at `span_rad`.
    fn gate_after_fragment(
        expected_length: LengthExpectation,
        fragment_px: f64,
        span_rad: f64,
    ) -> (f64, f64) {
        let camera = CameraSection {
            selection: BlobChoice::Predicted,
            expected_length,
            ..CameraSection::default()
        };
        let intrinsics = CameraIntrinsics::from_hfov(640, 480, 60.0);
        let mut metering = Metering::new(&camera, None).expect("a pipeline");
        metering.remember(&measured(fragment_px));
        let expected = TargetExpectation {
            los_ned: Vec3::new(1.0, 0.0, 0.0),
            span_rad: Some(span_rad),
        };
        metering.orient(Mat3::identity(), Vec3::zeros(), Some(expected));
        match metering.selection(&intrinsics) {
            BlobSelection::NearestWithin {
                radius_px,
                length_px,
                ..
            } => (radius_px, length_px),
            other => panic!("not a gate: {other:?}"),
        }
    }

    /// With `estimated`, a fragment measured short does not shrink what the next frame looks
    /// for: the gate and the size term take the estimator's span (0.2 rad, 111 px at a
    /// 554 px focal length), where `last_measured` takes the fragment's 40 px; a fragment
    /// longer than the prediction is still allowed for.
    #[test]
    fn the_estimators_span_keeps_a_fragment_from_shrinking_the_gate() {
        let focal_px = CameraIntrinsics::from_hfov(640, 480, 60.0).focal_px;
        let gate_px = focal_px * 3f64.to_radians().tan();
        let span_px = 2.0 * focal_px * 0.1f64.tan();
        let (radius, length) = gate_after_fragment(LengthExpectation::LastMeasured, 40.0, 0.2);
        assert!((length - 40.0).abs() < 1e-9 && (radius - gate_px - 20.0).abs() < 1e-9);
        let (radius, length) = gate_after_fragment(LengthExpectation::Estimated, 40.0, 0.2);
        assert!(
            (length - span_px).abs() < 1e-9,
            "{length} against {span_px}"
        );
        assert!((radius - gate_px - 0.5 * span_px).abs() < 1e-9);
        let (_, length) = gate_after_fragment(LengthExpectation::Estimated, 150.0, 0.2);
        assert!((length - 150.0).abs() < 1e-9, "{length}");
    }
}
