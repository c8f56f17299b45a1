//! The gap-width and bulge limits: wall segments facing another body across a narrow gap are
//! no longer than the gap, and no segment bulges off its chord by more than `max_bulge`.

use crate::common;

use boundary1d::{SpacingParams, mesh_loop, mesh_loops};
use common::check_mesh;
use geom_curve::{ClosedCurve, CurveParams, Point2, circle_points};
use proptest::prelude::*;

fn circle(center: [f64; 2], radius: f64) -> ClosedCurve {
    let points = circle_points(Point2::new(center[0], center[1]), radius, 64).expect("circle");
    ClosedCurve::new(&points, &CurveParams::default()).expect("valid loop")
}

proptest! {
    /// Two unit-diameter circles `gap` apart: the segments at the gap's throat are at most
    /// about the gap wide (the cap holds at the geometry points and is interpolated between
    /// them), the rest of the law holds, and the gap only refines.
    #[test]
    fn segments_at_a_narrow_gap_are_no_longer_than_the_gap(gap in 1e-5..0.05f64, growth in 1.1..1.4f64) {
        let (a, b) = (circle([0.0, 0.0], 0.5), circle([1.0 + gap, 0.0], 0.5));
        let params = SpacingParams { growth, ..SpacingParams::default() };
        let meshes = mesh_loops(&[a.clone(), b.clone()], &params).expect("meshes");
        for (c, nodes) in [&a, &b].into_iter().zip(&meshes) {
            let (problems, _) = check_mesh(c, &params, nodes);
            prop_assert!(problems.is_empty(), "{:?}", problems);
        }
        let pts = &meshes[0].points;
        let n = pts.len();
        // the segment of the left circle nearest the throat (x = 0.5, y = 0)
        let throat = (0..n)
            .min_by(|&i, &j| {
                let d = |k: usize| (pts[k] - Point2::new(0.5, 0.0)).norm();
                d(i).total_cmp(&d(j))
            })
            .unwrap();
        for k in [throat + n - 1, throat] {
            let len = (pts[(k + 1) % n] - pts[k % n]).norm();
            prop_assert!(len <= 1.5 * gap, "segment {len:e} at a gap of {gap:e}");
        }
        // the gap only refines
        let lone = mesh_loop(&a, &params).expect("meshes");
        prop_assert!(n >= lone.len());
    }

    /// With `max_bulge`, every segment of a circle of radius R stays within it:
    /// `l²/8R <= max_bulge`.
    #[test]
    fn segments_bulge_no_more_than_max_bulge(radius in 0.1..10.0f64, bulge in 1e-6..1e-2f64) {
        let c = circle([0.0, 0.0], radius);
        let params = SpacingParams { max_bulge: bulge * radius, max_spacing: 10.0 * radius, ..SpacingParams::default() };
        let nodes = mesh_loop(&c, &params).expect("meshes");
        let p = &nodes.points;
        for i in 0..p.len() {
            let l = (p[(i + 1) % p.len()] - p[i]).norm();
            prop_assert!(l * l / (8.0 * radius) <= bulge * radius * (1.0 + 1e-6), "l = {l:e}");
        }
    }
}
