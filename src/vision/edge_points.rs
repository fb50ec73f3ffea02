//! Sub-pixel points on a blob's outline, whose maximum Feret diameter estimates the
//! silhouette's maximal length.
//!
//! 1. Edge lines: every edge pixel (boundary or ring) covered at least `min_coverage` gets
//!    the straight edge that covers it by its coverage ([`EdgeLine::through_pixel`]), with the
//!    normal from a Sobel gradient of the coverage (off by up to 2.6° on anti-aliased edges).
//! 2. Straight runs: where at least 3 nearby edge pixels (5 x 5) have normals within 20° and
//!    feet on one line, the normal is re-estimated as the perpendicular of the principal axis
//!    of those feet (more accurate than the gradient).
//! 3. Points: the foot of each edge line (the point of the line nearest the pixel centre:
//!    within 0.01 px of a straight edge). Pixels with coverage ≈ 0 are left out: their line
//!    says only that the edge lies beyond the pixel, which would overshoot by up to half a
//!    pixel.
//! 4. Corners: a corner pixel's own line is a compromise between its two edges, so its foot
//!    falls short of the vertex by up to half a pixel (a rectangle's length by up to 0.8 px).
//!    Where the lines of two straight runs up to 6 px apart cross at more than 14.5°, and the
//!    wedge they bound explains the coverage of the 3 x 3 pixels around the crossing, the
//!    crossing is added as a point. The check rejects crossings of lines that are not both
//!    straight edges through that corner (tangents of curves, thin parts where a pixel sees
//!    both sides).
//!
//! Its accuracy on test images is in `docs/findings.md`, The image pipeline's accuracy and
//! cost.

use super::feret::PixelPoint;
use super::subpixel_edge::{EdgeLine, pixel_area_inside};

/// Normals of a straight run agree within 20° (cosine 0.94).
const RUN_MIN_COSINE: f64 = 0.94;
/// Feet farther than these from a pixel's line are not on its run: first around the gradient
/// line (2.6° off at most: 0.09 px at 2 px), then around the first fit.
const RUN_GATES_PX: [f64; 2] = [0.15, 0.05];
/// A straight run has at least this many edge pixels...
const RUN_MIN_PIXELS: usize = 3;
/// ...whose feet spread this much (sum of squared distances from their mean, px²: 3 feet
/// spaced 1 px along a line give 2).
const RUN_MIN_SPREAD_PX2: f64 = 1.0;
/// Two edge lines form a corner when they cross at more than 14.5° (sine 0.25), so that a 20°
/// tip qualifies; the crossing of lines at 14.5° moves by 1/sin 14.5° = 4 times their offset
/// errors (~0.01 px). Tangents of curves that cross this steeply are rejected by the coverage
/// check (a tangent wedge over-covers the pixels around its vertex).
const CORNER_MIN_SINE: f64 = 0.25;
/// Corner lines come from edge pixels at most this far apart (each axis), px, and the corner
/// lies within this of both: the straight-run pixels nearest a corner can be several pixels
/// from it (runs need 3 agreeing pixels; the corner pixel and its neighbours see both edges).
const CORNER_REACH_PX: isize = 6;

/// Coverage weights on a rectangle of pixels and which of them are edge pixels.
#[derive(Debug, Default, Clone)]
pub(crate) struct CoverageGrid {
    /// Image column of the grid's first column.
    pub u0: usize,
    /// Image row of the grid's first row.
    pub v0: usize,
    /// Columns.
    pub width: usize,
    /// Rows.
    pub height: usize,
    /// Coverage per pixel, row-major (0 outside the blob and its ring).
    pub weights: Vec<f32>,
    /// Whether a pixel is a boundary pixel of the blob or in its ring.
    pub is_edge: Vec<bool>,
}

impl CoverageGrid {
    /// Resets to a `width` x `height` grid at (u0, v0), all weights 0, no edges.
    pub fn reset(&mut self, u0: usize, v0: usize, width: usize, height: usize) {
        (self.u0, self.v0, self.width, self.height) = (u0, v0, width, height);
        self.weights.clear();
        self.weights.resize(width * height, 0.0);
        self.is_edge.clear();
        self.is_edge.resize(width * height, false);
    }

    /// Weight at grid position (x, y), replicating the grid's edge outside it.
    fn weight_clamped(&self, x: isize, y: isize) -> f64 {
        let x = x.clamp(0, self.width as isize - 1) as usize;
        let y = y.clamp(0, self.height as isize - 1) as usize;
        f64::from(self.weights[y * self.width + x])
    }

    /// Image position of the centre of grid pixel (x, y).
    fn centre(&self, x: isize, y: isize) -> (f64, f64) {
        (
            (self.u0 as isize + x) as f64 + 0.5,
            (self.v0 as isize + y) as f64 + 0.5,
        )
    }

