//! Property tests on generated loops: smooth wavy loops, polygons with corners (including tiny
//! corner-to-corner edges), several loops together and NACA sections, under random spacing
//! parameters and both placements. Every mesh must pass `common::check_mesh`.

use crate::common;

use boundary1d::{
    Boundary1dError, NodePlacement, SpacingParams, mesh_loop, mesh_loops, spacing_limits,
};
use common::check_mesh;
use geom_curve::{ClosedCurve, CurveParams, Point2, circle_points, naca};
use proptest::prelude::*;
use std::f64::consts::TAU;
use testkit::shapes::{wavy, wavy_loop};

fn params_strategy() -> impl Strategy<Value = SpacingParams> {
    (
        1.05..2.0f64,
        120.0..176.0f64,
        0.01..1.0f64,
        1e-6..0.05f64,
        any::<bool>(),
        any::<bool>(),
    )
        .prop_map(
            |(growth, refine_angle_deg, max_spacing, first_height, medial_axis, on_curve)| {
                SpacingParams {
                    growth,
                    refine_angle_deg,
                    max_spacing,
                    first_height,
                    medial_axis,
                    placement: if on_curve {
                        NodePlacement::OnCurve
                    } else {
                        NodePlacement::OnPolyline
                    },
                    ..SpacingParams::default()
                }
            },
        )
}

