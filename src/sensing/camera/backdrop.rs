//! What lay behind the target in each frame of a world scene, by the truth: open sky, the
//! ground, the horizon across the target, or cloud; and how the frames of each fared. The
//! counts only report (the summary's `background`); nothing in the loop reads them.

use std::collections::VecDeque;

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
    /// Of those frames, the ones the estimator took (trusted: `Ok`, and fused by a Kalman
    /// filter whose gates did not keep them out).
    pub trusted: u64,
    /// The RMS distance over the trusted frames alone, px (null without any).
    pub trusted_centroid_vs_silhouette_rms_px: Option<f64>,
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

/// A sum of squared centroid errors.
#[derive(Debug, Clone, Copy, Default)]
struct SquaredErrors {
    frames: u64,
    sum_px2: f64,
}

impl SquaredErrors {
    fn add(&mut self, sq_px2: Option<f64>) {
        if let Some(sq) = sq_px2 {
            self.frames += 1;
            self.sum_px2 += sq;
        }
    }

    fn rms_px(&self) -> Option<f64> {
        (self.frames > 0).then(|| (self.sum_px2 / self.frames as f64).sqrt())
    }
}

/// Sums of one kind's frames.
#[derive(Debug, Clone, Copy, Default)]
struct Tally {
    frames: u64,
    lost: u64,
    silhouette: SquaredErrors,
    trusted: u64,
    trusted_silhouette: SquaredErrors,
}

impl Tally {
    fn report(&self) -> BackdropFrames {
        BackdropFrames {
            frames: self.frames,
            lost: self.lost,
            centroid_vs_silhouette_rms_px: self.silhouette.rms_px(),
            trusted: self.trusted,
            trusted_centroid_vs_silhouette_rms_px: self.trusted_silhouette.rms_px(),
        }
    }
}

/// A frame counted but not yet delivered to the estimator (the camera's latency).
#[derive(Debug, Clone, Copy)]
struct Unsettled {
    index: u64,
    kind: FrameBackground,
    silhouette_sq_px2: Option<f64>,
}

/// What a frame showed behind its target.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FrameBackground {
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
    /// Its frame number.
    pub index: u64,
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
    /// Frames counted and not yet delivered, oldest first.
    unsettled: VecDeque<Unsettled>,
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
            unsettled: VecDeque::new(),
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

    /// Counts a measured frame; returns what lay behind its target.
    pub fn count(
        &mut self,
        frame: &BackdropFrame,
        intrinsics: &CameraIntrinsics,
    ) -> FrameBackground {
        let kind = self.classify(frame.truth, frame.follower, intrinsics);
        let tally = &mut self.tallies[kind as usize];
        tally.frames += 1;
        tally.lost += u64::from(!frame.ok);
        tally.silhouette.add(frame.silhouette_sq_px2);
        self.unsettled.push_back(Unsettled {
            index: frame.index,
            kind,
            silhouette_sq_px2: frame.silhouette_sq_px2,
        });
        kind
    }

    /// The frame `index` reached the estimator, which took it (`trusted`) or not; frames
    /// counted before it that never reached it are dropped.
    pub fn settle(&mut self, index: u64, trusted: bool) {
        while let Some(frame) = self.unsettled.front().copied() {
            if frame.index > index {
                return;
            }
            self.unsettled.pop_front();
            if frame.index == index && trusted {
                let tally = &mut self.tallies[frame.kind as usize];
                tally.trusted += 1;
                tally.trusted_silhouette.add(frame.silhouette_sq_px2);
            }
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

    /// Frames 0-3 against ground, 1 px, 2 px, 3 px and 4 px off: frame 0 never reaches the
    /// estimator (a later frame settles first), frame 1 is taken, frame 2 kept out, frame 3
    /// not settled yet. Every counted frame is in the RMS over all; only frame 1 is trusted.
    #[test]
    fn only_frames_the_estimator_took_are_trusted() {
        let cam = CameraIntrinsics::from_hfov(640, 480, 60.0);
        let follower = FollowerPose::at_origin(EulerAngles::new(0.0, 0.0, 0.0));
        let truth = ImageMeasurement {
            y_i_px: 0.0,
            z_i_px: -40.0,
            b_i_px: 20.0,
        };
        let mut a = audit();
        for index in 0..4 {
            let off_px = (index + 1) as f64;
            let frame = BackdropFrame {
                index,
                truth: &truth,
                follower: &follower,
                ok: true,
                silhouette_sq_px2: Some(off_px * off_px),
            };
            a.count(&frame, &cam);
        }
        a.settle(1, true);
        a.settle(2, false);
        let ground = a.counts().ground;
        assert_eq!((ground.frames, ground.trusted), (4, 1));
        let all = ground.centroid_vs_silhouette_rms_px.expect("counted");
        assert!((all - 7.5f64.sqrt()).abs() < 1e-12, "{all}");
        assert_eq!(ground.trusted_centroid_vs_silhouette_rms_px, Some(2.0));
        a.settle(3, true);
        assert_eq!(a.counts().ground.trusted, 2);
    }
}
