//! Checks and measures on closed polygonal loops: validity (enough finite, distinct points; not
//! open; no self-intersection), signed area and orientation, point-in-loop, and whether
//! several loops are free of crossings so that a caller can then test their nesting.
//!
//! Owns polygon-level predicates only: the curve fitted through the points is
//! [`crate::ClosedCurve`]. Orientation, segment crossing and point in loop are the exact
//! predicates of `geom-predicates`, so "touching" and "collinear" are decided exactly on the
//! given coordinates. The intersection searches use its sort-and-sweep over the edges'
//! bounding boxes: O(n log n) for airfoil-like loops (a few edges share any vertical line),
//! O(n²) only in contrived inputs where most edges overlap in x.

use geom_predicates::{Aabb, find_overlapping_pair, orient2d, segment_intersection};
use serde::{Deserialize, Serialize};

use crate::{CurveError, Point2};

/// Largest coordinate magnitude accepted by [`validate_loop`].
///
/// The supported range of the whole pipeline is: every coordinate within ±1e20 and every loop
/// at least 1e-20 across. Why: the mesh works with lengths from about 1e-12 of a loop's size
/// (relative tolerances, the thinnest first layers) up to some 1e6 times it (far fields), and
/// forms their squares and fourth powers (areas, orientation predicates, Jacobian
/// determinants); the Delaunay library (spade) refuses non-zero coordinates below 1.8e-43 or
/// above 3.4e38. Sizes in [1e-20, 1e20] keep all of these more than ten decades away from the
/// limits of `f64` and of spade, and cover any physical unit choice.
pub const MAX_COORDINATE: f64 = 1e20;
/// Smallest loop size (bounding-box diagonal) accepted by [`validate_loop`]; see
/// [`MAX_COORDINATE`].
pub const MIN_LOOP_SIZE: f64 = 1e-20;

/// What [`validate_loop`] checks and with which tolerances.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LoopCheckParams {
    /// Two consecutive points closer than this times the loop's bounding-box diagonal are
    /// duplicates. Dimensionless; default 1e-12.
    pub duplicate_rel_tolerance: f64,
    /// Whether to reject loops that look open (see [`CurveError::OpenLoop`]). Default true;
    /// turn it off for shapes with a genuinely long straight closing edge given by its two
    /// end points only, such as a half disc.
    pub detect_open_gap: bool,
    /// The closing edge is suspicious when longer than this many times the longest other
    /// edge. Dimensionless; default 10.
    pub open_gap_edge_ratio: f64,
    /// ... and longer than this fraction of the perimeter. Dimensionless; default 0.05.
    pub open_gap_perimeter_fraction: f64,
}

impl Default for LoopCheckParams {
    fn default() -> Self {
        Self {
            duplicate_rel_tolerance: 1e-12,
            detect_open_gap: true,
            open_gap_edge_ratio: 10.0,
            open_gap_perimeter_fraction: 0.05,
        }
    }
}

/// Where two edges meet.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EdgeCrossing {
    /// The first edge (edge i runs from point i to point i + 1, the last edge closes the loop).
    pub edge_a: usize,
    /// The second edge.
    pub edge_b: usize,
    /// A point common to both edges.
    pub point: Point2<f64>,
}

