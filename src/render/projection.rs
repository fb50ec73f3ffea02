//! The clip-space projection that makes the rasteriser agree with [`CameraIntrinsics`].
//!
//! A camera/body point (X fwd, Y right, Z down) lands at pixel u = cx + l Y/X, v = cy + l Z/X
//! ((3.1); docs/equations.md, What the camera measures). wgpu maps NDC to framebuffer pixels by u = (x_ndc + 1) W / 2,
//! v = (1 - y_ndc) H / 2 and samples pixel (i, j) at its centre (i + 0.5, j + 0.5), the same
//! convention as `camera.rs`. So with w_clip = X:
//! `x_clip = (2 cx / W - 1) X + (2 l / W) Y`, `y_clip = (1 - 2 cy / H) X - (2 l / H) Z`.
//! Depth is reversed (near plane -> 1, far plane -> 0) for f32 depth precision:
//! `z_clip = (n f - n X) / (f - n)`. Points behind the camera (X ≤ 0) fall outside the clip
//! volume and are clipped, never drawn.

use nalgebra::Matrix4;

use crate::render::camera::{CameraIntrinsics, TargetPoseInCamera};

/// Near clipping plane, ft along body x: target parts closer than this are not drawn.
pub const NEAR_PLANE_FT: f64 = 0.5;
/// Far clipping plane, ft along body x: target parts farther than this are not drawn.
pub const FAR_PLANE_FT: f64 = 10_000.0;

/// The 4x4 matrix taking homogeneous camera/body points (X, Y, Z, 1), ft, to wgpu clip space.
pub fn clip_from_body(intrinsics: &CameraIntrinsics) -> Matrix4<f64> {
    clip_from_body_in_window(
        intrinsics,
        &PixelWindow {
            u0_px: 0,
            v0_px: 0,
            width_px: intrinsics.width_px,
            height_px: intrinsics.height_px,
        },
    )
}

/// A rectangle of the image, in whole pixels: columns u0 .. u0 + width, rows v0 .. v0 +
/// height; it may reach beyond the image.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PixelWindow {
    /// First column, px.
    pub u0_px: i64,
    /// First row, px.
    pub v0_px: i64,
    /// Width, px.
    pub width_px: u32,
    /// Height, px.
    pub height_px: u32,
}

/// [`clip_from_body`] for a framebuffer that covers only `window` of the image: the camera
/// with its principal point moved to (cx - u0, cy - v0) and the window's size. A point lands
/// at the framebuffer pixel of its image pixel minus (u0, v0): a whole-pixel shift, so each
/// sample falls where it falls in the whole image.
pub fn clip_from_body_in_window(
    intrinsics: &CameraIntrinsics,
    window: &PixelWindow,
) -> Matrix4<f64> {
    let w = f64::from(window.width_px);
    let h = f64::from(window.height_px);
    let cx = intrinsics.cx() - window.u0_px as f64;
    let cy = intrinsics.cy() - window.v0_px as f64;
    let l = intrinsics.focal_px;
    let (n, f) = (NEAR_PLANE_FT, FAR_PLANE_FT);
    #[rustfmt::skip]
    let m = Matrix4::new(
        2.0 * cx / w - 1.0, 2.0 * l / w, 0.0,          0.0,
        1.0 - 2.0 * cy / h, 0.0,         -2.0 * l / h, 0.0,
        -n / (f - n),       0.0,         0.0,          n * f / (f - n),
        1.0,                0.0,         0.0,          0.0,
    );
    m
}

/// The homogeneous transform taking target-body points to camera/body points.
pub fn body_from_target(pose: &TargetPoseInCamera) -> Matrix4<f64> {
    let mut m = Matrix4::identity();
    m.fixed_view_mut::<3, 3>(0, 0)
        .copy_from(&pose.body_from_target);
    m.fixed_view_mut::<3, 1>(0, 3)
        .copy_from(&pose.position_body_ft);
    m
}

