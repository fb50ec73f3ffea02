//! The camera's pan/tilt gimbal (seed 8.2 "Field of View"; `docs/equations.md`, Frames and
//! angles).
//!
//! Camera frame C: pan ψ_g about the body z axis (positive right), then tilt θ_g about the
//! panned y axis (positive up, like pitch): L_CB is the DCM L(0, θ_g, ψ_g) of `docs/equations.md`, Frames and angles; with both zero
//! the camera looks along the body x axis. The angles are measured (encoders), so the sensing
//! transform uses L_CB L_BE of the frame's capture.
//!
//! With `kind = "roll_pan_tilt"` a roll axis ρ_g about the body x axis comes first (outermost):
//! L_CB = L(0, θ_g, ψ_g) L(ρ_g, 0, 0). Its law holds it at minus the bank of the gimbal's base
//! (as the navigation knows it), so that the pan turns about the vertical of the pitch plane
//! whatever the bank; the pan and tilt then point the camera in the rolled axes.
//!
//! Each axis is a first-order servo, θ̇ = (θ_c - θ)/τ limited to ±`rate_limit`, held inside its
//! angle limits. The pointing law aims the camera at a line of sight given in NED: the
//! estimator's prediction of where the target is now (the latest measured frame brought
//! forward by the follower's own motion, or the Kalman filter's r̂), turned into body axes with
//! the follower's attitude now. So the body's rotation since the frame is fed forward, and
//! while frames measure the target the camera keeps it near the image centre; while none does
//! it keeps pointing where the estimator predicts, and once the target has been missing for
//! `search_after_s` it circles about that prediction with a radius growing at
//! `search_growth_dps` up to `search_max_deg` (one circle every `search_period_s`). Before the
//! target is first seen there is no prediction: the camera points along the cue
//! (`camera.gimbal.cue`, a line of sight NED from a radar or an operator) or ahead, and from
//! `search_after_s` after the start circles about it the same way.

use crate::frames::{EulerAngles, Mat3, Vec3, wrap_angle_rad};
use crate::scenario::GimbalSection;
use std::f64::consts::{FRAC_PI_2, PI};

/// Length of the gimbal's state: `[ψ_g, θ_g, ρ_g]` (ρ_g held at 0 without a roll axis).
pub const GIMBAL_STATE_LEN: usize = 3;

/// The names of the gimbal's state elements (for messages).
pub const GIMBAL_STATE_NAMES: [&str; GIMBAL_STATE_LEN] =
    ["gimbal: pan, rad", "gimbal: tilt, rad", "gimbal: roll, rad"];

/// The gimbal's angles, rad.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct GimbalAngles {
    /// Pan ψ_g, positive right.
    pub pan_rad: f64,
    /// Tilt θ_g, positive up.
    pub tilt_rad: f64,
    /// Roll ρ_g about the body x axis, positive right wing down (0 without a roll axis).
    pub roll_rad: f64,
}

impl GimbalAngles {
    /// The angles of a state slice.
    pub fn of(x: &[f64]) -> Self {
        Self {
            pan_rad: x[0],
            tilt_rad: x[1],
            roll_rad: x[2],
        }
    }

    /// L_CB: body to camera axes.
    pub fn camera_from_body(&self) -> Mat3 {
        let panned = EulerAngles::new(0.0, self.tilt_rad, self.pan_rad).body_from_ned();
        if self.roll_rad == 0.0 {
            panned
        } else {
            panned * self.rolled_from_body()
        }
    }

    /// L(ρ_g, 0, 0): body to the roll axis' (the pan's base) axes.
    fn rolled_from_body(&self) -> Mat3 {
        EulerAngles::new(self.roll_rad, 0.0, 0.0).body_from_ned()
    }

    /// `direction_body` in the roll axis' axes (itself without a roll).
    fn rolled(&self, direction_body: &Vec3) -> Vec3 {
        if self.roll_rad == 0.0 {
            *direction_body
        } else {
            self.rolled_from_body() * direction_body
        }
    }

