//! The spacing field of each loop: `l_α` from the circumcircle curvature, the caps from `δ`
//! and the corners, break points, the optional medial-axis refinement across loops, and the
//! graded field `h` (the cap made `(g − 1)`-Lipschitz in arc length along the loop).
//!
//! Owns the values at the geometry points; turning the field into nodes is `grading`'s job.

use geom_curve::curvature::circumcircle_curvature;
use geom_curve::{ClosedCurve, Point2};
use geom_predicates::distance_to_loop;

use crate::{Boundary1dError, NodePlacement, SpacingParams};

/// The spacing data of one loop at its geometry points, exposed for inspection and tests.
#[derive(Debug, Clone, PartialEq)]
pub struct LoopSpacing {
    /// Arc length from `t = 0` to each geometry point, `n + 1` values (the last is the loop's
    /// length), measured along the curve or the polygon as [`SpacingParams::placement`] says.
    pub arc_positions: Vec<f64>,
    /// `l_α = 2R·cos(α_refine/2)` at each point (infinite where the neighbours are collinear).
    pub l_alpha: Vec<f64>,
    /// The spacing cap at each point: `min(l_α, δ)`, `min(l_extru, δ)` at corners, then
    /// lowered by the medial-axis step when enabled. Between points the cap is interpolated
    /// linearly in arc length, except that a corner's value holds at the corner only: along
    /// a segment leaving a corner the cap is that of the segment's other end (`δ` if it is a
    /// corner too).
    pub cap: Vec<f64>,
    /// Indices of the break points (local minima of `cap` and all corners) after the
    /// medial-axis step, increasing.
    pub break_points: Vec<usize>,
    /// The graded spacing `h` at each point: `min over s' of cap(s') + (g − 1)·|s − s'|`.
    pub graded: Vec<f64>,
    /// Whether each point is a corner of the curve.
    pub is_corner: Vec<bool>,
}

/// Computes the spacing data of every loop (all loops together for the medial-axis step).
///
/// # Errors
/// [`Boundary1dError::InvalidParameter`] for bad `params`.
pub fn spacing_limits(
    curves: &[ClosedCurve],
    params: &SpacingParams,
) -> Result<Vec<LoopSpacing>, Boundary1dError> {
    spacing_limits_each(&per_loop(curves.len(), params, None)?, curves)
}

/// The parameters of each loop: `params`, with its `max_spacing` replaced by the loop's own
/// cap where `caps` gives one. Checks `params` and the caps.
pub(crate) fn per_loop(
    loops: usize,
    params: &SpacingParams,
    caps: Option<&[f64]>,
) -> Result<Vec<SpacingParams>, Boundary1dError> {
    params.validate()?;
    let Some(caps) = caps else {
        return Ok(vec![*params; loops]);
    };
    if caps.len() != loops {
        return Err(Boundary1dError::InvalidParameter {
            name: "loop max_spacing",
            value: caps.len() as f64,
            reason: "give one cap per loop",
        });
    }
    caps.iter()
        .map(|&max_spacing| {
            let p = SpacingParams {
                max_spacing,
                ..*params
            };
            p.validate().map(|()| p)
        })
        .collect()
}

/// [`spacing_limits`] with parameters per loop (they differ only in `max_spacing`; growth and
/// the medial-axis switch are taken from the first).
fn spacing_limits_each(
    params: &[SpacingParams],
    curves: &[ClosedCurve],
) -> Result<Vec<LoopSpacing>, Boundary1dError> {
    let Some(first) = params.first() else {
        return Ok(Vec::new());
    };
    let mut loops: Vec<LoopSpacing> = curves
        .iter()
        .zip(params)
        .map(|(curve, p)| initial_spacing(curve, p))
        .collect();
    if first.medial_axis {
        cap_by_gap_width(curves, &mut loops);
        for spacing in &mut loops {
            spacing.break_points = break_points(&spacing.cap, &spacing.is_corner);
        }
        refine_across_gaps(curves, &mut loops, first.growth - 1.0);
    }
    for (spacing, p) in loops.iter_mut().zip(params) {
        settle_corner_caps(spacing, p.max_spacing);
        spacing.break_points = break_points(&spacing.cap, &spacing.is_corner);
        spacing.graded = graded_field(&spacing.cap, &spacing.arc_positions, first.growth - 1.0);
    }
    Ok(loops)
}

