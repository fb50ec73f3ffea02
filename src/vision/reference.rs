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

use super::image_view::RgbaView;
use super::target_colour::ColourGate;
use crate::frames::{Mat3, Vec3};
use crate::render::camera::CameraIntrinsics;

/// Pixels around the previous frame's target mask that explain nothing at least (its
/// anti-aliased edge, and the target's motion in the image between frames).
pub(crate) const TARGET_MARGIN_PX: usize = 3;
/// Pixels on the ring of the local colour model.
const RING_POINTS: usize = 16;
/// A pixel within this colour distance of the remembered background in its direction is
/// background without looking further, grey levels: half the default detection floor.
const EXPLAINED_GREY: f64 = 4.0;
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
    /// The colours on the ring around the pixel being explained.
    ring_colours: Vec<[f32; 3]>,
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

/// The colour nearest `p` among `colours` and their pairwise mixtures (None when empty).
fn nearest_mixture(colours: &[[f32; 3]], p: [f32; 3]) -> Option<[f32; 3]> {
    let mut best: Option<([f32; 3], f32)> = None;
    for (k, &a) in colours.iter().enumerate() {
        for &b in &colours[k..] {
            let q = nearest_on_segment(p, a, b);
            let d = distance2(p, q);
            if best.is_none_or(|(_, bd)| d < bd) {
                best = Some((q, d));
            }
        }
    }
    best.map(|(q, _)| q)
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
        let explained2 = (EXPLAINED_GREY * EXPLAINED_GREY) as f32;
        if self.ring.is_empty() {
            self.set_ring_radius(DEFAULT_RING_RADIUS_PX);
        }
        let to_previous = self.views_to_previous();
        let window = self.is_window(frame);
        let (w, h) = (frame.width, frame.height);
        self.locate_in_previous(frame, to_previous.as_ref());
        self.reference.clear();
        self.reference.reserve(w * h);
        self.carried.clear();
        self.carried.reserve(w * h);
        let mut differences = Vec::new();
        for v in 0..h {
            for u in 0..w {
                let p = rgb_f32(frame, v * w + u);
                let at = self.in_previous[v * w + u];
                let seen = at.map_or(Seen::Outside, |(x, y)| self.previous.sample(x, y));
                self.carried.push(match seen {
                    Seen::Colour(c) => Some(c),
                    _ => None,
                });
                let reference = match (seen, at) {
                    (Seen::Colour(c), Some((x, y))) => {
                        differences.push(distance2(p, c));
                        if distance2(p, c) < explained2 {
                            c
                        } else {
                            self.remembered_colours(x, y);
                            if self.gate.is_some() {
                                // A memory mislaid by a frame's errors leaves the ring.
                                self.push_ring_colours(frame, u, v, window);
                            }
                            self.explain(p)
                        }
                    }
                    // A strip the camera's turn brought into view at the image's edge holds
                    // no target yet: the memory did not see it and the ring lies half outside.
                    // (The image's edge, not a tracking window's: a target may enter a window.)
                    (Seen::Outside, _)
                        if to_previous.is_some() && self.at_image_edge(frame, u, v) =>
                    {
                        p
                    }
                    _ => {
                        self.ring_colours.clear();
                        self.push_ring_colours(frame, u, v, window);
                        self.explain(p)
                    }
                };
                self.reference.push(reference);
            }
        }
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

    /// The remembered background at position (x, y) of the memory and at
    /// [`PARALLAX_POINTS`] points [`PARALLAX_PX`] around it, into `ring_colours`: ground at a
    /// finite distance moves by parallax beyond the camera's rotation, and a pixel an edge
    /// moved onto is a mixture of the colours on either side of it.
    fn remembered_colours(&mut self, x: f64, y: f64) {
        self.ring_colours.clear();
        for k in 0..=PARALLAX_POINTS {
            let (dx, dy) = if k == 0 {
                (0.0, 0.0)
            } else {
                let a = std::f64::consts::TAU * k as f64 / PARALLAX_POINTS as f64;
                (PARALLAX_PX * a.cos(), PARALLAX_PX * a.sin())
            };
            if let Seen::Colour(c) = self.previous.sample(x + dx, y + dy) {
                self.ring_colours.push(c);
            }
        }
    }

    /// The reference of a pixel of colour `p` from the background colours around it
    /// (`ring_colours`): the nearest of them and their pairwise mixtures. With the target's
    /// colour known, where that does not explain `p` (within twice [`EXPLAINED_GREY`], the
    /// detection floor): the background colour `p` is a mixture of with a shade of the
    /// target, or else `p` itself (neither background nor target: a field's edge the memory
    /// mislaid).
    fn explain(&self, p: [f32; 3]) -> [f32; 3] {
        let nearest = nearest_mixture(&self.ring_colours, p).unwrap_or(p);
        let Some(gate) = self.gate else {
            return nearest;
        };
        let floor = (2.0 * EXPLAINED_GREY) as f32;
        if distance2(p, nearest) < floor * floor {
            return nearest;
        }
        gate.best_background(p, &self.ring_colours).unwrap_or(p)
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

    /// The map from the frame being measured to the memory, when both views are known.
    fn views_to_previous(&self) -> Option<Warp> {
        let now = self.geometry?;
        Some(Warp {
            ned_from_now: now.camera_from_ned.transpose(),
            now,
            before: self.previous.geometry?,
        })
    }

    /// Adds to `ring_colours` the pixels on a ring of radius `ring_radius_px` around (u, v)
    /// (those inside the frame and not on the target the memory measured): a pixel an edge
    /// between two fields cuts is a mixture of the two, and the ring crosses both. The ring
    /// around a pixel near one end of the target crosses the target's other parts, whose
    /// colour would explain it. In a tracking window (`window`, [`Self::is_window`], decided
    /// once per frame) a ring point beyond the window is taken where its ray leaves the
    /// window, on the border: the ring about a target 130 px long
    /// has a radius of about 90 px, and a window 80 px tall about it would otherwise leave
    /// only the ring's points on the target itself, which explain its wings as background.
    fn push_ring_colours(&mut self, frame: &RgbaView<'_>, u: usize, v: usize, window: bool) {
        let on_target = &self.on_previous_target;
        let from_target = on_target[v * frame.width + u];
        for &(du, dv) in &self.ring {
            let at = if window {
                Some(onto_border(frame, u, v, du, dv))
            } else {
                inside(frame, u as isize + du, v as isize + dv)
            };
            if let Some(i) = at
                && !(from_target && on_target[i])
            {
                self.ring_colours.push(rgb_f32(frame, i));
            }
        }
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

/// The index of pixel (u, v) of `frame`, when inside it.
fn inside(frame: &RgbaView<'_>, u: isize, v: isize) -> Option<usize> {
    let (w, h) = (frame.width as isize, frame.height as isize);
    (u >= 0 && v >= 0 && u < w && v < h).then(|| (v * w + u) as usize)
}

/// The index of the pixel of `frame` at (u, v) + (du, dv), or, beyond the frame, where the
/// ray from (u, v) towards it leaves the frame.
fn onto_border(frame: &RgbaView<'_>, u: usize, v: usize, du: isize, dv: isize) -> usize {
    let (w, h) = (frame.width as f64, frame.height as f64);
    let (x, y) = (u as f64, v as f64);
    // The largest share t of the step that stays within [0, w - 1] x [0, h - 1].
    let reach = |from: f64, step: isize, last: f64| match step {
        0 => 1.0,
        s if s > 0 => (last - from) / s as f64,
        s => from / -s as f64,
    };
    let t = reach(x, du, w - 1.0)
        .min(reach(y, dv, h - 1.0))
        .clamp(0.0, 1.0);
    let uu = (x + t * du as f64).round().clamp(0.0, w - 1.0) as usize;
    let vv = (y + t * dv as f64).round().clamp(0.0, h - 1.0) as usize;
    vv * frame.width + uu
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
