//! `[camera.gimbal]`: the camera's pan/tilt (or roll/pan/tilt) gimbal (docs/equations.md,
//! Gimballed camera; `sensing::gimbal`).

use super::check::{self, Check};
use serde::{Deserialize, Serialize};

/// The camera's mount.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum GimbalKind {
    /// Fixed on the body (with `camera.mount_pitch_deg`).
    None,
    /// Pan about body z, then tilt about the panned y.
    PanTilt,
    /// A roll axis about body x that levels the pan axis against the follower's bank, then
    /// pan and tilt as `pan_tilt`: the line of sight to a target below the follower stays
    /// away from the pan axis while the follower rolls (see `roll_limits_deg`).
    RollPanTilt,
}

impl GimbalKind {
    /// Whether the gimbal has a roll axis under its pan.
    pub fn has_roll_axis(self) -> bool {
        self == Self::RollPanTilt
    }
}

/// Where the gimbal points before the camera has seen the target.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum GimbalCue {
    /// Ahead, as a camera fixed on the nose looks (the seed's).
    None,
    /// Along `cue_deg`, a bearing and elevation an operator states.
    Bearing,
    /// Along the true line of sight to the target at t = 0, as a radar or a datalink gives it.
    Target,
}

/// `[camera.gimbal]`. The defaults are of a small-UAV pan/tilt camera: tilt from straight down
/// to 30° up and pan over most of a turn (commercial two-axis payload gimbals range from
/// ±160° to continuous pan), rates of the order of 100 °/s (surveillance pan/tilt heads run
/// from a few to several hundred °/s), and a servo a few times faster than the follower's
/// attitude (τ = 0.05 s).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct GimbalSection {
    /// None (the camera is fixed), a pan/tilt gimbal, or one with a roll axis under its pan.
    pub kind: GimbalKind,
    /// Pan range [min, max], deg, positive right. A range of a full turn, [-180, 180], has
    /// no stop: the pan turns on a slip ring, the short way to any bearing (commercial
    /// payload gimbals range from ±160° to continuous pan). With stops, a line of sight
    /// crossing behind the camera holds the pan at the stop on its side, and one crossing the
    /// pan axis can send it the long way round.
    pub pan_limits_deg: [f64; 2],
    /// Tilt range [min, max], deg, positive up, within ±180°. Beyond -90° (+90°) the camera
    /// tilts through nadir (zenith), and the pointing law takes whichever angle pair that
    /// looks along the line of sight its servos reach sooner: a target passing under the
    /// follower is followed by the tilt instead of by half a turn of the pan (see
    /// `keyhole_deg`).
    pub tilt_limits_deg: [f64; 2],
    /// With a tilt range beyond ±90°, the half angle of the cone about nadir and zenith in
    /// which the pan holds and the tilt alone points the camera, deg, in [0, 45]. Near the
    /// pole a line of sight passing a little to one side turns the exact pan by up to 180°
    /// within a few degrees of travel (the keyhole); holding the pan there leaves the target
    /// at most this far off the image centre. Choice: 10°, inside the half field of view of
    /// any camera wider than 20°.
    pub keyhole_deg: f64,
    /// With `kind = "roll_pan_tilt"`, the roll axis' range [min, max], deg, positive right
    /// wing down, within ±90°. The roll axis turns the pan axis by minus the follower's bank
    /// (as its navigation knows it), so that the pan turns about the vertical of the
    /// follower's pitch plane. A pan/tilt camera's pan axis is the body's z: in a bank of 30°
    /// a target 60° below the horizon lies 0-30° from it, inside the keyhole, and a roll
    /// reversal at 60-90 °/s swings the exact pan by 90° and more in a fraction of a second
    /// (docs/findings.md, A roll axis for the camera). Choice: ±60°, twice the follower's bank
    /// limit, for the gusts' bank on top of it.
    pub roll_limits_deg: [f64; 2],
    /// Largest rate of each axis, deg/s.
    pub rate_limit_dps: f64,
    /// Time constant of each axis' servo, s.
    pub time_constant_s: f64,
    /// The camera searches about the predicted line of sight once the target has been missing
    /// this long, s.
    pub search_after_s: f64,
    /// The search circle's radius grows at this rate, deg/s.
    pub search_growth_dps: f64,
    /// ... up to this radius, deg.
    pub search_max_deg: f64,
    /// One search circle takes this long, s.
    pub search_period_s: f64,
    /// `none` (default), `bearing` or `target`: where the camera points at t = 0 and until it
    /// first measures the target (a cue, as from a radar or an operator). The search circles
    /// about the cue, or about ahead without one, from `search_after_s` after the start while
    /// the target has never been seen.
    pub cue: GimbalCue,
    /// The cue of `cue = "bearing"`: [azimuth from north, positive east; elevation above the
    /// horizon], deg, azimuth in [-360, 360], elevation in [-90, 90].
    pub cue_deg: [f64; 2],
}

