//! Properties of the fitted curve on generated loops (proptest): interpolation, C1/C2
//! continuity at smooth points, exact curvature and length on circles up to the Lagrange
//! stencil's truncation error, corners as C0 breaks, arc length and its inverse, closest
//! point.

use geom_curve::curvature::circumcircle_curvature;
use geom_curve::{ClosedCurve, CurveError, CurveParams, Point2, circle_points};
use proptest::prelude::*;
use std::f64::consts::TAU;
use testkit::shapes::{wavy, wavy_loop};

/// Checks C1 and C2 continuity (in the chord-length parameter) and G1/G2 at every smooth
/// input point, and C0 at every point.
fn check_continuity(curve: &ClosedCurve) -> Result<(), TestCaseError> {
    let segments = curve.segments();
    let n = segments.len();
    let size = curve.total_length();
    for i in 0..n {
        let before = &segments[(i + n - 1) % n];
        let after = &segments[i];
        let gap = (before.point(1.0) - after.point(0.0)).norm();
        prop_assert!(gap < 1e-13 * size, "C0 at {}: {}", i, gap);
        if curve.is_corner(i) {
            continue;
        }
        let (h0, h1) = (before.chord_length(), after.chord_length());
        let d1_jump = (before.d1(1.0) / h0 - after.d1(0.0) / h1).norm();
        let d2_jump = (before.d2(1.0) / (h0 * h0) - after.d2(0.0) / (h1 * h1)).norm();
        let d2_scale = 1.0 + after.d2(0.0).norm() / (h1 * h1);
        prop_assert!(d1_jump < 1e-10, "C1 at {}: {}", i, d1_jump);
        prop_assert!(d2_jump < 1e-9 * d2_scale, "C2 at {}: {}", i, d2_jump);
        let t = i as f64;
        let tangent_jump = (before.d1(1.0).normalize() - curve.tangent(t)).norm();
        prop_assert!(tangent_jump < 1e-10, "G1 at {}", i);
        let k_before = before.d1(1.0).perp(&before.d2(1.0)) / before.d1(1.0).norm().powi(3);
        prop_assert!(
            (k_before - curve.curvature(t)).abs() < 1e-8 * (1.0 + k_before.abs()),
            "G2 at {}",
            i
        );
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn smooth_loops_are_interpolated_and_c2(w in wavy(12..300), half_width in 1usize..4) {
        let points = w.points(Point2::origin(), 1.0);
        let params = CurveParams { lagrange_half_width: half_width, ..CurveParams::default() };
        let curve = ClosedCurve::new(&points, &params).unwrap();
        prop_assert!(curve.corners().is_empty());
        for (i, p) in points.iter().enumerate() {
            prop_assert!((curve.point(i as f64) - p).norm() < 1e-14);
        }
        check_continuity(&curve)?;
    }

    #[test]
    fn circles_have_curvature_one_over_r_and_length_two_pi_r(
        n in 10usize..400, radius in 1e-3..1e3f64, cx in -5.0..5.0f64, cy in -5.0..5.0f64,
    ) {
        let center = Point2::new(cx, cy);
        let points = circle_points(center, radius, n).unwrap();
        // the circumcircle estimate is exact on circle points
        for i in 0..n {
            let k = circumcircle_curvature(points[(i + n - 1) % n], points[i], points[(i + 1) % n]);
            prop_assert!((k * radius - 1.0).abs() < 1e-9);
        }
        let curve = ClosedCurve::new(&points, &CurveParams::default()).unwrap();
        prop_assert!(curve.corners().is_empty());
        // tolerances from the truncation error of the quartic Lagrange stencil, h the
        // angular spacing: curvature O(h^4), position and length O(h^6)
        let h = TAU / n as f64;
        let curvature_tol = 0.2 * h.powi(4) + 1e-9;
        let shape_tol = 0.01 * h.powi(6) + 1e-12;
        for j in 0..4 * n {
            let t = j as f64 / 4.0;
            let k = curve.curvature(t);
            prop_assert!((k * radius - 1.0).abs() < curvature_tol, "t={} k·R={}", t, k * radius);
            let r = (curve.point(t) - center).norm() / radius;
            prop_assert!((r - 1.0).abs() < shape_tol, "t={} r/R={}", t, r);
        }
        let length_error = curve.total_length() / (TAU * radius) - 1.0;
        prop_assert!(length_error.abs() < shape_tol, "{}", length_error);
        // from point 0 to point k: k/n of the circumference
        let k = n / 4;
        let part = curve.arc_length(0.0, k as f64) / (TAU * radius * k as f64 / n as f64) - 1.0;
        prop_assert!(part.abs() < shape_tol, "{}", part);
    }

    #[test]
    fn arc_length_inverse_and_closest_point_round_trip(
        n in 12usize..200, amplitude in 0.0..0.3f64, phase in 0.0..TAU,
        t in 0.0..1.0f64, scale in 1e-3..1e3f64,
    ) {
        let points: Vec<_> = wavy_loop(n, Point2::origin(), 1.0, amplitude, 2, phase)
            .iter().map(|p| Point2::from(p.coords * scale)).collect();
        let curve = ClosedCurve::new(&points, &CurveParams::default()).unwrap();
        let t = t * n as f64;
        let s = curve.arc_length(0.0, t);
        prop_assert!(s >= 0.0 && s <= curve.total_length());
        let back = curve.t_at_arc_length(s);
        prop_assert!((curve.point(back) - curve.point(t)).norm() < 1e-11 * scale, "{} vs {}", back, t);
        // wrapping: one more turn lands on the same parameter
        let again = curve.t_at_arc_length(s + curve.total_length());
        prop_assert!((curve.point(again) - curve.point(t)).norm() < 1e-11 * scale);
        prop_assert!((curve.arc_length(t, t + n as f64) - curve.total_length()).abs() < 1e-12 * scale);
        let (t_found, p_found, distance) = curve.closest_point(curve.point(t));
        prop_assert!(distance < 1e-12 * scale, "distance {}", distance);
        prop_assert!((p_found - curve.point(t)).norm() < 1e-12 * scale);
        prop_assert!((curve.point(t_found) - p_found).norm() < 1e-12 * scale);
    }

    #[test]
    fn closest_point_is_global_even_far_away(
        n in 12usize..120, amplitude in 0.0..0.4f64, phase in 0.0..TAU,
        px in -4.0..4.0f64, py in -4.0..4.0f64,
    ) {
        let points = wavy_loop(n, Point2::origin(), 1.0, amplitude, 3, phase);
        let curve = ClosedCurve::new(&points, &CurveParams::default()).unwrap();
        let p = Point2::new(px, py);
        let (t, q, distance) = curve.closest_point(p);
        prop_assert!(((q - p).norm() - distance).abs() < 1e-14);
        prop_assert!((curve.point(t) - q).norm() < 1e-12);
        // no sample of the curve is closer
        let samples = 64 * n;
        let sampled = (0..samples)
            .map(|j| (curve.point(j as f64 * n as f64 / samples as f64) - p).norm())
            .fold(f64::INFINITY, f64::min);
        prop_assert!(distance <= sampled + 1e-12, "{} > {}", distance, sampled);
    }

    #[test]
    fn polygon_corners_are_c0_breaks_with_straight_sides(
        per_side in 1usize..12, width in 0.5..3.0f64, height in 0.5..3.0f64,
    ) {
        // a rectangle with `per_side` points per side: the 4 vertices are corners and every
        // side is fitted by straight segments
        let vertices = [(0.0, 0.0), (width, 0.0), (width, height), (0.0, height)];
        let mut points = Vec::new();
        for k in 0..4 {
            let (a, b) = (vertices[k], vertices[(k + 1) % 4]);
            for j in 0..per_side {
                let f = j as f64 / per_side as f64;
                points.push(Point2::new(a.0 + f * (b.0 - a.0), a.1 + f * (b.1 - a.1)));
            }
        }
        let curve = ClosedCurve::new(&points, &CurveParams::default()).unwrap();
        let expected: Vec<usize> = (0..4).map(|k| k * per_side).collect();
        prop_assert_eq!(curve.corners(), expected.as_slice());
        for j in 0..8 * points.len() {
            let p = curve.point(j as f64 / 8.0);
            let on_side = p.x.abs() < 1e-12 || (p.x - width).abs() < 1e-12
                || p.y.abs() < 1e-12 || (p.y - height).abs() < 1e-12;
            prop_assert!(on_side, "{}", p);
        }
        prop_assert!((curve.total_length() - 2.0 * (width + height)).abs() < 1e-12);
        check_continuity(&curve)?;
    }
}

#[test]
fn invalid_parameters_and_loops_are_errors() {
    let points = circle_points(Point2::origin(), 1.0, 20).unwrap();
    for bad in [0.0, -5.0, 181.0, f64::NAN] {
        let params = CurveParams {
            corner_angle_deg: bad,
            ..CurveParams::default()
        };
        assert!(matches!(
            ClosedCurve::new(&points, &params),
            Err(CurveError::InvalidParameter {
                name: "corner_angle_deg",
                ..
            })
        ));
    }
    for bad in [0, 9] {
        let params = CurveParams {
            lagrange_half_width: bad,
            ..CurveParams::default()
        };
        assert!(ClosedCurve::new(&points, &params).is_err());
    }
    let bowtie = [
        Point2::new(0.0, 0.0),
        Point2::new(1.0, 1.0),
        Point2::new(1.0, 0.0),
        Point2::new(0.0, 1.0),
    ];
    assert!(matches!(
        ClosedCurve::new(&bowtie, &CurveParams::default()),
        Err(CurveError::SelfIntersection { .. })
    ));
}

#[test]
fn a_triangle_is_three_straight_sides() {
    let points = [
        Point2::new(0.0, 0.0),
        Point2::new(1.0, 0.0),
        Point2::new(0.0, 1.0),
    ];
    let curve = ClosedCurve::new(&points, &CurveParams::default()).unwrap();
    assert_eq!(curve.corners(), &[0, 1, 2]);
    assert!((curve.total_length() - (2.0 + 2f64.sqrt())).abs() < 1e-14);
    assert!((curve.point(1.5) - Point2::new(0.5, 0.5)).norm() < 1e-15);
}

#[test]
fn evaluation_never_panics_on_odd_parameters() {
    let points = circle_points(Point2::origin(), 1.0, 16).unwrap();
    let curve = ClosedCurve::new(&points, &CurveParams::default()).unwrap();
    for t in [f64::NAN, f64::INFINITY, -1e-300, -3.5, 1e6, 16.0] {
        let _ = curve.point(t);
        let _ = curve.curvature(t);
        let _ = curve.t_at_arc_length(t);
        let _ = curve.closest_point(Point2::new(t, 0.0));
    }
    assert!((curve.point(16.0) - points[0]).norm() < 1e-15);
    assert!((curve.point(-1.0) - points[15]).norm() < 1e-15);
}
