//! The background each pixel is explained by, for a textured world behind the target
//! (`camera.segmentation = "motion"`): a per-pixel reference colour the segmenter measures
//! colour distances against instead of a smooth surface fitted to the border.
//!
//! A pixel's reference is the nearest to its colour of:
//! 1. The remembered background in its direction, and around it. The memory is the last
//!    frame, mapped into this one by the camera's motion between them, taken from the
//!    follower's navigation attitude, position and gimbal angles (the pose the sensing path
//!    already uses; never the truth): a direction at infinity (sky, clouds, the horizon) by
//!    the homography K' R K⁻¹ of the rotation; a direction below the horizon, when the
//!    ground's elevation is known (from a map: flat ground), through the ground's
//!    point, which takes in the ground's parallax. Its colours within [`PARALLAX_PX`] and
//!    their mixtures explain what the mapping leaves (an edge moved by a little parallax).
//!    Where the target was measured (its blob's box grown by the ring's radius) and where it
//!    was expected (a gated selection's gate), the frame does not replace the memory: the
//!    memory carries the background it had there, so the background under a target that
//!    moves against the world is known from earlier frames, and a blob that was only a part
//!    of the target cannot let the rest explain itself.
//! 2. Where the memory has nothing (the first frames under the target, a strip the camera's
//!    turn brought into view), the nearest colour on a ring of [`RING_POINTS`] pixels around
//!    the pixel, of a radius beyond the target's half length, or mixture of two of them (the
//!    local colour model): around a pixel of a compact target the ring lies on background
//!    whose colours it does not match; a pixel of a field, a road or the sky has pixels of its
//!    own kind on the ring. For a pixel where the previous frame measured the target, the
//!    ring takes no colours where that target lay: the ring about a wing tip crosses the
//!    fuselage and the other wing, whose colour would explain the tip. In a tracking window
//!    smaller than the ring, a ring point beyond the window is taken on the window's border.
//!    A strip at the image's edge is taken for background.
//! 3. With the target's colour learned (`camera.target_colour_tolerance_deg`,
//!    `super::target_colour`), a pixel neither explains is offered the memory's colours and
//!    the ring's together: it is target only as a mixture of one of them with a shade of the
//!    target's colour, and otherwise its own reference (background). A memory mislaid about
//!    the target (it carries old background there for many frames) then no longer makes
//!    fields' edges into target.
//!
//! Assumptions, and where it breaks (docs/findings.md, The scene and the vision against it):
//! the background is at infinity or on the flat ground; the target's colour differs from
//! the colours of the background around it and their mixtures; parallax beyond
//! [`PARALLAX_PX`] per frame (ground the follower does not know the height of, or seen
//! steeply down from low height), a background that changes, and a target at rest against the
//! world since before the memory saw the background behind it are taken for target or lost.

mod pixels;

use super::image_view::RgbaView;
use super::target_colour::ColourGate;
use crate::frames::{Mat3, Vec3};
use crate::render::camera::CameraIntrinsics;
use pixels::{PixelExplainer, threads_for};

/// Pixels around the previous frame's target mask that explain nothing at least (its
/// anti-aliased edge, and the target's motion in the image between frames).
pub(crate) const TARGET_MARGIN_PX: usize = 3;
/// Pixels on the ring of the local colour model.
const RING_POINTS: usize = 16;
/// Points around a remembered pixel whose colours (and mixtures) explain a pixel that moved
/// by parallax.
const PARALLAX_POINTS: usize = 8;
/// Their distance from it, px: the parallax of one frame that the memory absorbs (ground
/// seen up to about 60° below the horizon at formation_scene's start).
const PARALLAX_PX: f64 = 2.0;
/// The ring's radius before any target was measured, px.
pub(crate) const DEFAULT_RING_RADIUS_PX: f64 = 24.0;

/// How a frame's pixels look into the world: the camera (binned or not), its orientation and
/// position as the follower's navigation knows them, and the ground's height when known.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ViewGeometry {
    /// The camera the pixels are of (image coordinates of the view's origin included).
    pub intrinsics: CameraIntrinsics,
    /// L_CB L_BE: camera axes (x along the optical axis, y right, z down) from NED.
    pub camera_from_ned: Mat3,
    /// The camera's position, NED, ft.
    pub position_ned_ft: Vec3,
    /// The flat ground's NED down coordinate, ft, when the follower knows it (the terrain's
    /// elevation from a map): directions below the horizon then map between frames through
    /// the ground's point (its parallax) at the navigated height above it, the others as
    /// directions at infinity.
    pub ground_down_ft: Option<f64>,
}

