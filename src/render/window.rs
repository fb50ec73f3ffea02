//! Drawing the target only around itself.
//!
//! On a software adapter (lavapipe) a 4x multisampled frame costs its clear and its resolve
//! over every sample of the image, whatever the target covers: at 640x480 that is most of a
//! frame's time (docs/findings.md, Rendering on lavapipe). The target covers a small
//! window of the image, and the sky needs no multisampling (it is the same at every sample of
//! a pixel). So a frame is drawn as a one-sample sky over the image, and the target (with
//! depth, multisampled when the camera has several samples) into a framebuffer that covers
//! the bounding box of its projected vertices
//! ([`crate::render::projection::clip_from_body_in_window`]), resolved and copied into place. The window moves by whole pixels, so every sample falls where it
//! would in the whole image. One-sample cameras draw the target the same way, so that a frame
//! drawn only in a region of the image (`render::region`) has, there, the pixels of the whole
//! frame: the target's window does not depend on the region.

use crate::frames::Vec3;
use crate::render::camera::{AircraftPose, CameraIntrinsics, TargetPoseInCamera};
use crate::render::projection::{NEAR_PLANE_FT, PixelWindow};
use crate::render::region::ImageRegion;

/// Pixels of sky kept around the target's projected bounding box.
const MARGIN_PX: f64 = 2.0;
/// The smallest window side, px.
const MIN_SIDE_PX: u32 = 16;

/// How one frame is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FramePlan {
    /// Everything multisampled over the whole image: the target is near the camera (part of
    /// it is behind the near plane) or its window would cover a quarter of the image or more.
    Whole,
    /// Only sky: the target projects outside the image.
    SkyOnly,
    /// Sky over the image, the target multisampled in this window.
    Window(PixelWindow),
}

/// The side of a window framebuffer holding `extent_px` pixels: the next of 16, 20, 24, 28,
/// 32, 40, 48, 56, 64, 80... (four sizes an octave), so that few framebuffers serve every
/// frame (the renderer keeps them) and a window is at most 25% wider than its
/// target. The clear and resolve of a multisampled framebuffer cost in proportion to its
/// area on lavapipe, so a tight window is most of a frame's saving.
pub fn window_side_px(extent_px: u32) -> u32 {
    let extent = extent_px.max(MIN_SIDE_PX);
    let step = 1u32 << (31 - (extent - 1).leading_zeros()).saturating_sub(2);
    extent.div_ceil(step) * step
}

/// Plans a frame: the window around the projection of the target's vertices
/// `vertices_ft` (target axes) at `pose`, a rectangle of [`window_side_px`] sides. The
/// silhouette lies in the convex hull of the projected vertices (every vertex in front of the
/// camera), so in their bounding box. Planned from the pose: the renderer draws the truth, and
/// a frame drawn in a region of the image has the window the whole frame has.
pub fn plan_frame(
    vertices_ft: &[Vec3],
    pose: &TargetPoseInCamera,
    intrinsics: &CameraIntrinsics,
) -> FramePlan {
    let whole = ImageRegion::whole(intrinsics);
    plan_frame_with_others(vertices_ft, pose, &[], &whole, intrinsics)
}

/// [`plan_frame`] for the target at `pose` and other aircraft drawn with it (the same mesh
/// at their own poses and scales) in a frame that reads back `region` of the image: one
/// window around the target and every other aircraft that reaches into the region (the
/// others leave the region's pixels as they are). An aircraft wholly behind the camera is
/// left out (it would only force the whole frame); one only partly behind the near plane,
/// as the target, draws the whole frame.
pub fn plan_frame_with_others(
    vertices_ft: &[Vec3],
    pose: &TargetPoseInCamera,
    others: &[AircraftPose],
    region: &ImageRegion,
    intrinsics: &CameraIntrinsics,
) -> FramePlan {
    let target = vertices_ft
        .iter()
        .map(|v| pose.body_from_target * v + pose.position_body_ft);
    let Some(mut bounds) = projected_bounds(target, intrinsics) else {
        return FramePlan::Whole;
    };
    for other in others {
        let points = vertices_ft.iter().map(|v| other.body_point(v));
        if points.clone().all(|p| p.x <= 0.0) {
            continue;
        }
        let Some(b) = projected_bounds(points, intrinsics) else {
            return FramePlan::Whole;
        };
        if b.overlaps(region) {
            bounds = if bounds.overlaps(&ImageRegion::whole(intrinsics)) {
                bounds.union(&b)
            } else {
                b
            };
        }
    }
    plan_bounds(&bounds, intrinsics)
}

