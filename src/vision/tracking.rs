//! The tracking window: where in the next frame to look for the target.
//!
//! A tracker predicts the target's silhouette from what it knows, never from the truth: the
//! last measured silhouette (its centroid, its bounding box and its maximal length) and the
//! camera's orientation at both captures, C_k = L_CB L_BE (the follower's attitude, the
//! camera's mount and gimbal angles, all known to the follower). Between two captures the
//! camera turns by C_k C_jᵀ; a point seen along the line of sight `los` (camera axes) at
//! capture j is seen along C_k C_jᵀ los at capture k, whatever its range, if the camera does
//! not move. So the corners of the last bounding box are carried into the new
//! image exactly for the camera's rotation (a pinhole camera's rotation maps the image by a
//! homography, which maps the box, and the silhouette inside it, into the quadrilateral of
//! the carried corners). What the rotation does not explain is the motion of the target
//! relative to the follower (translation over the frame, the target's own turning) and the
//! change of range: the window adds a margin for it that grows with the target's size and
//! with the time since the last measurement, plus a fixed margin for the pixels the image
//! pipeline reads beyond the silhouette.

use crate::frames::Mat3;
use crate::render::camera::CameraIntrinsics;
use crate::render::region::ImageRegion;
use crate::vision::{BlobMeasurement, BlobStatus};

/// How far the target may move, or grow, in the image per second beyond what the camera's
/// rotation explains, in maximal lengths per second. The relative velocity across the line of
/// sight moves the silhouette by V/S of its own size per second (S its size, ft), and the
/// target's own roll swings its wing tips: 1.5 covers 12 ft/s across the line of sight of an
/// 8 ft target (what `formation.toml` needs: `docs/findings.md`, The image pipeline's
/// accuracy and cost); a target that moves faster is measured whole in that frame, and costs
/// its time.
pub const MOTION_LENGTHS_PER_S: f64 = 1.5;
/// Pixels added to every side besides the clearance the image pipeline needs: the partly
/// covered pixels outside the measured blob's mask (one ring) and the background border the
/// region's sky is fitted on (2 px), and a pixel of rounding.
const FIXED_MARGIN_PX: f64 = 4.0;
/// A line of sight whose x (forward) component is less than this (unit vector) is not
/// projected: the target is beyond 84° off the axis, at the edge of any useful camera.
const MIN_FORWARD_COSINE: f64 = 0.1;
/// Tracks older than this many frames are not trusted: the frame is drawn whole.
const MAX_AGE_FRAMES: u64 = 4;
/// A window of at least this fraction of the image is not worth the region's bookkeeping.
const MAX_IMAGE_FRACTION: f64 = 0.5;

/// What the tracker keeps of the last measured frame.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Track {
    frame_index: u64,
    /// Corners of the measured blob's bounding box (its pixels' outer edges), px.
    corners_px: [(f64, f64); 4],
    /// Maximal length, px.
    length_px: f64,
    /// L_CB L_BE, the camera's orientation when the frame was taken.
    camera_from_ned: Mat3,
}

/// Predicts the region of the next frame in which to look for the target.
#[derive(Debug, Clone, PartialEq)]
pub struct TrackingWindow {
    intrinsics: CameraIntrinsics,
    frame_period_s: f64,
    /// Pixels the image pipeline must find free of target beyond the silhouette
    /// ([`crate::vision::VisionPipeline::region_clearance_px`]).
    clearance_px: f64,
    track: Option<Track>,
}

impl TrackingWindow {
    /// A tracker without a track, for frames of `intrinsics` taken every `frame_period_s`,
    /// whose image pipeline needs `clearance_px` of sky around the target in a region.
    pub fn new(intrinsics: CameraIntrinsics, frame_period_s: f64, clearance_px: u32) -> Self {
        Self {
            intrinsics,
            frame_period_s,
            clearance_px: f64::from(clearance_px),
            track: None,
        }
    }

    /// Takes in the measurement of frame `frame_index`, taken with the camera at
    /// `camera_from_ned`: an `Ok` measurement becomes the track; any other loses it (the next
    /// frame is looked for in the whole image).
    pub fn observe(&mut self, frame_index: u64, blob: &BlobMeasurement, camera_from_ned: &Mat3) {
        self.track = match (blob.status, blob.bbox) {
            (BlobStatus::Ok, Some(b)) if blob.max_length_px.is_finite() => {
                let (u0, v0) = (f64::from(b.min_u), f64::from(b.min_v));
                let (u1, v1) = (f64::from(b.max_u) + 1.0, f64::from(b.max_v) + 1.0);
                Some(Track {
                    frame_index,
                    corners_px: [(u0, v0), (u1, v0), (u0, v1), (u1, v1)],
                    length_px: blob.max_length_px,
                    camera_from_ned: *camera_from_ned,
                })
            }
            _ => None,
        };
    }