    fn contains(&self, x: isize, y: isize) -> bool {
        x >= 0 && y >= 0 && x < self.width as isize && y < self.height as isize
    }
}

/// One edge pixel's line.
#[derive(Debug, Clone, Copy)]
struct PixelEdge {
    x: isize,
    y: isize,
    coverage: f64,
    line: EdgeLine,
    /// Part of a straight run (its normal was re-estimated from the run).
    straight: bool,
}

/// Finds outline points; owns its buffers between frames.
#[derive(Debug, Default, Clone)]
pub(crate) struct EdgePointFinder {
    edges: Vec<PixelEdge>,
    /// Per grid pixel: 0, or the index + 1 of its entry in `edges`.
    edge_at: Vec<u32>,
    refined: Vec<(EdgeLine, bool)>,
}

impl EdgePointFinder {
    /// Writes the outline points of the blob in `grid` into `points`. `min_coverage`: edge
    /// pixels covered less are ignored (noise). `corner_tolerance`: largest difference between
    /// a corner's predicted and measured coverage of a pixel.
    pub fn find(
        &mut self,
        grid: &CoverageGrid,
        min_coverage: f64,
        corner_tolerance: f64,
        points: &mut Vec<PixelPoint>,
    ) {
        points.clear();
        self.collect_lines(grid, min_coverage, points);
        self.straighten_runs(grid);
        for e in &self.edges {
            let (cu, cv) = grid.centre(e.x, e.y);
            let (u, v) = e.line.foot_px(cu, cv);
            points.push(PixelPoint::new(u, v));
        }
        self.add_corners(grid, min_coverage, corner_tolerance, points);
    }

    /// Step 1: a line per edge pixel covered at least `min_coverage`; pixels without a
    /// gradient (isolated) contribute their centre to `points` directly.
    fn collect_lines(
        &mut self,
        grid: &CoverageGrid,
        min_coverage: f64,
        points: &mut Vec<PixelPoint>,
    ) {
        self.edges.clear();
        self.edge_at.clear();
        self.edge_at.resize(grid.width * grid.height, 0);
        for y in 0..grid.height as isize {
            for x in 0..grid.width as isize {
                let local = y as usize * grid.width + x as usize;
                let coverage = f64::from(grid.weights[local]);
                if !grid.is_edge[local] || coverage < min_coverage {
                    continue;
                }
                let w = |dx: isize, dy: isize| grid.weight_clamped(x + dx, y + dy);
                let gx = w(1, -1) + 2.0 * w(1, 0) + w(1, 1) - w(-1, -1) - 2.0 * w(-1, 0) - w(-1, 1);
                let gy = w(-1, 1) + 2.0 * w(0, 1) + w(1, 1) - w(-1, -1) - 2.0 * w(0, -1) - w(1, -1);
                let (cu, cv) = grid.centre(x, y);
                // Outward normal: coverage decreases outward.
                match EdgeLine::through_pixel(cu, cv, coverage, -gx, -gy) {
                    Some(line) => {
                        self.edges.push(PixelEdge {
                            x,
                            y,
                            coverage,
                            line,
                            straight: false,
                        });
                        self.edge_at[local] = self.edges.len() as u32;
                    }
                    None => points.push(PixelPoint::new(cu, cv)),
                }
            }
        }
    }

    /// Step 2: re-estimates the normals of edge pixels on straight runs.
    fn straighten_runs(&mut self, grid: &CoverageGrid) {
        self.refined.clear();
        for e in &self.edges {
            let mut feet = [(0.0f64, 0.0f64); 25];
            let mut count = 0;
            for dy in -2..=2 {
                for dx in -2..=2 {
                    let (x, y) = (e.x + dx, e.y + dy);
                    if !grid.contains(x, y) {
                        continue;
                    }
                    let k = self.edge_at[y as usize * grid.width + x as usize];
                    if k == 0 {
                        continue;
                    }
                    let other_edge = &self.edges[k as usize - 1];
                    let other = other_edge.line;
                    if other.nx * e.line.nx + other.ny * e.line.ny >= RUN_MIN_COSINE {
                        let (cu, cv) = grid.centre(x, y);
                        feet[count] = other.foot_px(cu, cv);
                        count += 1;
                    }
                }
            }
            let r = run_line(e, &feet[..count], grid);
            self.refined.push(r.map_or((e.line, false), |l| (l, true)));
        }
        for (e, &(line, straight)) in self.edges.iter_mut().zip(self.refined.iter()) {
            e.line = line;
            e.straight = straight;
        }
    }

