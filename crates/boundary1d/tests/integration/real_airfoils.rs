//! Boundary meshes of the real airfoils, the 30P30N three elements together: every property
//! of `common::check_mesh` holds, for both placements, with and without the medial-axis step.

use crate::common;

use boundary1d::{NodePlacement, SpacingParams, mesh_loops};
use common::{check_mesh, load_curve, thirty_p_thirty_n};

fn thirty_p_params(medial_axis: bool, placement: NodePlacement) -> SpacingParams {
    SpacingParams {
        growth: 1.3,
        refine_angle_deg: 165.0,
        max_spacing: 0.05,
        first_height: 5e-6,
        medial_axis,
        placement,
        ..SpacingParams::default()
    }
}

#[test]
fn thirty_p_thirty_n_meshes_have_every_property() {
    let curves = thirty_p_thirty_n();
    for placement in [NodePlacement::OnCurve, NodePlacement::OnPolyline] {
        for medial_axis in [false, true] {
            let params = thirty_p_params(medial_axis, placement);
            let meshes = mesh_loops(&curves, &params).unwrap();
            assert_eq!(meshes.len(), 3);
            for (curve, nodes) in curves.iter().zip(&meshes) {
                let (problems, figures) = check_mesh(curve, &params, nodes);
                assert!(
                    problems.is_empty(),
                    "{placement:?} medial {medial_axis}: {problems:#?}"
                );
                assert!(figures.max_ratio > 1.25, "growth is used: {figures:?}");
                // nodes are not wasted: some segment nearly reaches its cap
                assert!(figures.max_cap_use > 0.8, "{figures:?}");
            }
        }
    }
}

#[test]
fn medial_axis_refines_the_gaps_between_elements() {
    let curves = thirty_p_thirty_n();
    let plain = mesh_loops(&curves, &thirty_p_params(false, NodePlacement::OnCurve)).unwrap();
    let refined = mesh_loops(&curves, &thirty_p_params(true, NodePlacement::OnCurve)).unwrap();
    let count =
        |meshes: &[boundary1d::BoundaryNodes]| meshes.iter().map(|m| m.len()).sum::<usize>();
    assert!(count(&refined) > count(&plain));
    // on the flap, spacing near the main element's trailing-edge corners grows at most
    // linearly with the distance to them: l <= l_extru + (g − 1)·(d + local geometry spacing)
    let params = thirty_p_params(true, NodePlacement::OnCurve);
    let main = &curves[1];
    let flap = &curves[2];
    let nodes = &refined[2];
    let geometry_spacing = flap
        .segments()
        .iter()
        .map(|s| s.chord_length())
        .fold(0.0, f64::max);
    let mut checked_near = 0;
    for k in 0..nodes.len() {
        let next = nodes.points[(k + 1) % nodes.len()];
        let length = (next - nodes.points[k]).norm();
        for &c in main.corners() {
            let d = (nodes.points[k] - main.input_points()[c]).norm();
            let limit = params.first_height + (params.growth - 1.0) * (d + geometry_spacing);
            assert!(
                length <= limit * 1.000001,
                "flap node {k}: {length} > {limit}"
            );
            if d < 0.05 {
                checked_near += 1;
            }
        }
    }
    assert!(checked_near > 0);
}

#[test]
fn single_airfoils_mesh_with_every_property() {
    for name in [
        "naca0012.dat",
        "naca0012-sharp-te-generated.dat",
        "rae2822.dat",
        "bat.dat",
    ] {
        let curve = load_curve(name);
        let scale = geom_curve::loops::bounding_box_diagonal(curve.input_points());
        for placement in [NodePlacement::OnCurve, NodePlacement::OnPolyline] {
            let params = SpacingParams {
                growth: 1.2,
                refine_angle_deg: 170.0,
                max_spacing: 0.05 * scale,
                first_height: 1e-4 * scale,
                medial_axis: true,
                placement,
                ..SpacingParams::default()
            };
            let nodes = boundary1d::mesh_loop(&curve, &params).unwrap();
            let (problems, _) = check_mesh(&curve, &params, &nodes);
            assert!(problems.is_empty(), "{name} {placement:?}: {problems:#?}");
        }
    }
}
