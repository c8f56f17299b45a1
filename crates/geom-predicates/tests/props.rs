//! Property tests of the predicates against exact integer arithmetic and brute force, and
//! unit cases of the 3D intersections.

use geom_predicates::{
    Aabb, PointTree, SegmentMeet, Sign, distance_to_loop, distance_to_polyline, insphere,
    insphere_sign, orient2d, orient2d_sign, orient3d, orient3d_sign, overlapping_pairs,
    point_in_loop, point_segment_distance, polygon_area, segment_distance, segment_intersection,
    segment_meet, segment_meets_triangle, segments_meet, triangles_meet, winding_number,
};
use proptest::prelude::*;

fn exact2(a: [i64; 2], b: [i64; 2], c: [i64; 2]) -> Sign {
    let (a, b, c) = (a.map(i128::from), b.map(i128::from), c.map(i128::from));
    let det = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    Sign::of(det as f64)
}

fn exact3(a: [i64; 3], b: [i64; 3], c: [i64; 3], d: [i64; 3]) -> Sign {
    let s = |p: [i64; 3]| [0, 1, 2].map(|k| i128::from(p[k]) - i128::from(d[k]));
    let (u, v, w) = (s(a), s(b), s(c));
    let det = u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
        + u[2] * (v[0] * w[1] - v[1] * w[0]);
    Sign::of(det as f64)
}

/// The in-sphere determinant in exact integer arithmetic (coordinates below 2^20).
fn exact_insphere(a: [i64; 3], b: [i64; 3], c: [i64; 3], d: [i64; 3], e: [i64; 3]) -> Sign {
    let row = |p: [i64; 3]| {
        let v = [0, 1, 2].map(|k| i128::from(p[k]) - i128::from(e[k]));
        [v[0], v[1], v[2], v[0] * v[0] + v[1] * v[1] + v[2] * v[2]]
    };
    let m = [row(a), row(b), row(c), row(d)];
    let det3 = |r: [usize; 3], c: [usize; 3]| {
        m[r[0]][c[0]] * (m[r[1]][c[1]] * m[r[2]][c[2]] - m[r[1]][c[2]] * m[r[2]][c[1]])
            - m[r[0]][c[1]] * (m[r[1]][c[0]] * m[r[2]][c[2]] - m[r[1]][c[2]] * m[r[2]][c[0]])
            + m[r[0]][c[2]] * (m[r[1]][c[0]] * m[r[2]][c[1]] - m[r[1]][c[1]] * m[r[2]][c[0]])
    };
    // Laplace expansion along the first row
    let det = m[0][0] * det3([1, 2, 3], [1, 2, 3]) - m[0][1] * det3([1, 2, 3], [0, 2, 3])
        + m[0][2] * det3([1, 2, 3], [0, 1, 3])
        - m[0][3] * det3([1, 2, 3], [0, 1, 2]);
    // Shewchuk's sign convention: positive inside for orient3d(a, b, c, d) > 0
    Sign::of(det as f64)
}

fn f2(p: [i64; 2]) -> [f64; 2] {
    p.map(|x| x as f64)
}

fn f3(p: [i64; 3]) -> [f64; 3] {
    p.map(|x| x as f64)
}

/// Coordinates up to 2^30 in 2D (2^20 in 3D): the naive determinant's products exceed 2^53
/// and round, the exact predicate must not.
fn p2() -> impl Strategy<Value = [i64; 2]> {
    prop_oneof![
        [-8i64..8, -8i64..8],
        [-(1i64 << 30)..(1i64 << 30), -(1i64 << 30)..(1i64 << 30)]
    ]
}

fn p3() -> impl Strategy<Value = [i64; 3]> {
    prop_oneof![
        [-4i64..4, -4i64..4, -4i64..4],
        [
            -(1i64 << 20)..(1i64 << 20),
            -(1i64 << 20)..(1i64 << 20),
            -(1i64 << 20)..(1i64 << 20)
        ]
    ]
}

/// A star-shaped loop around the origin: random angles taken in increasing order, each with
/// a random radius (simple; the origin is inside when no angular gap reaches a half turn).
fn star_loop() -> impl Strategy<Value = Vec<[f64; 2]>> {
    prop::collection::vec((0.0..std::f64::consts::TAU, 0.1..1.0f64), 3..80).prop_map(|mut v| {
        v.sort_by(|p, q| p.0.total_cmp(&q.0));
        v.dedup_by(|p, q| p.0 == q.0);
        v.iter().map(|&(a, r)| [r * a.cos(), r * a.sin()]).collect()
    })
}

