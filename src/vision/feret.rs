//! Maximum Feret diameter (the largest distance between two points of a set): convex hull by
//! Andrew's monotone chain, then rotating calipers over the hull's antipodal pairs.
//! O(n log n) for the sort, O(h) for the calipers.

/// A point in pixel coordinates: u right, v down, px.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PixelPoint {
    /// Column coordinate, px.
    pub u_px: f64,
    /// Row coordinate, px.
    pub v_px: f64,
}

impl PixelPoint {
    /// The point (u, v).
    pub fn new(u_px: f64, v_px: f64) -> Self {
        Self { u_px, v_px }
    }

    /// Euclidean distance to `other`, px.
    pub fn distance_px(&self, other: &PixelPoint) -> f64 {
        (self.u_px - other.u_px).hypot(self.v_px - other.v_px)
    }
}

/// The largest distance between two points of a set and a pair of points that attains it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FeretDiameter {
    /// The distance, px.
    pub length_px: f64,
    /// One end of the diameter.
    pub start: PixelPoint,
    /// The other end.
    pub end: PixelPoint,
}

impl FeretDiameter {
    /// The midpoint of its ends, (u, v), px: the bearing point `length_midpoint`.
    pub fn midpoint_px(&self) -> (f64, f64) {
        (
            0.5 * (self.start.u_px + self.end.u_px),
            0.5 * (self.start.v_px + self.end.v_px),
        )
    }
}

/// Twice the signed area of triangle (o, a, b); positive when o→a→b turns counter-clockwise
/// in a u-right, v-up sense (clockwise on screen, where v grows down).
fn cross(o: &PixelPoint, a: &PixelPoint, b: &PixelPoint) -> f64 {
    (a.u_px - o.u_px) * (b.v_px - o.v_px) - (a.v_px - o.v_px) * (b.u_px - o.u_px)
}

/// Reusable hull buffer, so repeated diameters allocate nothing once it has grown.
#[derive(Debug, Default, Clone)]
pub struct FeretFinder {
    hull: Vec<PixelPoint>,
}

impl FeretFinder {
    /// A finder with empty buffers.
    pub fn new() -> Self {
        Self::default()
    }

    /// The convex hull of the last [`FeretFinder::diameter`] call, without collinear points,
    /// in monotone-chain order.
    pub fn hull(&self) -> &[PixelPoint] {
        &self.hull
    }

    /// Maximum Feret diameter of `points`; reorders `points` and drops non-finite ones.
    /// `None` when no finite point is left.
    pub fn diameter(&mut self, points: &mut Vec<PixelPoint>) -> Option<FeretDiameter> {
        points.retain(|p| p.u_px.is_finite() && p.v_px.is_finite());
        convex_hull_into(points, &mut self.hull);
        diameter_of_convex_polygon(&self.hull)
    }
}

/// Maximum Feret diameter of `points` (non-finite points ignored); `None` when none is finite.
/// Allocates; use [`FeretFinder`] in loops.
pub fn max_feret_diameter(points: &[PixelPoint]) -> Option<FeretDiameter> {
    let mut owned = points.to_vec();
    FeretFinder::new().diameter(&mut owned)
}

/// Convex hull of finite `points` by Andrew's monotone chain: sorts `points` in place and writes
/// the hull vertices, without collinear or repeated points, into `hull` (one point for a single
/// distinct point, two for a collinear set). Non-finite points give a meaningless hull (no
/// panic); remove them first, as [`FeretFinder::diameter`] does.
pub fn convex_hull_into(points: &mut [PixelPoint], hull: &mut Vec<PixelPoint>) {
    hull.clear();
    // Adding 0.0 turns −0.0 into +0.0, so the total order agrees with the numeric one that the
    // cross products use (the chain needs points sorted numerically by u, then v).
    points.sort_unstable_by(|a, b| {
        (a.u_px + 0.0)
            .total_cmp(&(b.u_px + 0.0))
            .then((a.v_px + 0.0).total_cmp(&(b.v_px + 0.0)))
    });
    for p in points.iter() {
        while hull.len() >= 2 && cross(&hull[hull.len() - 2], &hull[hull.len() - 1], p) <= 0.0 {
            hull.pop();
        }
        if hull.last() != Some(p) {
            hull.push(*p);
        }
    }
    if hull.len() < 2 {
        return;
    }
    let lower_len = hull.len() + 1;
    for p in points.iter().rev().skip(1) {
        while hull.len() >= lower_len
            && cross(&hull[hull.len() - 2], &hull[hull.len() - 1], p) <= 0.0
        {
            hull.pop();
        }
        if hull.last() != Some(p) {
            hull.push(*p);
        }
    }
    // The upper chain ends on the first point again.
    if hull.len() > 1 && hull.first() == hull.last() {
        hull.pop();
    }
}