/// Checks that `points` form a simple closed polygon: at least 3 points, all finite and
/// within the supported range ([`MAX_COORDINATE`], [`MIN_LOOP_SIZE`]), no two consecutive
/// ones coinciding (closing edge included), not apparently open (when
/// `params.detect_open_gap`), and no two edges meeting except adjacent edges at their shared
/// point.
///
/// # Errors
/// The first fault found, in the order listed: [`CurveError::TooFewPoints`],
/// [`CurveError::NonFinitePoint`], [`CurveError::CoordinateTooLarge`],
/// [`CurveError::LoopTooSmall`], [`CurveError::OutlierPoint`] (when a stray point makes
/// others look like duplicates), [`CurveError::DuplicatePoint`], [`CurveError::OpenLoop`],
/// [`CurveError::SelfIntersection`].
pub fn validate_loop(points: &[Point2<f64>], params: &LoopCheckParams) -> Result<(), CurveError> {
    let n = points.len();
    if n < 3 {
        return Err(CurveError::TooFewPoints { count: n });
    }
    if let Some(index) = points
        .iter()
        .position(|p| !(p.x.is_finite() && p.y.is_finite()))
    {
        return Err(CurveError::NonFinitePoint {
            index,
            x: points[index].x,
            y: points[index].y,
        });
    }
    if let Some(index) = points
        .iter()
        .position(|p| p.x.abs() > MAX_COORDINATE || p.y.abs() > MAX_COORDINATE)
    {
        return Err(CurveError::CoordinateTooLarge {
            index,
            x: points[index].x,
            y: points[index].y,
        });
    }
    let size = bounding_box_diagonal(points);
    if size < MIN_LOOP_SIZE {
        return Err(CurveError::LoopTooSmall { size });
    }
    let tolerance = params.duplicate_rel_tolerance * size;
    for index in 0..n {
        let next = (index + 1) % n;
        let distance = (points[next] - points[index]).norm();
        if distance <= tolerance {
            if let Some(outlier) = outlier_hiding_edges(points, distance, params) {
                return Err(outlier);
            }
            return Err(CurveError::DuplicatePoint {
                index,
                next,
                distance,
                tolerance,
            });
        }
    }
    if params.detect_open_gap {
        let gap = (points[0] - points[n - 1]).norm();
        let longest_edge = (0..n - 1)
            .map(|i| (points[i + 1] - points[i]).norm())
            .fold(0.0, f64::max);
        let perimeter = perimeter(points);
        if gap > params.open_gap_edge_ratio * longest_edge
            && gap > params.open_gap_perimeter_fraction * perimeter
        {
            return Err(CurveError::OpenLoop {
                gap,
                longest_edge,
                perimeter,
            });
        }
    }
    if let Some(crossing) = find_self_intersection(points) {
        return Err(CurveError::SelfIntersection {
            edge_a: crossing.edge_a,
            edge_b: crossing.edge_b,
            x: crossing.point.x,
            y: crossing.point.y,
        });
    }
    Ok(())
}

/// When consecutive points at `distance` look like duplicates only because one stray point
/// inflates the loop's size: that point, as [`CurveError::OutlierPoint`]. The candidate is the
/// point farthest from the coordinate-wise median of the points.
fn outlier_hiding_edges(
    points: &[Point2<f64>],
    distance: f64,
    params: &LoopCheckParams,
) -> Option<CurveError> {
    if distance == 0.0 || points.len() < 4 {
        return None;
    }
    let median = |mut values: Vec<f64>| {
        values.sort_by(f64::total_cmp);
        values[values.len() / 2]
    };
    let centre = Point2::new(
        median(points.iter().map(|p| p.x).collect()),
        median(points.iter().map(|p| p.y).collect()),
    );
    let (index, _) = points
        .iter()
        .enumerate()
        .map(|(i, p)| (i, (p - centre).norm()))
        .max_by(|a, b| a.1.total_cmp(&b.1))?;
    let rest: Vec<Point2<f64>> = points
        .iter()
        .enumerate()
        .filter(|&(i, _)| i != index)
        .map(|(_, p)| *p)
        .collect();
    let rest_size = bounding_box_diagonal(&rest);
    if distance <= params.duplicate_rel_tolerance * rest_size {
        return None;
    }
    let (min, max) = rest
        .iter()
        .fold((rest[0], rest[0]), |(lo, hi), p| (lo.inf(p), hi.sup(p)));
    let p = points[index];
    let outside = Point2::new(p.x.clamp(min.x, max.x), p.y.clamp(min.y, max.y));
    Some(CurveError::OutlierPoint {
        index,
        x: p.x,
        y: p.y,
        distance: (p - outside).norm(),
        rest: rest_size,
    })
}

