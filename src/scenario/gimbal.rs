//! `[camera.gimbal]`: the camera's pan/tilt gimbal (docs/equations.md, Gimballed camera;
//! `sensing::gimbal`).

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
}

/// `[camera.gimbal]`. The defaults are of a small-UAV pan/tilt camera: tilt from straight down
/// to 30° up and pan over most of a turn (commercial two-axis payload gimbals range from
/// ±160° to continuous pan), rates of the order of 100 °/s (surveillance pan/tilt heads run
/// from a few to several hundred °/s), and a servo a few times faster than the follower's
/// attitude (τ = 0.05 s).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct GimbalSection {
    /// None (the camera is fixed) or a pan/tilt gimbal.
    pub kind: GimbalKind,
    /// Pan range [min, max], deg, positive right.
    pub pan_limits_deg: [f64; 2],
    /// Tilt range [min, max], deg, positive up.
    pub tilt_limits_deg: [f64; 2],
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
}

impl Default for GimbalSection {
    fn default() -> Self {
        Self {
            kind: GimbalKind::None,
            pan_limits_deg: [-170.0, 170.0],
            tilt_limits_deg: [-90.0, 30.0],
            rate_limit_dps: 120.0,
            time_constant_s: 0.05,
            search_after_s: 0.5,
            search_growth_dps: 10.0,
            search_max_deg: 20.0,
            search_period_s: 1.5,
        }
    }
}

impl GimbalSection {
    /// Checks every value.
    pub fn validate(&self) -> Check {
        for (key, [min, max], outer) in [
            ("camera.gimbal.pan_limits_deg", self.pan_limits_deg, 180.0),
            ("camera.gimbal.tilt_limits_deg", self.tilt_limits_deg, 90.0),
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
        )
    }
}
