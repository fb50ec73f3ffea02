//! The background each pixel is explained by, for a textured world behind the target
//! (`camera.segmentation = "motion"`): a per-pixel reference colour the segmenter measures
//! colour distances against instead of a smooth surface fitted to the border.
//!
//! A pixel's reference is whichever of two explanations is nearest its colour:
//! 1. The previous frame at the same direction. The background at infinity (sky, cloud, the
//!    distant ground) maps between frames by the homography K' R K⁻¹, R the camera's rotation
//!    between the frames, taken from the follower's navigation attitude and gimbal angles
//!    (the orientations the sensing path already uses; never the truth). Pixels within the
//!    ring's radius (below) of the previous frame's target (its blob, measured `Ok`) explain
//!    nothing; after a frame that measured nothing `Ok`, every pixel explains (a target
//!    missed then and still in the image at rest is missed again, until it moves). A pixel
//!    within the ring's radius of the frame's edge that the previous frame did not see (a
//!    strip the camera's turn brought into view) is taken for background.
//! 2. The nearest colour on a ring of [`RING_POINTS`] pixels around the pixel, of a radius
//!    beyond the target's half length (from the last measurement), or mixture of two of them
//!    (a pixel an edge cuts): the local colour model.
//!    Around a pixel of a compact target the ring lies on background, whose colours it does
//!    not match; a pixel of a field, a road, a cloud or the sky has pixels of its own kind
//!    on the ring (along the road, the edge, the horizon), and is explained.
//!
//! Assumptions, and where it breaks (docs/findings.md, The scene and the vision against it):
//! the background is far away, so that the camera's rotation alone moves it (ground at a
//! finite distance moves by parallax, f v sin²δ / h per second for ground seen δ below the
//! horizon from height h at speed v); the target's colour differs from the colours of the
//! background around it; background features smaller than the ring (a field corner, a
//! patch of cloud) that the previous frame does not explain are taken for target, and a
//! part of the target whose colour is on its ring (a grey wing over a grey road) is lost.

use super::image_view::RgbaView;
use crate::frames::Mat3;
use crate::render::camera::CameraIntrinsics;

/// Pixels around the previous frame's target mask that explain nothing at least (its
/// anti-aliased edge, and the target's motion in the image between frames).
pub(crate) const TARGET_MARGIN_PX: usize = 3;
/// Pixels on the ring of the local colour model.
const RING_POINTS: usize = 16;
/// The ring's radius before any target was measured, px.
pub(crate) const DEFAULT_RING_RADIUS_PX: f64 = 24.0;

/// How a frame's pixels look into the world: the camera (binned or not) and its orientation
/// as the follower's navigation knows it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ViewGeometry {
    /// The camera the pixels are of (image coordinates of the view's origin included).
    pub intrinsics: CameraIntrinsics,
    /// L_CB L_BE: camera axes (x along the optical axis, y right, z down) from NED.
    pub camera_from_ned: Mat3,
}

/// A measured frame kept for the next: its colours, which pixels may explain the next
/// frame's, where it lies in its image and how it looked.
#[derive(Debug, Clone, Default)]
struct StoredFrame {
    rgb: Vec<[f32; 3]>,
    usable: Vec<bool>,
    origin: [usize; 2],
    width: usize,
    height: usize,
    geometry: Option<ViewGeometry>,
}

impl StoredFrame {
    /// The colour at image position (u, v) (pixel centres at i + 0.5), bilinear, when the
    /// four pixels around it are inside the frame and usable.
    fn sample(&self, u_px: f64, v_px: f64) -> Seen {
        let x = u_px - 0.5 - self.origin[0] as f64;
        let y = v_px - 0.5 - self.origin[1] as f64;
        if !(x >= 0.0 && y >= 0.0) {
            return Seen::Outside;
        }
        let (i, j) = (x.floor() as usize, y.floor() as usize);
        if i + 1 >= self.width || j + 1 >= self.height {
            return Seen::Outside;
        }
        let (fx, fy) = ((x - i as f64) as f32, (y - j as f64) as f32);
        let k = j * self.width + i;
        let corners = [k, k + 1, k + self.width, k + self.width + 1];
        if corners.iter().any(|&c| !self.usable[c]) {
            return Seen::Unusable;
        }
        let weights = [
            (1.0 - fx) * (1.0 - fy),
            fx * (1.0 - fy),
            (1.0 - fx) * fy,
            fx * fy,
        ];
        let mut out = [0.0f32; 3];
        for (&c, w) in corners.iter().zip(weights) {
            for (o, p) in out.iter_mut().zip(self.rgb[c]) {
                *o += w * p;
            }
        }
        Seen::Colour(out)
    }
}