/// Whether the origin is strictly inside the star loop: every angular gap below a half turn.
fn origin_inside(points: &[[f64; 2]]) -> bool {
    let angles: Vec<f64> = points.iter().map(|p| p[1].atan2(p[0])).collect();
    let n = angles.len();
    (0..n).all(|i| {
        let gap = (angles[(i + 1) % n] - angles[i]).rem_euclid(std::f64::consts::TAU);
        gap < std::f64::consts::PI - 1e-9
    })
}

/// The winding number by summing the turning angles (reference, fine off the boundary).
fn angle_winding(p: [f64; 2], points: &[[f64; 2]]) -> i64 {
    let n = points.len();
    let mut total = 0.0;
    for i in 0..n {
        let (a, b) = (points[i], points[(i + 1) % n]);
        let (u, v) = ([a[0] - p[0], a[1] - p[1]], [b[0] - p[0], b[1] - p[1]]);
        total += (u[0] * v[1] - u[1] * v[0]).atan2(u[0] * v[0] + u[1] * v[1]);
    }
    (total / std::f64::consts::TAU).round() as i64
}

fn boxes() -> impl Strategy<Value = Vec<Aabb<3>>> {
    prop::collection::vec(
        ([0i32..40, 0i32..40, 0i32..40], [0i32..8, 0i32..8, 0i32..8]),
        0..60,
    )
    .prop_map(|v| {
        v.into_iter()
            .map(|(lo, size)| {
                let lo = lo.map(f64::from);
                Aabb {
                    lo,
                    hi: [0, 1, 2].map(|k| lo[k] + f64::from(size[k])),
                }
            })
            .collect()
    })
}

