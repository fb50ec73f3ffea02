//! What lay behind the target in each frame of a world scene, by the truth: open sky, the
//! ground, the horizon across the target, or cloud; and how the frames of each fared. The
//! counts only report (the summary's `background`); nothing in the loop reads them.

use crate::render::camera::CameraIntrinsics;
use crate::render::scene::{Backdrop, WorldScene, cloud_threshold};
use crate::sensing::geometry::FollowerPose;
use crate::vision::ImageMeasurement;

/// Pixels beyond half the target's true maximal length at which the background is sampled
/// around the target.
const RING_MARGIN_PX: f64 = 2.0;
/// Points sampled on that ring.
const RING_POINTS: usize = 8;

/// The frames of one kind of background.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct BackdropFrames {
    /// Frames whose target had this background (by the truth).
    pub frames: u64,
    /// Of those, frames whose measurement was not `Ok`.
    pub lost: u64,
    /// RMS distance of the measured centroid from the silhouette's true centroid over those
    /// frames' `Ok` measurements, px (null without any).
    pub centroid_vs_silhouette_rms_px: Option<f64>,
}

/// The frames of a world scene by what lay behind the target.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct BackgroundCounts {
    /// Open sky all round the target.
    pub sky: BackdropFrames,
    /// Ground all round it.
    pub ground: BackdropFrames,
    /// The horizon across it: ground on some side, sky or cloud on another.
    pub horizon: BackdropFrames,
    /// Cloud on some side (and no ground).
    pub cloud: BackdropFrames,
}

/// Sums of one kind's frames.
#[derive(Debug, Clone, Copy, Default)]
struct Tally {
    frames: u64,
    lost: u64,
    silhouette_frames: u64,
    silhouette_sq_px2: f64,
}

impl Tally {
    fn report(&self) -> BackdropFrames {
        BackdropFrames {
            frames: self.frames,
            lost: self.lost,
            centroid_vs_silhouette_rms_px: (self.silhouette_frames > 0)
                .then(|| (self.silhouette_sq_px2 / self.silhouette_frames as f64).sqrt()),
        }
    }
}

/// What a frame showed behind its target.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum FrameBackground {
    /// Open sky all round.
    Sky,
    /// Ground all round.
    Ground,
    /// Ground on some side, sky or cloud on another.
    Horizon,
    /// Cloud on some side, no ground.
    Cloud,
}

/// One measured frame, as the backdrop audit is given it.
pub(super) struct BackdropFrame<'a> {
    /// The target's true (yI, zI, bI), px.
    pub truth: &'a ImageMeasurement,
    /// The follower as it truly was (its camera's pose).
    pub follower: &'a FollowerPose,
    /// Whether the measurement stood (`Ok`).
    pub ok: bool,
    /// Its squared distance from the silhouette's true centroid, px² (None when not
    /// measured or not known).
    pub silhouette_sq_px2: Option<f64>,
}

/// The world and the counts so far.
#[derive(Debug)]
pub(super) struct BackdropAudit {
    scene: WorldScene,
    threshold: f32,
    tallies: [Tally; 4],
}

impl BackdropAudit {
    /// The audit of frames drawn against `scene`.
    pub fn new(scene: WorldScene) -> Self {
        let threshold = scene
            .clouds
            .map_or(2.0, |c| cloud_threshold(c.coverage, scene.seed));
        Self {
            scene,
            threshold,
            tallies: [Tally::default(); 4],
        }
    }

    /// What lay behind the target: the backdrop along the rays through its true reference
    /// point and through [`RING_POINTS`] points on a circle of half its true maximal length
    /// plus [`RING_MARGIN_PX`] around it.
    pub fn classify(
        &self,
        truth: &ImageMeasurement,
        follower: &FollowerPose,
        intrinsics: &CameraIntrinsics,
    ) -> FrameBackground {
        let ned_from_camera = follower.camera_from_ned().transpose();
        let radius_px = 0.5 * truth.b_i_px + RING_MARGIN_PX;
        let (mut ground, mut open) = (false, false);
        let mut cloud = false;
        for k in 0..=RING_POINTS {
            let angle = std::f64::consts::TAU * k as f64 / RING_POINTS as f64;
            let r = if k == 0 { 0.0 } else { radius_px };
            let y_px = truth.y_i_px + r * angle.cos();
            let z_px = truth.z_i_px + r * angle.sin();
            // Camera axes: x along the optical axis, y right (yI), z down (-zI).
            let ray = ned_from_camera * crate::frames::Vec3::new(intrinsics.focal_px, y_px, -z_px);
            match self
                .scene
                .backdrop(&follower.position_ned_ft, &ray, self.threshold)
            {
                Backdrop::Ground => ground = true,
                Backdrop::Sky => open = true,
                Backdrop::Cloud => (open, cloud) = (true, true),
            }
        }
        match (ground, open, cloud) {
            (true, true, _) => FrameBackground::Horizon,
            (true, false, _) => FrameBackground::Ground,
            (false, _, true) => FrameBackground::Cloud,
            (false, _, false) => FrameBackground::Sky,
        }
    }

    /// Counts a measured frame.
    pub fn count(&mut self, frame: &BackdropFrame, intrinsics: &CameraIntrinsics) {
        let kind = self.classify(frame.truth, frame.follower, intrinsics);
        let tally = &mut self.tallies[kind as usize];
        tally.frames += 1;
        tally.lost += u64::from(!frame.ok);
        if let Some(sq) = frame.silhouette_sq_px2 {
            tally.silhouette_frames += 1;
            tally.silhouette_sq_px2 += sq;
        }
    }

    /// The counts so far.
    pub fn counts(&self) -> BackgroundCounts {
        let [sky, ground, horizon, cloud] = self.tallies.map(|t| t.report());
        BackgroundCounts {
            sky,
            ground,
            horizon,
            cloud,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frames::EulerAngles;

    fn audit() -> BackdropAudit {
        BackdropAudit::new(WorldScene::ground_300_ft_below())
    }

    /// A level camera 300 ft above the plane sees its horizon on the image's centre row: a
    /// target there of 20 px spans it; 40 px above it is against sky, 40 px below against
    /// ground.
    #[test]
    fn classes_follow_the_horizon() {
        let cam = CameraIntrinsics::from_hfov(640, 480, 60.0);
        let follower = FollowerPose::at_origin(EulerAngles::new(0.0, 0.0, 0.0));
        let a = audit();
        let at = |z_i_px: f64| {
            let truth = ImageMeasurement {
                y_i_px: 0.0,
                z_i_px,
                b_i_px: 20.0,
            };
            a.classify(&truth, &follower, &cam)
        };
        assert_eq!(at(0.0), FrameBackground::Horizon);
        assert_eq!(at(40.0), FrameBackground::Sky);
        assert_eq!(at(-40.0), FrameBackground::Ground);
    }
}
