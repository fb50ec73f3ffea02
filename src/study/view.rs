//! The apparent-size study's geometry: the target on the camera's optical axis at a range,
//! turned by yaw, pitch and roll relative to the camera, and the seed's flat four-point model
//! of its apparent size (8.1)-(8.2).

use super::setting::Setting;
use crate::frames::{EulerAngles, Vec3};
use crate::render::camera::{CameraIntrinsics, TargetPoseInCamera};
use crate::sensing::CaptureGeometry;

/// The study-file section of the view keys (`view.yaw_deg`, ...).
pub const VIEW_SECTION: &str = "view";

/// How the camera sees the target: the target's attitude relative to the camera's axes
/// (3-2-1 Euler angles; all zero: the target flies straight away from the camera, seen from
/// behind; yaw 90°: side-on, nose to the right; pitch 90°: nose up, seen from above) and its
/// range along the optical axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct View {
    /// Yaw ψ, deg (`view.yaw_deg`, default 0).
    pub yaw_deg: f64,
    /// Pitch θ, deg (`view.pitch_deg`, default 0).
    pub pitch_deg: f64,
    /// Roll φ, deg (`view.roll_deg`, default 0).
    pub roll_deg: f64,
    /// Range from the camera to the target's reference point, ft (`view.range_ft`, default 50).
    pub range_ft: f64,
}

impl Default for View {
    fn default() -> Self {
        Self {
            yaw_deg: 0.0,
            pitch_deg: 0.0,
            roll_deg: 0.0,
            range_ft: 50.0,
        }
    }
}

impl View {
    /// The view a case's `view.*` settings describe (others are the scenario's), or why not.
    pub fn from_settings(settings: &[Setting]) -> Result<View, String> {
        let mut view = View::default();
        for setting in settings {
            let Some(field) = setting
                .key
                .strip_prefix(VIEW_SECTION)
                .and_then(|k| k.strip_prefix('.'))
            else {
                continue;
            };
            let value = match &setting.value {
                toml::Value::Integer(i) => *i as f64,
                toml::Value::Float(f) if f.is_finite() => *f,
                other => return Err(format!("{} = {other} is not a finite number", setting.key)),
            };
            match field {
                "yaw_deg" => view.yaw_deg = value,
                "pitch_deg" => view.pitch_deg = value,
                "roll_deg" => view.roll_deg = value,
                "range_ft" if value > 0.0 => view.range_ft = value,
                "range_ft" => return Err(format!("view.range_ft = {value} must be > 0")),
                _ => {
                    return Err(format!(
                        "unknown key {}; the view keys are view.yaw_deg, view.pitch_deg, \
                         view.roll_deg and view.range_ft",
                        setting.key
                    ));
                }
            }
        }
        Ok(view)
    }

    /// The target's attitude relative to the camera.
    pub fn attitude(&self) -> EulerAngles {
        EulerAngles::new(
            self.roll_deg.to_radians(),
            self.pitch_deg.to_radians(),
            self.yaw_deg.to_radians(),
        )
    }

    /// The capture geometry of this view: a level camera at the origin looking north, the
    /// target `range_ft` north of it.
    pub fn geometry(&self) -> CaptureGeometry {
        CaptureGeometry::on_axis(self.range_ft, self.attitude())
    }
}

/// The seed's flat target (8.1)-(8.2): wing tips, nose and tail in target-body axes, ft.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FourPoints {
    /// Right wing tip P_r (largest y).
    pub right_tip_ft: Vec3,
    /// Left wing tip P_l (smallest y).
    pub left_tip_ft: Vec3,
    /// Nose P_n (largest x).
    pub nose_ft: Vec3,
    /// Tail P_t (smallest x).
    pub tail_ft: Vec3,
}

/// Vertices within this distance of an extreme count as tied; the point is their mean (so
/// that a box's "nose" is the middle of its front face).
const TIE_FT: f64 = 1e-6;

