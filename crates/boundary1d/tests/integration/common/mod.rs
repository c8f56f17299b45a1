//! Test kit: fixture loading and the property checker every boundary-mesh test ends with.

#![allow(dead_code)]

use boundary1d::{BoundaryNodes, NodePlacement, SpacingParams};
use geom_curve::ClosedCurve;
use geom_curve::curvature::circumcircle_curvature;

/// Reads, parses and fits a Selig file from `fixtures/geometry`.
pub use testkit::fixtures::selig_curve as load_curve;

/// The three 30P30N elements.
pub fn thirty_p_thirty_n() -> Vec<ClosedCurve> {
    testkit::fixtures::THIRTY_P_THIRTY_N
        .iter()
        .map(|name| load_curve(name))
        .collect()
}

/// Arc length from t = 0 to each geometry point, along the curve or the polygon.
pub fn arc_positions(curve: &ClosedCurve, placement: NodePlacement) -> Vec<f64> {
    let points = curve.input_points();
    let n = points.len();
    let mut s = vec![0.0];
    for i in 0..n {
        let step = match placement {
            NodePlacement::OnCurve => curve.arc_length(i as f64, (i + 1) as f64),
            NodePlacement::OnPolyline => (points[(i + 1) % n] - points[i]).norm(),
        };
        s.push(s[i] + step);
    }
    s
}

/// Arc position of parameter t (t in [0, n]).
pub fn arc_at(curve: &ClosedCurve, placement: NodePlacement, positions: &[f64], t: f64) -> f64 {
    match placement {
        NodePlacement::OnCurve => curve.arc_length(0.0, t),
        NodePlacement::OnPolyline => {
            let n = curve.segment_count();
            let i = (t.floor() as usize).min(n - 1);
            positions[i] + (t - i as f64) * (positions[i + 1] - positions[i])
        }
    }
}

/// The raw spacing cap at each geometry point, computed here independently of the crate:
/// min(l_α, δ), and min(l_extru, δ) at corners.
pub fn raw_caps(curve: &ClosedCurve, params: &SpacingParams) -> Vec<f64> {
    let points = curve.input_points();
    let n = points.len();
    (0..n)
        .map(|i| {
            if curve.is_corner(i) {
                return params.first_height.min(params.max_spacing);
            }
            let k = circumcircle_curvature(points[(i + n - 1) % n], points[i], points[(i + 1) % n]);
            let l_alpha = 2.0 * (params.refine_angle_deg.to_radians() / 2.0).cos() / k.abs();
            l_alpha.min(params.max_spacing)
        })
        .collect()
}

/// Summary figures of a checked mesh.
#[derive(Debug, Default, Clone, Copy)]
pub struct Figures {
    /// Largest ratio of neighbouring segment lengths (arc length).
    pub max_ratio: f64,
    /// Largest segment length divided by the cap over its span.
    pub max_cap_use: f64,
    /// Largest ratio of neighbouring chord lengths.
    pub max_chord_ratio: f64,
}

