//! `[scene]`: the world behind the target (docs/equations.md, Scene). The default is the sky
//! of `[camera]` (`camera.sky`, fixed on the screen), so frames are those of a scenario
//! without the section.

use super::check::{self, Check};
use serde::{Deserialize, Serialize};

/// What the camera sees behind the target.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SceneKind {
    /// The sky of `[camera]` (`sky`, `sky_rgb`, ...), the same on every frame whatever the
    /// camera's attitude.
    Sky,
    /// A world fixed in NED, drawn from the camera's true pose: sky by elevation, a horizon,
    /// the ground below, clouds and the sun (the keys below). `camera.sky` is then unused.
    World,
}

/// `[scene]`. The defaults are a clear day over farmland: a deep blue zenith fading to a pale
/// horizon, square fields of 400 ft (a small farm's, about 4 acres) with a 30 ft road every
/// fourth edge, haze hiding the ground over about 2 miles (10,000 ft), the sun 30° high behind
/// the start (south, the follower flying north), no clouds and no glare.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SceneSection {
    /// `sky` (default: `[camera]`'s sky) or `world`.
    pub kind: SceneKind,
    /// Seed of the ground's fields and the clouds (the world is the same for every
    /// `run.seed`).
    pub seed: u32,
    /// Sky colour straight up, RGB 0-255.
    pub zenith_rgb: [u8; 3],
    /// Sky colour at the horizon, and of the haze, RGB 0-255.
    pub horizon_rgb: [u8; 3],
    /// Draw the ground (false: haze below the horizon).
    pub ground: bool,
    /// The ground's height below the follower's start (`follower.initial_position_ft`), ft.
    pub ground_below_start_ft: f64,
    /// Side of a square field, ft.
    pub field_ft: f64,
    /// A road along every this many field edges, each way.
    pub road_every_fields: u32,
    /// Width of a road, ft.
    pub road_width_ft: f64,
    /// Fraction of the cloud sheet that is cloud, 0-1 (0: no clouds).
    pub cloud_coverage: f64,
    /// The cloud sheet's height above the follower's start, ft (a thin sheet: clouds are
    /// drawn behind the target, never between it and the camera).
    pub cloud_above_start_ft: f64,
    /// About the size of one cloud, ft (the noise's lattice spacing).
    pub cloud_size_ft: f64,
    /// The sun's azimuth from north, positive east, deg.
    pub sun_azimuth_deg: f64,
    /// The sun's elevation above the horizon, deg.
    pub sun_elevation_deg: f64,
    /// Glare around the sun, 0 (none) to 1 (white at the sun; falls off over about 6°).
    pub sun_glare: f64,
    /// Distance over which haze hides the ground and clouds (to 1/e of their colour), ft.
    pub visibility_ft: f64,
}

impl Default for SceneSection {
    fn default() -> Self {
        Self {
            kind: SceneKind::Sky,
            seed: 1,
            zenith_rgb: [70, 110, 190],
            horizon_rgb: [200, 212, 228],
            ground: true,
            ground_below_start_ft: 500.0,
            field_ft: 400.0,
            road_every_fields: 4,
            road_width_ft: 30.0,
            cloud_coverage: 0.0,
            cloud_above_start_ft: 1000.0,
            cloud_size_ft: 800.0,
            sun_azimuth_deg: 180.0,
            sun_elevation_deg: 30.0,
            sun_glare: 0.0,
            visibility_ft: 10_000.0,
        }
    }
}

impl SceneSection {
    /// Checks every value.
    pub fn validate(&self) -> Check {
        check::in_closed(
            "scene.ground_below_start_ft",
            self.ground_below_start_ft,
            1.0,
            1e5,
        )?;
        check::in_closed("scene.field_ft", self.field_ft, 1.0, 1e5)?;
        check::int_in(
            "scene.road_every_fields",
            i64::from(self.road_every_fields),
            1,
            1000,
        )?;
        check::in_closed("scene.road_width_ft", self.road_width_ft, 0.0, 1e4)?;
        check::in_closed("scene.cloud_coverage", self.cloud_coverage, 0.0, 1.0)?;
        check::in_closed(
            "scene.cloud_above_start_ft",
            self.cloud_above_start_ft,
            1.0,
            1e5,
        )?;
        check::in_closed("scene.cloud_size_ft", self.cloud_size_ft, 1.0, 1e5)?;
        check::in_closed("scene.sun_azimuth_deg", self.sun_azimuth_deg, -360.0, 360.0)?;
        check::in_closed(
            "scene.sun_elevation_deg",
            self.sun_elevation_deg,
            -90.0,
            90.0,
        )?;
        check::in_closed("scene.sun_glare", self.sun_glare, 0.0, 1.0)?;
        check::in_closed("scene.visibility_ft", self.visibility_ft, 1.0, 1e7)
    }
}