    /// Step 4: corners where the lines of two straight runs cross (see the module doc).
    fn add_corners(
        &self,
        grid: &CoverageGrid,
        min_coverage: f64,
        tolerance: f64,
        points: &mut Vec<PixelPoint>,
    ) {
        // A fully covered or nearly empty pixel does not fix where its edge is.
        let usable = |e: &PixelEdge| {
            e.straight && e.coverage >= min_coverage && e.coverage <= 1.0 - min_coverage
        };
        let reach = CORNER_REACH_PX;
        // Each pair once: the later pixel in raster order.
        let later = (0..=reach)
            .flat_map(move |dy| (-reach..=reach).map(move |dx| (dx, dy)))
            .filter(|&(dx, dy)| dy > 0 || dx > 0);
        for e in self.edges.iter().filter(|e| usable(e)) {
            for (dx, dy) in later.clone() {
                let (x, y) = (e.x + dx, e.y + dy);
                if !grid.contains(x, y) {
                    continue;
                }
                let k = self.edge_at[y as usize * grid.width + x as usize];
                if k == 0 || !usable(&self.edges[k as usize - 1]) {
                    continue;
                }
                let other = self.edges[k as usize - 1];
                let Some((u, v)) = e.line.intersection(&other.line, CORNER_MIN_SINE) else {
                    continue;
                };
                if wedge_explains_coverage(grid, [e, &other], (u, v), tolerance) {
                    points.push(PixelPoint::new(u, v));
                }
            }
        }
    }
}

/// The line of the straight run through `e`'s pixel, re-placed to cover that pixel by its
/// coverage; `None` when the feet do not make a run. `feet`: feet of the nearby edge lines
/// whose normals agree with `e`'s. Twice: keep the feet within [`RUN_GATES_PX`] of the current
/// line (a pixel next to a corner has a normal within 20° but a foot off the edge), then fit
/// the principal axis of at least [`RUN_MIN_PIXELS`] feet spread at least
/// [`RUN_MIN_SPREAD_PX2`].
fn run_line(e: &PixelEdge, feet: &[(f64, f64)], grid: &CoverageGrid) -> Option<EdgeLine> {
    let (cu, cv) = grid.centre(e.x, e.y);
    let mut line = e.line;
    let mut on_line = [(0.0f64, 0.0f64); 25];
    for gate in RUN_GATES_PX {
        let mut count = 0;
        for f in feet {
            if (line.nx * f.0 + line.ny * f.1 - line.offset_px).abs() <= gate {
                on_line[count] = *f;
                count += 1;
            }
        }
        if count < RUN_MIN_PIXELS {
            return None;
        }
        let run = &on_line[..count];
        let n = count as f64;
        let mu = run.iter().map(|f| f.0).sum::<f64>() / n;
        let mv = run.iter().map(|f| f.1).sum::<f64>() / n;
        let (mut suu, mut suv, mut svv) = (0.0, 0.0, 0.0);
        for &(fu, fv) in run {
            suu += (fu - mu) * (fu - mu);
            suv += (fu - mu) * (fv - mv);
            svv += (fv - mv) * (fv - mv);
        }
        if suu + svv < RUN_MIN_SPREAD_PX2 {
            return None;
        }
        // Principal axis of the scatter matrix: the run's direction; the normal is
        // perpendicular, oriented outward like the gradient's.
        let (tv, tu) = (0.5 * (2.0 * suv).atan2(suu - svv)).sin_cos();
        let (mut nx, mut ny) = (-tv, tu);
        if nx * e.line.nx + ny * e.line.ny < 0.0 {
            (nx, ny) = (-nx, -ny);
        }
        line = EdgeLine::through_pixel(cu, cv, e.coverage, nx, ny)?;
    }
    Some(line)
}