/// What the previous frame saw in a direction.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Seen {
    /// Nothing: the direction was outside it (or behind its camera, or it is unknown).
    Outside,
    /// Its target, or what lay around it.
    Unusable,
    /// This background colour.
    Colour([f32; 3]),
}

/// The per-pixel background references of the frame being measured, and the frame before.
#[derive(Debug, Clone, Default)]
pub(crate) struct MotionReference {
    /// The last committed frame (the one the guidance measured last).
    previous: StoredFrame,
    /// The frame measured last, committed by [`Self::commit`].
    pending: StoredFrame,
    /// Offsets of the ring's pixels, (du, dv).
    ring: Vec<(isize, isize)>,
    /// The ring's radius, px.
    ring_radius_px: usize,
    /// The colours on the ring around the pixel being explained.
    ring_colours: Vec<[f32; 3]>,
    /// Reference colour of each pixel of the frame being measured, row-major.
    pub reference: Vec<[f32; 3]>,
    /// The geometry of the next frame to be measured.
    geometry: Option<ViewGeometry>,
}

fn distance2(a: [f32; 3], b: [f32; 3]) -> f32 {
    (0..3).map(|c| (a[c] - b[c]) * (a[c] - b[c])).sum()
}

/// The point of the segment from `a` to `b` nearest `p` (colours).
fn nearest_on_segment(p: [f32; 3], a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    let ab: [f32; 3] = std::array::from_fn(|c| b[c] - a[c]);
    let length2: f32 = ab.iter().map(|x| x * x).sum();
    if length2 <= f32::EPSILON {
        return a;
    }
    let t = ((0..3).map(|c| (p[c] - a[c]) * ab[c]).sum::<f32>() / length2).clamp(0.0, 1.0);
    std::array::from_fn(|c| a[c] + t * ab[c])
}

fn rgb_f32(frame: &RgbaView<'_>, idx: usize) -> [f32; 3] {
    frame.rgb(idx).map(|x| x as f32)
}

impl MotionReference {
    /// Sets how the next frame measured looks into the world (None: unknown, the previous
    /// frame then explains nothing).
    pub fn set_geometry(&mut self, geometry: Option<ViewGeometry>) {
        self.geometry = geometry;
    }

    /// Fills `reference` for `frame`; returns the background's noise σ per channel, grey
    /// levels: the robust scale of the pixels' distances to the previous frame where it
    /// explains them (their difference holds two frames' noise), else `floor`.
    pub fn build(&mut self, frame: &RgbaView<'_>, floor: f64, explained: f64) -> f64 {
        let explained2 = (explained * explained) as f32;
        if self.ring.is_empty() {
            self.set_ring_radius(DEFAULT_RING_RADIUS_PX);
        }
        let to_previous = self.rotation_to_previous();
        let (w, h) = (frame.width, frame.height);
        self.reference.clear();
        self.reference.reserve(w * h);
        let mut differences = Vec::new();
        for v in 0..h {
            for u in 0..w {
                let p = rgb_f32(frame, v * w + u);
                let seen = to_previous.map_or(Seen::Outside, |(m, k)| {
                    let (iu, iv) = (u + frame.origin[0], v + frame.origin[1]);
                    self.warp(&m, &k, iu as f64 + 0.5, iv as f64 + 0.5)
                });
                // A strip the camera's turn brought into view at the image's edge holds no
                // target yet: the previous frame did not see it and the ring lies half outside.
                // (The image's edge, not a tracking window's: a target may enter a window.)
                if seen == Seen::Outside && to_previous.is_some() && self.at_image_edge(frame, u, v)
                {
                    self.reference.push(p);
                    continue;
                }
                let warped = match seen {
                    Seen::Colour(c) => Some(c),
                    _ => None,
                };
                let explained = warped.is_some_and(|a| distance2(p, a) < explained2);
                let nearest = if explained {
                    None
                } else {
                    self.nearest_on_ring(frame, u, v, p)
                };
                let reference = match (warped, nearest) {
                    (Some(a), Some(b)) if distance2(p, a) <= distance2(p, b) => a,
                    (Some(a), None) => a,
                    (_, Some(b)) => b,
                    (None, None) => p,
                };
                if let Some(a) = warped {
                    differences.push(distance2(p, a));
                }
                self.reference.push(reference);
            }
        }
        noise_sigma(&mut differences, floor)
    }