    /// The pan and tilt that point the camera along `direction_rolled` (any length, in the
    /// roll axis' axes: the body's without one), with the roll `roll_rad`.
    pub fn pointing_along(direction_rolled: &Vec3, roll_rad: f64) -> Self {
        Self {
            pan_rad: direction_rolled.y.atan2(direction_rolled.x),
            tilt_rad: (-direction_rolled.z).atan2(direction_rolled.x.hypot(direction_rolled.y)),
            roll_rad,
        }
    }
}

/// A two-axis (pan/tilt) or three-axis (roll/pan/tilt) gimbal with its servos and pointing
/// law.
#[derive(Debug, Clone, PartialEq)]
pub struct Gimbal {
    /// None for a pan without stops (a slip ring).
    pan_limits_rad: Option<[f64; 2]>,
    tilt_limits_rad: [f64; 2],
    /// [0, 0] without a roll axis.
    roll_limits_rad: [f64; 2],
    /// Whether it has a roll axis (`kind = "roll_pan_tilt"`).
    roll_axis: bool,
    rate_limit_rps: f64,
    time_constant_s: f64,
    search_after_s: f64,
    search_growth_rps: f64,
    search_max_rad: f64,
    search_omega_rps: f64,
    /// Half angle of the cone about the poles in which the pan holds (tilt beyond ±90°), rad.
    keyhole_rad: f64,
    /// The line of sight NED the camera points along until the target is first seen.
    cue_ned: Option<Vec3>,
}

impl Gimbal {
    /// The gimbal a `[camera.gimbal]` section describes, cued along `cue_ned` (a line of sight
    /// NED, any length) when given.
    pub fn new(section: &GimbalSection, cue_ned: Option<Vec3>) -> Self {
        let radians = |deg: [f64; 2]| deg.map(f64::to_radians);
        Self {
            pan_limits_rad: section.pan_stops_deg().map(radians),
            tilt_limits_rad: radians(section.tilt_limits_deg),
            roll_limits_rad: if section.kind.has_roll_axis() {
                radians(section.roll_limits_deg)
            } else {
                [0.0; 2]
            },
            roll_axis: section.kind.has_roll_axis(),
            rate_limit_rps: section.rate_limit_dps.to_radians(),
            time_constant_s: section.time_constant_s,
            search_after_s: section.search_after_s,
            search_growth_rps: section.search_growth_dps.to_radians(),
            search_max_rad: section.search_max_deg.to_radians(),
            search_omega_rps: std::f64::consts::TAU / section.search_period_s,
            keyhole_rad: section.keyhole_deg.to_radians(),
            cue_ned,
        }
    }

    /// Whether the gimbal has a roll axis (`kind = "roll_pan_tilt"`).
    pub fn has_roll_axis(&self) -> bool {
        self.roll_axis
    }

    /// The line of sight NED the camera points along until the target is first seen.
    pub fn cue_ned(&self) -> Option<Vec3> {
        self.cue_ned
    }

    /// At the start the camera looks along the cue, or ahead without one (as near as its
    /// limits allow), for a follower whose L_BE is `body_from_ned`.
    pub fn initial_state(&self, body_from_ned: &Mat3) -> [f64; GIMBAL_STATE_LEN] {
        let roll_rad = self.roll_command_rad(body_from_ned);
        let level = GimbalAngles {
            roll_rad,
            ..GimbalAngles::default()
        };
        let angles = self.cue_ned.map_or(level, |cue| {
            GimbalAngles::pointing_along(&level.rolled(&(body_from_ned * cue)), roll_rad)
        });
        self.clamped(&angles)
    }