/// The first pair of edges of the loop that meet where they should not: non-adjacent edges
/// that touch or cross, or adjacent edges that fold back onto each other (collinear and
/// overlapping). `None` for a simple polygon. Points must be finite.
pub fn find_self_intersection(points: &[Point2<f64>]) -> Option<EdgeCrossing> {
    let n = points.len();
    if n < 2 {
        return None;
    }
    // Adjacent edges i-1 and i meet at point i; they overlap only if they fold back.
    for i in 0..n {
        let prev = points[(i + n - 1) % n];
        let here = points[i];
        let next = points[(i + 1) % n];
        if orient2d(prev.into(), here.into(), next.into()) == 0.0
            && (prev - here).dot(&(next - here)) > 0.0
        {
            let point = if (prev - here).norm() <= (next - here).norm() {
                prev
            } else {
                next
            };
            return Some(EdgeCrossing {
                edge_a: (i + n - 1) % n,
                edge_b: i,
                point,
            });
        }
    }
    let edges: Vec<SweepEdge> = (0..n).map(|i| SweepEdge::new(0, i, points)).collect();
    let adjacent = |a: &SweepEdge, b: &SweepEdge| {
        let (i, j) = (a.edge, b.edge);
        i == j || (i + 1) % n == j || (j + 1) % n == i
    };
    first_crossing(&edges, adjacent).map(|(a, b, point)| {
        let (edge_a, edge_b) = (a.edge.min(b.edge), a.edge.max(b.edge));
        EdgeCrossing {
            edge_a,
            edge_b,
            point,
        }
    })
}

/// Checks that no edge of one loop touches or crosses an edge of another loop. Each loop
/// should already have passed [`validate_loop`]. Once this holds, nesting is decided by
/// [`loop_inside_loop`] (walls inside the far field, walls outside each other).
///
/// # Errors
/// [`CurveError::LoopsCross`] naming both loops (indices into `loops`), their edges and a
/// common point.
pub fn check_loops_disjoint<L: AsRef<[Point2<f64>]>>(loops: &[L]) -> Result<(), CurveError> {
    let mut edges = Vec::new();
    for (loop_index, points) in loops.iter().enumerate() {
        let points = points.as_ref();
        edges.extend((0..points.len()).map(|i| SweepEdge::new(loop_index, i, points)));
    }
    match first_crossing(&edges, |a, b| a.loop_index == b.loop_index) {
        None => Ok(()),
        Some((a, b, point)) => {
            let (first, second) = if a.loop_index < b.loop_index {
                (a, b)
            } else {
                (b, a)
            };
            Err(CurveError::LoopsCross {
                loop_a: first.loop_index,
                edge_a: first.edge,
                loop_b: second.loop_index,
                edge_b: second.edge,
                x: point.x,
                y: point.y,
            })
        }
    }
}

/// Whether `point` lies inside the closed loop (non-zero winding number), whatever the loop's
/// orientation. Exact for points off the boundary; for a point exactly on an edge the answer
/// may be either.
pub fn point_in_loop(point: Point2<f64>, points: &[Point2<f64>]) -> bool {
    geom_predicates::point_in_loop(point.into(), points)
}

/// Whether loop `inner` lies inside loop `outer`, assuming the two do not cross (check that
/// with [`check_loops_disjoint`] first): then one point of `inner` decides.
pub fn loop_inside_loop(inner: &[Point2<f64>], outer: &[Point2<f64>]) -> bool {
    inner.first().is_some_and(|&p| point_in_loop(p, outer))
}

/// Signed area (shoelace formula): positive for a counter-clockwise loop.
pub fn signed_area(points: &[Point2<f64>]) -> f64 {
    geom_predicates::polygon_area(points.iter().copied())
}