    /// Whether pixel (u, v) of `frame` lies within the ring's radius of the whole image's
    /// edge (unknown intrinsics: of the frame's own edge).
    fn at_image_edge(&self, frame: &RgbaView<'_>, u: usize, v: usize) -> bool {
        let (iu, iv) = (u + frame.origin[0], v + frame.origin[1]);
        let (width, height) = self.geometry.map_or((frame.width, frame.height), |g| {
            (
                g.intrinsics.width_px as usize,
                g.intrinsics.height_px as usize,
            )
        });
        let from_edge = iu
            .min(iv)
            .min(width.saturating_sub(iu + 1))
            .min(height.saturating_sub(iv + 1));
        from_edge < self.ring_radius_px
    }

    /// The rotation from the frame being measured's camera axes to the previous frame's,
    /// and the previous camera, when both orientations are known.
    fn rotation_to_previous(&self) -> Option<(Mat3, CameraIntrinsics)> {
        let now = self.geometry?;
        let before = self.previous.geometry?;
        Some((
            before.camera_from_ned * now.camera_from_ned.transpose(),
            before.intrinsics,
        ))
    }

    /// The previous frame's colour in the direction of image position (u, v) of the frame
    /// being measured.
    fn warp(&self, rotation: &Mat3, before: &CameraIntrinsics, u: f64, v: f64) -> Seen {
        let Some(now) = self.geometry.map(|g| g.intrinsics) else {
            return Seen::Outside;
        };
        let ray = crate::frames::Vec3::new(now.focal_px, u - now.cx(), v - now.cy());
        let r = rotation * ray;
        if r.x <= 0.0 {
            return Seen::Outside;
        }
        let u_before = before.cx() + before.focal_px * r.y / r.x;
        let v_before = before.cy() + before.focal_px * r.z / r.x;
        self.previous.sample(u_before, v_before)
    }

    /// The colour nearest `p` among the pixels on a ring of radius `ring_radius_px` around
    /// (u, v) (those inside the frame) and their pairwise mixtures: a pixel an edge between
    /// two fields cuts is a mixture of the two, and the ring crosses both.
    fn nearest_on_ring(
        &mut self,
        frame: &RgbaView<'_>,
        u: usize,
        v: usize,
        p: [f32; 3],
    ) -> Option<[f32; 3]> {
        self.ring_colours.clear();
        for &(du, dv) in &self.ring {
            let (uu, vv) = (u as isize + du, v as isize + dv);
            if uu >= 0 && vv >= 0 && (uu as usize) < frame.width && (vv as usize) < frame.height {
                let q = rgb_f32(frame, vv as usize * frame.width + uu as usize);
                self.ring_colours.push(q);
            }
        }
        let mut best: Option<([f32; 3], f32)> = None;
        for (k, &a) in self.ring_colours.iter().enumerate() {
            for &b in &self.ring_colours[k..] {
                let q = nearest_on_segment(p, a, b);
                let d = distance2(p, q);
                if best.is_none_or(|(_, bd)| d < bd) {
                    best = Some((q, d));
                }
            }
        }
        best.map(|(q, _)| q)
    }