impl ViewGeometry {
    /// The direction (any length), in `before`'s camera axes, in which `before` saw what
    /// this view sees along `direction_ned`.
    fn seen_from(&self, before: &ViewGeometry, direction_ned: &Vec3) -> Vec3 {
        let height_ft = self
            .ground_down_ft
            .map_or(0.0, |g| g - self.position_ned_ft.z);
        if height_ft > 0.0 && direction_ned.z > 0.0 {
            let ground_point = self.position_ned_ft + direction_ned * (height_ft / direction_ned.z);
            before.camera_from_ned * (ground_point - before.position_ned_ft)
        } else {
            before.camera_from_ned * direction_ned
        }
    }
}

/// A measured frame kept for the next: its colours, which pixels may explain the next
/// frame's, where it lies in its image and how it looked.
#[derive(Debug, Clone, Default)]
struct StoredFrame {
    rgb: Vec<[f32; 3]>,
    usable: Vec<bool>,
    /// The target measured in it, its mask grown by [`TARGET_MARGIN_PX`].
    target: Vec<bool>,
    origin: [usize; 2],
    width: usize,
    height: usize,
    geometry: Option<ViewGeometry>,
}

impl StoredFrame {
    /// Whether image position (u, v) lay on the target measured in this frame (its grown
    /// mask).
    fn was_target(&self, u_px: f64, v_px: f64) -> bool {
        let x = u_px - self.origin[0] as f64;
        let y = v_px - self.origin[1] as f64;
        if !(x >= 0.0 && y >= 0.0) {
            return false;
        }
        let (i, j) = (x as usize, y as usize);
        i < self.width && j < self.height && self.target[j * self.width + i]
    }

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
    /// Reference colour of each pixel of the frame being measured, row-major.
    pub reference: Vec<[f32; 3]>,
    /// The remembered background in the direction of each pixel of the frame being measured,
    /// where the memory has one, row-major.
    carried: Vec<Option<[f32; 3]>>,
    /// Where each pixel of the frame being measured lies in the memory's image, row-major.
    in_previous: Vec<Option<(f64, f64)>>,
    /// Whether each pixel of the frame being measured lay on the target the memory measured
    /// (the ring does not take its colours there), row-major.
    on_previous_target: Vec<bool>,
    /// The geometry of the next frame to be measured.
    geometry: Option<ViewGeometry>,
    /// The target's colour, when known: a pixel the background does not explain is
    /// target only as a mixture of a shade of it and a background colour around it.
    gate: Option<ColourGate>,
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
    /// levels: the robust scale of the pixels' distances to the remembered background where
    /// it sees them (their difference holds two frames' noise), else `floor`.
    pub fn build(&mut self, frame: &RgbaView<'_>, floor: f64) -> f64 {
        self.build_on(frame, floor, threads_for(frame.width, frame.height))
    }

    /// [`Self::build`] on `threads` threads.
    fn build_on(&mut self, frame: &RgbaView<'_>, floor: f64, threads: usize) -> f64 {
        if self.ring.is_empty() {
            self.set_ring_radius(DEFAULT_RING_RADIUS_PX);
        }
        let to_previous = self.views_to_previous();
        let window = self.is_window(frame);
        let (w, h) = (frame.width, frame.height);
        self.locate_in_previous(frame, to_previous.as_ref());
        let image_size = self.geometry.map_or((w, h), |g| {
            let i = g.intrinsics;
            (i.width_px as usize, i.height_px as usize)
        });
        let explainer = PixelExplainer {
            frame,
            previous: &self.previous,
            in_previous: &self.in_previous,
            on_previous_target: &self.on_previous_target,
            ring: &self.ring,
            ring_radius_px: self.ring_radius_px,
            gate: self.gate,
            window,
            new_strip_at_edge: to_previous.is_some(),
            image_size,
        };
        self.reference.clear();
        self.reference.resize(w * h, [0.0; 3]);
        self.carried.clear();
        self.carried.resize(w * h, None);
        let mut differences =
            explainer.explain_rows(&mut self.reference, &mut self.carried, threads);
        noise_sigma(&mut differences, floor)
    }

    /// Where each pixel of `frame` lies in the memory's image, and whether it lay on the
    /// target the memory measured there.
    fn locate_in_previous(&mut self, frame: &RgbaView<'_>, to_previous: Option<&Warp>) {
        let (w, h) = (frame.width, frame.height);
        self.in_previous.clear();
        self.in_previous.extend((0..w * h).map(|i| {
            let (iu, iv) = (i % w + frame.origin[0], i / w + frame.origin[1]);
            to_previous.and_then(|warp| warp.position(iu as f64 + 0.5, iv as f64 + 0.5))
        }));
        let previous = &self.previous;
        self.on_previous_target.clear();
        self.on_previous_target.extend(
            self.in_previous
                .iter()
                .map(|at| at.is_some_and(|(x, y)| previous.was_target(x, y))),
        );
    }

    /// The map from the frame being measured to the memory, when both views are known.
    fn views_to_previous(&self) -> Option<Warp> {
        let now = self.geometry?;
        Some(Warp {
            ned_from_now: now.camera_from_ned.transpose(),
            now,
            before: self.previous.geometry?,
        })
    }