/// Whether the loop is counter-clockwise (positive signed area).
pub fn is_counter_clockwise(points: &[Point2<f64>]) -> bool {
    signed_area(points) > 0.0
}

/// Makes the loop counter-clockwise by reversing it when needed, keeping the first point
/// first (so an airfoil still starts at its trailing edge). Returns whether it was reversed.
pub fn make_counter_clockwise(points: &mut [Point2<f64>]) -> bool {
    if signed_area(points) < 0.0 {
        points[1..].reverse();
        true
    } else {
        false
    }
}

/// Perimeter of the closed loop, closing edge included.
pub fn perimeter(points: &[Point2<f64>]) -> f64 {
    let n = points.len();
    (0..n)
        .map(|i| (points[(i + 1) % n] - points[i]).norm())
        .sum()
}

/// Length of the diagonal of the axis-aligned bounding box of the points (0 when empty), the
/// "size" that relative tolerances refer to.
pub fn bounding_box_diagonal(points: &[Point2<f64>]) -> f64 {
    let Some(first) = points.first() else {
        return 0.0;
    };
    let (mut min, mut max) = (*first, *first);
    for p in points {
        min = min.inf(p);
        max = max.sup(p);
    }
    (max - min).norm()
}

/// An edge as the sweep sees it.
#[derive(Debug, Clone, Copy)]
struct SweepEdge {
    loop_index: usize,
    edge: usize,
    a: Point2<f64>,
    b: Point2<f64>,
}

impl SweepEdge {
    /// Edge `edge` of the closed loop `points`, from point `edge` to the next.
    fn new(loop_index: usize, edge: usize, points: &[Point2<f64>]) -> Self {
        Self {
            loop_index,
            edge,
            a: points[edge],
            b: points[(edge + 1) % points.len()],
        }
    }
}

/// The first pair of edges (in the sweep's order) that share a point, skipping pairs for which
/// `skip` is true, with a common point.
fn first_crossing(
    edges: &[SweepEdge],
    skip: impl Fn(&SweepEdge, &SweepEdge) -> bool,
) -> Option<(SweepEdge, SweepEdge, Point2<f64>)> {
    let boxes: Vec<Aabb<2>> = edges
        .iter()
        .map(|e| Aabb::of_segment(e.a.into(), e.b.into(), 0.0))
        .collect();
    find_overlapping_pair(&boxes, |i, j| {
        let (e, f) = (edges[i], edges[j]);
        if skip(&e, &f) {
            return None;
        }
        segments_meet(e.a, e.b, f.a, f.b).map(|point| (e, f, point))
    })
}