    /// Sets the ring's radius, px of the frames measured next: beyond the target's half
    /// length, so that the ring around a target pixel lies on background.
    pub fn set_ring_radius(&mut self, radius_px: f64) {
        let r = radius_px.max(2.0);
        self.ring_radius_px = r.ceil() as usize;
        self.ring = (0..RING_POINTS)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / RING_POINTS as f64;
                (
                    (r * a.cos()).round() as isize,
                    (r * a.sin()).round() as isize,
                )
            })
            .collect();
    }

    /// Keeps `frame` as the candidate previous frame, the pixels of the `target` pixels'
    /// bounding box (the measured blob's mask, when it was measured `Ok`) grown by the ring's
    /// radius unusable: the measured blob may be a part of the target, and what is left of it
    /// must not explain itself in the next frame.
    pub fn keep(&mut self, frame: &RgbaView<'_>, target: impl Iterator<Item = usize>) {
        let (w, h) = (frame.width, frame.height);
        let kept = &mut self.pending;
        kept.rgb.clear();
        kept.rgb.extend((0..w * h).map(|i| rgb_f32(frame, i)));
        kept.usable.clear();
        kept.usable.resize(w * h, true);
        kept.origin = frame.origin;
        (kept.width, kept.height) = (w, h);
        kept.geometry = self.geometry;
        let bounds = target.fold(None, |b: Option<[usize; 4]>, i| {
            let (u, v) = (i % w, i / w);
            Some(b.map_or([u, v, u, v], |[u0, v0, u1, v1]| {
                [u0.min(u), v0.min(v), u1.max(u), v1.max(v)]
            }))
        });
        let Some([u0, v0, u1, v1]) = bounds else {
            return;
        };
        let m = self.ring_radius_px.max(TARGET_MARGIN_PX);
        let (u0, u1) = (u0.saturating_sub(m), (u1 + m + 1).min(w));
        for v in v0.saturating_sub(m)..(v1 + m + 1).min(h) {
            kept.usable[v * w + u0..v * w + u1].fill(false);
        }
    }

    /// Whether the frame being measured has a previous frame to be explained by (its
    /// orientation and the previous one's known).
    pub fn has_previous(&self) -> bool {
        self.rotation_to_previous().is_some()
    }

    /// Makes the frame kept last the previous frame of the next one measured.
    pub fn commit(&mut self) {
        std::mem::swap(&mut self.previous, &mut self.pending);
    }
}

