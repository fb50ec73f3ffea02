//! Ground truth for the image pipeline from geometry alone: where the target's reference point
//! (the mesh origin) projects, and the true maximal length of the projected mesh (maximum
//! Feret diameter of the projected vertices: the silhouette is the projection of the mesh, and
//! the farthest pair of silhouette points is a pair of projected vertices because the
//! silhouette's convex hull is the hull of the projected vertices).
//!
//! The measured centroid is the silhouette's area centroid, not the projected reference point;
//! the difference between the two is part of what the simulator reports.

use super::ImageMeasurement;
use crate::frames::Vec3;
use crate::render::camera::{CameraIntrinsics, TargetPoseInCamera};

use super::feret::{FeretDiameter, FeretFinder, PixelPoint};

/// The true image of the target in one frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImageTruth {
    /// Projected reference point, yI (right of the principal point), px.
    pub y_i_px: f64,
    /// Projected reference point, zI (above the principal point), px.
    pub z_i_px: f64,
    /// Maximal length of the projected mesh, px.
    pub b_i_px: f64,
    /// The farthest pair of projected vertices, pixel coordinates (u right, v down).
    pub feret: FeretDiameter,
    /// Every projected vertex lies within the image rectangle [0, width] x [0, height].
    pub inside_image: bool,
}

impl ImageTruth {
    /// The truth as the measurement it should be compared with.
    pub fn image_measurement(&self) -> ImageMeasurement {
        ImageMeasurement {
            y_i_px: self.y_i_px,
            z_i_px: self.z_i_px,
            b_i_px: self.b_i_px,
        }
    }
}

/// Computes [`ImageTruth`]s, keeping its point and hull buffers between frames.
#[derive(Debug, Default, Clone)]
pub struct TruthProjector {
    points: Vec<PixelPoint>,
    feret: FeretFinder,
}

impl TruthProjector {
    /// A projector with empty buffers.
    pub fn new() -> Self {
        Self::default()
    }

    /// The image truth of a mesh with vertices `vertices_target_ft` (target-body coordinates,
    /// ft) posed by `pose` and seen through `camera`. `None` when the mesh has no vertices, a
    /// coordinate is not finite, or the reference point or any vertex is not in front of the
    /// camera (X ≤ 0: a pinhole projection of it does not exist).
    pub fn image_truth(
        &mut self,
        vertices_target_ft: &[Vec3],
        pose: &TargetPoseInCamera,
        camera: &CameraIntrinsics,
    ) -> Option<ImageTruth> {
        let (y_i_px, z_i_px) = camera.image_from_body(&pose.position_body_ft)?;
        if !(y_i_px.is_finite() && z_i_px.is_finite()) {
            return None;
        }
        let (w, h) = (f64::from(camera.width_px), f64::from(camera.height_px));
        self.points.clear();
        let mut inside_image = true;
        for vertex in vertices_target_ft {
            let p_body = pose.body_from_target_point(vertex);
            let (y, z) = camera.image_from_body(&p_body)?;
            let (u, v) = camera.pixel_from_image(y, z);
            if !(u.is_finite() && v.is_finite()) {
                return None;
            }
            inside_image &= (0.0..=w).contains(&u) && (0.0..=h).contains(&v);
            self.points.push(PixelPoint::new(u, v));
        }
        let feret = self.feret.diameter(&mut self.points)?;
        Some(ImageTruth {
            y_i_px,
            z_i_px,
            b_i_px: feret.length_px,
            feret,
            inside_image,
        })
    }
}

