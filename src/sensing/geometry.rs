//! What the sensing stage is given at an instant: the true geometry the camera images, and the
//! follower's own navigation solution that sensing turns the measurement with.
//!
//! [`FollowerPose`] is the one type through which the follower's pose and its camera's
//! pointing enter sensing. A [`CaptureGeometry`] carries it twice: `follower`, the truth, which
//! the renderer draws and the measurement audit projects from; and `navigation`, what the
//! follower believes about itself, which the sensing transform (3.3)-(3.12), the tracking
//! window and the frame records use. Today `navigation` is the truth ([`CaptureGeometry::exact`]);
//! with `[navigation]`'s error models (INS/GPS, gimbal encoders, mount misalignment) the
//! simulation supplies the follower's own solution here without touching the sensors.

use crate::frames::{EulerAngles, Mat3, Vec3};
use crate::render::camera::{AircraftPose, TargetPoseInCamera};

/// Another aircraft in the camera's world (a teammate, or a target not tracked): drawn in
/// every frame with the tracked target, as the target's mesh at its size.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OtherAircraft {
    /// Its reference point, NED, ft (true).
    pub position_ned_ft: Vec3,
    /// Its attitude (true).
    pub attitude: EulerAngles,
    /// Its size (span), ft.
    pub size_ft: f64,
}

impl OtherAircraft {
    /// How a camera on `follower` (its true pose) sees it, drawn with a mesh of
    /// `mesh_size_ft`.
    pub fn pose_from(&self, follower: &FollowerPose, mesh_size_ft: f64) -> AircraftPose {
        let camera_from_ned = follower.camera_from_ned();
        AircraftPose {
            pose: TargetPoseInCamera {
                position_body_ft: camera_from_ned
                    * (self.position_ned_ft - follower.position_ned_ft),
                body_from_target: camera_from_ned * self.attitude.body_from_ned().transpose(),
            },
            scale: self.size_ft / mesh_size_ft,
        }
    }
}

/// The follower's pose and its camera's pointing, true or as its navigation knows them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FollowerPose {
    /// R_F, NED, ft.
    pub position_ned_ft: Vec3,
    /// The velocity the follower's track follows, NED, ft/s.
    pub velocity_ned_fps: Vec3,
    /// The follower's attitude (L_BE).
    pub attitude: EulerAngles,
    /// The camera's orientation on the body, L_CB: the gimbal's angles over the fixed mount
    /// (identity: camera = body).
    pub camera_from_body: Mat3,
}

impl FollowerPose {
    /// A follower at rest at the origin with its camera along the body x axis, turned by
    /// `attitude` (for views and benches that place only the camera).
    pub fn at_origin(attitude: EulerAngles) -> Self {
        Self {
            position_ned_ft: Vec3::zeros(),
            velocity_ned_fps: Vec3::zeros(),
            attitude,
            camera_from_body: Mat3::identity(),
        }
    }

    /// L_CB L_BE: NED to camera axes.
    pub fn camera_from_ned(&self) -> Mat3 {
        self.camera_from_body * self.attitude.body_from_ned()
    }
}

/// Where the follower and target are when the sensors act.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CaptureGeometry {
    /// R_T - R_F, NED, ft (true).
    pub relative_ned_ft: Vec3,
    /// Target attitude (true).
    pub target_attitude: EulerAngles,
    /// The follower as it is: what the camera images.
    pub follower: FollowerPose,
    /// The follower as its navigation knows itself: what sensing turns measurements with.
    pub navigation: FollowerPose,
    /// Where the follower expects the target, and how large: the estimator's prediction, or
    /// before the target is first seen the gimbal's cue; `None` without either. The image
    /// pipeline's `predicted` selection reads it.
    pub expected: Option<TargetExpectation>,
}

/// Where the follower expects the target in a frame, and how large it expects it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TargetExpectation {
    /// The line of sight NED (any length).
    pub los_ned: Vec3,
    /// The target's span seen broadside at the predicted range, rad: 1/|r̂| (r̂ = R̂/b̂);
    /// `None` for a cue, which says nothing of the range.
    pub span_rad: Option<f64>,
}

impl CaptureGeometry {
    /// The geometry of a follower whose navigation is exact (its solution is the truth).
    pub fn exact(
        relative_ned_ft: Vec3,
        target_attitude: EulerAngles,
        follower: FollowerPose,
    ) -> Self {
        Self {
            relative_ned_ft,
            target_attitude,
            follower,
            navigation: follower,
            expected: None,
        }
    }

    /// A level camera at the origin looking north with exact navigation, the target
    /// `range_ft` north of it in `target_attitude` (relative to the camera's axes): the
    /// geometry of one view of the target.
    pub fn on_axis(range_ft: f64, target_attitude: EulerAngles) -> Self {
        Self::exact(
            Vec3::new(range_ft, 0.0, 0.0),
            target_attitude,
            FollowerPose::at_origin(EulerAngles::new(0.0, 0.0, 0.0)),
        )
    }

    /// L_CB L_BE, NED to camera axes, as the follower's navigation knows it: the rotation
    /// sensing turns measurements with.
    pub fn camera_from_ned(&self) -> Mat3 {
        self.navigation.camera_from_ned()
    }

    /// R as the follower reconstructs it from what its true camera sees, turned back with
    /// the camera's orientation as its navigation knows it: (L_CB L_BE)_navᵀ (L_CB L_BE) R,
    /// NED, ft (for the continuous sensors, which measure in the camera's axes). R itself when
    /// the navigation is the truth.
    pub fn sensed_relative_ned_ft(&self) -> Vec3 {
        if self.navigation == self.follower {
            return self.relative_ned_ft;
        }
        self.camera_from_ned().transpose()
            * (self.follower.camera_from_ned() * self.relative_ned_ft)
    }

    /// The target's true pose in the true camera axes (what a frame draws).
    pub fn pose(&self) -> TargetPoseInCamera {
        let camera_from_ned = self.follower.camera_from_ned();
        TargetPoseInCamera {
            position_body_ft: camera_from_ned * self.relative_ned_ft,
            body_from_target: camera_from_ned * self.target_attitude.body_from_ned().transpose(),
        }
    }
}