    /// The roll axis' command for a base whose L_BE is `body_from_ned`: minus its bank,
    /// within the limits (0 without a roll axis).
    fn roll_command_rad(&self, body_from_ned: &Mat3) -> f64 {
        if !self.roll_axis {
            return 0.0;
        }
        let [min, max] = self.roll_limits_rad;
        let bank_rad = EulerAngles::from_body_from_ned(body_from_ned).phi_rad;
        (-bank_rad).clamp(min, max)
    }

    /// The commanded angles at `t_s`: along the predicted line of sight `line_of_sight_ned`
    /// (before the target is first seen, the cue; without one, hold the present angles, or
    /// search about ahead) for a follower whose L_BE is `body_from_ned`, plus the search
    /// circle when the target has been missing for `missing_s`; inside the limits.
    pub fn command(
        &self,
        x: &[f64],
        line_of_sight_ned: Option<Vec3>,
        body_from_ned: &Mat3,
        missing_s: f64,
        t_s: f64,
    ) -> GimbalAngles {
        let now = GimbalAngles::of(x);
        let searching_s = missing_s - self.search_after_s;
        let roll_rad = self.roll_command_rad(body_from_ned);
        let mut angles = match line_of_sight_ned.or(self.cue_ned) {
            Some(los) => self.nearest_pointing(&now.rolled(&(body_from_ned * los)), &now),
            None if searching_s > 0.0 => GimbalAngles::default(),
            None => return GimbalAngles { roll_rad, ..now },
        };
        angles.roll_rad = roll_rad;
        if searching_s > 0.0 {
            let radius = (self.search_growth_rps * searching_s).min(self.search_max_rad);
            let (s, c) = (self.search_omega_rps * t_s).sin_cos();
            angles.pan_rad += radius * c;
            angles.tilt_rad += radius * s;
        }
        let [pan_rad, tilt_rad, roll_rad] = self.clamped(&angles);
        GimbalAngles {
            pan_rad,
            tilt_rad,
            roll_rad,
        }
    }

    /// The angles that point along `direction_rolled` (in the roll axis' axes, the body's
    /// without one) nearest the present angles `now`, the roll held. The
    /// pan is taken nearest the present one: a target crossing behind the camera's pan range
    /// holds the pan at the limit on its side instead of swinging the long way round (a pan
    /// without stops turns through the back). With a
    /// tilt range beyond ±90° the camera can also look along the direction over the pole,
    /// (ψ + π, ±180° - θ): the pair the servos reach sooner is taken, and within the keyhole
    /// cone about the pole the pan holds while the tilt points the camera as near the
    /// direction as the held pan allows. So a line of sight passing under (or over) the
    /// follower is followed by the tilt through nadir (zenith) instead of by half a turn of
    /// the pan.
    fn nearest_pointing(&self, direction_rolled: &Vec3, now: &GimbalAngles) -> GimbalAngles {
        let near_pan = |a: GimbalAngles| GimbalAngles {
            pan_rad: now.pan_rad + wrap_angle_rad(a.pan_rad - now.pan_rad),
            ..a
        };
        let direct = near_pan(GimbalAngles::pointing_along(direction_rolled, now.roll_rad));
        let [tilt_min, tilt_max] = self.tilt_limits_rad;
        if tilt_min >= -FRAC_PI_2 && tilt_max <= FRAC_PI_2 {
            return direct;
        }
        let d = direction_rolled;
        let from_pole_rad = d.x.hypot(d.y).atan2(d.z.abs());
        if from_pole_rad < self.keyhole_rad {
            let (sin_pan, cos_pan) = now.pan_rad.sin_cos();
            return GimbalAngles {
                tilt_rad: (-d.z).atan2(d.x * cos_pan + d.y * sin_pan),
                ..*now
            };
        }
        let over = near_pan(GimbalAngles {
            pan_rad: direct.pan_rad + PI,
            tilt_rad: PI.copysign(direct.tilt_rad) - direct.tilt_rad,
            ..direct
        });
        let slew_rad = |a: &GimbalAngles| {
            let reachable = self.clamped(a) == [a.pan_rad, a.tilt_rad, a.roll_rad];
            let slew = (a.pan_rad - now.pan_rad)
                .abs()
                .max((a.tilt_rad - now.tilt_rad).abs());
            (!reachable, slew)
        };
        if slew_rad(&over) < slew_rad(&direct) {
            over
        } else {
            direct
        }
    }

