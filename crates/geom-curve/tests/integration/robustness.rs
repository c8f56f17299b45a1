//! Hostile but realistic geometry (issue 15): extreme scales, overflowing coordinates, stray
//! points and splines that cross themselves give one honest error, in bounded time.

use std::time::{Duration, Instant};

use geom_curve::loops::{MAX_COORDINATE, MIN_LOOP_SIZE, validate_loop};
use geom_curve::{ClosedCurve, CurveError, CurveParams, LoopCheckParams, Point2, naca, selig};

fn scaled(points: &[Point2<f64>], scale: f64) -> Vec<Point2<f64>> {
    points
        .iter()
        .map(|p| Point2::from(p.coords * scale))
        .collect()
}

/// D4: `naca = "0012"`, `scale = 1e-100` hung in the arc-length quadrature; 1e150 too.
#[test]
fn d4_extreme_scales_are_refused_at_once() {
    let foil = naca::naca4("0012", 101, true).unwrap();
    for scale in [1e-300, 1e-100, 1e-80, 1e-40, 1e-21] {
        let started = Instant::now();
        let err = ClosedCurve::new(&scaled(&foil, scale), &CurveParams::default()).unwrap_err();
        assert!(
            matches!(err, CurveError::LoopTooSmall { .. }),
            "{scale}: {err}"
        );
        assert!(err.to_string().contains("1e-20 to 1e20"), "{err}");
        assert!(started.elapsed() < Duration::from_secs(1));
    }
    for scale in [1e21, 1e150, 1e300] {
        let err = ClosedCurve::new(&scaled(&foil, scale), &CurveParams::default()).unwrap_err();
        assert!(
            matches!(err, CurveError::CoordinateTooLarge { .. }),
            "{scale}: {err}"
        );
    }
    const { assert!(MIN_LOOP_SIZE < 1e-19 && MAX_COORDINATE > 1e19) };
}

/// Inside the supported range the curve is scale-free: lengths scale exactly with the input.
#[test]
fn d4_curves_are_scale_free_within_the_supported_range() {
    let foil = naca::naca4("0012", 101, true).unwrap();
    let unit = ClosedCurve::new(&foil, &CurveParams::default()).unwrap();
    for scale in [1e-19, 1e-10, 1e10, 1e19] {
        let started = Instant::now();
        let curve = ClosedCurve::new(&scaled(&foil, scale), &CurveParams::default()).unwrap();
        assert!(started.elapsed() < Duration::from_secs(2), "{scale}");
        let ratio = curve.total_length() / (scale * unit.total_length());
        assert!((ratio - 1.0).abs() < 1e-12, "scale {scale}: ratio {ratio}");
        assert_eq!(curve.corners(), unit.corners(), "scale {scale}");
        let t = curve.t_at_arc_length(0.3 * curve.total_length());
        assert!((t - unit.t_at_arc_length(0.3 * unit.total_length())).abs() < 1e-9);
    }
}

/// D10: overflow was reported as "points 0 and 1 coincide (distance inf <= tolerance inf)".
#[test]
fn d10_overflowing_coordinates_are_called_too_large() {
    let points = [
        Point2::new(0.0, 0.0),
        Point2::new(1e300, 0.0),
        Point2::new(1e300, 1e300),
        Point2::new(-1e300, 1e300),
    ];
    let err = validate_loop(&points, &LoopCheckParams::default()).unwrap_err();
    assert_eq!(
        err,
        CurveError::CoordinateTooLarge {
            index: 1,
            x: 1e300,
            y: 0.0
        }
    );
    let text = err.to_string();
    assert!(
        text.contains("too large") && !text.contains("inf"),
        "{text}"
    );
}

/// D10: one outlier point blamed points 0 and 1 as duplicates.
#[test]
fn d10_a_stray_point_is_named() {
    let mut points: Vec<Point2<f64>> = (0..12)
        .map(|i| {
            let a = std::f64::consts::TAU * f64::from(i) / 12.0;
            Point2::new(a.cos(), a.sin())
        })
        .collect();
    points[7] = Point2::new(3e13, -2e13);
    let err = validate_loop(&points, &LoopCheckParams::default()).unwrap_err();
    match err {
        CurveError::OutlierPoint { index, rest, .. } => {
            assert_eq!(index, 7);
            assert!(rest > 1.0 && rest < 3.0, "{rest}");
        }
        other => panic!("expected the stray point, got {other}"),
    }
    // genuine duplicates are still duplicates
    let mut dup = points.clone();
    dup[7] = Point2::new(0.5, -0.8);
    dup.insert(3, dup[3] + nalgebra_free_offset());
    assert!(matches!(
        validate_loop(&dup, &LoopCheckParams::default()),
        Err(CurveError::DuplicatePoint { index: 3, .. })
    ));
}

fn nalgebra_free_offset() -> geom_curve::Vector2<f64> {
    geom_curve::Vector2::new(1e-14, 0.0)
}

/// D10: a spline through the user's points that crossed itself surfaced later as "boundary
/// edges cross: loop 0 edge 79" about generated nodes.
#[test]
fn d10_a_self_crossing_spline_is_reported_with_its_input_points() {
    let points: Vec<Point2<f64>> = [
        [0.06971741461783336, 0.04538547481352843],
        [0.10997013992343459, 0.9139668005057804],
        [-0.0877191844144865, 0.019024013064764804],
        [-0.12120862925664855, -0.07025697347562893],
        [0.016851140959853055, -0.9107031811460276],
        [0.3465504629583448, -0.2951652869385133],
    ]
    .iter()
    .map(|p| Point2::new(p[0], p[1]))
    .collect();
    // the polygon itself is simple
    let lenient = LoopCheckParams {
        detect_open_gap: false,
        ..LoopCheckParams::default()
    };
    assert_eq!(validate_loop(&points, &lenient), Ok(()));
    let params = CurveParams {
        loop_checks: lenient,
        ..CurveParams::default()
    };
    let err = ClosedCurve::new(&points, &params).unwrap_err();
    assert!(
        matches!(
            err,
            CurveError::SplineCrossesItself {
                from_a: 0,
                to_a: 1,
                from_b: 1,
                to_b: 2,
                ..
            }
        ),
        "{err}"
    );
    assert!(
        err.to_string().contains("input points 0-1 and 1-2"),
        "{err}"
    );
}

/// The Lednicer layout read from real data: the RAE 2822 fixture written as Lednicer.
#[test]
fn lednicer_file_gives_the_same_loop_as_its_selig_twin() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    let selig_points = selig::parse(
        &std::fs::read_to_string(dir.join("../../../../fixtures/geometry/rae2822.dat")).unwrap(),
    )
    .unwrap();
    let lednicer_text = std::fs::read_to_string(dir.join("rae2822-lednicer.dat")).unwrap();
    assert!(geom_curve::lednicer::looks_like_lednicer(&lednicer_text));
    let lednicer_points = selig::parse(&lednicer_text).unwrap();
    assert_eq!(lednicer_points.len(), selig_points.len());
    for (a, b) in lednicer_points.iter().zip(&selig_points) {
        assert!((a - b).norm() < 1e-12, "{a} vs {b}");
    }
    assert!(ClosedCurve::new(&lednicer_points, &CurveParams::default()).is_ok());
}
