//! The follower's own sensors in the loop (`[navigation]`, [`crate::navigation`]): what each
//! consumer of the follower's own state reads. The estimator, the sensing transform, the
//! gimbal's pointing and servo, the guidance (command frame, velocity feedback) and the
//! autopilot's wind estimate read the navigation solution, the air data and the encoders; the
//! plant, the flight controller's inner loops and the renderer keep the truth. With every
//! sensor perfect each function returns the truth itself, untouched.

use super::Simulation;
use super::build::{capture_geometry, mounted_camera};
use crate::frames::{EulerAngles, Mat3, Vec3};
use crate::guidance::signals::FollowerFeedback;
use crate::navigation::{NavigationErrors, OwnSensors};
use crate::scenario::{OwnMotion, Scenario};
use crate::sensing::gimbal::Gimbal;
use crate::sensing::{CaptureGeometry, FollowerPose, FrameRecord};
use std::borrow::Cow;

/// The gimbal's angles as its encoders read them: the slice itself when they read the truth.
pub(super) fn encoder_reading<'a>(own: &OwnSensors, gimbal_x: &'a [f64]) -> Cow<'a, [f64]> {
    match own.camera() {
        Some(camera) if !gimbal_x.is_empty() => {
            let error = camera.encoder_error_rad();
            Cow::Owned(gimbal_x.iter().zip(error).map(|(x, e)| x + e).collect())
        }
        _ => Cow::Borrowed(gimbal_x),
    }
}

/// The follower's own sensors of a run and its camera's mounts.
#[derive(Debug)]
pub(super) struct OwnSensing {
    /// What the follower's navigation, air data and camera geometry read.
    pub(super) sensors: OwnSensors,
    /// The camera's true fixed mount on the body (or the gimbal's base), L_CB: what the
    /// renderer draws with.
    pub(super) mount: Mat3,
    /// The mount as the follower believes it is (`[camera]`'s, without misalignment).
    pub(super) nominal_mount: Mat3,
    /// Which navigated position the own-motion consumers (estimator, measurement hold) read.
    own_motion: OwnMotion,
}

impl OwnSensing {
    /// The sensors `[navigation]` states for a follower starting at `attitude`, and the
    /// camera's mounts.
    pub(super) fn new(scenario: &Scenario, attitude: &EulerAngles) -> Self {
        let sensors = OwnSensors::new(scenario, attitude);
        let nominal_mount = scenario.camera.camera_from_body();
        Self {
            mount: sensors
                .camera()
                .map_or(nominal_mount, |c| c.true_mount(&nominal_mount)),
            nominal_mount,
            sensors,
            own_motion: scenario.estimator.own_motion,
        }
    }

    /// The error of the position the follower's own-motion consumers read: the INS/GPS
    /// solution's, or the INS's own integration's (`estimator.own_motion`).
    fn position_error_ned_ft(&self, errors: &NavigationErrors) -> Vec3 {
        match self.own_motion {
            OwnMotion::Position => errors.position_ned_ft,
            OwnMotion::Inertial => errors.inertial_position_ned_ft,
        }
    }

    /// `geometry` with the follower's navigation of itself: its INS/GPS's position,
    /// velocity and attitude, its camera on the nominal mount at the angles the encoders
    /// read. The geometry as it is when the navigation and the camera geometry are perfect.
    pub(super) fn navigated(
        &self,
        mut geometry: CaptureGeometry,
        gimbal: Option<&Gimbal>,
        gimbal_x: &[f64],
    ) -> CaptureGeometry {
        let errors = self.sensors.navigation_errors();
        if errors.is_none() && self.sensors.camera().is_none() {
            return geometry;
        }
        let e = errors.unwrap_or_default();
        let truth = geometry.follower;
        let angles = encoder_reading(&self.sensors, gimbal_x);
        geometry.navigation = FollowerPose {
            position_ned_ft: truth.position_ned_ft + self.position_error_ned_ft(&e),
            velocity_ned_fps: truth.velocity_ned_fps + e.velocity_ned_fps,
            attitude: e.attitude(&truth.attitude),
            camera_from_body: mounted_camera(&self.nominal_mount, gimbal, &angles),
        };
        geometry
    }
}