/// The bounding box of projected points, px: `[u_min, u_max, v_min, v_max]`.
#[derive(Debug, Clone, Copy)]
struct PixelBounds([f64; 4]);

impl PixelBounds {
    /// Whether the box, with the margin, reaches into `region`.
    fn overlaps(&self, region: &ImageRegion) -> bool {
        let [u_min, u_max, v_min, v_max] = self.0;
        let (u0, v0) = (f64::from(region.u0_px), f64::from(region.v0_px));
        u_max > u0 - MARGIN_PX
            && v_max > v0 - MARGIN_PX
            && u_min < f64::from(region.u_end_px()) + MARGIN_PX
            && v_min < f64::from(region.v_end_px()) + MARGIN_PX
    }

    fn union(&self, other: &Self) -> Self {
        let [a, b] = [self.0, other.0];
        Self([
            a[0].min(b[0]),
            a[1].max(b[1]),
            a[2].min(b[2]),
            a[3].max(b[3]),
        ])
    }
}

/// The bounding box of `points` (camera/body axes, ft) projected, or None when a point is
/// not well in front of the camera (the frame is then drawn whole).
fn projected_bounds(
    points: impl Iterator<Item = Vec3>,
    intrinsics: &CameraIntrinsics,
) -> Option<PixelBounds> {
    let (mut u_min, mut u_max) = (f64::INFINITY, f64::NEG_INFINITY);
    let (mut v_min, mut v_max) = (f64::INFINITY, f64::NEG_INFINITY);
    for p in points {
        // (A NaN depth is not in front either.)
        if p.x.is_nan() || p.x <= 2.0 * NEAR_PLANE_FT {
            return None;
        }
        let (u, v) = intrinsics.pixel_of_direction(&p)?;
        u_min = u_min.min(u);
        u_max = u_max.max(u);
        v_min = v_min.min(v);
        v_max = v_max.max(v);
    }
    Some(PixelBounds([u_min, u_max, v_min, v_max]))
}

/// The plan of a frame whose aircraft project into `bounds`.
fn plan_bounds(bounds: &PixelBounds, intrinsics: &CameraIntrinsics) -> FramePlan {
    if !bounds.overlaps(&ImageRegion::whole(intrinsics)) {
        return FramePlan::SkyOnly;
    }
    let [u_min, u_max, v_min, v_max] = bounds.0;
    let u0 = (u_min - MARGIN_PX).floor();
    let v0 = (v_min - MARGIN_PX).floor();
    let side = |extent: f64| window_side_px(extent.min(f64::from(u32::MAX / 2)) as u32);
    let (width_px, height_px) = (
        side((u_max + MARGIN_PX).ceil() - u0),
        side((v_max + MARGIN_PX).ceil() - v0),
    );
    if 4 * u64::from(width_px) * u64::from(height_px)
        >= u64::from(intrinsics.width_px) * u64::from(intrinsics.height_px)
    {
        return FramePlan::Whole;
    }
    FramePlan::Window(PixelWindow {
        u0_px: u0 as i64,
        v0_px: v0 as i64,
        width_px,
        height_px,
    })
}

/// The part of `window` inside a region of the image: where it starts in the window and in
/// the image, and its size (None when they do not overlap).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct WindowCopy {
    /// First column and row in the window, px.
    pub from_px: [u32; 2],
    /// First column and row in the image, px.
    pub to_px: [u32; 2],
    /// Width and height, px.
    pub size_px: [u32; 2],
}