    /// The servos' rates toward `command`: (θ_c - θ)/τ within ±rate, zero at a limit.
    pub fn derivative(&self, x: &[f64], command: &GimbalAngles, dx: &mut [f64]) {
        let now = GimbalAngles::of(x);
        for (i, (angle, commanded, [min, max])) in [
            (now.pan_rad, command.pan_rad, self.pan_range_rad()),
            (now.tilt_rad, command.tilt_rad, self.tilt_limits_rad),
            (now.roll_rad, command.roll_rad, self.roll_limits_rad),
        ]
        .into_iter()
        .enumerate()
        {
            let rate = ((commanded - angle) / self.time_constant_s)
                .clamp(-self.rate_limit_rps, self.rate_limit_rps);
            let blocked = (angle >= max && rate > 0.0) || (angle <= min && rate < 0.0);
            dx[i] = if blocked { 0.0 } else { rate };
        }
    }

    /// Holds the angles inside their limits after a step; a pan without stops is wrapped
    /// into (-180°, 180°].
    pub fn normalize(&self, x: &mut [f64]) {
        let mut clamped = self.clamped(&GimbalAngles::of(x));
        // Only beyond ±180°: the wrap's arithmetic would move an angle inside by its last bits.
        if self.pan_limits_rad.is_none() && clamped[0].abs() > PI {
            clamped[0] = wrap_angle_rad(clamped[0]);
        }
        x.copy_from_slice(&clamped);
    }

    /// The pan's range, rad: its stops, or unbounded without them.
    fn pan_range_rad(&self) -> [f64; 2] {
        self.pan_limits_rad
            .unwrap_or([f64::NEG_INFINITY, f64::INFINITY])
    }