impl Simulation {
    /// Where follower and target are at (t, x): the truth, and the follower's navigation of
    /// itself.
    pub(super) fn geometry_at(&self, t_s: f64, x: &[f64]) -> CaptureGeometry {
        let slices = self.layout.split(x);
        let truth = capture_geometry(
            self.target.as_ref(),
            &self.follower,
            slices.follower,
            t_s,
            &self.camera_from_body(slices.gimbal),
        );
        self.own
            .navigated(truth, self.gimbal.as_ref(), slices.gimbal)
    }

    /// R_F as the follower's navigation knows it for a follower slice (the position its
    /// own-motion consumers read, `estimator.own_motion`), NED, ft.
    pub(super) fn navigated_position_ned_ft(&self, follower_x: &[f64]) -> Vec3 {
        let truth = self.follower.position_ned_ft(follower_x);
        self.own
            .sensors
            .navigation_errors()
            .map_or(truth, |e| truth + self.own.position_error_ned_ft(&e))
    }

    /// The follower's attitude as its navigation knows it for a follower slice.
    pub(super) fn navigated_attitude(&self, follower_x: &[f64]) -> EulerAngles {
        let truth = self.follower.attitude(follower_x);
        self.own
            .sensors
            .navigation_errors()
            .map_or(truth, |e| e.attitude(&truth))
    }

    /// The follower's feedback to the guidance with its navigated velocity: V_a + e_v, and
    /// the shortfall V_F - V_a - e_v.
    pub(super) fn navigated_feedback(&self, follower_x: &[f64]) -> Option<FollowerFeedback> {
        let feedback = self.follower.feedback(follower_x)?;
        Some(match self.own.sensors.navigation_errors() {
            None => feedback,
            Some(e) => FollowerFeedback {
                realised_velocity_ned_fps: feedback.realised_velocity_ned_fps + e.velocity_ned_fps,
                velocity_shortfall_ned_fps: feedback.velocity_shortfall_ned_fps
                    - e.velocity_ned_fps,
            },
        })
    }

    /// L_CB L_BE of the gimbal's base as the pointing law knows it: the nominal mount and the
    /// navigated attitude.
    pub(super) fn navigated_base_from_ned(&self, follower_x: &[f64]) -> Mat3 {
        self.own.nominal_mount * self.navigated_attitude(follower_x).body_from_ned()
    }

    /// A delivered frame as the estimator gets it: stamped with the exposure clock's jitter,
    /// and with the follower's navigated position looked up at that stamp, as the follower's
    /// own software does (its position then, brought along its navigated velocity
    /// `follower_velocity_ned_fps`; the attitude's change over a few milliseconds is left
    /// out). A stamp error so moves the frame's time and its own-motion reference together,
    /// and only the relative motion over the error reaches the estimator.
    pub(super) fn stamped(
        &mut self,
        record: &FrameRecord,
        follower_velocity_ned_fps: &Vec3,
    ) -> FrameRecord {
        match self.own.sensors.camera_mut() {
            Some(camera) => {
                let t_s = camera.stamp_s(record.t_s);
                FrameRecord {
                    t_s,
                    follower_position_ned_ft: record.follower_position_ned_ft
                        + follower_velocity_ned_fps * (t_s - record.t_s),
                    ..*record
                }
            }
            None => *record,
        }
    }

    /// The follower's own sensors advance one tick and the autopilot holds what they read
    /// over the step.
    pub(super) fn advance_own_sensors(&mut self, dt_s: f64) {
        let follower_x = self.layout.split(&self.state).follower;
        let attitude = self.follower.attitude(follower_x);
        self.own.sensors.advance(dt_s, &attitude);
        self.follower
            .hold_own_state_errors(self.own.sensors.own_state_errors());
    }

    /// The follower as its navigation knows itself now, when that is not the truth.
    pub(super) fn navigation_reading(&self) -> Option<FollowerPose> {
        self.own
            .sensors
            .ins()
            .map(|_| self.capture_geometry().navigation)
    }
}