impl WindowCopy {
    /// The overlap of `window` and `region` (the whole image, or the part of it a frame
    /// draws).
    pub fn of(window: &PixelWindow, region: &ImageRegion) -> Option<Self> {
        let axis = |start: i64, len: u32, region_start: u32, region_len: u32| {
            let first = start.max(i64::from(region_start));
            let last =
                (start + i64::from(len)).min(i64::from(region_start) + i64::from(region_len));
            (last > first).then(|| ((first - start) as u32, first as u32, (last - first) as u32))
        };
        let (fu, tu, w) = axis(window.u0_px, window.width_px, region.u0_px, region.width_px)?;
        let (fv, tv, h) = axis(
            window.v0_px,
            window.height_px,
            region.v0_px,
            region.height_px,
        )?;
        Some(Self {
            from_px: [fu, fv],
            to_px: [tu, tv],
            size_px: [w, h],
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frames::Mat3;

    fn pose(x: f64, y: f64, z: f64) -> TargetPoseInCamera {
        TargetPoseInCamera {
            position_body_ft: Vec3::new(x, y, z),
            body_from_target: Mat3::identity(),
        }
    }

    fn wing() -> Vec<Vec3> {
        vec![
            Vec3::new(-3.0, -4.0, -0.5),
            Vec3::new(2.0, 4.0, 1.0),
            Vec3::new(0.0, 0.5, -0.2),
        ]
    }

    /// Sides grow by a quarter of their octave at most.
    #[test]
    fn window_sides_come_in_four_sizes_an_octave() {
        assert_eq!(window_side_px(1), 16);
        assert_eq!(window_side_px(16), 16);
        assert_eq!(window_side_px(17), 20);
        assert_eq!(window_side_px(33), 40);
        assert_eq!(window_side_px(64), 64);
        assert_eq!(window_side_px(65), 80);
        assert_eq!(window_side_px(210), 224);
        for extent in 1..5000 {
            let side = window_side_px(extent);
            assert!(side >= extent && (side <= 16 || 4 * side < 5 * extent + 4 * 16));
        }
    }

    /// The window contains every projected vertex, with the margin.
    #[test]
    fn window_covers_the_projected_vertices() {
        let cam = CameraIntrinsics::from_hfov(640, 480, 60.0);
        let vertices = wing();
        let p = pose(100.0, 20.0, -5.0);
        let FramePlan::Window(w) = plan_frame(&vertices, &p, &cam) else {
            panic!("expected a window");
        };
        for c in &vertices {
            let b = p.body_from_target * c + p.position_body_ft;
            let u = cam.cx() + cam.focal_px * b.y / b.x;
            let v = cam.cy() + cam.focal_px * b.z / b.x;
            assert!(u - MARGIN_PX >= w.u0_px as f64);
            assert!(u + MARGIN_PX <= (w.u0_px + i64::from(w.width_px)) as f64);
            assert!(v - MARGIN_PX >= w.v0_px as f64);
            assert!(v + MARGIN_PX <= (w.v0_px + i64::from(w.height_px)) as f64);
        }
    }

    /// Near targets are drawn whole; targets off the image are not drawn; big windows fall
    /// back to the whole image.
    #[test]
    fn plans_fall_back() {
        let cam = CameraIntrinsics::from_hfov(640, 480, 60.0);
        let vertices = wing();
        assert_eq!(
            plan_frame(&vertices, &pose(2.0, 0.0, 0.0), &cam),
            FramePlan::Whole
        );
        assert_eq!(
            plan_frame(&vertices, &pose(6.0, 0.0, 0.0), &cam),
            FramePlan::Whole
        );
        assert_eq!(
            plan_frame(&vertices, &pose(100.0, 500.0, 0.0), &cam),
            FramePlan::SkyOnly
        );
        assert_eq!(
            plan_frame(&vertices, &pose(-100.0, 0.0, 0.0), &cam),
            FramePlan::Whole
        );
    }

    /// The copy is the overlap of window and image (or region), at both ends.
    #[test]
    fn copy_is_clipped_to_the_image() {
        let cam = ImageRegion::whole(&CameraIntrinsics::from_hfov(640, 480, 60.0));
        let window = |u0, v0| PixelWindow {
            u0_px: u0,
            v0_px: v0,
            width_px: 64,
            height_px: 64,
        };
        assert_eq!(
            WindowCopy::of(&window(10, 20), &cam),
            Some(WindowCopy {
                from_px: [0, 0],
                to_px: [10, 20],
                size_px: [64, 64]
            })
        );
        assert_eq!(
            WindowCopy::of(&window(-10, 450), &cam),
            Some(WindowCopy {
                from_px: [10, 0],
                to_px: [0, 450],
                size_px: [54, 30]
            })
        );
        assert_eq!(WindowCopy::of(&window(640, 0), &cam), None);
        let region = ImageRegion {
            u0_px: 30,
            v0_px: 40,
            width_px: 20,
            height_px: 100,
        };
        assert_eq!(
            WindowCopy::of(&window(10, 20), &region),
            Some(WindowCopy {
                from_px: [20, 20],
                to_px: [30, 40],
                size_px: [20, 44]
            })
        );
    }
}
