//! Planar geometry helpers: exact orientation (Shewchuk's predicates from `robust`), segment
//! crossing and distance, polygon area, and a sort-and-sweep over bounding boxes that finds
//! candidate pairs of segments whatever their sizes.

use robust::{Coord, orient2d};

pub(crate) type P2 = [f64; 2];

/// Twice the signed area of triangle abc, exact in sign.
#[inline]
pub(crate) fn orient(a: P2, b: P2, c: P2) -> f64 {
    orient2d(
        Coord { x: a[0], y: a[1] },
        Coord { x: b[0], y: b[1] },
        Coord { x: c[0], y: c[1] },
    )
}

#[inline]
pub(crate) fn sub(a: P2, b: P2) -> P2 {
    [a[0] - b[0], a[1] - b[1]]
}

#[inline]
pub(crate) fn dot(a: P2, b: P2) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

#[inline]
pub(crate) fn cross(a: P2, b: P2) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

#[inline]
pub(crate) fn dist(a: P2, b: P2) -> f64 {
    let d = sub(a, b);
    dot(d, d).sqrt()
}

/// True when the closed segments ab and cd share a point (crossing, touching or overlapping).
pub(crate) fn segments_meet(a: P2, b: P2, c: P2, d: P2) -> bool {
    let o1 = orient(a, b, c);
    let o2 = orient(a, b, d);
    let o3 = orient(c, d, a);
    let o4 = orient(c, d, b);
    if ((o1 > 0.0 && o2 < 0.0) || (o1 < 0.0 && o2 > 0.0))
        && ((o3 > 0.0 && o4 < 0.0) || (o3 < 0.0 && o4 > 0.0))
    {
        return true;
    }
    let on = |p: P2, q: P2, r: P2| {
        r[0] >= p[0].min(q[0])
            && r[0] <= p[0].max(q[0])
            && r[1] >= p[1].min(q[1])
            && r[1] <= p[1].max(q[1])
    };
    (o1 == 0.0 && on(a, b, c))
        || (o2 == 0.0 && on(a, b, d))
        || (o3 == 0.0 && on(c, d, a))
        || (o4 == 0.0 && on(c, d, b))
}

fn point_segment_distance(p: P2, a: P2, b: P2) -> f64 {
    dist(p, closest_on_segment(p, a, b))
}

/// The point of the closed segment ab nearest to `p`.
pub(crate) fn closest_on_segment(p: P2, a: P2, b: P2) -> P2 {
    let ab = sub(b, a);
    let l2 = dot(ab, ab);
    let t = if l2 > 0.0 {
        (dot(sub(p, a), ab) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    [a[0] + t * ab[0], a[1] + t * ab[1]]
}

/// Least distance between the closed segments ab and cd.
pub(crate) fn segment_distance(a: P2, b: P2, c: P2, d: P2) -> f64 {
    if segments_meet(a, b, c, d) {
        return 0.0;
    }
    point_segment_distance(a, c, d)
        .min(point_segment_distance(b, c, d))
        .min(point_segment_distance(c, a, b))
        .min(point_segment_distance(d, a, b))
}

/// Signed area of a polygon (positive when counter-clockwise).
pub(crate) fn signed_area(points: &[P2]) -> f64 {
    mesh_model::polygon_area(points.iter().copied())
}

/// An axis-aligned box.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Aabb {
    pub lo: P2,
    pub hi: P2,
}

impl Aabb {
    pub(crate) fn of_segment(a: P2, b: P2, inflate: f64) -> Self {
        Aabb {
            lo: [a[0].min(b[0]) - inflate, a[1].min(b[1]) - inflate],
            hi: [a[0].max(b[0]) + inflate, a[1].max(b[1]) + inflate],
        }
    }
}

/// Calls `visit(i, j)` (i < j in input order is not guaranteed) for every pair of boxes that
/// overlap, by sorting on the low x and sweeping. Works for boxes of very different sizes,
/// which fixed-radius neighbour queries do not.
pub(crate) fn overlapping_pairs(boxes: &[Aabb], mut visit: impl FnMut(usize, usize)) {
    let mut order: Vec<u32> = (0..boxes.len() as u32).collect();
    order.sort_unstable_by(|&a, &b| boxes[a as usize].lo[0].total_cmp(&boxes[b as usize].lo[0]));
    for (k, &i) in order.iter().enumerate() {
        let bi = boxes[i as usize];
        for &j in &order[k + 1..] {
            let bj = boxes[j as usize];
            if bj.lo[0] > bi.hi[0] {
                break;
            }
            if bj.lo[1] <= bi.hi[1] && bj.hi[1] >= bi.lo[1] {
                visit(i as usize, j as usize);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crossing_touching_and_apart() {
        assert!(segments_meet(
            [0.0, 0.0],
            [1.0, 1.0],
            [0.0, 1.0],
            [1.0, 0.0]
        ));
        assert!(segments_meet(
            [0.0, 0.0],
            [1.0, 0.0],
            [1.0, 0.0],
            [2.0, 1.0]
        ));
        assert!(!segments_meet(
            [0.0, 0.0],
            [1.0, 0.0],
            [0.0, 1.0],
            [1.0, 1.0]
        ));
        assert!(
            (segment_distance([0.0, 0.0], [1.0, 0.0], [0.5, 2.0], [0.5, 1.0]) - 1.0).abs() < 1e-15
        );
    }

    #[test]
    fn sweep_finds_exactly_the_overlapping_pairs() {
        let boxes = [
            Aabb::of_segment([0.0, 0.0], [10.0, 0.0], 0.1),
            Aabb::of_segment([5.0, -1.0], [5.0, 1.0], 0.0),
            Aabb::of_segment([20.0, 0.0], [21.0, 0.0], 0.0),
            Aabb::of_segment([9.0, 5.0], [9.5, 6.0], 0.0),
        ];
        let mut pairs = Vec::new();
        overlapping_pairs(&boxes, |i, j| pairs.push((i.min(j), i.max(j))));
        assert_eq!(pairs, vec![(0, 1)]);
    }
}