    fn clamped(&self, a: &GimbalAngles) -> [f64; GIMBAL_STATE_LEN] {
        let [pan_min, pan_max] = self.pan_range_rad();
        let [tilt_min, tilt_max] = self.tilt_limits_rad;
        let [roll_min, roll_max] = self.roll_limits_rad;
        [
            a.pan_rad.clamp(pan_min, pan_max),
            a.tilt_rad.clamp(tilt_min, tilt_max),
            a.roll_rad.clamp(roll_min, roll_max),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenario::GimbalKind;
    use crate::sensing::{image_from_relative_position, scaled_relative_position};
    use proptest::prelude::*;

    fn gimbal() -> Gimbal {
        Gimbal::new(&GimbalSection::default(), None)
    }

    proptest! {
        /// The sensing transform's round trip (3.1)-(3.12) through a gimbal: a point projected with L_CB L_BE and read
        /// back with the same rotation gives R/b, for any attitude and gimbal angles that keep
        /// the point in front of the camera.
        #[test]
        fn sensing_round_trip_through_the_gimbal(
            phi in -1.0f64..1.0, theta in -0.8f64..0.8, psi in -3.0f64..3.0,
            pan in -2.5f64..2.5, tilt in -1.4f64..0.5,
            bearing in -0.5f64..0.5, elevation in -0.4f64..0.4, range in 5.0f64..500.0,
        ) {
            let camera_from_body = GimbalAngles { pan_rad: pan, tilt_rad: tilt, roll_rad: 0.0 }.camera_from_body();
            let camera_from_ned = camera_from_body * EulerAngles::new(phi, theta, psi).body_from_ned();
            let p_camera = crate::sensing::line_of_sight_body(bearing, elevation) * range;
            let rel_ned = camera_from_ned.transpose() * p_camera;
            let m = image_from_relative_position(&rel_ned, &camera_from_ned, 8.0, 554.0).expect("ahead");
            let r = scaled_relative_position(&m, 554.0, &camera_from_ned);
            prop_assert!((r - rel_ned / 8.0).norm() <= 1e-9 * rel_ned.norm());
        }
    }

    /// Pointing along a direction centres it: the direction is the camera's x axis.
    #[test]
    fn pointing_centres_the_direction() {
        let u_body = Vec3::new(30.0, 20.0, -10.0);
        let angles = GimbalAngles::pointing_along(&u_body, 0.0);
        let in_camera = angles.camera_from_body() * u_body;
        assert!(in_camera.y.abs() < 1e-12 && in_camera.z.abs() < 1e-12 && in_camera.x > 0.0);
        assert!(
            angles.pan_rad > 0.0 && angles.tilt_rad > 0.0,
            "right and up"
        );
    }

    /// The servo is rate limited and stops at its limits; the command stays inside them.
    #[test]
    fn servo_rate_and_angle_limits() {
        let g = gimbal();
        let mut dx = [0.0; 3];
        let far = GimbalAngles {
            pan_rad: 3.0,
            tilt_rad: -3.0,
            roll_rad: 0.5,
        };
        g.derivative(&[0.0, 0.0, 0.0], &far, &mut dx);
        let rate = GimbalSection::default().rate_limit_dps.to_radians();
        assert_eq!(dx, [rate, -rate, 0.0], "no roll axis: the roll holds");
        let pan_max = GimbalSection::default().pan_limits_deg[1].to_radians();
        g.derivative(&[pan_max, 0.0, 0.0], &far, &mut dx);
        assert_eq!(dx[0], 0.0);
        let behind = g.command(
            &[0.0, 0.0, 0.0],
            Some(Vec3::new(-1.0, -0.01, 0.0)),
            &Mat3::identity(),
            0.0,
            0.0,
        );
        assert!(behind.pan_rad >= -pan_max - 1e-12);
        // Behind on the right while panned right: hold the right limit, not the left one.
        let right = g.command(
            &[2.9, 0.0, 0.0],
            Some(Vec3::new(-1.0, -0.01, 0.0)),
            &Mat3::identity(),
            0.0,
            0.0,
        );
        assert_eq!(right.pan_rad, pan_max);
    }

    /// A line of sight passing under the follower, from ahead and below to behind and below:
    /// a gimbal whose tilt stops at nadir swings its pan to its limit (the keyhole), one that
    /// tilts through nadir follows it with the tilt, the pan held within the keyhole cone,
    /// and centres it again beyond.
    #[test]
    fn a_line_of_sight_under_the_follower_is_followed_through_nadir() {
        let level = Mat3::identity();
        let sweep = |section: &GimbalSection| {
            let g = Gimbal::new(section, None);
            let mut x = [0.0, -0.5, 0.0];
            let mut largest_pan_rad: f64 = 0.0;
            for k in 0..=160 {
                let elevation = (-10.0 - k as f64).to_radians(); // below, ahead to behind
                let los = Vec3::new(elevation.cos(), 0.02, -elevation.sin());
                let a = g.command(&x, Some(los), &level, 0.0, 0.0);
                largest_pan_rad = largest_pan_rad.max(a.pan_rad.abs());
                let in_camera = a.camera_from_body() * los;
                let centred = in_camera.x > 0.0 && in_camera.y.hypot(in_camera.z) < 1e-9;
                x = [a.pan_rad, a.tilt_rad, a.roll_rad];
                if k == 160 {
                    return (
                        largest_pan_rad.to_degrees(),
                        centred,
                        a.tilt_rad.to_degrees(),
                    );
                }
            }
            unreachable!()
        };
        let stops_at_nadir = GimbalSection::default();
        let (pan_deg, _, _) = sweep(&stops_at_nadir);
        assert!(pan_deg > 160.0, "the keyhole: pan {pan_deg}°");
        let through_nadir = GimbalSection {
            tilt_limits_deg: [-180.0, 30.0],
            ..GimbalSection::default()
        };
        let (pan_deg, centred, tilt_deg) = sweep(&through_nadir);
        // The line of sight passes 0.02 to the right: centring it at the keyhole cone's edge,
        // 10° from nadir, takes atan(0.02 / sin 10°) = 6.6° of pan, which then holds.
        assert!(pan_deg < 7.0, "pan {pan_deg}°");
        assert!(
            centred && (tilt_deg + 170.0).abs() < 1.0,
            "tilt {tilt_deg}°"
        );
        let no_keyhole = GimbalSection {
            keyhole_deg: 0.0,
            ..through_nadir
        };
        let (pan_deg, _, _) = sweep(&no_keyhole);
        assert!(
            pan_deg > 45.0,
            "exact pointing swings the pan near nadir: {pan_deg}°"
        );
    }

    /// Missing the target, the camera circles about the prediction, wider with time, up to
    /// the largest radius.
    #[test]
    fn search_widens_about_the_prediction() {
        let g = gimbal();
        let section = GimbalSection::default();
        let los = Some(Vec3::new(1.0, 0.0, 0.0));
        let offset = |missing: f64, t: f64| {
            let a = g.command(&[0.0, 0.0, 0.0], los, &Mat3::identity(), missing, t);
            a.pan_rad.hypot(a.tilt_rad)
        };
        assert_eq!(offset(0.0, 0.3), 0.0);
        let early = offset(section.search_after_s + 0.5, 0.3);
        let later = offset(section.search_after_s + 1.0, 0.3);
        assert!(later > early && early > 0.0, "{early} {later}");
        let widest = offset(section.search_after_s + 1000.0, 0.3);
        assert!((widest - section.search_max_deg.to_radians()).abs() < 1e-9);
    }

    #[test]
    fn a_never_seen_target_is_searched_for_about_ahead_or_the_cue() {
        let section = GimbalSection::default();
        let level = Mat3::identity();
        let at = |gimbal: &Gimbal, missing_s: f64| {
            let x = [0.0, -0.2, 0.0];
            gimbal.command(&x, None, &level, missing_s, 0.3)
        };
        let uncued = gimbal();
        assert_eq!(
            at(&uncued, 0.2),
            GimbalAngles::of(&[0.0, -0.2, 0.0]),
            "holds at first"
        );
        let searching = at(&uncued, section.search_after_s + 1.0);
        let radius = searching.pan_rad.hypot(searching.tilt_rad);
        assert!((radius - section.search_growth_dps.to_radians()).abs() < 1e-9);
        let down = Vec3::new(1.0, 0.0, 1.0);
        let cued = Gimbal::new(&section, Some(down));
        assert_eq!(
            cued.initial_state(&level),
            [0.0, -std::f64::consts::FRAC_PI_4, 0.0]
        );
        let centred = at(&cued, 0.2);
        assert!((centred.tilt_rad + std::f64::consts::FRAC_PI_4).abs() < 1e-12);
    }

    /// The largest angle between the camera's axis and the line of sight `los_at(t)` (NED)
    /// after the first 0.05 s, the follower's attitude `body_from_ned_at(t)`, the servos
    /// integrated at 1 ms over 2 s, deg.
    fn largest_pointing_error_deg(
        section: &GimbalSection,
        los_at: impl Fn(f64) -> Vec3,
        body_from_ned_at: impl Fn(f64) -> Mat3,
    ) -> f64 {
        let g = Gimbal::new(section, Some(los_at(0.0)));
        let dt_s = 1e-3;
        let mut x = g.initial_state(&body_from_ned_at(0.0));
        let mut dx = [0.0; GIMBAL_STATE_LEN];
        let mut largest_deg: f64 = 0.0;
        for k in 0..2000 {
            let t_s = k as f64 * dt_s;
            let (los, body_from_ned) = (los_at(t_s), body_from_ned_at(t_s));
            let command = g.command(&x, Some(los), &body_from_ned, 0.0, t_s);
            let axis = (GimbalAngles::of(&x).camera_from_body() * body_from_ned).transpose()
                * Vec3::new(1.0, 0.0, 0.0);
            if t_s > 0.05 {
                largest_deg = largest_deg.max(axis.angle(&los).to_degrees());
            }
            g.derivative(&x, &command, &mut dx);
            x.iter_mut().zip(dx).for_each(|(a, rate)| *a += rate * dt_s);
            g.normalize(&mut x);
        }
        largest_deg
    }

    /// The largest pointing error while a line of sight fixed in NED, 55° below the horizon
    /// abeam on the right, is held as the follower rolls from 40° left wing down to 30° right
    /// at 90 °/s (a weave's reversal), deg.
    fn largest_pointing_error_in_a_roll_reversal_deg(section: &GimbalSection) -> f64 {
        let elevation = -55f64.to_radians();
        let los = Vec3::new(0.0, elevation.cos(), -elevation.sin());
        let roll_rate_rps = 90f64.to_radians();
        let bank_at =
            |t_s: f64| (-40f64.to_radians() + roll_rate_rps * t_s).min(30f64.to_radians());
        largest_pointing_error_deg(
            section,
            |_| los,
            |t_s| EulerAngles::new(bank_at(t_s), 0.0, 0.0).body_from_ned(),
        )
    }

    /// In a roll reversal a line of sight below the follower passes through the pan axis (the
    /// body's z): a pan/tilt camera, even one that tilts through nadir, loses it from a 60°
    /// image (85° off at worst; 30° is the image's horizontal half-width). The roll axis keeps
    /// the pan axis level and the camera on it: its servo lags a 90 °/s bank by up to
    /// 90 °/s × τ = 4.5°, and the pan and tilt, pointing in the rolled axes the encoder reads,
    /// take most of that up (1.7° off at worst; the test allows 3°).
    #[test]
    fn a_roll_axis_keeps_the_camera_on_a_target_below_through_a_roll_reversal() {
        let pan_tilt = GimbalSection {
            kind: GimbalKind::PanTilt,
            tilt_limits_deg: [-120.0, 90.0],
            ..GimbalSection::default()
        };
        let rolling = GimbalSection {
            kind: GimbalKind::RollPanTilt,
            ..pan_tilt.clone()
        };
        let pan_tilt_deg = largest_pointing_error_in_a_roll_reversal_deg(&pan_tilt);
        let rolling_deg = largest_pointing_error_in_a_roll_reversal_deg(&rolling);
        assert!(pan_tilt_deg > 30.0, "pan/tilt: {pan_tilt_deg}°");
        assert!(rolling_deg < 3.0, "roll/pan/tilt: {rolling_deg}°");
    }

    /// The roll axis levels the pan axis: with the roll at minus the bank, the camera
    /// pointed along a line of sight centres it, and with the follower's pitch level the
    /// image's horizontal is level whatever its bank.
    #[test]
    fn the_roll_axis_levels_the_pan_axis() {
        let section = GimbalSection {
            kind: GimbalKind::RollPanTilt,
            ..GimbalSection::default()
        };
        let g = Gimbal::new(&section, Some(Vec3::new(1.0, 0.3, 0.8)));
        let body_from_ned = EulerAngles::new(0.5, 0.0, 1.0).body_from_ned();
        let x = g.initial_state(&body_from_ned);
        assert!((x[2] + 0.5).abs() < 1e-12, "roll {}", x[2]);
        let camera_from_ned = GimbalAngles::of(&x).camera_from_body() * body_from_ned;
        let centred = camera_from_ned * Vec3::new(1.0, 0.3, 0.8);
        assert!(centred.y.abs() < 1e-9 && centred.z.abs() < 1e-9 && centred.x > 0.0);
        let camera_y_down = camera_from_ned.transpose() * Vec3::new(0.0, 1.0, 0.0);
        assert!(
            camera_y_down.z.abs() < 1e-9,
            "the image's horizontal is level: {camera_y_down}"
        );
    }

    /// A line of sight crossing behind a level follower, its bearing from 160° through 180°
    /// to -160° at 20 °/s: a pan with stops at ±170° holds at its stop on the near side while
    /// the bearing goes on, 30° off at the end (the image's half-width: the target leaves a
    /// 60° image). A pan without stops (a range of a full turn) follows it the short way
    /// through 180°, lagging 20 °/s × τ = 1°, and its angle is kept in (-180°, 180°].
    #[test]
    fn a_pan_without_stops_follows_a_line_of_sight_round_behind() {
        let bearing_at = |t_s: f64| (160.0 + 20.0 * t_s).to_radians();
        let los_at = |t_s: f64| Vec3::new(bearing_at(t_s).cos(), bearing_at(t_s).sin(), 0.0);
        let with_limits = |pan_limits_deg| GimbalSection {
            kind: GimbalKind::PanTilt,
            pan_limits_deg,
            ..GimbalSection::default()
        };
        let stopped = with_limits([-170.0, 170.0]);
        let continuous = with_limits([-180.0, 180.0]);
        assert_eq!(stopped.pan_stops_deg(), Some([-170.0, 170.0]));
        assert_eq!(continuous.pan_stops_deg(), None);
        let stopped_deg = largest_pointing_error_deg(&stopped, los_at, |_| Mat3::identity());
        let continuous_deg = largest_pointing_error_deg(&continuous, los_at, |_| Mat3::identity());
        assert!(stopped_deg > 29.0, "stops at ±170°: {stopped_deg:.1}°");
        assert!(continuous_deg < 1.5, "no stops: {continuous_deg:.1}°");
        let g = Gimbal::new(&continuous, None);
        let mut x = [3.2, 0.0, 0.0];
        g.normalize(&mut x);
        assert!((x[0] - (3.2 - std::f64::consts::TAU)).abs() < 1e-12);
    }

    /// A target passing the level follower 12 ft abeam at 35 ft/s (an S-turn leg crossing its
    /// track at the floor speed), from 35 ft ahead to 35 ft behind: the line of sight turns
    /// at up to 35 / 12 rad/s = 167 °/s. The 8 ft target then spans 2 atan(4 / 12) = 37° of
    /// the 60° image, so it touches the image's border once the camera is 30° - 18.4° = 11.6°
    /// off it. At 120 °/s (the default) the pan falls 18.2° behind; at 300 °/s it lags 8.2°,
    /// about the servo's 167 °/s × τ = 8.4° alone.
    #[test]
    fn a_close_pass_is_followed_by_a_servo_faster_than_the_line_of_sight() {
        let (miss_ft, speed_fps) = (12.0, 35.0);
        let los_at = |t_s: f64| Vec3::new(35.0 - speed_fps * t_s, miss_ft, 0.0).normalize();
        let error_at_rate_deg = |rate_limit_dps: f64| {
            let section = GimbalSection {
                rate_limit_dps,
                ..GimbalSection::default()
            };
            largest_pointing_error_deg(&section, los_at, |_| Mat3::identity())
        };
        let (slow_deg, fast_deg) = (error_at_rate_deg(120.0), error_at_rate_deg(300.0));
        println!("largest pointing error: {slow_deg:.1}° at 120 °/s, {fast_deg:.1}° at 300 °/s");
        assert!(slow_deg > 11.6, "120 °/s: {slow_deg:.1}°");
        assert!(fast_deg < 11.6, "300 °/s: {fast_deg:.1}°");
    }
}