impl Default for GimbalSection {
    fn default() -> Self {
        Self {
            kind: GimbalKind::None,
            pan_limits_deg: [-170.0, 170.0],
            tilt_limits_deg: [-90.0, 30.0],
            roll_limits_deg: [-60.0, 60.0],
            rate_limit_dps: 120.0,
            time_constant_s: 0.05,
            search_after_s: 0.5,
            search_growth_dps: 10.0,
            search_max_deg: 20.0,
            search_period_s: 1.5,
            keyhole_deg: 10.0,
            cue: GimbalCue::None,
            cue_deg: [0.0, 0.0],
        }
    }
}

impl GimbalSection {
    /// The pan's stops [min, max], deg: None for a range of a full turn (a slip ring).
    pub fn pan_stops_deg(&self) -> Option<[f64; 2]> {
        (self.pan_limits_deg != [-180.0, 180.0]).then_some(self.pan_limits_deg)
    }

    /// Checks every value.
    pub fn validate(&self) -> Check {
        for (key, [min, max], outer) in [
            ("camera.gimbal.pan_limits_deg", self.pan_limits_deg, 180.0),
            ("camera.gimbal.tilt_limits_deg", self.tilt_limits_deg, 180.0),
            ("camera.gimbal.roll_limits_deg", self.roll_limits_deg, 90.0),
        ] {
            check::require(
                min.is_finite()
                    && max.is_finite()
                    && -outer <= min
                    && min <= 0.0
                    && 0.0 <= max
                    && max <= outer,
                key,
                format!("[{min}, {max}]"),
                format!("[min, max] with -{outer} <= min <= 0 <= max <= {outer}"),
            )?;
        }
        check::in_closed("camera.gimbal.keyhole_deg", self.keyhole_deg, 0.0, 45.0)?;
        check::in_closed(
            "camera.gimbal.rate_limit_dps",
            self.rate_limit_dps,
            0.1,
            10_000.0,
        )?;
        check::in_closed(
            "camera.gimbal.time_constant_s",
            self.time_constant_s,
            1e-3,
            10.0,
        )?;
        check::in_closed(
            "camera.gimbal.search_after_s",
            self.search_after_s,
            0.0,
            1e4,
        )?;
        check::in_closed(
            "camera.gimbal.search_growth_dps",
            self.search_growth_dps,
            0.0,
            1e3,
        )?;
        check::in_closed(
            "camera.gimbal.search_max_deg",
            self.search_max_deg,
            0.0,
            90.0,
        )?;
        check::in_closed(
            "camera.gimbal.search_period_s",
            self.search_period_s,
            0.01,
            1e3,
        )?;
        let [azimuth_deg, elevation_deg] = self.cue_deg;
        check::require(
            (-360.0..=360.0).contains(&azimuth_deg) && (-90.0..=90.0).contains(&elevation_deg),
            "camera.gimbal.cue_deg",
            format!("[{azimuth_deg}, {elevation_deg}]"),
            "[azimuth, elevation] with azimuth in [-360, 360] and elevation in [-90, 90]",
        )
    }

    /// The unit line of sight NED of `cue_deg`.
    pub fn cue_bearing_ned(&self) -> [f64; 3] {
        let [azimuth, elevation] = self.cue_deg.map(f64::to_radians);
        [
            elevation.cos() * azimuth.cos(),
            elevation.cos() * azimuth.sin(),
            -elevation.sin(),
        ]
    }
}
