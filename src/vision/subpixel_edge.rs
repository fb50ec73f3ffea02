//! Where a straight edge crosses a pixel, from the pixel's coverage and the edge's normal.
//!
//! A half-plane {x : n·(x − c) ≤ s} (n a unit normal pointing out of the target, c the pixel
//! centre) covers the unit pixel square with area A(s). With a = max(|nx|, |ny|),
//! b = min(|nx|, |ny|) and t = s + (a + b)/2 the distance from the square's innermost corner:
//! A = t²/(2ab) for t ≤ b, (t − b/2)/a for b ≤ t ≤ a, 1 − (a + b − t)²/(2ab) beyond.
//! [`edge_offset_px`] inverts it. For an axis-aligned edge this is s = α − 1/2; for a 45° edge
//! near a corner the simple formula would be off by up to 0.2 px.

/// Signed distance s from the pixel centre to a straight edge along its outward unit normal
/// (nx, ny), such that the target covers the fraction `coverage` of the pixel, px. The result
/// lies in [−(a + b)/2, (a + b)/2]; coverage outside [0, 1] is clamped. A zero or non-finite
/// normal gives 0 (the pixel centre).
pub(crate) fn edge_offset_px(coverage: f64, nx: f64, ny: f64) -> f64 {
    let norm = nx.hypot(ny);
    if !(norm.is_finite() && norm > 0.0) {
        return 0.0;
    }
    let (p, q) = ((nx / norm).abs(), (ny / norm).abs());
    let (a, b) = if p >= q { (p, q) } else { (q, p) };
    let alpha = if coverage.is_finite() {
        coverage.clamp(0.0, 1.0)
    } else {
        0.0
    };
    // a ≥ 1/√2, so the corner regions' widths b/(2a) are well defined.
    let corner = b / (2.0 * a);
    let t = if alpha <= corner {
        (2.0 * a * b * alpha).sqrt()
    } else if alpha <= 1.0 - corner {
        a * alpha + 0.5 * b
    } else {
        a + b - (2.0 * a * b * (1.0 - alpha)).sqrt()
    };
    t - 0.5 * (a + b)
}

/// A straight edge in pixel coordinates: the target side is {x : n·x ≤ offset}, n a unit
/// outward normal.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct EdgeLine {
    /// Outward unit normal, u component.
    pub nx: f64,
    /// Outward unit normal, v component.
    pub ny: f64,
    /// n·x on the line, px.
    pub offset_px: f64,
}

impl EdgeLine {
    /// The edge through the pixel with centre (cu, cv) that covers the fraction `coverage` of
    /// it with outward normal (nx, ny) (any length); `None` for a zero or non-finite normal.
    pub fn through_pixel(cu: f64, cv: f64, coverage: f64, nx: f64, ny: f64) -> Option<Self> {
        let norm = nx.hypot(ny);
        if !(norm.is_finite() && norm > 0.0) {
            return None;
        }
        let (nx, ny) = (nx / norm, ny / norm);
        let s = edge_offset_px(coverage, nx, ny);
        Some(Self {
            nx,
            ny,
            offset_px: nx * cu + ny * cv + s,
        })
    }

    /// The point of the line nearest the pixel centre (cu, cv).
    pub fn foot_px(&self, cu: f64, cv: f64) -> (f64, f64) {
        let d = self.offset_px - (self.nx * cu + self.ny * cv);
        (cu + d * self.nx, cv + d * self.ny)
    }

    /// Where this line meets `other`, when they cross at an angle whose sine is at least
    /// `min_sine`.
    pub fn intersection(&self, other: &EdgeLine, min_sine: f64) -> Option<(f64, f64)> {
        let det = self.nx * other.ny - self.ny * other.nx;
        if det.abs() < min_sine {
            return None;
        }
        let u = (self.offset_px * other.ny - self.ny * other.offset_px) / det;
        let v = (self.nx * other.offset_px - self.offset_px * other.nx) / det;
        Some((u, v))
    }
}

