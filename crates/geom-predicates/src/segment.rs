//! Segments: whether two closed 2D segments meet (decided exactly), where, and distances from
//! points to segments, polylines and closed loops in any dimension.

use crate::orient::orient2d;
use crate::vector::{cross2, dist, dot, sub};

/// One of the four end points of [`segment_meet`]'s segments `a b` and `c d`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Endpoint {
    /// `a`, the start of the first segment.
    A,
    /// `b`, the end of the first segment.
    B,
    /// `c`, the start of the second segment.
    C,
    /// `d`, the end of the second segment.
    D,
}

/// How two closed segments meet, decided exactly on the given coordinates.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum SegmentMeet {
    /// No common point.
    Disjoint,
    /// A proper crossing: each segment has its end points strictly on both sides of the other's
    /// line, so they share exactly one point, interior to both.
    Proper,
    /// An end point lies on the other segment (touching, or collinear and overlapping). The
    /// first found in the order `c`, `d` (on `a b`), then `a`, `b` (on `c d`).
    Touch(Endpoint),
}

/// Whether `x` lies in the closed bounding box of `p q` (for a point known to be collinear
/// with `p q`: whether it lies on the segment).
#[inline]
fn within(p: [f64; 2], q: [f64; 2], x: [f64; 2]) -> bool {
    x[0] >= p[0].min(q[0])
        && x[0] <= p[0].max(q[0])
        && x[1] >= p[1].min(q[1])
        && x[1] <= p[1].max(q[1])
}

/// How the closed segments `a b` and `c d` meet: four exact orientations, then for collinear
/// triples a bounding-box test. A degenerate segment (`a == b`) is a point and meets what
/// contains it.
pub fn segment_meet(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> SegmentMeet {
    let o1 = orient2d(a, b, c);
    let o2 = orient2d(a, b, d);
    let o3 = orient2d(c, d, a);
    let o4 = orient2d(c, d, b);
    let opposite = |u: f64, v: f64| (u > 0.0 && v < 0.0) || (u < 0.0 && v > 0.0);
    if opposite(o1, o2) && opposite(o3, o4) {
        return SegmentMeet::Proper;
    }
    if o1 == 0.0 && within(a, b, c) {
        SegmentMeet::Touch(Endpoint::C)
    } else if o2 == 0.0 && within(a, b, d) {
        SegmentMeet::Touch(Endpoint::D)
    } else if o3 == 0.0 && within(c, d, a) {
        SegmentMeet::Touch(Endpoint::A)
    } else if o4 == 0.0 && within(c, d, b) {
        SegmentMeet::Touch(Endpoint::B)
    } else {
        SegmentMeet::Disjoint
    }
}

/// True when the closed segments `a b` and `c d` share a point (crossing, touching or
/// overlapping).
#[inline]
pub fn segments_meet(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> bool {
    segment_meet(a, b, c, d) != SegmentMeet::Disjoint
}

/// A common point of the closed segments `a b` and `c d`, or `None` when they are disjoint:
/// the touching end point (exact), or for a proper crossing the intersection of the two lines
/// (rounded).
pub fn segment_intersection(
    a: [f64; 2],
    b: [f64; 2],
    c: [f64; 2],
    d: [f64; 2],
) -> Option<[f64; 2]> {
    match segment_meet(a, b, c, d) {
        SegmentMeet::Disjoint => None,
        SegmentMeet::Proper => {
            let r = sub(b, a);
            let s = sub(d, c);
            let t = cross2(sub(c, a), s) / cross2(r, s);
            Some([a[0] + r[0] * t, a[1] + r[1] * t])
        }
        SegmentMeet::Touch(Endpoint::A) => Some(a),
        SegmentMeet::Touch(Endpoint::B) => Some(b),
        SegmentMeet::Touch(Endpoint::C) => Some(c),
        SegmentMeet::Touch(Endpoint::D) => Some(d),
    }
}

/// The parameter `t` in `[0, 1]` of the point of the closed segment `a b` nearest to `p`
/// (0 for a degenerate segment).
#[inline]
pub fn project_on_segment<const D: usize>(p: [f64; D], a: [f64; D], b: [f64; D]) -> f64 {
    let ab = sub(b, a);
    let l2 = dot(ab, ab);
    if l2 > 0.0 {
        (dot(sub(p, a), ab) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    }
}

/// The point of the closed segment `a b` nearest to `p`.
#[inline]
pub fn closest_on_segment<const D: usize>(p: [f64; D], a: [f64; D], b: [f64; D]) -> [f64; D] {
    let t = project_on_segment(p, a, b);
    std::array::from_fn(|k| a[k] + t * (b[k] - a[k]))
}

/// The distance from `p` to the closed segment `a b`.
#[inline]
pub fn point_segment_distance<const D: usize>(p: [f64; D], a: [f64; D], b: [f64; D]) -> f64 {
    dist(p, closest_on_segment(p, a, b))
}

/// The least distance between the closed 2D segments `a b` and `c d` (0 when they meet).
pub fn segment_distance(a: [f64; 2], b: [f64; 2], c: [f64; 2], d: [f64; 2]) -> f64 {
    if segments_meet(a, b, c, d) {
        return 0.0;
    }
    point_segment_distance(a, c, d)
        .min(point_segment_distance(b, c, d))
        .min(point_segment_distance(c, a, b))
        .min(point_segment_distance(d, a, b))
}

/// The distance from `p` to the polyline through `points` (closed by the edge from the last
/// point back to the first when `closed`), or `reach` when it is not less: segments whose
/// bounding box lies farther than the best distance so far are skipped. `f64::INFINITY` for
/// no limit; an empty polyline gives `reach`, a single point its distance.
pub fn distance_to_polyline<const D: usize, P: Copy + Into<[f64; D]>>(
    p: [f64; D],
    points: &[P],
    closed: bool,
    reach: f64,
) -> f64 {
    let n = points.len();
    let edges = match n {
        0 => 0,
        1 => 1,
        _ if closed => n,
        _ => n - 1,
    };
    let mut best = reach;
    for k in 0..edges {
        let (a, b): ([f64; D], [f64; D]) = (points[k].into(), points[(k + 1) % n].into());
        if (0..D).any(|i| p[i] < a[i].min(b[i]) - best || p[i] > a[i].max(b[i]) + best) {
            continue;
        }
        best = best.min(point_segment_distance(p, a, b));
    }
    best
}

/// The distance from `p` to the closed polygon (loop) `points`, or `reach` when not less; see
/// [`distance_to_polyline`].
#[inline]
pub fn distance_to_loop<const D: usize, P: Copy + Into<[f64; D]>>(
    p: [f64; D],
    points: &[P],
    reach: f64,
) -> f64 {
    distance_to_polyline(p, points, true, reach)
}