/// [`TruthProjector::image_truth`] with fresh buffers (allocates; keep a projector in loops).
pub fn image_truth(
    vertices_target_ft: &[Vec3],
    pose: &TargetPoseInCamera,
    camera: &CameraIntrinsics,
) -> Option<ImageTruth> {
    TruthProjector::new().image_truth(vertices_target_ft, pose, camera)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frames::{EulerAngles, Mat3};

    fn camera() -> CameraIntrinsics {
        CameraIntrinsics {
            width_px: 640,
            height_px: 480,
            focal_px: 500.0,
        }
    }

    fn square_ft(half: f64) -> Vec<Vec3> {
        vec![
            Vec3::new(0.0, -half, -half),
            Vec3::new(0.0, half, -half),
            Vec3::new(0.0, half, half),
            Vec3::new(0.0, -half, half),
        ]
    }

    /// A 4 ft square facing the camera at 100 ft, centred 10 ft right and 5 ft up: its image is
    /// a square of side l·4/100 = 20 px whose maximal length is the diagonal, 20√2 px, and the
    /// reference point is at (l·10/100, l·5/100) = (50, 25) px. Pure arithmetic: 1e-9.
    #[test]
    fn square_facing_camera() {
        let pose = TargetPoseInCamera {
            position_body_ft: Vec3::new(100.0, 10.0, -5.0),
            body_from_target: Mat3::identity(),
        };
        let t = image_truth(&square_ft(2.0), &pose, &camera()).unwrap();
        assert!((t.y_i_px - 50.0).abs() < 1e-9);
        assert!((t.z_i_px - 25.0).abs() < 1e-9);
        assert!((t.b_i_px - 20.0 * 2f64.sqrt()).abs() < 1e-9);
        assert!(t.inside_image);
        let m = t.image_measurement();
        assert_eq!(
            (m.y_i_px, m.z_i_px, m.b_i_px),
            (t.y_i_px, t.z_i_px, t.b_i_px)
        );
        // Feret ends are opposite corners: (u, v) = (320 + 50 ± 10, 240 − 25 ± 10).
        let ends = [t.feret.start, t.feret.end];
        for e in ends {
            assert!(((e.u_px - 370.0).abs() - 10.0).abs() < 1e-9);
            assert!(((e.v_px - 215.0).abs() - 10.0).abs() < 1e-9);
        }
    }

    /// Turned 60° about the body z axis the square's corners lie at different depths; the
    /// truth's length equals the brute-force maximum distance between the directly projected
    /// corners (same arithmetic, 1e-9).
    #[test]
    fn rotated_square_matches_direct_projection() {
        let rot = EulerAngles::new(0.0, 0.0, 60f64.to_radians())
            .body_from_ned()
            .transpose();
        let pose = TargetPoseInCamera {
            position_body_ft: Vec3::new(80.0, -3.0, 2.0),
            body_from_target: rot,
        };
        let cam = camera();
        let verts = square_ft(2.0);
        let t = image_truth(&verts, &pose, &cam).unwrap();
        let pts: Vec<(f64, f64)> = verts
            .iter()
            .map(|p| {
                let (y, z) = cam
                    .image_from_body(&pose.body_from_target_point(p))
                    .unwrap();
                cam.pixel_from_image(y, z)
            })
            .collect();
        let mut brute = 0.0f64;
        for a in &pts {
            for b in &pts {
                brute = brute.max((a.0 - b.0).hypot(a.1 - b.1));
            }
        }
        assert!((t.b_i_px - brute).abs() < 1e-9);
    }

    /// A vertex behind the camera, no vertices, or NaN give no truth; a mesh reaching past the
    /// image edge is flagged as not inside.
    #[test]
    fn unprojectable_and_partly_outside() {
        let cam = camera();
        let mut pose = TargetPoseInCamera {
            position_body_ft: Vec3::new(1.0, 0.0, 0.0),
            body_from_target: Mat3::identity(),
        };
        let long = [Vec3::new(-2.0, 0.0, 0.0), Vec3::new(2.0, 0.0, 0.0)];
        assert!(image_truth(&long, &pose, &cam).is_none());
        assert!(image_truth(&[], &pose, &cam).is_none());
        assert!(image_truth(&[Vec3::new(f64::NAN, 0.0, 0.0)], &pose, &cam).is_none());
        pose.position_body_ft = Vec3::new(10.0, 0.0, 0.0);
        let wide = [Vec3::new(0.0, -20.0, 0.0), Vec3::new(0.0, 20.0, 0.0)];
        let t = image_truth(&wide, &pose, &cam).unwrap();
        assert!(!t.inside_image);
        assert!((t.b_i_px - 2000.0).abs() < 1e-9);
    }
}