    /// The region in which to look for the target in frame `frame_index`, taken with the
    /// camera at `camera_from_ned`; `None` (look at the whole image) without a recent track,
    /// when the target's last silhouette cannot be carried into this frame (it turned to the
    /// side of or behind the camera), or when the region would be much of the image.
    pub fn predict(&self, frame_index: u64, camera_from_ned: &Mat3) -> Option<ImageRegion> {
        let track = self.track.as_ref()?;
        let age_frames = frame_index.checked_sub(track.frame_index)?;
        if age_frames > MAX_AGE_FRAMES {
            return None;
        }
        let now_from_then = camera_from_ned * track.camera_from_ned.transpose();
        let (mut u_min, mut u_max) = (f64::INFINITY, f64::NEG_INFINITY);
        let (mut v_min, mut v_max) = (f64::INFINITY, f64::NEG_INFINITY);
        for &(u, v) in &track.corners_px {
            let (u, v) = self.carried(&now_from_then, u, v)?;
            u_min = u_min.min(u);
            u_max = u_max.max(u);
            v_min = v_min.min(v);
            v_max = v_max.max(v);
        }
        let age_s = age_frames as f64 * self.frame_period_s;
        let margin_px =
            MOTION_LENGTHS_PER_S * age_s * track.length_px + FIXED_MARGIN_PX + self.clearance_px;
        let region = ImageRegion::covering(
            u_min - margin_px,
            u_max + margin_px,
            v_min - margin_px,
            v_max + margin_px,
            &self.intrinsics,
        )?;
        let image_pixels = ImageRegion::whole(&self.intrinsics).pixel_count() as f64;
        (region.pixel_count() as f64 <= MAX_IMAGE_FRACTION * image_pixels).then_some(region)
    }

    /// The maximal length the track predicts, px: the last measured one (None without a
    /// track).
    pub fn predicted_length_px(&self) -> Option<f64> {
        self.track.as_ref().map(|t| t.length_px)
    }

    /// Where the point seen at pixel (u, v) is seen after the camera turned by
    /// `now_from_then`; `None` when it is not well in front of the camera.
    fn carried(&self, now_from_then: &Mat3, u_px: f64, v_px: f64) -> Option<(f64, f64)> {
        let los = now_from_then * self.intrinsics.direction_of_pixel(u_px, v_px);
        // (NaN is not in front either.)
        let in_front = los.x > MIN_FORWARD_COSINE * los.norm();
        if !in_front {
            return None;
        }
        self.intrinsics.pixel_of_direction(&los)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frames::EulerAngles;
    use crate::vision::PixelBox;

    fn blob(min_u: u32, min_v: u32, max_u: u32, max_v: u32) -> BlobMeasurement {
        BlobMeasurement {
            status: BlobStatus::Ok,
            centroid_u_px: 0.5 * f64::from(min_u + max_u + 1),
            centroid_v_px: 0.5 * f64::from(min_v + max_v + 1),
            max_length_px: f64::from(max_u + 1 - min_u),
            area_px: 1.0,
            pixel_count: 1,
            bbox: Some(PixelBox {
                min_u,
                min_v,
                max_u,
                max_v,
            }),
            feret: None,
            blob_count: 1,
            background_noise_sigma: 0.3,
        }
    }

    fn tracker() -> TrackingWindow {
        TrackingWindow::new(CameraIntrinsics::from_hfov(640, 480, 60.0), 1.0 / 30.0, 5)
    }

    /// Without rotation the window is the box grown by the margins, one frame later.
    #[test]
    fn still_camera_grows_the_box_by_the_margins() {
        let mut t = tracker();
        let level = EulerAngles::new(0.0, 0.0, 0.3).body_from_ned();
        assert_eq!(t.predict(1, &level), None);
        t.observe(10, &blob(300, 200, 359, 219), &level);
        let margin = MOTION_LENGTHS_PER_S / 30.0 * 60.0 + 4.0 + 5.0;
        let r = t.predict(11, &level).expect("a window");
        // Carrying the corners through the identity rounds: within a pixel.
        let bounds = [
            f64::from(r.u0_px),
            f64::from(r.u_end_px()),
            f64::from(r.v0_px),
            f64::from(r.v_end_px()),
        ];
        let expected = [
            300.0 - margin,
            360.0 + margin,
            200.0 - margin,
            220.0 + margin,
        ];
        for (got, want) in bounds.iter().zip(expected) {
            assert!((got - want).abs() <= 1.0, "{r:?}");
        }
        // Too old, or a lost frame: whole image.
        assert_eq!(t.predict(10 + MAX_AGE_FRAMES + 1, &level), None);
        let mut lost = blob(300, 200, 359, 219);
        lost.status = BlobStatus::Truncated;
        t.observe(12, &lost, &level);
        assert_eq!(t.predict(13, &level), None);
    }

    /// A roll of the follower turns the image about its centre: the window follows the box's
    /// corners (after a 90° roll to the right, what was right of the centre is above it).
    #[test]
    fn roll_carries_the_window_around_the_centre() {
        let mut t = tracker();
        t.observe(0, &blob(500, 236, 509, 243), &Mat3::identity());
        let rolled = EulerAngles::new(std::f64::consts::FRAC_PI_2, 0.0, 0.0).body_from_ned();
        let r = t.predict(1, &rolled).expect("a window");
        // The box 180-190 px right of the centre (320, 240) is now 180-190 px above it.
        let (u_mid, v_mid) = (
            f64::from(r.u0_px) + 0.5 * f64::from(r.width_px),
            f64::from(r.v0_px) + 0.5 * f64::from(r.height_px),
        );
        assert!((u_mid - 320.0).abs() < 1.0, "{r:?}");
        assert!((v_mid - (240.0 - 185.0)).abs() < 1.0, "{r:?}");
    }
}