proptest! {
    #[test]
    fn orient2d_is_exact_and_antisymmetric(a in p2(), b in p2(), c in p2()) {
        let s = orient2d_sign(f2(a), f2(b), f2(c));
        prop_assert_eq!(s, exact2(a, b, c));
        prop_assert_eq!(orient2d_sign(f2(b), f2(a), f2(c)), s.reversed());
        prop_assert_eq!(orient2d_sign(f2(b), f2(c), f2(a)), s);
        // a point exactly on the line through a and b (integer steps along it)
        let on = [2 * b[0] - a[0], 2 * b[1] - a[1]];
        prop_assert_eq!(orient2d(f2(a), f2(b), f2(on)), 0.0);
    }

    #[test]
    fn orient3d_is_exact_and_antisymmetric(a in p3(), b in p3(), c in p3(), d in p3()) {
        let s = orient3d_sign(f3(a), f3(b), f3(c), f3(d));
        prop_assert_eq!(s, exact3(a, b, c, d));
        prop_assert_eq!(orient3d_sign(f3(b), f3(a), f3(c), f3(d)), s.reversed());
        prop_assert_eq!(orient3d_sign(f3(b), f3(c), f3(a), f3(d)), s);
        let on = [0, 1, 2].map(|k| a[k] + (b[k] - a[k]) - (c[k] - a[k]));
        prop_assert_eq!(orient3d(f3(a), f3(b), f3(c), f3(on)), 0.0);
    }

    #[test]
    fn insphere_is_exact(a in p3(), b in p3(), c in p3(), d in p3(), e in p3()) {
        prop_assert_eq!(insphere_sign(f3(a), f3(b), f3(c), f3(d), f3(e)), exact_insphere(a, b, c, d, e));
        // swapping two corners reverses the orientation and so the sign
        prop_assert_eq!(
            insphere_sign(f3(b), f3(a), f3(c), f3(d), f3(e)),
            exact_insphere(a, b, c, d, e).reversed()
        );
    }

    #[test]
    fn segment_meet_is_symmetric(
        a in [0i64..6, 0i64..6], b in [0i64..6, 0i64..6],
        c in [0i64..6, 0i64..6], d in [0i64..6, 0i64..6],
    ) {
        let (a, b, c, d) = (f2(a), f2(b), f2(c), f2(d));
        let m = segment_meet(a, b, c, d);
        let meets = m != SegmentMeet::Disjoint;
        for other in [
            segment_meet(c, d, a, b), segment_meet(b, a, c, d),
            segment_meet(a, b, d, c), segment_meet(d, c, b, a),
        ] {
            prop_assert_eq!(other != SegmentMeet::Disjoint, meets);
            prop_assert_eq!(other == SegmentMeet::Proper, m == SegmentMeet::Proper);
        }
        prop_assert_eq!(segments_meet(a, b, c, d), meets);
        prop_assert_eq!(segment_intersection(a, b, c, d).is_some(), meets);
        if let Some(x) = segment_intersection(a, b, c, d) {
            prop_assert!(point_segment_distance(x, a, b) < 1e-12);
            prop_assert!(point_segment_distance(x, c, d) < 1e-12);
        }
        let gap = segment_distance(a, b, c, d);
        prop_assert_eq!(gap == 0.0, meets);
        prop_assert_eq!(gap, segment_distance(c, d, a, b));
    }

    #[test]
    fn point_in_loop_agrees_with_the_winding_number(
        points in star_loop(),
        q in [-1.2..1.2f64, -1.2..1.2f64],
    ) {
        // off the boundary, where the angle sum is a safe reference
        prop_assume!(distance_to_loop(q, &points, f64::INFINITY) > 1e-9);
        let w = angle_winding(q, &points);
        prop_assert_eq!(winding_number(q, &points), w);
        prop_assert_eq!(point_in_loop(q, &points), w != 0);
        let mut reversed = points.clone();
        reversed.reverse();
        prop_assert_eq!(winding_number(q, &reversed), -w);
        let area = polygon_area(points.iter().copied());
        prop_assert!((polygon_area(reversed.iter().copied()) + area).abs() <= 1e-12);
        if origin_inside(&points) {
            prop_assert!(point_in_loop([0.0, 0.0], &points));
        }
    }

    #[test]
    fn loop_distance_is_the_least_segment_distance(
        points in star_loop(),
        q in [-1.2..1.2f64, -1.2..1.2f64],
        reach in 0.01..2.0f64,
    ) {
        let n = points.len();
        let brute = (0..n)
            .map(|i| point_segment_distance(q, points[i], points[(i + 1) % n]))
            .fold(f64::INFINITY, f64::min);
        prop_assert_eq!(distance_to_loop(q, &points, f64::INFINITY), brute);
        prop_assert_eq!(distance_to_loop(q, &points, reach), brute.min(reach));
        let open = (0..n - 1)
            .map(|i| point_segment_distance(q, points[i], points[i + 1]))
            .fold(f64::INFINITY, f64::min);
        prop_assert_eq!(distance_to_polyline(q, &points, false, f64::INFINITY), open);
    }

    #[test]
    fn sweep_finds_exactly_the_overlapping_pairs(boxes in boxes()) {
        let mut brute = Vec::new();
        for i in 0..boxes.len() {
            for j in i + 1..boxes.len() {
                if boxes[i].overlaps(&boxes[j]) {
                    brute.push((i, j));
                }
            }
        }
        prop_assert_eq!(overlapping_pairs(&boxes), brute);
    }

    #[test]
    fn kd_tree_agrees_with_brute_force(
        points in prop::collection::vec([-10.0..10.0f64, -10.0..10.0f64, -10.0..10.0f64], 1..300),
        q in [-12.0..12.0f64, -12.0..12.0f64, -12.0..12.0f64],
        radius in 0.0..6.0f64,
    ) {
        let tree = PointTree::new(&points);
        let d = |p: [f64; 3]| ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt();
        let best = points.iter().map(|&p| d(p)).fold(f64::INFINITY, f64::min);
        let (i, dist) = tree.nearest(q).unwrap();
        prop_assert!((d(points[i]) - best).abs() <= 1e-12 && (dist - best).abs() <= 1e-12);
        let mut found: Vec<usize> = tree.within(q, radius).into_iter().map(|(i, _)| i).collect();
        found.sort_unstable();
        // away from the sphere itself, where squaring the radius may round either way
        prop_assume!(points.iter().all(|&p| (d(p) - radius).abs() > 1e-9));
        let brute: Vec<usize> = (0..points.len()).filter(|&i| d(points[i]) <= radius).collect();
        prop_assert_eq!(found, brute);
    }

    #[test]
    fn triangle_tests_ignore_order(
        t in [[-3i64..3, -3i64..3, -3i64..3], [-3i64..3, -3i64..3, -3i64..3], [-3i64..3, -3i64..3, -3i64..3]],
        u in [[-3i64..3, -3i64..3, -3i64..3], [-3i64..3, -3i64..3, -3i64..3], [-3i64..3, -3i64..3, -3i64..3]],
    ) {
        let (t, u) = (t.map(f3), u.map(f3));
        let collinear = |x: [[f64; 3]; 3]| {
            [0, 1, 2].iter().all(|&k| {
                let drop = |p: [f64; 3]| match k { 0 => [p[1], p[2]], 1 => [p[0], p[2]], _ => [p[0], p[1]] };
                orient2d(drop(x[0]), drop(x[1]), drop(x[2])) == 0.0
            })
        };
        prop_assume!(!collinear(t) && !collinear(u));
        let m = triangles_meet(t, u);
        prop_assert_eq!(triangles_meet(u, t), m);
        prop_assert_eq!(triangles_meet([t[1], t[2], t[0]], [u[0], u[2], u[1]]), m);
        // a shared corner always meets
        prop_assert!(triangles_meet(t, [t[0], u[1], u[2]]) || collinear([t[0], u[1], u[2]]));
    }
}