/// Diameter of a convex polygon given as its vertices in hull order (no collinear vertices), by
/// rotating calipers: for each edge, the vertex farthest from its supporting line is antipodal
/// to both ends; every diametral pair is such an antipodal pair (Shamos 1978).
fn diameter_of_convex_polygon(hull: &[PixelPoint]) -> Option<FeretDiameter> {
    let n = hull.len();
    let first = *hull.first()?;
    let mut best = FeretDiameter {
        length_px: 0.0,
        start: first,
        end: first,
    };
    let mut consider = |a: &PixelPoint, b: &PixelPoint| {
        let d = a.distance_px(b);
        if d > best.length_px {
            best = FeretDiameter {
                length_px: d,
                start: *a,
                end: *b,
            };
        }
    };
    if n <= 3 {
        for i in 0..n {
            for j in i + 1..n {
                consider(&hull[i], &hull[j]);
            }
        }
        return Some(best);
    }
    let mut j = 1;
    for i in 0..n {
        let a = &hull[i];
        let b = &hull[(i + 1) % n];
        // Advance j while the next vertex is farther from edge (a, b); the distance is unimodal
        // around a convex polygon, so this stops within n steps (the bound guards rounding).
        let mut steps = 0;
        while steps < n && cross(a, b, &hull[(j + 1) % n]).abs() > cross(a, b, &hull[j]).abs() {
            j = (j + 1) % n;
            steps += 1;
        }
        consider(a, &hull[j]);
        consider(b, &hull[j]);
        // With an edge parallel to (a, b) the next vertex is antipodal too.
        let next = &hull[(j + 1) % n];
        consider(a, next);
        consider(b, next);
    }
    Some(best)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn brute_force_diameter(points: &[PixelPoint]) -> f64 {
        let mut best = 0.0f64;
        for a in points {
            for b in points {
                best = best.max(a.distance_px(b));
            }
        }
        best
    }

    /// Degenerate sets: none, one point, repeated points, collinear points.
    #[test]
    fn degenerate_sets() {
        assert!(max_feret_diameter(&[]).is_none());
        assert!(max_feret_diameter(&[PixelPoint::new(f64::NAN, 1.0)]).is_none());
        let one = max_feret_diameter(&[PixelPoint::new(2.0, 3.0)]).unwrap();
        assert_eq!(one.length_px, 0.0);
        let same = vec![PixelPoint::new(1.0, 1.0); 5];
        assert_eq!(max_feret_diameter(&same).unwrap().length_px, 0.0);
        let line: Vec<_> = (0..10)
            .map(|i| PixelPoint::new(f64::from(i), 2.0 * f64::from(i)))
            .collect();
        let d = max_feret_diameter(&line).unwrap();
        // Exact arithmetic on small integers: only the final sqrt rounds.
        assert!((d.length_px - 9.0 * 5f64.sqrt()).abs() < 1e-12);
    }

    /// −0.0 and +0.0 are the same coordinate: (−0, 4) sorts between (0, 0) and (0, 5) (a
    /// case proptest found when the sort used the raw IEEE total order).
    #[test]
    fn negative_zero_sorts_as_zero() {
        let pts = [
            PixelPoint::new(0.0, 0.0),
            PixelPoint::new(0.0, 5.0),
            PixelPoint::new(-0.0, 4.0),
        ];
        assert_eq!(max_feret_diameter(&pts).unwrap().length_px, 5.0);
    }

    /// Integer grids have many parallel hull edges (the case where calipers can skip a pair):
    /// the diameter of a w x h grid of points is its diagonal, exactly.
    #[test]
    fn grid_diagonals() {
        for w in 1..8 {
            for h in 1..8 {
                let pts: Vec<_> = (0..w)
                    .flat_map(|i| (0..h).map(move |j| PixelPoint::new(f64::from(i), f64::from(j))))
                    .collect();
                let d = max_feret_diameter(&pts).unwrap().length_px;
                let expected = f64::from(w - 1).hypot(f64::from(h - 1));
                assert!((d - expected).abs() < 1e-12, "{w}x{h}: {d} vs {expected}");
            }
        }
    }

    proptest! {
        /// Hull + calipers equal the O(n²) maximum pairwise distance (to rounding, 1e-9
        /// relative), and the reported endpoints are input points at that distance.
        #[test]
        fn calipers_match_brute_force(
            raw in prop::collection::vec((-100.0f64..100.0, -100.0f64..100.0), 1..80),
            snap in any::<bool>(),
        ) {
            // Snapping to a coarse grid makes ties and collinear hull points common.
            let pts: Vec<PixelPoint> = raw
                .iter()
                .map(|&(u, v)| if snap {
                    PixelPoint::new((u / 20.0).round(), (v / 20.0).round())
                } else {
                    PixelPoint::new(u, v)
                })
                .collect();
            let d = max_feret_diameter(&pts).unwrap();
            let expected = brute_force_diameter(&pts);
            prop_assert!((d.length_px - expected).abs() <= 1e-9 * (1.0 + expected));
            prop_assert!((d.start.distance_px(&d.end) - d.length_px).abs() < 1e-12);
            prop_assert!(pts.contains(&d.start) && pts.contains(&d.end));
        }
    }
}