fn assert_valid(curves: &[ClosedCurve], params: &SpacingParams) -> Result<(), TestCaseError> {
    let meshes = mesh_loops(curves, params).map_err(|e| TestCaseError::fail(e.to_string()))?;
    prop_assert_eq!(meshes.len(), curves.len());
    for (curve, nodes) in curves.iter().zip(&meshes) {
        let (problems, _) = check_mesh(curve, params, nodes);
        prop_assert!(problems.is_empty(), "{:?}: {:#?}", params, problems);
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn smooth_loops(w in wavy(16..200), radius in 0.1..3.0f64, params in params_strategy()) {
        let points = w.points(Point2::origin(), radius);
        let curve = ClosedCurve::new(&points, &CurveParams::default()).unwrap();
        assert_valid(&[curve], &params)?;
    }

    #[test]
    fn polygons_with_corners_and_short_edges(
        per_side in 1usize..10, width in 0.01..3.0f64, height in 0.001..3.0f64,
        notch in 0.0..0.5f64, params in params_strategy(),
    ) {
        // a rectangle with a small step in its top side: corners, short corner-to-corner
        // edges (the step, as small as 0 .. 0.5 of the height) and straight sides
        let step = notch * height;
        let mut vertices = vec![(0.0, 0.0), (width, 0.0), (width, height)];
        if step > 1e-9 {
            vertices.push((0.5 * width, height));
            vertices.push((0.5 * width, height - step));
        }
        vertices.push((0.0, height - step));
        let mut points = Vec::new();
        for k in 0..vertices.len() {
            let (a, b) = (vertices[k], vertices[(k + 1) % vertices.len()]);
            for j in 0..per_side {
                let f = j as f64 / per_side as f64;
                points.push(Point2::new(a.0 + f * (b.0 - a.0), a.1 + f * (b.1 - a.1)));
            }
        }
        let curve = ClosedCurve::new(&points, &CurveParams::default()).unwrap();
        prop_assert_eq!(curve.corners().len(), vertices.len());
        assert_valid(&[curve], &params)?;
    }

    #[test]
    fn several_loops_together(
        n in 24usize..120, amplitude in 0.0..0.2f64, phase in 0.0..TAU, gap in 0.005..1.0f64,
        params in params_strategy(),
    ) {
        // a wavy body, a small circle at `gap` from it and a far-field circle around both
        let body = wavy_loop(n, Point2::origin(), 1.0, amplitude, 2, phase);
        let max_radius = 1.0 + amplitude;
        let small = circle_points(Point2::new(max_radius + gap + 0.2, 0.0), 0.2, 40).unwrap();
        let far = circle_points(Point2::origin(), 10.0, 64).unwrap();
        let curves: Vec<_> = [body, small, far]
            .iter()
            .map(|p| ClosedCurve::new(p, &CurveParams::default()).unwrap())
            .collect();
        assert_valid(&curves, &params)?;
    }

    #[test]
    fn naca_sections(
        camber in 0u8..7, position in 1u8..7, thickness in 6u8..25, closed in any::<bool>(),
        per_side in 40usize..120, params in params_strategy(),
    ) {
        let digits = format!("{camber}{position}{thickness:02}");
        let points = naca::naca4(&digits, per_side, closed).unwrap();
        let curve = ClosedCurve::new(&points, &CurveParams::default()).unwrap();
        assert_valid(&[curve], &params)?;
    }

    #[test]
    fn circles_use_few_nodes(
        n in 16usize..300, radius in 0.01..100.0f64, growth in 1.05..2.0f64,
        refine_angle_deg in 120.0..176.0f64,
    ) {
        // on a circle l_α is constant: at least 2πR/l_α segments are needed, and the law
        // uses at most 1/q times that (q = ln g/(g − 1), the step in ∫ds/h), plus rounding
        let params = SpacingParams {
            growth, refine_angle_deg, max_spacing: 1e9, first_height: 1.0,
            medial_axis: true, placement: NodePlacement::OnCurve,
            ..SpacingParams::default()
        };
        let points = circle_points(Point2::origin(), radius, n).unwrap();
        let curve = ClosedCurve::new(&points, &CurveParams::default()).unwrap();
        let nodes = mesh_loop(&curve, &params).unwrap();
        let l_alpha = 2.0 * radius * (refine_angle_deg.to_radians() / 2.0).cos();
        let minimum = curve.total_length() / l_alpha;
        let q = growth.ln() / (growth - 1.0);
        prop_assert!(nodes.len() as f64 >= minimum * (1.0 - 1e-6));
        prop_assert!((nodes.len() as f64) <= minimum / q + 1.0, "{} nodes for minimum {}", nodes.len(), minimum);
        let (problems, _) = check_mesh(&curve, &params, &nodes);
        prop_assert!(problems.is_empty(), "{:#?}", problems);
    }
}

#[test]
fn corner_spacing_is_the_first_height() {
    // a long thin rectangle: each corner's two segments are within [l_extru/g, l_extru]
    let points = [
        Point2::new(0.0, 0.0),
        Point2::new(4.0, 0.0),
        Point2::new(4.0, 1.0),
        Point2::new(0.0, 1.0),
    ];
    let curve = ClosedCurve::new(&points, &CurveParams::default()).unwrap();
    let params = SpacingParams {
        first_height: 1e-3,
        max_spacing: 0.2,
        ..SpacingParams::default()
    };
    let nodes = mesh_loop(&curve, &params).unwrap();
    let m = nodes.len();
    for k in (0..m).filter(|&k| nodes.is_corner[k]) {
        for neighbour in [(k + 1) % m, (k + m - 1) % m] {
            let length = (nodes.points[neighbour] - nodes.points[k]).norm();
            assert!(length <= params.first_height * (1.0 + 1e-9), "{length}");
            assert!(length >= params.first_height / params.growth, "{length}");
        }
    }
    // the long sides reach max_spacing in the middle
    let longest = (0..m)
        .map(|k| (nodes.points[(k + 1) % m] - nodes.points[k]).norm())
        .fold(0.0, f64::max);
    assert!(longest > 0.8 * params.max_spacing && longest <= params.max_spacing);
}

#[test]
fn spacing_limits_expose_the_law() {
    let points = circle_points(Point2::origin(), 2.0, 64).unwrap();
    let curve = ClosedCurve::new(&points, &CurveParams::default()).unwrap();
    let params = SpacingParams {
        max_spacing: 10.0,
        ..SpacingParams::default()
    };
    let limits = spacing_limits(std::slice::from_ref(&curve), &params).unwrap();
    let expected = 2.0 * 2.0 * (165f64.to_radians() / 2.0).cos();
    for &l in &limits[0].l_alpha {
        assert!((l - expected).abs() < 1e-9 * expected);
    }
    assert!(
        limits[0]
            .graded
            .iter()
            .all(|&h| (h - expected).abs() < 1e-9)
    );
    assert_eq!(limits[0].arc_positions.len(), 65);
}

#[test]
fn invalid_parameters_are_named() {
    let points = circle_points(Point2::origin(), 1.0, 32).unwrap();
    let curve = ClosedCurve::new(&points, &CurveParams::default()).unwrap();
    let cases = [
        (
            "growth",
            SpacingParams {
                growth: 1.0,
                ..SpacingParams::default()
            },
        ),
        (
            "growth",
            SpacingParams {
                growth: f64::NAN,
                ..SpacingParams::default()
            },
        ),
        (
            "refine_angle_deg",
            SpacingParams {
                refine_angle_deg: 90.0,
                ..SpacingParams::default()
            },
        ),
        (
            "refine_angle_deg",
            SpacingParams {
                refine_angle_deg: 180.0,
                ..SpacingParams::default()
            },
        ),
        (
            "max_spacing",
            SpacingParams {
                max_spacing: 0.0,
                ..SpacingParams::default()
            },
        ),
        (
            "max_spacing",
            SpacingParams {
                max_spacing: f64::INFINITY,
                ..SpacingParams::default()
            },
        ),
        (
            "first_height",
            SpacingParams {
                first_height: -1.0,
                ..SpacingParams::default()
            },
        ),
    ];
    for (name, params) in cases {
        match mesh_loop(&curve, &params) {
            Err(Boundary1dError::InvalidParameter { name: got, .. }) => assert_eq!(got, name),
            other => panic!("{name}: expected an error, got {other:?}"),
        }
    }
    assert!(
        mesh_loops(&[], &SpacingParams::default())
            .unwrap()
            .is_empty()
    );
}