#[test]
fn orient3d_sign_convention() {
    let (o, x, y, z) = ([0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]);
    assert!(orient3d(o, x, y, z) < 0.0);
    assert!(orient3d(o, y, x, z) > 0.0);
    assert_eq!(orient3d(o, x, y, [3.0, 4.0, 0.0]), 0.0);
}

#[test]
fn insphere_sign_convention() {
    // orient3d(o, y, x, z) > 0: the centre of the unit cube's corner sphere is inside
    let (o, x, y, z) = ([0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]);
    assert!(insphere(o, y, x, z, [0.5; 3]) > 0.0);
    assert!(insphere(o, y, x, z, [2.0; 3]) < 0.0);
    assert_eq!(insphere(o, y, x, z, [1.0; 3]), 0.0);
}

#[test]
fn segment_and_triangle_cases() {
    let t = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]];
    let hit = |p: [f64; 3], q: [f64; 3]| segment_meets_triangle(p, q, t[0], t[1], t[2]);
    assert!(hit([0.5, 0.5, -1.0], [0.5, 0.5, 1.0])); // pierces
    assert!(!hit([3.0, 3.0, -1.0], [3.0, 3.0, 1.0])); // misses
    assert!(!hit([0.5, 0.5, 0.5], [0.5, 0.5, 1.0])); // above
    assert!(hit([0.5, 0.5, 0.0], [0.5, 0.5, 1.0])); // end point on the face
    assert!(hit([1.0, 1.0, -1.0], [1.0, 1.0, 1.0])); // through the hypotenuse
    assert!(hit([0.0, 0.0, 1.0], [0.0, 0.0, -1.0])); // through a corner
    assert!(hit([-1.0, 0.5, 0.0], [3.0, 0.5, 0.0])); // coplanar, across
    assert!(hit([0.2, 0.2, 0.0], [0.3, 0.3, 0.0])); // coplanar, inside
    assert!(!hit([-1.0, -1.0, 0.0], [-1.0, 3.0, 0.0])); // coplanar, beside
    // triangles: crossing, stacked, coplanar nested, touching along an edge
    let lifted = |dz: f64| t.map(|p| [p[0], p[1], p[2] + dz]);
    let standing = [[0.5, 0.5, -1.0], [0.5, 0.5, 1.0], [3.0, 3.0, 0.0]];
    assert!(triangles_meet(t, standing));
    assert!(!triangles_meet(t, lifted(1.0)));
    assert!(triangles_meet(t, lifted(0.0)));
    let small = [[0.1, 0.1, 0.0], [0.5, 0.1, 0.0], [0.1, 0.5, 0.0]];
    assert!(triangles_meet(t, small) && triangles_meet(small, t));
    let wall = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [1.0, 0.0, 1.0]];
    assert!(triangles_meet(t, wall));
}

#[test]
fn polygon_area_keeps_small_cells_far_from_the_origin() {
    assert_eq!(
        polygon_area([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]),
        1.0
    );
    assert_eq!(polygon_area([[0.0, 0.0], [0.0, 1.0], [1.0, 0.0]]), -0.5);
    assert_eq!(polygon_area::<[f64; 2]>([]), 0.0);
    let thin = [[1.0, 0.0], [1.0 + 1e-9, 0.0], [1.0, 1e-9]];
    assert!((polygon_area(thin) / 0.5e-18 - 1.0).abs() < 1e-6);
}