/// [`spacing_limits`] where each loop has its own largest spacing `caps[i]`.
///
/// # Errors
/// As [`spacing_limits`], and [`Boundary1dError::InvalidParameter`] when `caps` does not have
/// one finite positive value per curve.
pub fn spacing_limits_with_caps(
    curves: &[ClosedCurve],
    params: &SpacingParams,
    caps: &[f64],
) -> Result<Vec<LoopSpacing>, Boundary1dError> {
    spacing_limits_each(&per_loop(curves.len(), params, Some(caps))?, curves)
}

/// `l_α`, caps and break points before the medial-axis step.
fn initial_spacing(curve: &ClosedCurve, params: &SpacingParams) -> LoopSpacing {
    let points = curve.input_points();
    let n = points.len();
    let factor = 2.0 * (0.5 * params.refine_angle_deg.to_radians()).cos();
    let l_alpha: Vec<f64> = (0..n)
        .map(|i| {
            let kappa =
                circumcircle_curvature(points[(i + n - 1) % n], points[i], points[(i + 1) % n]);
            if kappa == 0.0 {
                f64::INFINITY
            } else {
                // the refinement angle's length, or the length whose bulge l²κ/8 is max_bulge
                (factor / kappa.abs()).min((8.0 * params.max_bulge / kappa.abs()).sqrt())
            }
        })
        .collect();
    let is_corner: Vec<bool> = (0..n).map(|i| curve.is_corner(i)).collect();
    let corner_spacing = params.first_height.min(params.max_spacing);
    let cap: Vec<f64> = (0..n)
        .map(|i| {
            if is_corner[i] {
                corner_spacing
            } else {
                l_alpha[i].min(params.max_spacing)
            }
        })
        .collect();
    let arc_positions = match params.placement {
        NodePlacement::OnCurve => curve.cumulative_lengths().to_vec(),
        NodePlacement::OnPolyline => {
            let mut s = Vec::with_capacity(n + 1);
            s.push(0.0);
            for i in 0..n {
                let last = s[i];
                s.push(last + (points[(i + 1) % n] - points[i]).norm());
            }
            s
        }
    };
    let break_points = break_points(&cap, &is_corner);
    LoopSpacing {
        arc_positions,
        l_alpha,
        cap,
        break_points,
        graded: Vec::new(),
        is_corner,
    }
}

/// The cap of segment `from → other` at its end `from`, for linear interpolation along the
/// segment: the point's cap at smooth points; at a corner, whose cap `l_extru` is a point
/// constraint (its circumcircle spans the corner and means nothing), the cap of the other
/// end, or `δ` when both ends are corners.
pub(crate) fn interpolation_cap(
    spacing: &LoopSpacing,
    from: usize,
    other: usize,
    max_spacing: f64,
) -> f64 {
    match (spacing.is_corner[from], spacing.is_corner[other]) {
        (false, _) => spacing.cap[from],
        (true, false) => spacing.cap[other],
        (true, true) => max_spacing,
    }
}

/// Lowers each corner's cap to the interpolation caps of its two segments at the corner, so
/// that the spacing field is continuous there (a corner never gets a larger spacing than the
/// smooth points next to it allow).
fn settle_corner_caps(spacing: &mut LoopSpacing, max_spacing: f64) {
    let n = spacing.cap.len();
    for c in 0..n {
        if spacing.is_corner[c] {
            let before = interpolation_cap(spacing, c, (c + n - 1) % n, max_spacing);
            let after = interpolation_cap(spacing, c, (c + 1) % n, max_spacing);
            spacing.cap[c] = spacing.cap[c].min(before).min(after);
        }
    }
}

/// Local minima of `cap` (cyclic; at a plateau both ends count) and every corner.
pub(crate) fn break_points(cap: &[f64], is_corner: &[bool]) -> Vec<usize> {
    let n = cap.len();
    (0..n)
        .filter(|&i| {
            let (before, here, after) = (cap[(i + n - 1) % n], cap[i], cap[(i + 1) % n]);
            is_corner[i] || (here <= before && here <= after && (here < before || here < after))
        })
        .collect()
}