/// Per-channel σ from squared RGB distances between two noisy frames: the median distance
/// over √2 χ₃'s median (1.538), at least `floor`.
fn noise_sigma(differences: &mut [f32], floor: f64) -> f64 {
    if differences.is_empty() {
        return floor;
    }
    let mid = differences.len() / 2;
    let (_, median, _) = differences.select_nth_unstable_by(mid, f32::total_cmp);
    (f64::from(median.sqrt()) / (1.538 * std::f64::consts::SQRT_2)).max(floor)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frames::{EulerAngles, Vec3};
    use crate::vision::{BlobSelection, BlobStatus, VisionConfig, VisionPipeline};

    const WIDTH: u32 = 96;
    const HEIGHT: u32 = 72;
    const TARGET_RGB: [u8; 3] = [150, 150, 165];

    /// A world at infinity of 8° tiles of pseudo-random field colours, seen by a camera of
    /// orientation `camera_from_ned`, with a grey disc of radius 6 px (at least 35 grey levels from every tile, in blue) at (u, v) if any.
    fn frame(
        camera_from_ned: &Mat3,
        intrinsics: &CameraIntrinsics,
        disc: Option<(f64, f64)>,
    ) -> Vec<u8> {
        let mut rgba = Vec::with_capacity((WIDTH * HEIGHT * 4) as usize);
        for v in 0..HEIGHT {
            for u in 0..WIDTH {
                let (uc, vc) = (f64::from(u) + 0.5, f64::from(v) + 0.5);
                let ray = Vec3::new(
                    intrinsics.focal_px,
                    uc - intrinsics.cx(),
                    vc - intrinsics.cy(),
                );
                let d = camera_from_ned.transpose() * ray;
                let tile = 8f64.to_radians();
                let az = (d.y.atan2(d.x) / tile).floor() as i64;
                let el = ((-d.z).atan2(d.x.hypot(d.y)) / tile).floor() as i64;
                let hash = ((az * 73_856_093) ^ (el * 19_349_663)).rem_euclid(997) as u8;
                let mut rgb = [80 + hash % 100, 110 + hash % 90, 70 + (hash / 3) % 60];
                if let Some((du, dv)) = disc
                    && (uc - du).hypot(vc - dv) < 6.0
                {
                    rgb = TARGET_RGB;
                }
                rgba.extend_from_slice(&[rgb[0], rgb[1], rgb[2], 255]);
            }
        }
        rgba
    }

    /// Measures the two frames (the target enters in the second) with the motion reference,
    /// told that the second was taken at `told_now`.
    fn measure_pair(told_now: &Mat3) -> crate::vision::BlobMeasurement {
        let intrinsics = CameraIntrinsics::from_hfov(WIDTH, HEIGHT, 60.0);
        let config = VisionConfig {
            motion_reference: true,
            ..VisionConfig::default()
        };
        let mut motion = VisionPipeline::new(config).unwrap();
        let first = frame(&before(), &intrinsics, None);
        let second = frame(&now(), &intrinsics, Some(CENTRE));
        let mut last = None;
        for (pixels, told) in [(first, before()), (second, *told_now)] {
            motion.set_view_geometry(Some(ViewGeometry {
                intrinsics,
                camera_from_ned: told,
            }));
            last = Some(motion.measure(&pixels, WIDTH, HEIGHT, NEAR_CENTRE).unwrap());
            motion.commit_frame();
        }
        last.unwrap()
    }

    const CENTRE: (f64, f64) = (47.3, 35.8);

    /// The camera follows the blob nearest its prediction (both segmentations below).
    const NEAR_CENTRE: BlobSelection = BlobSelection::NearestTo {
        u_px: CENTRE.0 + 2.0,
        v_px: CENTRE.1 - 1.0,
    };

    fn before() -> Mat3 {
        EulerAngles::new(0.0, 0.05, 0.3).body_from_ned()
    }

    fn now() -> Mat3 {
        EulerAngles::new(0.02, 0.09, 0.36).body_from_ned()
    }

    /// Invariant: against a textured background at infinity (8° tiles, finer than the local
    /// colour ring), the previous frame turned by the camera's rotation between the frames
    /// explains the background: the target that entered is measured, its centroid within
    /// 0.3 px of its centre (a few slivers remain where the bilinear warp blurs a tile's hard
    /// edge, and on the strip the rotation brought into view). Told the wrong rotation
    /// (none), the background is not explained, and the target is not measured; nor is it
    /// by today's threshold against a colour surface fitted to the border.
    #[test]
    fn rotated_previous_frame_explains_a_textured_world() {
        let m = measure_pair(&now());
        assert_eq!(m.status, BlobStatus::Ok);
        let off_px = (m.centroid_u_px - CENTRE.0).hypot(m.centroid_v_px - CENTRE.1);
        assert!(off_px < 0.3, "centroid {off_px} px off");
        let fails = |m: &crate::vision::BlobMeasurement| {
            let off_px = (m.centroid_u_px - CENTRE.0).hypot(m.centroid_v_px - CENTRE.1);
            m.status != BlobStatus::Ok || off_px.is_nan() || off_px >= 1.0
        };
        let unturned = measure_pair(&before());
        assert!(fails(&unturned), "told no rotation: {unturned:?}");
        let intrinsics = CameraIntrinsics::from_hfov(WIDTH, HEIGHT, 60.0);
        let threshold = VisionPipeline::new(VisionConfig::default())
            .unwrap()
            .measure(
                &frame(&now(), &intrinsics, Some(CENTRE)),
                WIDTH,
                HEIGHT,
                NEAR_CENTRE,
            )
            .unwrap();
        assert!(fails(&threshold), "border-fitted threshold: {threshold:?}");
    }

    /// Invariant: a first frame (no previous frame to explain its background) measures
    /// nothing.
    #[test]
    fn first_frame_only_sets_up() {
        let intrinsics = CameraIntrinsics::from_hfov(WIDTH, HEIGHT, 60.0);
        let config = VisionConfig {
            motion_reference: true,
            ..VisionConfig::default()
        };
        let mut motion = VisionPipeline::new(config).unwrap();
        motion.set_view_geometry(Some(ViewGeometry {
            intrinsics,
            camera_from_ned: now(),
        }));
        let pixels = frame(&now(), &intrinsics, Some(CENTRE));
        let m = motion
            .measure(&pixels, WIDTH, HEIGHT, BlobSelection::Largest)
            .unwrap();
        assert_eq!(m.status, BlobStatus::NotFound);
    }
}