/// Pixel position (u, v) and NDC depth where the rasteriser puts a camera/body point, or `None`
/// when it is clipped (behind the near plane or beyond the far plane). Mirrors the GPU's
/// arithmetic in f64, for tests.
pub fn pixel_from_body_via_clip(
    intrinsics: &CameraIntrinsics,
    p_body_ft: &crate::frames::Vec3,
) -> Option<(f64, f64, f64)> {
    let c = clip_from_body(intrinsics) * p_body_ft.push(1.0);
    if !(c.w > 0.0 && c.z >= 0.0 && c.z <= c.w) {
        return None;
    }
    let (x, y, z) = (c.x / c.w, c.y / c.w, c.z / c.w);
    let u = (x + 1.0) * 0.5 * f64::from(intrinsics.width_px);
    let v = (1.0 - y) * 0.5 * f64::from(intrinsics.height_px);
    Some((u, v, z))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frames::Vec3;

    #[test]
    fn clip_projection_matches_intrinsics() {
        let cam = CameraIntrinsics::from_hfov(640, 480, 60.0);
        for p in [
            Vec3::new(200.0, 50.0, 30.0),
            Vec3::new(33.0, -8.0, 2.5),
            Vec3::new(1.0, 0.3, -0.2),
        ] {
            let (y, z) = cam.image_from_body(&p).unwrap();
            let (u, v) = cam.pixel_from_image(y, z);
            let (u2, v2, depth) = pixel_from_body_via_clip(&cam, &p).unwrap();
            assert!(
                (u - u2).abs() < 1e-9 && (v - v2).abs() < 1e-9,
                "{u} {v} vs {u2} {v2}"
            );
            assert!((0.0..=1.0).contains(&depth));
        }
    }

    /// In a window's framebuffer a point lands at its image pixel minus the window's origin,
    /// with the same depth, wherever the window is (even partly outside the image).
    #[test]
    fn window_projection_is_a_whole_pixel_shift() {
        let cam = CameraIntrinsics::from_hfov(640, 480, 60.0);
        let window = PixelWindow {
            u0_px: 400,
            v0_px: -20,
            width_px: 128,
            height_px: 128,
        };
        let whole = clip_from_body(&cam);
        let windowed = clip_from_body_in_window(&cam, &window);
        for p in [Vec3::new(100.0, 30.0, -12.0), Vec3::new(40.0, 9.0, -13.0)] {
            let to_pixel = |m: &Matrix4<f64>, w: f64, h: f64| {
                let c = m * p.push(1.0);
                let (x, y, z) = (c.x / c.w, c.y / c.w, c.z / c.w);
                ((x + 1.0) * 0.5 * w, (1.0 - y) * 0.5 * h, z)
            };
            let (u, v, z) = to_pixel(&whole, 640.0, 480.0);
            let (uw, vw, zw) = to_pixel(&windowed, 128.0, 128.0);
            assert!((uw - (u - 400.0)).abs() < 1e-9, "{uw} vs {u}");
            assert!((vw - (v + 20.0)).abs() < 1e-9, "{vw} vs {v}");
            assert!((zw - z).abs() < 1e-15);
        }
        assert_eq!(
            clip_from_body_in_window(
                &cam,
                &PixelWindow {
                    u0_px: 0,
                    v0_px: 0,
                    width_px: 640,
                    height_px: 480
                }
            ),
            whole
        );
    }

    #[test]
    fn depth_is_reversed_and_spans_near_to_far() {
        let cam = CameraIntrinsics::from_hfov(160, 120, 60.0);
        let near = pixel_from_body_via_clip(&cam, &Vec3::new(NEAR_PLANE_FT, 0.0, 0.0)).unwrap();
        let far = pixel_from_body_via_clip(&cam, &Vec3::new(FAR_PLANE_FT, 0.0, 0.0)).unwrap();
        assert!((near.2 - 1.0).abs() < 1e-12 && far.2.abs() < 1e-12);
    }

    #[test]
    fn points_behind_the_camera_are_clipped() {
        let cam = CameraIntrinsics::from_hfov(160, 120, 60.0);
        assert!(pixel_from_body_via_clip(&cam, &Vec3::new(-5.0, 0.0, 0.0)).is_none());
        assert!(pixel_from_body_via_clip(&cam, &Vec3::new(0.1, 0.0, 0.0)).is_none());
    }
}
