//! The diameter of a point set (the largest distance between two of its points), exact, by
//! branch and bound over a tree of boxes: a pair of boxes whose farthest corners are no
//! farther apart than the best pair found so far is never opened. A start from a pair of
//! mutually far points prunes almost every box pair of a mesh, so the cost grows nearly
//! linearly with the vertex count (all pairs: 37 s for 120 000 vertices).

use crate::frames::Vec3;

/// Points per leaf box.
const LEAF_POINTS: usize = 16;

/// A box of the tree: its bounds and either two children or a run of points.
#[derive(Debug, Clone, Copy)]
struct Node {
    min: Vec3,
    max: Vec3,
    /// Children (indices into the node list), or none for a leaf.
    children: Option<(usize, usize)>,
    /// The leaf's points: a range of the reordered point list.
    start: usize,
    end: usize,
}

/// The largest distance between two of `points` (0 for fewer than two).
pub fn diameter(points: &[Vec3]) -> f64 {
    if points.len() < 2 {
        return 0.0;
    }
    let mut ordered = points.to_vec();
    let mut nodes = Vec::with_capacity(2 * points.len() / LEAF_POINTS + 2);
    build(&mut ordered, 0, points.len(), &mut nodes);
    let mut best_sq = far_pair_start(points);
    let root = nodes.len() - 1;
    let mut stack = vec![(root, root)];
    while let Some((a, b)) = stack.pop() {
        let (na, nb) = (nodes[a], nodes[b]);
        if farthest_corner_sq(&na, &nb) <= best_sq {
            continue;
        }
        let split_a = match (na.children, nb.children) {
            (None, None) => {
                best_sq = best_sq.max(leaf_pairs(&ordered, &na, &nb));
                continue;
            }
            (Some(_), None) => true,
            (None, Some(_)) => false,
            (Some(_), Some(_)) => a == b || extent_sq(&na) >= extent_sq(&nb),
        };
        match (split_a, na.children, nb.children) {
            (true, Some((l, r)), _) if a == b => stack.extend([(l, l), (l, r), (r, r)]),
            (true, Some((l, r)), _) => stack.extend([(l, b), (r, b)]),
            (false, _, Some((l, r))) => stack.extend([(a, l), (a, r)]),
            _ => {}
        }
    }
    best_sq.sqrt()
}

/// Builds the tree over `points[start..end]` (reordering them), children before parents;
/// returns the index of the subtree's root.
fn build(points: &mut [Vec3], start: usize, end: usize, nodes: &mut Vec<Node>) -> usize {
    let (min, max) = bounds(&points[start..end]);
    let children = if end - start > LEAF_POINTS {
        let axis = (max - min).imax();
        let middle = start + (end - start) / 2;
        points[start..end]
            .select_nth_unstable_by(middle - start, |p, q| p[axis].total_cmp(&q[axis]));
        let left = build(points, start, middle, nodes);
        let right = build(points, middle, end, nodes);
        Some((left, right))
    } else {
        None
    };
    nodes.push(Node {
        min,
        max,
        children,
        start,
        end,
    });
    nodes.len() - 1
}

/// The smallest box holding `points`.
fn bounds(points: &[Vec3]) -> (Vec3, Vec3) {
    points.iter().fold(
        (Vec3::repeat(f64::INFINITY), Vec3::repeat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.inf(p), hi.sup(p)),
    )
}

/// The squared distance between the farthest corners of two boxes: no pair of their points
/// is farther apart.
fn farthest_corner_sq(a: &Node, b: &Node) -> f64 {
    (0..3)
        .map(|i| {
            let span = (a.max[i] - b.min[i]).abs().max((b.max[i] - a.min[i]).abs());
            span * span
        })
        .sum()
}

/// The squared length of a box's diagonal.
fn extent_sq(node: &Node) -> f64 {
    (node.max - node.min).norm_squared()
}

/// The largest squared distance between a point of one leaf and a point of the other.
fn leaf_pairs(points: &[Vec3], a: &Node, b: &Node) -> f64 {
    let mut best: f64 = 0.0;
    for p in &points[a.start..a.end] {
        for q in &points[b.start..b.end] {
            best = best.max((p - q).norm_squared());
        }
    }
    best
}

/// A squared distance to start from: the farthest point from the first, then the farthest
/// from that one, twice (a pair of mutually far points, close to the diameter).
fn far_pair_start(points: &[Vec3]) -> f64 {
    let farthest = |from: &Vec3| {
        points
            .iter()
            .map(|p| (p - from).norm_squared())
            .enumerate()
            .fold(
                (0, 0.0),
                |best, (i, d)| if d > best.1 { (i, d) } else { best },
            )
    };
    let (mut at, mut best_sq) = farthest(&points[0]);
    for _ in 0..2 {
        let (next, d) = farthest(&points[at]);
        best_sq = best_sq.max(d);
        at = next;
    }
    best_sq
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    fn all_pairs(points: &[Vec3]) -> f64 {
        let mut best: f64 = 0.0;
        for (i, a) in points.iter().enumerate() {
            for b in &points[i + 1..] {
                best = best.max((a - b).norm());
            }
        }
        best
    }

    /// The tree's answer is the all-pairs answer, exactly, for clouds, shells and lines.
    #[test]
    fn equals_all_pairs() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        for n in [2, 3, 17, 100, 1000, 3000] {
            let cloud: Vec<Vec3> = (0..n)
                .map(|_| Vec3::new(rng.random(), rng.random::<f64>() * 3.0, rng.random()))
                .collect();
            assert_eq!(diameter(&cloud), all_pairs(&cloud), "cloud of {n}");
            let shell: Vec<Vec3> = cloud
                .iter()
                .map(|p| (p - Vec3::repeat(0.5)).normalize())
                .collect();
            assert_eq!(diameter(&shell), all_pairs(&shell), "shell of {n}");
        }
        let line: Vec<Vec3> = (0..500)
            .map(|i| Vec3::new(f64::from(i), 0.0, 0.0))
            .collect();
        assert_eq!(diameter(&line), 499.0);
        assert_eq!(diameter(&[Vec3::zeros()]), 0.0);
    }
}