    /// Whether `frame` is a tracking window inside a larger image (the view's image size
    /// known): its border was placed beyond the target's predicted box, on background.
    fn is_window(&self, frame: &RgbaView<'_>) -> bool {
        self.geometry.is_some_and(|g| {
            frame.width < g.intrinsics.width_px as usize
                || frame.height < g.intrinsics.height_px as usize
        })
    }

    /// Sets the target's colour test for the frames measured next (None: none).
    pub fn set_colour_gate(&mut self, gate: Option<ColourGate>) {
        self.gate = gate;
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

    /// Keeps `frame` as the candidate memory of the background, except in `exclusion` (a box
    /// [u0, v0, u1, v1] of the frame's pixels, inclusive: where the target was measured, or
    /// where it was expected when it was not): there the memory carries the background it
    /// had (warped into this frame by [`Self::build`]), and knows none where it had none. A
    /// blob that was only a part of the target must not let the rest explain itself.
    pub fn keep(&mut self, frame: &RgbaView<'_>, exclusion: Option<[usize; 4]>) {
        let (w, h) = (frame.width, frame.height);
        let kept = &mut self.pending;
        kept.rgb.clear();
        kept.rgb.extend((0..w * h).map(|i| rgb_f32(frame, i)));
        kept.usable.clear();
        kept.usable.resize(w * h, true);
        kept.target.clear();
        kept.target.resize(w * h, false);
        kept.origin = frame.origin;
        (kept.width, kept.height) = (w, h);
        kept.geometry = self.geometry;
        let Some([u0, v0, u1, v1]) = exclusion else {
            return;
        };
        let carried = (self.carried.len() == w * h).then_some(&self.carried);
        for v in v0..=v1.min(h - 1) {
            for i in v * w + u0..=v * w + u1.min(w - 1) {
                match carried.and_then(|c| c[i]) {
                    Some(c) => kept.rgb[i] = c,
                    None => kept.usable[i] = false,
                }
            }
        }
    }

    /// Marks the pixels `target` (of the frame kept last, row-major) as its measured target,
    /// grown by [`TARGET_MARGIN_PX`]: the next frame's ring takes no colours there.
    pub fn mark_target(&mut self, target: impl Iterator<Item = usize>) {
        let kept = &mut self.pending;
        let (w, h) = (kept.width, kept.height);
        let m = TARGET_MARGIN_PX;
        for i in target {
            let (u, v) = (i % w, i / w);
            for vv in v.saturating_sub(m)..=(v + m).min(h.saturating_sub(1)) {
                for uu in u.saturating_sub(m)..=(u + m).min(w.saturating_sub(1)) {
                    kept.target[vv * w + uu] = true;
                }
            }
        }
    }

    /// The box about the pixels `target` of a frame `width` pixels wide that the memory
    /// keeps out: their bounding box grown by the ring's radius (None without pixels).
    pub fn exclusion_about(
        &self,
        target: impl Iterator<Item = usize>,
        width: usize,
    ) -> Option<[usize; 4]> {
        let [u0, v0, u1, v1] = target.fold(None, |b: Option<[usize; 4]>, i| {
            let (u, v) = (i % width, i / width);
            Some(b.map_or([u, v, u, v], |[u0, v0, u1, v1]| {
                [u0.min(u), v0.min(v), u1.max(u), v1.max(v)]
            }))
        })?;
        let m = self.ring_radius_px.max(TARGET_MARGIN_PX);
        Some([u0.saturating_sub(m), v0.saturating_sub(m), u1 + m, v1 + m])
    }

    /// Whether the frame being measured has a previous frame to be explained by (its
    /// orientation and the previous one's known).
    pub fn has_previous(&self) -> bool {
        self.views_to_previous().is_some()
    }

    /// Makes the frame kept last the previous frame of the next one measured.
    pub fn commit(&mut self) {
        std::mem::swap(&mut self.previous, &mut self.pending);
    }
}

/// The map of a frame's image positions into the memory's image (one per frame).
struct Warp {
    /// (L_CB L_BE)ᵀ of the frame.
    ned_from_now: Mat3,
    now: ViewGeometry,
    before: ViewGeometry,
}

impl Warp {
    /// Where image position (u, v) of the frame lies in the memory's image: the same
    /// direction at infinity (the homography K' R K⁻¹ of the camera's rotation), or the same
    /// point of the ground where the frame's view knows it (None: behind the memory's
    /// camera).
    fn position(&self, u: f64, v: f64) -> Option<(f64, f64)> {
        let direction_ned = self.ned_from_now * self.now.intrinsics.direction_of_pixel(u, v);
        let seen = self.now.seen_from(&self.before, &direction_ned);
        self.before.intrinsics.pixel_of_direction(&seen)
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
mod tests;