/// Area of the pixel [u0, u0 + 1] x [v0, v0 + 1] on the target side of every line in `lines`
/// (Sutherland-Hodgman clipping of the square, then the shoelace formula), px².
pub(crate) fn pixel_area_inside(u0: f64, v0: f64, lines: &[EdgeLine]) -> f64 {
    // A square clipped by k half-planes has at most 4 + k vertices.
    const MAX_VERTICES: usize = 12;
    let mut poly = [(0.0f64, 0.0f64); MAX_VERTICES];
    let mut next = [(0.0f64, 0.0f64); MAX_VERTICES];
    poly[..4].copy_from_slice(&[
        (u0, v0),
        (u0 + 1.0, v0),
        (u0 + 1.0, v0 + 1.0),
        (u0, v0 + 1.0),
    ]);
    let mut n = 4;
    for line in lines {
        let inside = |p: (f64, f64)| line.offset_px - (line.nx * p.0 + line.ny * p.1);
        let mut m = 0;
        for k in 0..n {
            let (a, b) = (poly[k], poly[(k + 1) % n]);
            let (da, db) = (inside(a), inside(b));
            if da >= 0.0 && m < MAX_VERTICES {
                next[m] = a;
                m += 1;
            }
            if (da >= 0.0) != (db >= 0.0) && m < MAX_VERTICES {
                let t = da / (da - db);
                next[m] = (a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1));
                m += 1;
            }
        }
        poly[..m].copy_from_slice(&next[..m]);
        n = m;
        if n < 3 {
            return 0.0;
        }
    }
    let twice: f64 = (0..n)
        .map(|k| {
            let (a, b) = (poly[k], poly[(k + 1) % n]);
            a.0 * b.1 - b.0 * a.1
        })
        .sum();
    0.5 * twice.abs()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Area of the unit square centred at 0 on the side n·x ≤ s, by 400x400 supersampling
    /// (area error ≤ perimeter/400 ≈ 0.004).
    fn covered_area(nx: f64, ny: f64, s: f64) -> f64 {
        let n = 400;
        let mut inside = 0;
        for i in 0..n {
            for j in 0..n {
                let x = (f64::from(i) + 0.5) / f64::from(n) - 0.5;
                let y = (f64::from(j) + 0.5) / f64::from(n) - 0.5;
                if nx * x + ny * y <= s {
                    inside += 1;
                }
            }
        }
        f64::from(inside) / f64::from(n * n)
    }

    /// Inverting the supersampled coverage of edges at many angles and offsets recovers the
    /// offset to 0.01 px (area error 0.004 divided by the edge's chord, ≥ 0.5 away from the
    /// extreme corners; near corners the sqrt branch amplifies it, so those use 0.03).
    #[test]
    fn inverts_half_plane_coverage() {
        for k in 0..24 {
            let angle = f64::from(k) * std::f64::consts::PI / 12.0 + 0.013;
            let (ny, nx) = angle.sin_cos();
            let half = 0.5 * (nx.abs() + ny.abs());
            for m in 1..20 {
                let s = -half + 2.0 * half * f64::from(m) / 20.0;
                let alpha = covered_area(nx, ny, s);
                let got = edge_offset_px(alpha, nx, ny);
                let tol = if !(0.1..=0.9).contains(&alpha) {
                    0.03
                } else {
                    0.01
                };
                assert!((got - s).abs() < tol, "angle {angle}, s {s}: got {got}");
            }
        }
    }

    /// Axis-aligned edges give s = α − 1/2 exactly; degenerate inputs give the centre or the
    /// clamped extremes.
    #[test]
    fn axis_aligned_and_degenerate() {
        assert!((edge_offset_px(0.3, 1.0, 0.0) + 0.2).abs() < 1e-12);
        assert!((edge_offset_px(0.75, 0.0, -2.0) - 0.25).abs() < 1e-12);
        assert_eq!(edge_offset_px(0.3, 0.0, 0.0), 0.0);
        assert_eq!(edge_offset_px(0.3, f64::NAN, 1.0), 0.0);
        let h = std::f64::consts::FRAC_1_SQRT_2;
        assert!((edge_offset_px(2.0, 1.0, 1.0) - h).abs() < 1e-12);
        assert!((edge_offset_px(-1.0, 1.0, 1.0) + h).abs() < 1e-12);
    }

    /// A line built from a pixel's coverage covers that pixel by exactly that area (to
    /// rounding); two perpendicular lines through a corner clip the expected rectangle; lines
    /// meet where they should.
    #[test]
    fn edge_lines_and_clipped_areas() {
        for (alpha, nx, ny) in [
            (0.3, 1.0, 0.0),
            (0.05, 0.6, 0.8),
            (0.7, -0.2, 0.9),
            (0.95, -1.0, -1.0),
        ] {
            let line = EdgeLine::through_pixel(10.5, 20.5, alpha, nx, ny).unwrap();
            let area = pixel_area_inside(10.0, 20.0, &[line]);
            assert!((area - alpha).abs() < 1e-9, "{alpha} {nx} {ny}: {area}");
        }
        // x ≤ 3.3 and y ≤ 7.6 leave 0.3 x 0.6 of pixel (3, 7).
        let right = EdgeLine {
            nx: 1.0,
            ny: 0.0,
            offset_px: 3.3,
        };
        let bottom = EdgeLine {
            nx: 0.0,
            ny: 1.0,
            offset_px: 7.6,
        };
        assert!((pixel_area_inside(3.0, 7.0, &[right, bottom]) - 0.18).abs() < 1e-12);
        let (u, v) = right.intersection(&bottom, 0.3).unwrap();
        assert!((u - 3.3).abs() < 1e-12 && (v - 7.6).abs() < 1e-12);
        assert!(right.intersection(&right, 0.3).is_none());
        assert_eq!(right.foot_px(1.0, 2.0), (3.3, 2.0));
        assert!(EdgeLine::through_pixel(0.5, 0.5, 0.5, 0.0, 0.0).is_none());
    }
}
