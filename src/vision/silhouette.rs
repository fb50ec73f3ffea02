//! The true centroid of the target's silhouette, from the mesh: the area centroid of the union
//! of its projected triangles. The image pipeline measures the centroid of the silhouette it
//! segments; the projection of the target's reference point (the mesh origin) is another
//! point (several pixels away at close range), so the vision's centroid error is measured
//! against this one.
//!
//! The union is integrated on scan lines: each line, every triangle it crosses gives an
//! interval; the intervals are merged, and their lengths and first moments summed exactly
//! along the line. Lines are spaced [`LINES_PER_PX`] to a pixel, at most [`MAX_LINES`] over
//! the silhouette's height, so the centroid is exact along the lines and the midpoint rule's
//! across them: between lines the union's width is linear but at corners, and a silhouette
//! H px tall with n lines errs by about H / (6 n²) px (a triangle's exact bound): 0.003 px
//! for the height of a 1080-line image, 1/(384 H) px below the cap. The cap keeps the cost
//! the same at any resolution once the silhouette is 32 px tall (why: `docs/findings.md`,
//! The image pipeline's accuracy and cost).

use crate::frames::Vec3;
use crate::render::camera::{CameraIntrinsics, TargetPoseInCamera};

/// Scan lines per pixel of the silhouette's height.
const LINES_PER_PX: f64 = 8.0;
/// Most scan lines over the silhouette's height.
const MAX_LINES: f64 = 256.0;

/// One line's stretch of one triangle: left and right end (yI, px).
type Interval = (f64, f64);

/// Computes silhouette centroids, keeping its buffers between frames.
#[derive(Debug, Default, Clone)]
pub struct SilhouetteCentroid {
    projected: Vec<(f64, f64)>,
    /// The intervals of each scan line (a line's few intervals are sorted alone: sorting all
    /// lines' together cost more than the rest of the frame's truth).
    lines: Vec<Vec<Interval>>,
}

impl SilhouetteCentroid {
    /// The centroid (yI, zI), px, of the silhouette of the mesh (`vertices_target_ft`,
    /// `triangles`) posed by `pose` and seen through `camera`; None when a vertex is not in
    /// front of the camera or the silhouette has no area.
    pub fn centroid(
        &mut self,
        vertices_target_ft: &[Vec3],
        triangles: &[[u32; 3]],
        pose: &TargetPoseInCamera,
        camera: &CameraIntrinsics,
    ) -> Option<(f64, f64)> {
        self.projected.clear();
        for vertex in vertices_target_ft {
            let (y, z) = camera.image_from_body(&pose.body_from_target_point(vertex))?;
            if !(y.is_finite() && z.is_finite()) {
                return None;
            }
            self.projected.push((y, z));
        }
        let (z_min, z_max) = self
            .projected
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(p.1), hi.max(p.1))
            });
        let lines = ((z_max - z_min) * LINES_PER_PX)
            .clamp(1.0, MAX_LINES)
            .ceil();
        let spacing = (z_max - z_min) / lines;
        if spacing.is_nan() || spacing <= 0.0 {
            return None;
        }
        let lines = lines as usize;
        self.lines
            .resize_with(self.lines.len().max(lines), Vec::new);
        self.lines.iter_mut().for_each(Vec::clear);
        for t in triangles {
            let corners = t.map(|i| self.projected.get(i as usize).copied());
            if let [Some(a), Some(b), Some(c)] = corners {
                cross_lines([a, b, c], z_min, spacing, &mut self.lines[..lines]);
            }
        }
        union_centroid(&mut self.lines[..lines], z_min, spacing)
    }
}

/// The intervals where the lines z = z_min + (k + ½) spacing cross a triangle, each pushed
/// to its line's list.
fn cross_lines(corners: [(f64, f64); 3], z_min: f64, spacing: f64, lines: &mut [Vec<Interval>]) {
    let lo = corners.iter().map(|c| c.1).fold(f64::INFINITY, f64::min);
    let hi = corners
        .iter()
        .map(|c| c.1)
        .fold(f64::NEG_INFINITY, f64::max);
    let first = ((lo - z_min) / spacing - 0.5).ceil().max(0.0) as usize;
    let last = (((hi - z_min) / spacing - 0.5).floor().max(-1.0) + 1.0) as usize;
    for k in first..last.min(lines.len()) {
        let z = z_min + (k as f64 + 0.5) * spacing;
        let mut left = f64::INFINITY;
        let mut right = f64::NEG_INFINITY;
        for (i, a) in corners.iter().enumerate() {
            let b = corners[(i + 1) % 3];
            if (a.1 <= z) != (b.1 <= z) {
                let y = a.0 + (z - a.1) * (b.0 - a.0) / (b.1 - a.1);
                left = left.min(y);
                right = right.max(y);
            }
        }
        if left < right {
            lines[k].push((left, right));
        }
    }
}

