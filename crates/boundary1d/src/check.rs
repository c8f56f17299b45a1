//! Checks around node placement: before it, that the smallest spacing is one floating point
//! can resolve at the loop's coordinates; after it, that the nodes make simple polygons that
//! do not cross each other, and when they do, whether the curves themselves cross (the C2
//! spline through the user's points) or the spacing is too coarse.
//!
//! Owns these checks only; the predicates are `geom_curve::loops`'.

use geom_curve::loops::{check_loops_disjoint, find_self_intersection};
use geom_curve::{ClosedCurve, CurveError};

use crate::spacing::LoopSpacing;
use crate::{Boundary1dError, BoundaryNodes, MIN_RELATIVE_SPACING};

/// Samples per segment when looking for where two curves cross.
const CURVE_SAMPLES: usize = 16;

/// The smallest graded spacing of the loop must be at least [`MIN_RELATIVE_SPACING`] times
/// the largest coordinate magnitude of its points.
pub(crate) fn resolution(
    curve: &ClosedCurve,
    spacing: &LoopSpacing,
    loop_index: usize,
) -> Result<(), Boundary1dError> {
    let points = curve.input_points();
    let size = points
        .iter()
        .map(|p| p.x.abs().max(p.y.abs()))
        .fold(0.0, f64::max);
    let limit = MIN_RELATIVE_SPACING * size;
    let Some((i, &h)) = spacing
        .graded
        .iter()
        .enumerate()
        .min_by(|a, b| a.1.total_cmp(b.1))
    else {
        return Ok(());
    };
    if h >= limit {
        return Ok(());
    }
    let advice = if spacing.is_corner.iter().any(|&c| c) {
        "raise first_height (the spacing at corners)"
    } else {
        "the points turn too tightly there: smooth them"
    };
    Err(Boundary1dError::SpacingBelowResolution {
        loop_index,
        spacing: h,
        x: points[i].x,
        y: points[i].y,
        limit,
        advice,
    })
}

/// The nodes of every loop must be distinct in sequence and form simple polygons that do not
/// cross each other.
pub(crate) fn nodes(
    curves: &[ClosedCurve],
    meshes: &[BoundaryNodes],
) -> Result<(), Boundary1dError> {
    for (loop_index, mesh) in meshes.iter().enumerate() {
        let n = mesh.points.len();
        if let Some(node) = (0..n).find(|&k| mesh.points[k] == mesh.points[(k + 1) % n]) {
            return Err(Boundary1dError::NodesCoincide {
                loop_index,
                node,
                x: mesh.points[node].x,
                y: mesh.points[node].y,
            });
        }
        if let Some(crossing) = find_self_intersection(&mesh.points) {
            return Err(Boundary1dError::NodesCrossThemselves {
                loop_index,
                x: crossing.point.x,
                y: crossing.point.y,
            });
        }
    }
    let polygons: Vec<&[geom_curve::Point2<f64>]> =
        meshes.iter().map(|m| m.points.as_slice()).collect();
    let Err(CurveError::LoopsCross {
        loop_a,
        loop_b,
        x,
        y,
        ..
    }) = check_loops_disjoint(&polygons)
    else {
        return Ok(());
    };
    let sampled: Vec<Vec<geom_curve::Point2<f64>>> = curves
        .iter()
        .map(|c| c.sampled_polyline(CURVE_SAMPLES))
        .collect();
    if let Err(CurveError::LoopsCross {
        loop_a,
        loop_b,
        x,
        y,
        ..
    }) = check_loops_disjoint(&sampled)
    {
        return Err(Boundary1dError::SplinesCross {
            loop_a,
            loop_b,
            x,
            y,
        });
    }
    Err(Boundary1dError::NodesCross {
        loop_a,
        loop_b,
        x,
        y,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use geom_curve::{CurveParams, Point2};

    fn nodes_of(points: &[(f64, f64)]) -> BoundaryNodes {
        BoundaryNodes {
            t: (0..points.len()).map(|i| i as f64).collect(),
            points: points.iter().map(|&(x, y)| Point2::new(x, y)).collect(),
            is_corner: vec![false; points.len()],
        }
    }

    /// D10 (issue 15): crossing node polygons surfaced in afsf2d as "boundary edges cross:
    /// loop 0 edge 79"; they are reported here, in terms of the spacing.
    #[test]
    fn crossing_or_coinciding_nodes_are_reported() {
        let square = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];
        let pts: Vec<Point2<f64>> = square.iter().map(|&(x, y)| Point2::new(x, y)).collect();
        let curve = ClosedCurve::new(&pts, &CurveParams::default()).unwrap();
        let bowtie = nodes_of(&[(0.0, 0.0), (1.0, 1.0), (1.0, 0.0), (0.0, 1.0)]);
        let err = nodes(std::slice::from_ref(&curve), &[bowtie]).unwrap_err();
        assert!(
            matches!(
                err,
                Boundary1dError::NodesCrossThemselves { loop_index: 0, .. }
            ),
            "{err}"
        );
        let repeated = nodes_of(&[(0.0, 0.0), (1.0, 0.0), (1.0, 0.0), (0.0, 1.0)]);
        let err = nodes(std::slice::from_ref(&curve), &[repeated]).unwrap_err();
        assert!(
            matches!(err, Boundary1dError::NodesCoincide { node: 1, .. }),
            "{err}"
        );
        // two node polygons that cross while the curves do not
        let far: Vec<Point2<f64>> = pts.iter().map(|p| Point2::new(p.x + 1.5, p.y)).collect();
        let far_curve = ClosedCurve::new(&far, &CurveParams::default()).unwrap();
        let a = nodes_of(&square);
        let b = nodes_of(&[(0.9, 0.5), (2.5, 0.0), (2.5, 1.0)]);
        let err = nodes(&[curve, far_curve], &[a, b]).unwrap_err();
        assert!(
            matches!(
                err,
                Boundary1dError::NodesCross {
                    loop_a: 0,
                    loop_b: 1,
                    ..
                }
            ),
            "{err}"
        );
    }
}