/// A common point of the closed segments ab and cd, decided exactly; `None` if disjoint.
fn segments_meet(
    a: Point2<f64>,
    b: Point2<f64>,
    c: Point2<f64>,
    d: Point2<f64>,
) -> Option<Point2<f64>> {
    segment_intersection(a.into(), b.into(), c.into(), d.into()).map(Point2::from)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn pts(coords: &[(f64, f64)]) -> Vec<Point2<f64>> {
        coords.iter().map(|&(x, y)| Point2::new(x, y)).collect()
    }

    fn unit_square() -> Vec<Point2<f64>> {
        pts(&[(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)])
    }

    #[test]
    fn square_is_valid_and_counter_clockwise() {
        let square = unit_square();
        assert_eq!(validate_loop(&square, &LoopCheckParams::default()), Ok(()));
        assert!((signed_area(&square) - 1.0).abs() < 1e-15);
        assert!(is_counter_clockwise(&square));
        assert!((perimeter(&square) - 4.0).abs() < 1e-15);
    }

    #[test]
    fn make_counter_clockwise_reverses_and_keeps_the_first_point() {
        let mut square = unit_square();
        square[1..].reverse();
        assert!(!is_counter_clockwise(&square));
        assert!(make_counter_clockwise(&mut square));
        assert_eq!(square, unit_square());
        assert!(!make_counter_clockwise(&mut square));
    }

    #[test]
    fn each_fault_is_reported() {
        let params = LoopCheckParams::default();
        assert_eq!(
            validate_loop(&unit_square()[..2], &params),
            Err(CurveError::TooFewPoints { count: 2 })
        );
        let mut nan = unit_square();
        nan[2].y = f64::NAN;
        assert!(matches!(
            validate_loop(&nan, &params),
            Err(CurveError::NonFinitePoint { index: 2, .. })
        ));
        let mut dup = unit_square();
        dup.insert(2, dup[2] + nalgebra::Vector2::new(1e-14, 0.0));
        assert!(matches!(
            validate_loop(&dup, &params),
            Err(CurveError::DuplicatePoint {
                index: 2,
                next: 3,
                ..
            })
        ));
        let mut closing_dup = unit_square();
        closing_dup.push(closing_dup[0]);
        assert!(matches!(
            validate_loop(&closing_dup, &params),
            Err(CurveError::DuplicatePoint {
                index: 4,
                next: 0,
                ..
            })
        ));
        let bowtie = pts(&[(0.0, 0.0), (1.0, 1.0), (1.0, 0.0), (0.0, 1.0)]);
        match validate_loop(&bowtie, &params) {
            Err(CurveError::SelfIntersection {
                edge_a: 0,
                edge_b: 2,
                x,
                y,
            }) => assert!((x - 0.5).abs() < 1e-15 && (y - 0.5).abs() < 1e-15),
            other => panic!("expected a self-intersection, got {other:?}"),
        }
    }

    #[test]
    fn fold_back_and_touching_are_self_intersections() {
        // the third point goes back along the second edge
        let fold = pts(&[(0.0, 0.0), (2.0, 0.0), (1.0, 0.0), (1.0, 1.0)]);
        assert!(find_self_intersection(&fold).is_some());
        // a vertex touching a non-adjacent edge
        let touch = pts(&[(0.0, 0.0), (2.0, 0.0), (2.0, 2.0), (1.0, 0.0), (0.0, 2.0)]);
        let crossing = find_self_intersection(&touch).unwrap();
        assert_eq!(crossing.point, Point2::new(1.0, 0.0));
        // a degenerate triangle
        let flat = pts(&[(0.0, 0.0), (1.0, 0.0), (3.0, 0.0)]);
        assert!(find_self_intersection(&flat).is_some());
    }

    #[test]
    fn an_open_curve_is_detected() {
        // upper half of a circle only: the closing edge is the diameter
        let half: Vec<_> = (0..=40)
            .map(|i| {
                let a = std::f64::consts::PI * f64::from(i) / 40.0;
                Point2::new(a.cos(), a.sin())
            })
            .collect();
        let err = validate_loop(&half, &LoopCheckParams::default()).unwrap_err();
        assert!(matches!(err, CurveError::OpenLoop { gap, .. } if (gap - 2.0).abs() < 1e-12));
        assert!(err.to_string().contains("close the loop or add points"));
        let lenient = LoopCheckParams {
            detect_open_gap: false,
            ..LoopCheckParams::default()
        };
        assert_eq!(validate_loop(&half, &lenient), Ok(()));
    }

    #[test]
    fn loops_crossing_each_other_are_named() {
        let a = unit_square();
        let far: Vec<_> = a
            .iter()
            .map(|p| p + nalgebra::Vector2::new(5.0, 0.0))
            .collect();
        let overlapping: Vec<_> = a
            .iter()
            .map(|p| p + nalgebra::Vector2::new(0.5, 0.5))
            .collect();
        assert_eq!(check_loops_disjoint(&[a.clone(), far.clone()]), Ok(()));
        let err = check_loops_disjoint(&[far, a, overlapping]).unwrap_err();
        assert!(matches!(
            err,
            CurveError::LoopsCross {
                loop_a: 1,
                loop_b: 2,
                ..
            }
        ));
    }

    #[test]
    fn containment() {
        let outer: Vec<_> = unit_square()
            .iter()
            .map(|p| Point2::new(p.x * 10.0 - 5.0, p.y * 10.0 - 5.0))
            .collect();
        let inner = unit_square();
        assert!(loop_inside_loop(&inner, &outer));
        assert!(!loop_inside_loop(&outer, &inner));
        assert!(point_in_loop(Point2::new(0.5, 0.5), &inner));
        assert!(!point_in_loop(Point2::new(1.5, 0.5), &inner));
        let mut clockwise = inner.clone();
        clockwise[1..].reverse();
        assert!(point_in_loop(Point2::new(0.5, 0.5), &clockwise));
    }

    /// A star-shaped loop: one point per angle sector with a random radius, always simple;
    /// at least 5 sectors so that no angular gap reaches 180° and the origin is inside.
    fn star_loop() -> impl Strategy<Value = Vec<Point2<f64>>> {
        (5usize..200)
            .prop_flat_map(|n| {
                (
                    Just(n),
                    prop::collection::vec((0.1..1.0f64, 0.05..0.95f64), n),
                )
            })
            .prop_map(|(n, samples)| {
                samples
                    .iter()
                    .enumerate()
                    .map(|(i, &(radius, jitter))| {
                        let angle = std::f64::consts::TAU * (i as f64 + jitter) / n as f64;
                        Point2::new(radius * angle.cos(), radius * angle.sin())
                    })
                    .collect()
            })
    }

    /// O(n²) reference: does any pair of non-adjacent edges meet?
    fn brute_force_has_crossing(points: &[Point2<f64>]) -> bool {
        let n = points.len();
        for i in 0..n {
            for j in i + 1..n {
                let adjacent = j == i + 1 || (i == 0 && j == n - 1);
                if adjacent {
                    continue;
                }
                let e = |k: usize| (points[k], points[(k + 1) % n]);
                let ((a, b), (c, d)) = (e(i), e(j));
                if segments_meet(a, b, c, d).is_some() {
                    return true;
                }
            }
        }
        false
    }

    proptest! {
        #[test]
        fn star_loops_are_simple_and_counter_clockwise(points in star_loop()) {
            let lenient = LoopCheckParams { detect_open_gap: false, ..LoopCheckParams::default() };
            prop_assert_eq!(validate_loop(&points, &lenient), Ok(()));
            prop_assert!(signed_area(&points) > 0.0);
            prop_assert!(point_in_loop(Point2::origin(), &points));
            prop_assert!(!point_in_loop(Point2::new(1.01, 0.0), &points));
            let mut reversed = points.clone();
            prop_assert!(!make_counter_clockwise(&mut reversed));
            reversed[1..].reverse();
            prop_assert!((signed_area(&reversed) + signed_area(&points)).abs() < 1e-12);
        }

        #[test]
        fn sweep_agrees_with_brute_force(
            coords in prop::collection::vec((0i32..12, 0i32..12), 4..14)
        ) {
            // small integer grids make touching and collinear cases frequent
            let points: Vec<_> = coords.iter().map(|&(x, y)| Point2::new(f64::from(x), f64::from(y))).collect();
            let n = points.len();
            let has_duplicate = (0..n).any(|i| points[i] == points[(i + 1) % n]);
            prop_assume!(!has_duplicate);
            let folds = (0..n).any(|i| {
                let (p, h, q) = (points[(i + n - 1) % n], points[i], points[(i + 1) % n]);
                orient2d(p.into(), h.into(), q.into()) == 0.0 && (p - h).dot(&(q - h)) > 0.0
            });
            let found = find_self_intersection(&points).is_some();
            prop_assert_eq!(found, folds || brute_force_has_crossing(&points));
        }
    }
}