/// The area centroid of the union of each line's intervals (sorted here, line by line).
fn union_centroid(lines: &mut [Vec<Interval>], z_min: f64, spacing: f64) -> Option<(f64, f64)> {
    let (mut area, mut moment_y, mut moment_z) = (0.0, 0.0, 0.0);
    for (k, intervals) in lines.iter_mut().enumerate() {
        intervals.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
        let z = z_min + (k as f64 + 0.5) * spacing;
        let (length, moment) = union_along_line(intervals);
        area += length;
        moment_y += moment;
        moment_z += z * length;
    }
    (area > 0.0).then(|| (moment_y / area, moment_z / area))
}

/// The length of the union of sorted intervals and its first moment ∫ y dy.
fn union_along_line(sorted: &[Interval]) -> (f64, f64) {
    let (mut length, mut moment) = (0.0, 0.0);
    let mut add = |left: f64, right: f64| {
        length += right - left;
        moment += 0.5 * (right * right - left * left);
    };
    let mut open: Option<Interval> = None;
    for &(left, right) in sorted {
        open = match open {
            Some((a, b)) if left <= b => Some((a, b.max(right))),
            Some((a, b)) => {
                add(a, b);
                Some((left, right))
            }
            None => Some((left, right)),
        };
    }
    if let Some((a, b)) = open {
        add(a, b);
    }
    (length, moment)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frames::Mat3;

    /// A camera of focal length 100 px: 1 px per ft at 100 ft.
    const CAMERA_1_PX_PER_FT: CameraIntrinsics = CameraIntrinsics {
        width_px: 640,
        height_px: 480,
        focal_px: 100.0,
    };

    /// The target 100 ft ahead, unrotated.
    fn ahead_100_ft() -> TargetPoseInCamera {
        TargetPoseInCamera {
            position_body_ft: Vec3::new(100.0, 0.0, 0.0),
            body_from_target: Mat3::identity(),
        }
    }

    /// Two overlapping squares facing the camera: the union's centroid, not the mean of the
    /// squares' centroids (the overlap counts once).
    #[test]
    fn overlapping_squares_count_their_overlap_once() {
        let square = |y0: f64, z0: f64, base: u32| {
            let v = vec![
                Vec3::new(0.0, y0, -z0),
                Vec3::new(0.0, y0 + 2.0, -z0),
                Vec3::new(0.0, y0 + 2.0, -z0 - 2.0),
                Vec3::new(0.0, y0, -z0 - 2.0),
            ];
            (v, [[base, base + 1, base + 2], [base, base + 2, base + 3]])
        };
        let (mut vertices, t1) = square(0.0, 0.0, 0);
        let (v2, t2) = square(1.0, 0.0, 4);
        vertices.extend(v2);
        let triangles = [t1, t2].concat();
        let (y, z) = SilhouetteCentroid::default()
            .centroid(&vertices, &triangles, &ahead_100_ft(), &CAMERA_1_PX_PER_FT)
            .expect("in front");
        // Union: y in [0, 3] ft, z (up) in [0, 2] ft at range 100 ft, focal 100 px: 1 px per ft.
        assert!((y - 1.5).abs() < 1e-9, "y {y}");
        assert!((z - 1.0).abs() < 1e-9, "z {z}");
    }

    /// The silhouette centroid of one triangle facing the camera at 100 ft: a right triangle
    /// with legs `width_ft` along y and `height_ft` up (1 px per ft).
    fn right_triangle_centroid(width_ft: f64, height_ft: f64) -> (f64, f64) {
        let vertices = [
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(0.0, width_ft, 0.0),
            Vec3::new(0.0, 0.0, -height_ft),
        ];
        SilhouetteCentroid::default()
            .centroid(
                &vertices,
                &[[0, 1, 2]],
                &ahead_100_ft(),
                &CAMERA_1_PX_PER_FT,
            )
            .expect("in front")
    }

    /// A triangle: its centroid is the mean of its corners.
    #[test]
    fn triangle_centroid_is_the_mean_of_its_corners() {
        let (y, z) = right_triangle_centroid(30.0, 12.0);
        // Exact along lines, midpoint rule across 8 lines per px: within 1e-3 px.
        assert!((y - 10.0).abs() < 1e-3, "y {y}");
        assert!((z - 4.0).abs() < 1e-3, "z {z}");
    }

    /// A triangle 1200 px tall gets the capped 256 lines (4.7 px apart): its centroid errs by
    /// H / (6 n²) = 0.003 px in z (the midpoint rule on the linear width); y is exact along
    /// the lines (measured 1e-4 px off 100: the projection's rounding at this size).
    #[test]
    fn a_tall_silhouette_is_integrated_on_capped_lines() {
        let (y, z) = right_triangle_centroid(300.0, 1200.0);
        let bound = 1200.0 / (6.0 * MAX_LINES * MAX_LINES);
        assert!((y - 100.0).abs() < 1e-3, "y {y}");
        // Measured: the error is the bound itself (0.0030518 px), to the last digit.
        assert!((z - 400.0).abs() <= 1.001 * bound, "z {z}, bound {bound}");
    }
}