impl FourPoints {
    /// The extremes of a mesh along its x (nose, tail) and y (wing tips) axes (None without
    /// vertices).
    pub fn of_mesh(vertices_ft: &[Vec3]) -> Option<FourPoints> {
        let extreme = |along: &dyn Fn(&Vec3) -> f64| -> Option<Vec3> {
            let best = vertices_ft
                .iter()
                .map(along)
                .fold(f64::NEG_INFINITY, f64::max);
            let tied: Vec<&Vec3> = vertices_ft
                .iter()
                .filter(|v| along(v) >= best - TIE_FT)
                .collect();
            (!tied.is_empty())
                .then(|| tied.iter().fold(Vec3::zeros(), |s, v| s + **v) / tied.len() as f64)
        };
        Some(FourPoints {
            right_tip_ft: extreme(&|v| v.y)?,
            left_tip_ft: extreme(&|v| -v.y)?,
            nose_ft: extreme(&|v| v.x)?,
            tail_ft: extreme(&|v| -v.x)?,
        })
    }

    fn points(&self) -> [Vec3; 4] {
        [
            self.right_tip_ft,
            self.left_tip_ft,
            self.nose_ft,
            self.tail_ft,
        ]
    }

    /// (8.1)-(8.2) as the camera sees them: the four points in camera axes (8.1), projected
    /// by the pinhole camera, and the largest distance between two of them, px (None when a
    /// point is not in front of the camera). (8.2) as printed measures the rotated points in
    /// three dimensions, which a rotation does not change; the camera sees their spread
    /// across the line of sight.
    pub fn image_length_px(
        &self,
        pose: &TargetPoseInCamera,
        camera: &CameraIntrinsics,
    ) -> Option<f64> {
        let projected = self
            .points()
            .iter()
            .map(|p| camera.image_from_body(&pose.body_from_target_point(p)))
            .collect::<Option<Vec<(f64, f64)>>>()?;
        let mut longest_px: f64 = 0.0;
        for (i, a) in projected.iter().enumerate() {
            for b in &projected[i + 1..] {
                longest_px = longest_px.max((a.0 - b.0).hypot(a.1 - b.1));
            }
        }
        Some(longest_px)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn setting(key: &str, value: toml::Value) -> Setting {
        Setting {
            key: key.into(),
            value,
        }
    }

    #[test]
    fn view_keys_are_read_and_checked() {
        let view = View::from_settings(&[
            setting("view.yaw_deg", toml::Value::Integer(90)),
            setting("camera.hfov_deg", toml::Value::Integer(40)),
            setting("view.range_ft", toml::Value::Float(12.5)),
        ])
        .unwrap();
        assert_eq!(view.yaw_deg, 90.0);
        assert_eq!(view.range_ft, 12.5);
        assert_eq!(view.pitch_deg, 0.0);
        let bad = View::from_settings(&[setting("view.range_ft", toml::Value::Integer(0))]);
        assert!(bad.unwrap_err().contains("> 0"));
        let unknown = View::from_settings(&[setting("view.yaw", toml::Value::Integer(1))]);
        assert!(unknown.unwrap_err().contains("view.yaw_deg"));
        let text = View::from_settings(&[setting("view.yaw_deg", "x".into())]);
        assert!(text.unwrap_err().contains("finite number"));
    }

    /// A cross (span 8 along y, length 6 along x) seen from behind at 100 ft by a camera of
    /// focal length 500 px: the wing tips are 8 ft apart across the line of sight, 40 px;
    /// side-on the nose and tail are 6 ft apart, 30 px (the tips lie on the line of sight).
    #[test]
    fn four_point_length_of_a_cross() {
        let cross = [
            Vec3::new(0.0, 4.0, 0.0),
            Vec3::new(0.0, -4.0, 0.0),
            Vec3::new(3.0, 0.0, 0.0),
            Vec3::new(-3.0, 0.0, 0.0),
        ];
        let points = FourPoints::of_mesh(&cross).unwrap();
        let camera = CameraIntrinsics {
            width_px: 640,
            height_px: 480,
            focal_px: 500.0,
        };
        let length = |yaw_deg: f64| {
            let view = View {
                yaw_deg,
                range_ft: 100.0,
                ..View::default()
            };
            points
                .image_length_px(&view.geometry().pose(), &camera)
                .unwrap()
        };
        assert!((length(0.0) - 40.0).abs() < 1e-9);
        assert!((length(90.0) - 30.0).abs() < 1e-9);
    }

    #[test]
    fn tied_extremes_average() {
        let face = [Vec3::new(1.0, 1.0, 1.0), Vec3::new(1.0, -1.0, -1.0)];
        let points = FourPoints::of_mesh(&face).unwrap();
        assert_eq!(points.nose_ft, Vec3::new(1.0, 0.0, 0.0));
        assert!(FourPoints::of_mesh(&[]).is_none());
    }
}
