//! Pinhole camera intrinsics and the pixel conventions shared by renderer, vision and sensing.
//!
//! Image coordinates (yI right, zI up, px) are relative to the principal point, which sits at
//! the image centre (cx, cy) = (width/2, height/2). Pixel column u grows right, row v grows down,
//! and pixel (i, j) covers [i, i+1) x [j, j+1), so its centre is (i + 0.5, j + 0.5):
//! `u = cx + yI`, `v = cy - zI` ((3.1); docs/equations.md, What the camera measures).

use crate::frames::{Mat3, Vec3};

/// Resolution and focal length of a pinhole camera whose optical axis is body x.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CameraIntrinsics {
    /// Image width, px.
    pub width_px: u32,
    /// Image height, px.
    pub height_px: u32,
    /// Focal length l, px.
    pub focal_px: f64,
}

impl CameraIntrinsics {
    /// Intrinsics from a horizontal field of view: l = (width/2) / tan(hfov/2).
    pub fn from_hfov(width_px: u32, height_px: u32, hfov_deg: f64) -> Self {
        let focal_px = 0.5 * f64::from(width_px) / (0.5 * hfov_deg.to_radians()).tan();
        Self {
            width_px,
            height_px,
            focal_px,
        }
    }

    /// Principal point column cx, px.
    pub fn cx(&self) -> f64 {
        0.5 * f64::from(self.width_px)
    }

    /// Principal point row cy, px.
    pub fn cy(&self) -> f64 {
        0.5 * f64::from(self.height_px)
    }

    /// Image coordinates (yI, zI) of a body-frame point, or `None` when it is not in front of
    /// the camera (X ≤ 0).
    pub fn image_from_body(&self, p_body_ft: &Vec3) -> Option<(f64, f64)> {
        if p_body_ft.x <= 0.0 {
            return None;
        }
        Some((
            self.focal_px * p_body_ft.y / p_body_ft.x,
            -self.focal_px * p_body_ft.z / p_body_ft.x,
        ))
    }

    /// Pixel position (u, v) of a direction in camera axes (any length), or `None` when it
    /// does not point in front of the camera.
    pub fn pixel_of_direction(&self, direction_camera: &Vec3) -> Option<(f64, f64)> {
        let (y_i_px, z_i_px) = self.image_from_body(direction_camera)?;
        Some(self.pixel_from_image(y_i_px, z_i_px))
    }

    /// The direction in camera axes (unit focal length scaled by `focal_px`) through pixel
    /// position (u, v).
    pub fn direction_of_pixel(&self, u_px: f64, v_px: f64) -> Vec3 {
        Vec3::new(self.focal_px, u_px - self.cx(), v_px - self.cy())
    }

    /// Pixel position (u, v) of image coordinates (yI, zI).
    pub fn pixel_from_image(&self, y_i_px: f64, z_i_px: f64) -> (f64, f64) {
        (self.cx() + y_i_px, self.cy() - z_i_px)
    }

    /// Image coordinates (yI, zI) of pixel position (u, v).
    pub fn image_from_pixel(&self, u_px: f64, v_px: f64) -> (f64, f64) {
        (u_px - self.cx(), self.cy() - v_px)
    }
}

/// Where the target is and how it is turned, as the camera sees it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TargetPoseInCamera {
    /// Target reference point (mesh origin) in the camera/body frame, ft.
    pub position_body_ft: Vec3,
    /// Rotation taking target-body coordinates to camera/body coordinates:
    /// L_BE(follower) L_BE(target)ᵀ.
    pub body_from_target: Mat3,
}

impl TargetPoseInCamera {
    /// A pose the renderer clips whole (the target behind the camera): a frame of sky only,
    /// for a target hidden from view.
    pub fn hidden() -> Self {
        Self {
            position_body_ft: Vec3::new(-1e3, 0.0, 0.0),
            body_from_target: Mat3::identity(),
        }
    }

    /// A mesh vertex given in target-body coordinates, in camera/body coordinates.
    pub fn body_from_target_point(&self, p_target_ft: &Vec3) -> Vec3 {
        self.position_body_ft + self.body_from_target * p_target_ft
    }
}

/// Another aircraft drawn in the same frame as the target: the target's mesh at its own
/// pose, scaled by `scale` (its size over the target's).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AircraftPose {
    /// Where it is and how it is turned, as the camera sees it.
    pub pose: TargetPoseInCamera,
    /// Its size over the target's (the mesh's), > 0.
    pub scale: f64,
}

impl AircraftPose {
    /// A vertex of the target's mesh (target-body axes, ft) on this aircraft, in camera/body
    /// coordinates.
    pub fn body_point(&self, p_target_ft: &Vec3) -> Vec3 {
        self.pose
            .body_from_target_point(&(p_target_ft * self.scale))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sixty_degree_fov_at_640() {
        let cam = CameraIntrinsics::from_hfov(640, 480, 60.0);
        assert!((cam.focal_px - 320.0 / (30f64.to_radians()).tan()).abs() < 1e-9);
        // A point on the edge of the horizontal field of view lands on the image edge.
        let (y, z) = cam
            .image_from_body(&Vec3::new(1.0, (30f64).to_radians().tan(), 0.0))
            .unwrap();
        let (u, v) = cam.pixel_from_image(y, z);
        assert!((u - 640.0).abs() < 1e-9 && (v - 240.0).abs() < 1e-12);
    }

    #[test]
    fn pixel_image_round_trip() {
        let cam = CameraIntrinsics::from_hfov(1920, 1080, 45.0);
        let (u, v) = cam.pixel_from_image(12.25, -3.5);
        let (y, z) = cam.image_from_pixel(u, v);
        assert_eq!((y, z), (12.25, -3.5));
    }
}
