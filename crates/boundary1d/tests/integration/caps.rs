//! Per-loop largest spacing (`mesh_loops_with_caps`): a body and a far field meshed together,
//! each within its own cap and with every other property of the law intact.

use crate::common;

use boundary1d::{Boundary1dError, SpacingParams, mesh_loops_with_caps};
use common::check_mesh;
use geom_curve::{ClosedCurve, CurveParams, Point2, circle_points, naca};
use proptest::prelude::*;

fn curve(points: &[Point2<f64>]) -> ClosedCurve {
    ClosedCurve::new(points, &CurveParams::default()).expect("valid loop")
}

fn longest_segment(points: &[Point2<f64>]) -> f64 {
    (0..points.len())
        .map(|i| (points[(i + 1) % points.len()] - points[i]).norm())
        .fold(0.0, f64::max)
}

proptest! {
    #[test]
    fn each_loop_keeps_its_own_cap(body_cap in 0.01..0.2f64, far_cap in 0.5..4.0f64, growth in 1.1..1.5f64) {
        let body = curve(&naca::naca4("0012", 80, true).expect("naca"));
        let far = curve(&circle_points(Point2::new(0.5, 0.0), 20.0, 256).expect("circle"));
        let params = SpacingParams { growth, max_spacing: 1.0, first_height: 1e-4, ..SpacingParams::default() };
        let meshes = mesh_loops_with_caps(&[body.clone(), far.clone()], &params, &[body_cap, far_cap]).expect("meshes");
        for ((c, nodes), cap) in [&body, &far].into_iter().zip(&meshes).zip([body_cap, far_cap]) {
            let own = SpacingParams { max_spacing: cap, ..params };
            let (problems, _) = check_mesh(c, &own, nodes);
            prop_assert!(problems.is_empty(), "{:?}", problems);
            prop_assert!(longest_segment(&nodes.points) <= cap * (1.0 + 1e-9));
        }
        // The far field is meshed to its own, coarser cap, not to the body's.
        prop_assert!(longest_segment(&meshes[1].points) > body_cap);
    }
}

#[test]
fn one_cap_per_loop_is_required() {
    let c = curve(&circle_points(Point2::new(0.0, 0.0), 1.0, 64).expect("circle"));
    let p = SpacingParams::default();
    let err = mesh_loops_with_caps(std::slice::from_ref(&c), &p, &[0.1, 0.2])
        .expect_err("two caps, one loop");
    assert!(
        matches!(err, Boundary1dError::InvalidParameter { .. }),
        "{err}"
    );
    let err = mesh_loops_with_caps(&[c], &p, &[-1.0]).expect_err("negative cap");
    assert!(err.to_string().contains("max_spacing"), "{err}");
}
