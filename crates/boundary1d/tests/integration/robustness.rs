//! Hostile but realistic inputs (issue 15): extreme first heights and spacings give a mesh or
//! an error naming the estimate and the limit, never a panic, an abort or a hang.

use boundary1d::{Boundary1dError, SpacingParams, mesh_loops, mesh_loops_with_caps};
use geom_curve::{ClosedCurve, CurveParams, Point2, circle_points, naca};

fn curve(points: &[Point2<f64>]) -> ClosedCurve {
    ClosedCurve::new(points, &CurveParams::default()).expect("valid loop")
}

fn triangle() -> ClosedCurve {
    curve(&[
        Point2::new(0.0, 0.0),
        Point2::new(1.0, 0.0),
        Point2::new(0.0, 1.0),
    ])
}

/// D3: a first height of 1e-17 on a unit triangle panicked with `capacity overflow`.
#[test]
fn d3_tiny_first_height_on_a_triangle_does_not_panic() {
    for first_height in [1e-12, 1e-15, 1e-17, 1e-30, 1e-300, f64::MIN_POSITIVE] {
        let params = SpacingParams {
            first_height,
            ..SpacingParams::default()
        };
        match mesh_loops(&[triangle()], &params) {
            Ok(meshes) => {
                let points = &meshes[0].points;
                let n = points.len();
                for i in 0..n {
                    assert!(
                        points[(i + 1) % n] != points[i],
                        "first height {first_height}: nodes {i} and the next coincide"
                    );
                }
            }
            Err(e) => {
                let text = e.to_string();
                assert!(!text.contains('\n'), "{text}");
                assert!(text.contains("first_height"), "{text}");
            }
        }
    }
}

/// D3 at its root: the first height is checked against what the coordinates resolve.
#[test]
fn d3_first_height_below_resolution_names_the_limit() {
    let params = SpacingParams {
        first_height: 1e-17,
        ..SpacingParams::default()
    };
    let err = mesh_loops(&[triangle()], &params).unwrap_err();
    assert!(
        matches!(err, Boundary1dError::SpacingBelowResolution { limit, .. } if limit == 1e-12),
        "{err}"
    );
    let text = err.to_string();
    assert!(text.contains("raise first_height"), "{text}");
    // just above the limit it meshes
    let params = SpacingParams {
        first_height: 2e-12,
        ..SpacingParams::default()
    };
    assert!(mesh_loops(&[triangle()], &params).is_ok());
}

/// D5: `max_spacing = 1e-9` aborted on allocation failure (exit 134).
#[test]
fn d5_huge_node_counts_are_refused_before_allocating() {
    let body = curve(&naca::naca4("0012", 101, true).unwrap());
    let far = curve(&circle_points(Point2::new(0.5, 0.0), 20.0, 256).unwrap());
    for max_spacing in [1e-9, 1e-6] {
        let params = SpacingParams {
            max_spacing,
            ..SpacingParams::default()
        };
        let started = std::time::Instant::now();
        let err = mesh_loops_with_caps(&[body.clone(), far.clone()], &params, &[max_spacing; 2])
            .unwrap_err();
        assert!(started.elapsed().as_secs() < 5);
        match err {
            Boundary1dError::TooManyNodes {
                estimate, limit, ..
            } => {
                assert_eq!(limit, boundary1d::MAX_BOUNDARY_NODES);
                assert!(estimate > limit as f64);
            }
            other => panic!("{other}"),
        }
    }
    // the sum over loops counts: the far field alone at 2e-5 is ~6.3e6, the body ~1e5
    let params = SpacingParams {
        max_spacing: 1e-5,
        ..SpacingParams::default()
    };
    let err = mesh_loops_with_caps(&[body, far], &params, &[1e-5, 1e-5]).unwrap_err();
    assert!(
        matches!(err, Boundary1dError::TooManyNodes { loop_index: 1, .. }),
        "{err}"
    );
    assert!(err.to_string().contains("10000000"), "{err}");
}
