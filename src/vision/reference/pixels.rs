//! Each pixel's reference colour (`super`, steps 1-3 of the module's list). The pixels of a
//! frame are independent of each other, so a large frame's rows are shared among several
//! threads, each with its own scratch, and every pixel's reference is the same whichever
//! thread explained it.

use super::{PARALLAX_POINTS, PARALLAX_PX, Seen, StoredFrame, rgb_f32};
use crate::vision::image_view::RgbaView;
use crate::vision::target_colour::ColourGate;
use std::sync::OnceLock;

/// A pixel within this colour distance of the remembered background in its direction is
/// background without looking further, grey levels: half the default detection floor.
const EXPLAINED_GREY: f64 = 4.0;
/// Its square, in the colours' type.
const EXPLAINED2: f32 = (EXPLAINED_GREY * EXPLAINED_GREY) as f32;
/// Pixels each thread explaining a frame takes at least: below it a thread costs more to
/// start than it saves (a thread starts in tens of µs; a pixel the memory does not explain
/// costs about 0.5 µs).
const THREAD_MIN_PIXELS: usize = 4_096;

/// How many threads explain a `width` x `height` frame: one per core, each with at least
/// [`THREAD_MIN_PIXELS`] pixels; one on a thread of a pool of parallel runs (a sweep's
/// cases, a group's followers), whose runs already keep the cores busy.
pub(super) fn threads_for(width: usize, height: usize) -> usize {
    static CORES: OnceLock<usize> = OnceLock::new();
    if rayon::current_thread_index().is_some() {
        return 1;
    }
    let cores = *CORES.get_or_init(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    (width * height / THREAD_MIN_PIXELS).clamp(1, cores.min(height.max(1)))
}

/// One row of the frame's references and remembered colours.
struct Row<'a> {
    v: usize,
    reference: &'a mut [[f32; 3]],
    carried: &'a mut [Option<[f32; 3]>],
}

/// What explains the pixels of one frame: the frame, the memory mapped into it, the ring
/// and the target's colour.
pub(super) struct PixelExplainer<'a> {
    pub frame: &'a RgbaView<'a>,
    pub previous: &'a StoredFrame,
    /// Where each pixel lies in the memory's image, row-major.
    pub in_previous: &'a [Option<(f64, f64)>],
    /// Whether each pixel lay on the target the memory measured, row-major.
    pub on_previous_target: &'a [bool],
    /// Offsets of the ring's pixels, (du, dv).
    pub ring: &'a [(isize, isize)],
    /// The ring's radius, px.
    pub ring_radius_px: usize,
    pub gate: Option<ColourGate>,
    /// The frame is a tracking window inside a larger image.
    pub window: bool,
    /// The memory is of another view: a strip at the image's edge is newly in view.
    pub new_strip_at_edge: bool,
    /// The whole image's width and height, px.
    pub image_size: (usize, usize),
}

