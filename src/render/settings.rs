//! What a renderer draws besides the target's geometry: image size and sampling, the sky, the
//! sensor noise and the target's shading. Fixed for the life of a [`crate::render::Renderer`].

use crate::frames::Vec3;
use crate::render::camera::CameraIntrinsics;
use crate::render::scene::WorldScene;

/// Default sky colour (RGB, 0-255): light blue-grey, Rec. 601 luma 196.
pub const DEFAULT_SKY_RGB: [u8; 3] = [175, 200, 230];

/// The sky behind the target.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Sky {
    /// One colour everywhere (RGB, 0-255).
    Uniform {
        /// Sky colour.
        rgb: [u8; 3],
    },
    /// Linear blend from the top row's colour to the bottom row's (RGB, 0-255), by image row.
    VerticalGradient {
        /// Colour at the top of the image.
        top_rgb: [u8; 3],
        /// Colour at the bottom of the image.
        bottom_rgb: [u8; 3],
    },
    /// The world fixed in NED: sky by elevation, ground, clouds and sun, drawn from the
    /// camera's true pose ([`crate::render::Renderer::set_camera_in_world`]); the sun lights
    /// the target in place of [`TargetShading::light_dir_body`].
    World(WorldScene),
}

impl Default for Sky {
    fn default() -> Self {
        Sky::Uniform {
            rgb: DEFAULT_SKY_RGB,
        }
    }
}

/// Per-pixel Gaussian sensor noise, the same value added to R, G and B of every pixel (sky and
/// target) after readback, then rounded and clamped to 0-255. Deterministic: a function of
/// (seed, frame index, pixel); see [`crate::render::noise`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PixelNoise {
    /// Standard deviation, grey levels (0-255 scale).
    pub std_grey_levels: f64,
    /// Seed; frames with the same seed and frame index get the same noise.
    pub seed: u64,
}

/// What is drawn where the target is not, and the sensor noise on top.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Background {
    /// Sky colour or gradient.
    pub sky: Sky,
    /// Optional per-pixel noise (applies to the whole image).
    pub noise: Option<PixelNoise>,
}

/// How the target is shaded: flat faces, two-sided Lambert with one light fixed in camera axes,
/// grey between `unlit_grey` and `lit_grey` (keep both well below the sky so that the whole
/// silhouette stays darker than the background).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TargetShading {
    /// Grey level (0-255) of a face edge-on to the light.
    pub unlit_grey: u8,
    /// Grey level (0-255) of a face square to the light.
    pub lit_grey: u8,
    /// Direction towards the light, camera/body axes (need not be unit length).
    pub light_dir_body: Vec3,
}

impl Default for TargetShading {
    fn default() -> Self {
        Self {
            unlit_grey: 40,
            lit_grey: 100,
            // From above, slightly behind and right of the camera.
            light_dir_body: Vec3::new(-0.4, 0.3, -0.87),
        }
    }
}

/// Everything fixed for the life of a renderer.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RenderSettings {
    /// Camera resolution and focal length; the projection matches it exactly.
    pub intrinsics: CameraIntrinsics,
    /// Samples per pixel: 1 (aliased edges; pixel drawn when its centre is covered) or 4 (edge
    /// pixels blend target and sky by coverage; slower on lavapipe, docs/findings.md,
    /// Rendering on lavapipe).
    pub msaa_samples: u32,
    /// Draw the target (multisampled when there are several samples) only in a window around
    /// its projected bounding box, over a one-sample sky (see [`crate::render::window`]);
    /// false draws target and sky together over the whole image.
    pub target_window: bool,
    /// Sky and noise.
    pub background: Background,
    /// Target grey levels and light.
    pub shading: TargetShading,
}