/// The medial-axis step: cap every point by `l_b + slope·|P − P_b|` over the break points `b`
/// of all loops.
fn refine_across_gaps(curves: &[ClosedCurve], loops: &mut [LoopSpacing], slope: f64) {
    let sources: Vec<(Point2<f64>, f64)> = curves
        .iter()
        .zip(loops.iter())
        .flat_map(|(curve, spacing)| {
            spacing
                .break_points
                .iter()
                .map(|&b| (curve.input_points()[b], spacing.cap[b]))
        })
        .collect();
    for (curve, spacing) in curves.iter().zip(loops.iter_mut()) {
        for (p, cap) in curve.input_points().iter().zip(spacing.cap.iter_mut()) {
            for &(source, source_cap) in &sources {
                // cheap rejection before the square root
                let reach = *cap - source_cap;
                if reach <= 0.0 {
                    continue;
                }
                let offset = p - source;
                if offset.norm_squared() * slope * slope >= reach * reach {
                    continue;
                }
                *cap = cap.min(source_cap + slope * offset.norm());
            }
        }
    }
}

/// How many boundary segments may span the width of a gap between two loops: a point's cap is
/// at most `GAP_SPACING_RATIO ×` its distance to the nearest other loop.
///
/// Why: the dissertation's medial-axis step grades from break points only, so two smooth
/// bodies close together (two circles, a slat over a main element) keep wall segments many
/// times longer than the gap between them. The layers grown across such a gap meet in
/// needles, and a curved wall edge there bulges by `l²/8R`, more than the layers in the gap
/// are thick, so no straight-sided cell above it can be valid. With segments no longer than
/// the gap, the bulge is a small fraction of the gap (`w/8R` of it) and the fronts meet in
/// cells of aspect ratio near one.
pub const GAP_SPACING_RATIO: f64 = 1.0;

/// The gap-width step: caps every geometry point's spacing by [`GAP_SPACING_RATIO`] times its
/// distance to the polygon of every other loop. Distances are measured to the polygons
/// through the geometry points (the curves lie within a small fraction of a segment of
/// them). Brute force over point–segment pairs, with a bounding-box rejection against the
/// largest distance that could still lower the cap.
fn cap_by_gap_width(curves: &[ClosedCurve], loops: &mut [LoopSpacing]) {
    let polygons: Vec<&[Point2<f64>]> = curves.iter().map(ClosedCurve::input_points).collect();
    for (i, spacing) in loops.iter_mut().enumerate() {
        for (p, cap) in polygons[i].iter().zip(spacing.cap.iter_mut()) {
            for (j, other) in polygons.iter().enumerate() {
                if j == i {
                    continue;
                }
                let reach = *cap / GAP_SPACING_RATIO;
                let d = distance_to_loop((*p).into(), other, reach);
                if d < reach {
                    *cap = GAP_SPACING_RATIO * d;
                }
            }
        }
    }
}

/// `h_i = min_j cap_j + slope·d(i, j)`, d the arc length along the closed loop.
pub(crate) fn graded_field(cap: &[f64], arc_positions: &[f64], slope: f64) -> Vec<f64> {
    let n = cap.len();
    let mut h = cap.to_vec();
    for _ in 0..2 {
        for k in 1..=n {
            let i = k % n;
            let candidate = h[k - 1] + slope * (arc_positions[k] - arc_positions[k - 1]);
            h[i] = h[i].min(candidate);
        }
        for k in (0..n).rev() {
            let next = (k + 1) % n;
            let candidate = h[next] + slope * (arc_positions[k + 1] - arc_positions[k]);
            h[k] = h[k].min(candidate);
        }
    }
    h
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn break_points_are_minima_plateau_ends_and_corners() {
        let cap = [5.0, 3.0, 3.0, 5.0, 4.0, 6.0, 6.0];
        let corners = [false, false, false, false, false, false, true];
        assert_eq!(break_points(&cap, &corners), vec![1, 2, 4, 6]);
        // a flat field has no minima
        assert!(break_points(&[1.0; 5], &[false; 5]).is_empty());
    }

    #[test]
    fn graded_field_is_the_lipschitz_envelope_around_the_loop() {
        // 6 points, unit spacing, loop length 6
        let s = [0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0];
        let cap = [10.0, 10.0, 10.0, 0.5, 10.0, 10.0];
        let h = graded_field(&cap, &s, 0.25);
        // distance to point 3 along the loop: 3,2,1,0,1,2
        let expected = [1.25, 1.0, 0.75, 0.5, 0.75, 1.0];
        for (a, b) in h.iter().zip(expected) {
            assert!((a - b).abs() < 1e-15, "{h:?}");
        }
        // across the closure
        let cap = [0.5, 10.0, 10.0, 10.0, 10.0, 10.0];
        let h = graded_field(&cap, &s, 0.25);
        assert!(
            (h[5] - 0.75).abs() < 1e-15 && (h[3] - 1.25).abs() < 1e-15,
            "{h:?}"
        );
    }
}