impl PixelExplainer<'_> {
    /// Fills `reference` and `carried` (one entry per pixel of the frame, row-major) on
    /// `threads` threads, which take the rows in turn (the pixels that cost most, about the
    /// target, then fall to every thread); returns the squared distances of the pixels to
    /// the remembered background where it sees them, in no particular order.
    pub fn explain_rows(
        &self,
        reference: &mut [[f32; 3]],
        carried: &mut [Option<[f32; 3]>],
        threads: usize,
    ) -> Vec<f32> {
        let width = self.frame.width.max(1);
        let threads = threads.max(1);
        let mut shares: Vec<Vec<Row<'_>>> = (0..threads).map(|_| Vec::new()).collect();
        let rows = reference.chunks_mut(width).zip(carried.chunks_mut(width));
        for (v, (reference, carried)) in rows.enumerate() {
            shares[v % threads].push(Row {
                v,
                reference,
                carried,
            });
        }
        let mut shares = shares.into_iter();
        let own = shares.next().unwrap_or_default();
        std::thread::scope(|scope| {
            let others: Vec<_> = shares
                .map(|share| scope.spawn(move || self.explain_share(share)))
                .collect();
            let mut differences = self.explain_share(own);
            for share in others {
                differences.extend(share.join().expect("a thread of rows panicked"));
            }
            differences
        })
    }

    /// Explains the pixels of `rows`.
    fn explain_share(&self, rows: Vec<Row<'_>>) -> Vec<f32> {
        let mut colours = Vec::new();
        let mut differences = Vec::new();
        for row in rows {
            let pixels = row.reference.iter_mut().zip(row.carried.iter_mut());
            for (u, (reference, carried)) in pixels.enumerate() {
                (*reference, *carried) =
                    self.explain_pixel(u, row.v, &mut colours, &mut differences);
            }
        }
        differences
    }

    /// The reference of pixel (u, v) and the memory's colour in its direction, when it has
    /// one (then its squared distance from the pixel joins `differences`); `colours` is
    /// scratch.
    fn explain_pixel(
        &self,
        u: usize,
        v: usize,
        colours: &mut Vec<[f32; 3]>,
        differences: &mut Vec<f32>,
    ) -> ([f32; 3], Option<[f32; 3]>) {
        let i = v * self.frame.width + u;
        let p = rgb_f32(self.frame, i);
        let at = self.in_previous[i];
        let seen = at.map_or(Seen::Outside, |(x, y)| self.previous.sample(x, y));
        let carried = match seen {
            Seen::Colour(c) => Some(c),
            _ => None,
        };
        let reference = match (seen, at) {
            (Seen::Colour(c), Some((x, y))) => {
                let off2 = distance2(p, c);
                differences.push(off2);
                if off2 < EXPLAINED2 {
                    c
                } else {
                    self.remembered_colours(x, y, colours);
                    if self.gate.is_some() {
                        // A memory mislaid by a frame's errors leaves the ring.
                        self.push_ring_colours(u, v, colours);
                    }
                    self.explain(p, colours)
                }
            }
            // A strip the camera's turn brought into view at the image's edge holds
            // no target yet: the memory did not see it and the ring lies half outside.
            // (The image's edge, not a tracking window's: a target may enter a window.)
            (Seen::Outside, _) if self.new_strip_at_edge && self.at_image_edge(u, v) => p,
            _ => {
                colours.clear();
                self.push_ring_colours(u, v, colours);
                self.explain(p, colours)
            }
        };
        (reference, carried)
    }

    /// The remembered background at position (x, y) of the memory and at
    /// [`PARALLAX_POINTS`] points [`PARALLAX_PX`] around it, into `colours`: ground at a
    /// finite distance moves by parallax beyond the camera's rotation, and a pixel an edge
    /// moved onto is a mixture of the colours on either side of it.
    fn remembered_colours(&self, x: f64, y: f64, colours: &mut Vec<[f32; 3]>) {
        colours.clear();
        for k in 0..=PARALLAX_POINTS {
            let (dx, dy) = if k == 0 {
                (0.0, 0.0)
            } else {
                let a = std::f64::consts::TAU * k as f64 / PARALLAX_POINTS as f64;
                (PARALLAX_PX * a.cos(), PARALLAX_PX * a.sin())
            };
            if let Seen::Colour(c) = self.previous.sample(x + dx, y + dy) {
                colours.push(c);
            }
        }
    }

    /// The reference of a pixel of colour `p` from the background colours around it: the
    /// nearest of them and their pairwise mixtures. With the target's colour known, where
    /// that does not explain `p` (within twice [`EXPLAINED_GREY`], the detection floor): the
    /// background colour `p` is a mixture of with a shade of the target, or else `p` itself
    /// (neither background nor target: a field's edge the memory mislaid).
    fn explain(&self, p: [f32; 3], colours: &[[f32; 3]]) -> [f32; 3] {
        let nearest = nearest_mixture(colours, p).unwrap_or(p);
        let Some(gate) = self.gate else {
            return nearest;
        };
        let floor = (2.0 * EXPLAINED_GREY) as f32;
        if distance2(p, nearest) < floor * floor {
            return nearest;
        }
        gate.best_background(p, colours).unwrap_or(p)
    }

    /// Whether pixel (u, v) of the frame lies within the ring's radius of the whole image's
    /// edge.
    fn at_image_edge(&self, u: usize, v: usize) -> bool {
        let (iu, iv) = (u + self.frame.origin[0], v + self.frame.origin[1]);
        let (width, height) = self.image_size;
        let from_edge = iu
            .min(iv)
            .min(width.saturating_sub(iu + 1))
            .min(height.saturating_sub(iv + 1));
        from_edge < self.ring_radius_px
    }

    /// Adds to `colours` the pixels on a ring of radius `ring_radius_px` around (u, v)
    /// (those inside the frame and not on the target the memory measured): a pixel an edge
    /// between two fields cuts is a mixture of the two, and the ring crosses both. The ring
    /// around a pixel near one end of the target crosses the target's other parts, whose
    /// colour would explain it. In a tracking window (`window`) a ring point beyond the
    /// window is taken where its ray leaves the window, on the border: the ring about a
    /// target 130 px long has a radius of about 90 px, and a window 80 px tall about it
    /// would otherwise leave only the ring's points on the target itself, which explain its
    /// wings as background.
    fn push_ring_colours(&self, u: usize, v: usize, colours: &mut Vec<[f32; 3]>) {
        let frame = self.frame;
        let on_target = self.on_previous_target;
        let from_target = on_target[v * frame.width + u];
        for &(du, dv) in self.ring {
            let at = if self.window {
                Some(onto_border(frame, u, v, du, dv))
            } else {
                inside(frame, u as isize + du, v as isize + dv)
            };
            if let Some(i) = at
                && !(from_target && on_target[i])
            {
                colours.push(rgb_f32(frame, i));
            }
        }
    }
}