impl RenderSettings {
    /// Checks every setting; `max_texture_side_px` is the device's largest 2D texture side.
    /// The error names the setting, its value and the allowed range.
    pub fn validate(&self, max_texture_side_px: u32) -> Result<(), String> {
        let cam = &self.intrinsics;
        let max = max_texture_side_px;
        let bad = |msg: String| Err(msg);
        if cam.width_px == 0 || cam.height_px == 0 || cam.width_px > max || cam.height_px > max {
            return bad(format!(
                "image size {}x{} px must be between 1 and {max} px on each side",
                cam.width_px, cam.height_px
            ));
        }
        if !(cam.focal_px.is_finite() && cam.focal_px > 0.0) {
            return bad(format!("focal_px {} must be finite and > 0", cam.focal_px));
        }
        if !matches!(self.msaa_samples, 1 | 4) {
            return bad(format!("msaa_samples {} must be 1 or 4", self.msaa_samples));
        }
        if let Some(noise) = self.background.noise
            && !(noise.std_grey_levels.is_finite() && noise.std_grey_levels >= 0.0)
        {
            return bad(format!(
                "noise std_grey_levels {} must be finite and >= 0",
                noise.std_grey_levels
            ));
        }
        if let Sky::World(world) = &self.background.sky {
            validate_world(world)?;
        }
        let light = self.shading.light_dir_body;
        if !(light.iter().all(|x| x.is_finite()) && light.norm() > 0.0) {
            return bad(format!(
                "shading light_dir_body {light:?} must be a finite non-zero vector"
            ));
        }
        Ok(())
    }

    /// Settings with the default sky, no noise, default shading and 1 sample per pixel.
    pub fn new(intrinsics: CameraIntrinsics) -> Self {
        Self {
            intrinsics,
            msaa_samples: 1,
            target_window: true,
            background: Background::default(),
            shading: TargetShading::default(),
        }
    }
}

/// Checks the numbers of a world scene (the scenario's `[scene]` checks them first, with
/// their keys).
fn validate_world(world: &WorldScene) -> Result<(), String> {
    let positive = |name: &str, x: f64| {
        if x.is_finite() && x > 0.0 {
            Ok(())
        } else {
            Err(format!("scene {name} {x} must be finite and > 0"))
        }
    };
    positive("visibility_ft", world.visibility_ft)?;
    if let Some(g) = &world.ground {
        positive("field_ft", g.field_ft)?;
        positive("road_width_ft", g.road_width_ft)?;
        if g.road_every_fields == 0 || !g.down_ft.is_finite() {
            return Err(format!(
                "scene ground {g:?} needs roads every >= 1 field, a finite height"
            ));
        }
    }
    if let Some(c) = &world.clouds {
        positive("cloud cell_ft", c.cell_ft)?;
        if !((0.0..=1.0).contains(&c.coverage) && c.down_ft.is_finite()) {
            return Err(format!(
                "scene clouds {c:?} need coverage in [0, 1], a finite height"
            ));
        }
    }
    let sun = &world.sun;
    if !(sun.towards_ned.iter().all(|x| x.is_finite())
        && sun.towards_ned.norm() > 0.0
        && (0.0..=1.0).contains(&sun.glare))
    {
        return Err(format!(
            "scene sun {sun:?} needs a finite direction, glare in [0, 1]"
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn out_of_range_settings_are_named() {
        let good = RenderSettings::new(CameraIntrinsics::from_hfov(640, 480, 60.0));
        assert_eq!(good.validate(8192), Ok(()));
        let mut s = good;
        s.msaa_samples = 2;
        assert!(s.validate(8192).unwrap_err().contains("msaa_samples 2"));
        let mut s = good;
        s.intrinsics.width_px = 9000;
        assert!(s.validate(8192).unwrap_err().contains("9000x480"));
        let mut s = good;
        s.intrinsics.focal_px = f64::NAN;
        assert!(s.validate(8192).unwrap_err().contains("focal_px"));
        let mut s = good;
        s.background.noise = Some(PixelNoise {
            std_grey_levels: -1.0,
            seed: 0,
        });
        assert!(s.validate(8192).unwrap_err().contains("std_grey_levels"));
        let mut s = good;
        s.shading.light_dir_body = Vec3::zeros();
        assert!(s.validate(8192).unwrap_err().contains("light_dir_body"));
    }
}