/// Whether the wedge bounded by the two pixels' lines, with its vertex at `vertex`, predicts
/// the coverage of the 3 x 3 pixels around the vertex within `tolerance`; the vertex must lie
/// within [`CORNER_REACH_PX`] of both edge pixels, with its 3 x 3 neighbourhood on the grid.
fn wedge_explains_coverage(
    grid: &CoverageGrid,
    pixels: [&PixelEdge; 2],
    (u, v): (f64, f64),
    tolerance: f64,
) -> bool {
    let x = u.floor() - grid.u0 as f64;
    let y = v.floor() - grid.v0 as f64;
    let inside =
        x >= 1.0 && y >= 1.0 && x < (grid.width - 1) as f64 && y < (grid.height - 1) as f64;
    if !inside {
        return false; // also rejects NaN
    }
    let (x, y) = (x as isize, y as isize);
    let reach = CORNER_REACH_PX;
    if pixels
        .iter()
        .any(|p| (p.x - x).abs() > reach || (p.y - y).abs() > reach)
    {
        return false;
    }
    let wedge = [pixels[0].line, pixels[1].line];
    (-1..=1).all(|dy| {
        (-1..=1).all(|dx| {
            let (px, py) = (x + dx, y + dy);
            let measured = f64::from(grid.weights[py as usize * grid.width + px as usize]);
            let (cu, cv) = grid.centre(px, py);
            let predicted = pixel_area_inside(cu - 0.5, cv - 0.5, &wedge);
            (predicted - measured).abs() <= tolerance
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vision::synthetic::Shape;

    /// A grid of exact coverages (32 x 32 supersampling) of `shape`, edge pixels being those
    /// partly covered or fully covered beside a not fully covered one.
    fn grid_of(shape: &Shape, width: usize, height: usize) -> CoverageGrid {
        let mut grid = CoverageGrid::default();
        grid.reset(0, 0, width, height);
        let n = 32;
        for y in 0..height {
            for x in 0..width {
                let inside = (0..n * n)
                    .filter(|k| {
                        let su = x as f64 + (f64::from(k % n) + 0.5) / f64::from(n);
                        let sv = y as f64 + (f64::from(k / n) + 0.5) / f64::from(n);
                        shape.contains(su, sv)
                    })
                    .count();
                grid.weights[y * width + x] = inside as f32 / (n * n) as f32;
            }
        }
        for y in 1..height - 1 {
            for x in 1..width - 1 {
                let w = |dx: isize, dy: isize| {
                    grid.weights[(y as isize + dy) as usize * width + (x as isize + dx) as usize]
                };
                let all_full = (-1..=1).all(|dy| (-1..=1).all(|dx| w(dx, dy) == 1.0));
                grid.is_edge[y * width + x] = w(0, 0) > 0.0 && !all_full;
            }
        }
        grid
    }

    /// The four vertices of a square turned 30° are among the outline points to 0.05 px
    /// (found as crossings of the sides' lines; the sides' feet are within 0.01 px of the
    /// sides, so their crossing is within a few hundredths), and no point lies more than
    /// 0.05 px outside the square.
    #[test]
    fn square_corners_are_found() {
        let (cu, cv, side, turn) = (20.3f64, 19.6f64, 16.0f64, 30f64.to_radians());
        let square = Shape::Rectangle {
            u: cu,
            v: cv,
            length: side,
            breadth: side,
            angle_rad: turn,
        };
        let grid = grid_of(&square, 40, 40);
        let mut points = Vec::new();
        EdgePointFinder::default().find(&grid, 0.1, 0.06, &mut points);
        let (s, c) = turn.sin_cos();
        for (a, b) in [(1.0, 1.0), (1.0, -1.0), (-1.0, -1.0), (-1.0, 1.0)] {
            let h = 0.5 * side;
            let vertex = PixelPoint::new(cu + h * (a * c - b * s), cv + h * (a * s + b * c));
            let nearest = points
                .iter()
                .map(|p| p.distance_px(&vertex))
                .fold(f64::INFINITY, f64::min);
            assert!(
                nearest < 0.05,
                "vertex {vertex:?}: nearest point {nearest} px away"
            );
        }
        for p in &points {
            let (du, dv) = (p.u_px - cu, p.v_px - cv);
            let along = (du * c + dv * s).abs();
            let across = (-du * s + dv * c).abs();
            assert!(along.max(across) < 0.5 * side + 0.05, "{p:?} outside");
        }
    }

    /// No outline point of a disc lies more than 0.15 px outside its circle, and their Feret
    /// diameter is the diameter within 0.2 px. (Fully covered edge pixels give points inside,
    /// by design. Tangents 14.5° apart, the steepest crossing accepted, meet R(1/cos 7.25° − 1)
    /// = 0.008 R outside a circle of radius R, i.e. 0.09 px at R = 11, and the coverage check
    /// cannot tell so slight a bulge: measured 0.10 px.)
    #[test]
    fn disc_has_no_corners() {
        for radius in [3.5, 6.0, 11.0, 17.0] {
            let (cu, cv) = (20.2, 20.7);
            let disc = Shape::Disc {
                u: cu,
                v: cv,
                radius,
            };
            let grid = grid_of(&disc, 42, 42);
            let mut points = Vec::new();
            EdgePointFinder::default().find(&grid, 0.1, 0.06, &mut points);
            for p in &points {
                let r = (p.u_px - cu).hypot(p.v_px - cv);
                assert!(r < radius + 0.15, "radius {radius}: point at {r}");
            }
            let d = crate::vision::feret::max_feret_diameter(&points).unwrap();
            assert!(
                (d.length_px - 2.0 * radius).abs() < 0.2,
                "radius {radius}: {d:?}"
            );
        }
    }
}