pub(super) fn distance2(a: [f32; 3], b: [f32; 3]) -> f32 {
    let d = [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    d[0] * d[0] + d[1] * d[1] + d[2] * d[2]
}

fn dot(a: [f32; 3], b: [f32; 3]) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The colour nearest `p` among `colours` and their pairwise mixtures, the points of the
/// segments between two of them (None when empty); the first of equally near ones, in the
/// order of the pairs (a, b) = (colours[k], colours[m]), k ≤ m.
///
/// The hot loop of `MotionReference::build`: every pixel the memory does not explain
/// tries the pairs of its 16-25 colours, which repeat where the ring crosses one field. The
/// answer is the same to the bit as trying every pair in that order (the test
/// `nearest_mixture_is_the_nearest_point`), with less work: a colour equal to `p` is at
/// distance 0, which no pair betters; the row of pairs of a colour equal to the one before
/// it (neighbours on the ring, in one field) repeats that one's row in the same order, so
/// none of it can be strictly nearer; and a pair whose line lies farther from `p` than the
/// best point so far is not resolved to its nearest point ([`beyond_line`]).
pub(super) fn nearest_mixture(colours: &[[f32; 3]], p: [f32; 3]) -> Option<[f32; 3]> {
    if colours.contains(&p) {
        return Some(p);
    }
    // The first pair, the first colour with itself, is that colour: the best so far.
    let &first = colours.first()?;
    let mut best = (first, distance2(p, first));
    for (k, &a) in colours.iter().enumerate() {
        if k > 0 && colours[k - 1].map(f32::to_bits) == a.map(f32::to_bits) {
            continue;
        }
        let pa = [p[0] - a[0], p[1] - a[1], p[2] - a[2]];
        let pa2 = dot(pa, pa);
        for &b in &colours[k..] {
            let ab = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
            let length2 = dot(ab, ab);
            let q = if length2 <= f32::EPSILON {
                a
            } else {
                let along = dot(pa, ab);
                if beyond_line(pa2, along, length2, best.1) {
                    continue;
                }
                let t = (along / length2).clamp(0.0, 1.0);
                [a[0] + t * ab[0], a[1] + t * ab[1], a[2] + t * ab[2]]
            };
            let d = distance2(p, q);
            if d < best.1 {
                best = (q, d);
            }
        }
    }
    Some(best.0)
}

/// Whether the line through a segment lies so far from `p` that no point of the segment can
/// be nearer than `best2` (a squared distance), its nearest point computed or not: with
/// `pa2` = |p - a|², `along` = (p - a)·(b - a) and `length2` = |b - a|², the squared distance
/// from p to the line is (pa2 length2 - along²) / length2, and the segment's nearest point is
/// no nearer. No division: both sides are taken times length2. The margin, 10⁻³ (pa2 + 1)
/// grey level², is at least 3 times what f32 rounding can take off either side for colours
/// within 0-255 (the left side within 15 ε pa2 length2 of its exact value; a computed nearest
/// point's squared distance within 6·10⁻⁴ √pa2 of its own), so a pair it skips would not
/// have been strictly nearer, and the answer is the same to the bit.
fn beyond_line(pa2: f32, along: f32, length2: f32, best2: f32) -> bool {
    pa2 * length2 - along * along > (best2 + 1e-3 * pa2 + 1e-3) * length2
}

/// The index of pixel (u, v) of `frame`, when inside it.
fn inside(frame: &RgbaView<'_>, u: isize, v: isize) -> Option<usize> {
    let (w, h) = (frame.width as isize, frame.height as isize);
    (u >= 0 && v >= 0 && u < w && v < h).then(|| (v * w + u) as usize)
}

/// The index of the pixel of `frame` at (u, v) + (du, dv), or, beyond the frame, where the
/// ray from (u, v) towards it leaves the frame.
fn onto_border(frame: &RgbaView<'_>, u: usize, v: usize, du: isize, dv: isize) -> usize {
    inside(frame, u as isize + du, v as isize + dv)
        .unwrap_or_else(|| where_ray_leaves(frame, u, v, du, dv))
}

/// The index of the pixel where the ray from pixel (u, v) of `frame` towards (u, v) +
/// (du, dv) leaves the frame: the point itself when it is inside (the share below is then
/// 1; test `the_ray_ends_on_a_point_inside`).
fn where_ray_leaves(frame: &RgbaView<'_>, u: usize, v: usize, du: isize, dv: isize) -> usize {
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A ring point inside the frame is the pixel itself, as the ray's formula gives it, so
    /// taking it at once changes no ring colour.
    #[test]
    fn the_ray_ends_on_a_point_inside() {
        let rgba = vec![0u8; 37 * 23 * 4];
        let frame = RgbaView::new(&rgba, 37, 23).unwrap();
        let mut checked = 0;
        for (u, v) in [(0, 0), (5, 7), (36, 22), (18, 11)] {
            for du in -40..=40 {
                for dv in -30..=30 {
                    if let Some(i) = inside(&frame, u as isize + du, v as isize + dv) {
                        assert_eq!(
                            where_ray_leaves(&frame, u, v, du, dv),
                            i,
                            "({u}, {v}) + ({du}, {dv})"
                        );
                        checked += 1;
                    }
                }
            }
        }
        assert_eq!(checked, 4 * 37 * 23);
    }
}