/// Every property a boundary mesh must have; returns the problems found (empty when valid)
/// and the summary figures.
pub fn check_mesh(
    curve: &ClosedCurve,
    params: &SpacingParams,
    nodes: &BoundaryNodes,
) -> (Vec<String>, Figures) {
    let mut problems = Vec::new();
    let mut figures = Figures::default();
    let n = curve.segment_count();
    let m = nodes.len();
    let size = geom_curve::loops::bounding_box_diagonal(curve.input_points());
    if m < 3 || nodes.points.len() != m || nodes.is_corner.len() != m {
        problems.push(format!("bad sizes: {m} nodes"));
        return (problems, figures);
    }
    // increasing parameters within [0, n)
    for k in 0..m {
        if !(nodes.t[k] >= 0.0 && nodes.t[k] < n as f64) {
            problems.push(format!("t[{k}] = {} outside [0, {n})", nodes.t[k]));
        }
        if k + 1 < m && nodes.t[k + 1] <= nodes.t[k] {
            problems.push(format!(
                "t not increasing at {k}: {} then {}",
                nodes.t[k],
                nodes.t[k + 1]
            ));
        }
    }
    // corners are nodes, flagged, and only they are flagged
    for &c in curve.corners() {
        match nodes.t.iter().position(|&t| t == c as f64) {
            Some(k) if nodes.is_corner[k] => {}
            _ => problems.push(format!("corner {c} is not a flagged node")),
        }
    }
    for k in 0..m {
        if nodes.is_corner[k]
            && !(nodes.t[k].fract() == 0.0 && curve.is_corner(nodes.t[k] as usize))
        {
            problems.push(format!(
                "node {k} flagged as a corner at t = {}",
                nodes.t[k]
            ));
        }
    }
    // nodes on the curve or the polygon
    for k in 0..m {
        let p = nodes.points[k];
        let distance = match params.placement {
            NodePlacement::OnCurve => curve.closest_point(p).2,
            NodePlacement::OnPolyline => {
                let i = (nodes.t[k].floor() as usize).min(n - 1);
                let (a, b) = (curve.input_points()[i], curve.input_points()[(i + 1) % n]);
                let f = nodes.t[k] - i as f64;
                (a + (b - a) * f - p).norm()
            }
        };
        if distance > 1e-9 * size {
            problems.push(format!(
                "node {k} is {distance:e} off the {:?} geometry",
                params.placement
            ));
        }
    }
    // segment lengths within the cap over their span, neighbour ratios within g
    let positions = arc_positions(curve, params.placement);
    let total = positions[n];
    let caps = raw_caps(curve, params);
    // a corner's cap (l_extru) holds at the corner only; along a segment leaving it the cap
    // is interpolated from the other end (δ when both ends are corners)
    let end_cap = |from: usize, other: usize| match (curve.is_corner(from), curve.is_corner(other))
    {
        (false, _) => caps[from],
        (true, false) => caps[other],
        (true, true) => params.max_spacing,
    };
    let cap_at = |s: f64| {
        let i = positions
            .partition_point(|&p| p <= s)
            .saturating_sub(1)
            .min(n - 1);
        let j = (i + 1) % n;
        let f = ((s - positions[i]) / (positions[i + 1] - positions[i])).clamp(0.0, 1.0);
        let interpolated = end_cap(i, j) + f * (end_cap(j, i) - end_cap(i, j));
        // at a corner itself its own cap applies
        if f == 0.0 {
            interpolated.min(caps[i])
        } else if f == 1.0 {
            interpolated.min(caps[j])
        } else {
            interpolated
        }
    };
    let s_nodes: Vec<f64> = nodes
        .t
        .iter()
        .map(|&t| arc_at(curve, params.placement, &positions, t))
        .collect();
    let mut lengths = Vec::with_capacity(m);
    for k in 0..m {
        let s0 = s_nodes[k];
        let s1 = if k + 1 < m {
            s_nodes[k + 1]
        } else {
            s_nodes[0] + total
        };
        let length = s1 - s0;
        lengths.push(length);
        // the cap over the span: at both ends and at every geometry point inside
        let mut cap = cap_at(s0).min(cap_at(s1 % total));
        for (i, &p) in positions.iter().enumerate().take(n) {
            for shifted in [p, p + total] {
                if shifted > s0 && shifted < s1 {
                    cap = cap.min(caps[i]);
                }
            }
        }
        let use_of_cap = length / cap;
        figures.max_cap_use = figures.max_cap_use.max(use_of_cap);
        if use_of_cap > 1.0 + 1e-9 {
            problems.push(format!(
                "segment {k} (t {} ..) has length {length:e} > cap {cap:e}",
                nodes.t[k]
            ));
        }
        if length > params.max_spacing * (1.0 + 1e-9) {
            problems.push(format!("segment {k} longer than max_spacing: {length:e}"));
        }
    }
    for k in 0..m {
        let (a, b) = (lengths[k], lengths[(k + 1) % m]);
        let ratio = (a / b).max(b / a);
        figures.max_ratio = figures.max_ratio.max(ratio);
        if ratio > params.growth * (1.0 + 1e-6) {
            problems.push(format!(
                "segments {k} and {} have ratio {ratio} > {}",
                (k + 1) % m,
                params.growth
            ));
        }
        let chord = |j: usize| (nodes.points[(j + 1) % m] - nodes.points[j]).norm();
        let (ca, cb) = (chord(k), chord((k + 1) % m));
        figures.max_chord_ratio = figures.max_chord_ratio.max((ca / cb).max(cb / ca));
    }
    (problems, figures)
}
