//! Curvature-driven 1D boundary meshes on geometry curves (dissertation §3.1.1; method.md §2):
//! where to put the nodes on each closed boundary loop before the layers are grown.
//!
//! The spacing law, in short (the full reasoning is in this crate's `README.md`):
//! 1. at every geometry point, `l_α = 2R·cos(α_refine/2)` from the circumcircle radius `R`
//!    through the point and its neighbours (infinite on straight parts), capped by the maximum
//!    spacing `δ`; at a corner the cap is the first extrusion height `l_extru` (and no more than its
//!    smooth neighbours' caps);
//! 2. break points are the local minima of that cap, and every corner;
//! 3. optionally (medial axis), every point's cap is lowered to what growth from every break
//!    point of every loop allows across the gap: `l_b + (g − 1)·d`, `d` the Euclidean distance;
//! 4. the cap is made gradable along each loop: `h(s) = min_s' cap(s') + (g − 1)·|s − s'|`
//!    (arc length `s`), the continuous form of "grow by at most `g` from a break point";
//! 5. nodes are placed at equal steps of `∫ ds/h` between consecutive corners, the step being
//!    the largest that provably keeps every segment within the cap over its span and the
//!    ratio of neighbouring segments within `g`. A rounding of the node count is absorbed by
//!    lowering the field only where it is largest.
//!
//! Nodes are placed by arc length on the C2 Hermite curve ([`NodePlacement::OnCurve`], the
//! "curved" boundary mesh) or on the polygon through the geometry points
//! ([`NodePlacement::OnPolyline`], the "linear" one); nothing else differs.
//!
//! Owns spacing and node placement only: the curves come from `geom-curve`, and the loops'
//! roles, orientation and nesting are the caller's business. No file IO.
//!
//! # Example
//!
//! Nodes on a NACA 0012 section (its C2 curve from `geom-curve`): dense at the leading edge
//! where the curvature is high, a node at the sharp trailing edge spaced at the first layer
//! height, and no two neighbouring segments more than the growth ratio apart.
//!
//! ```
//! use boundary1d::{SpacingParams, mesh_loop};
//! use geom_curve::{ClosedCurve, CurveParams, naca};
//!
//! let points = naca::naca4("0012", 81, true)?; // counter-clockwise, trailing edge first
//! let curve = ClosedCurve::new(&points, &CurveParams::default())?;
//! let params = SpacingParams {
//!     growth: 1.2,            // neighbouring segments differ by at most 20 %
//!     refine_angle_deg: 165.0, // three nodes on an arc make at least 165°
//!     max_spacing: 0.05,      // chords
//!     first_height: 1e-3,     // the spacing at corners
//!     ..SpacingParams::default()
//! };
//! let nodes = mesh_loop(&curve, &params)?;
//!
//! let n = nodes.len();
//! assert!(n > 40 && n < 400, "{n} nodes");
//! assert!(nodes.is_corner.iter().filter(|&&c| c).count() == 1); // the trailing edge
//! let seg: Vec<f64> = (0..n).map(|k| (nodes.points[(k + 1) % n] - nodes.points[k]).norm()).collect();
//! for k in 0..n {
//!     assert!(seg[k] <= 0.05 * (1.0 + 1e-9));
//!     // the law holds on arc lengths; chords follow to within a fraction of a per cent
//!     let ratio = seg[k].max(seg[(k + 1) % n]) / seg[k].min(seg[(k + 1) % n]);
//!     assert!(ratio <= 1.2 * 1.001, "segments {k}, {}: ratio {ratio}", k + 1);
//! }
//! // every node lies on the curve, at its parameter t
//! for (t, p) in nodes.t.iter().zip(&nodes.points) {
//!     assert!((curve.point(*t) - p).norm() < 1e-12);
//! }
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod check;
mod grading;
pub mod spacing;

use geom_curve::{ClosedCurve, Point2};
use serde::{Deserialize, Serialize};

pub use spacing::{LoopSpacing, spacing_limits, spacing_limits_with_caps};

/// Errors of this crate.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Boundary1dError {
    /// A spacing parameter is outside its valid range. Use a value in the stated range.
    #[error("invalid spacing parameter {name} = {value}: {reason}")]
    InvalidParameter {
        /// The field of [`SpacingParams`].
        name: &'static str,
        /// The value given.
        value: f64,
        /// The valid range.
        reason: &'static str,
    },
    /// The corner spacings of a loop could not be made consistent with the node count of a
    /// very short corner-to-corner stretch (the corner spacing is lowered repeatedly until
    /// it fits). Should not happen; if it does, lower `first_height` or remove the tiny edge.
    #[error(
        "loop {loop_index}: corner spacings did not settle after {iterations} adjustments; lower first_height or remove very short corner-to-corner edges"
    )]
    CornerSpacingDidNotSettle {
        /// Index of the loop in the input slice.
        loop_index: usize,
        /// Adjustments tried.
        iterations: usize,
    },
    /// The spacing law asks for more nodes than [`MAX_BOUNDARY_NODES`]. Raise `max_spacing`
    /// or the growth ratio, or make the far field smaller.
    #[error(
        "loop {loop_index}: the boundary mesh would need about {estimate:.3e} nodes, more than the limit of {limit}; raise max_spacing or the growth, or shrink the far field"
    )]
    TooManyNodes {
        /// The loop at which the running total passed the limit.
        loop_index: usize,
        /// Estimated nodes of all loops up to and including this one.
        estimate: f64,
        /// [`MAX_BOUNDARY_NODES`].
        limit: usize,
    },
    /// Somewhere the spacing would fall below [`MIN_RELATIVE_SPACING`] times the size of the
    /// loop's coordinates, which floating point cannot resolve.
    #[error(
        "loop {loop_index}: the boundary spacing would be {spacing:.3e} near ({x:e}, {y:e}), below {limit:.3e} (1e-12 of the coordinates' size, what floating point resolves); {advice}"
    )]
    SpacingBelowResolution {
        /// Index of the loop.
        loop_index: usize,
        /// The smallest spacing of the loop.
        spacing: f64,
        /// Where it occurs.
        x: f64,
        /// Where it occurs.
        y: f64,
        /// The smallest spacing allowed there.
        limit: f64,
        /// What to change.
        advice: &'static str,
    },
    /// Two consecutive nodes came out equal (a guard: the resolution check should prevent it).
    #[error(
        "loop {loop_index}: boundary nodes {node} and the next coincide at ({x:e}, {y:e}); the spacing is below what the coordinates resolve: raise first_height"
    )]
    NodesCoincide {
        /// Index of the loop.
        loop_index: usize,
        /// Index of the first node.
        node: usize,
        /// Where.
        x: f64,
        /// Where.
        y: f64,
    },
    /// The C2 splines through two loops' points cross each other although the polygons through
    /// their points do not.
    #[error(
        "the C2 splines through the points of loop {loop_a} and loop {loop_b} cross near ({x:e}, {y:e}), although the polygons through the points do not: add points there"
    )]
    SplinesCross {
        /// First loop.
        loop_a: usize,
        /// Second loop.
        loop_b: usize,
        /// Where.
        x: f64,
        /// Where.
        y: f64,
    },
    /// The polygon through a loop's boundary nodes crosses itself although its curve does
    /// not: the spacing is too coarse for a thin part of the loop.
    #[error(
        "loop {loop_index}: the boundary mesh crosses itself near ({x:e}, {y:e}) although the curve does not: the spacing is too coarse for a thin part there; lower max_spacing or refine_angle_deg"
    )]
    NodesCrossThemselves {
        /// The loop.
        loop_index: usize,
        /// Where.
        x: f64,
        /// Where.
        y: f64,
    },
    /// The polygons through two loops' boundary nodes cross although the curves do not: the
    /// spacing is too coarse for a narrow gap.
    #[error(
        "the boundary mesh of loop {loop_a} crosses that of loop {loop_b} near ({x:e}, {y:e}) although the curves do not: the spacing is too coarse for the gap there; lower max_spacing or turn medial_axis on"
    )]
    NodesCross {
        /// First loop.
        loop_a: usize,
        /// Second loop.
        loop_b: usize,
        /// Where.
        x: f64,
        /// Where.
        y: f64,
    },
}

/// Most boundary nodes [`mesh_loops`] will place over all loops together (10 million, some
/// 500 MB of boundary and layer data downstream); the count is estimated from the spacing
/// field before any node is allocated.
pub const MAX_BOUNDARY_NODES: usize = 10_000_000;

/// Smallest spacing relative to the size of a loop's coordinates (their largest magnitude):
/// below it, neighbouring nodes are fewer than ~5000 rounding units apart and the layers
/// grown from them cannot be told apart. The same ratio as the duplicate tolerance of
/// `geom_curve::LoopCheckParams`.
pub const MIN_RELATIVE_SPACING: f64 = 1e-12;

/// Where nodes go once their arc-length positions are known.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum NodePlacement {
    /// On the C2 Hermite curve, arc length measured along it (curved boundary mesh).
    #[default]
    OnCurve,
    /// On the straight edges between geometry points, arc length measured along the polygon
    /// (linear boundary mesh).
    OnPolyline,
}

/// The inputs of the spacing law `l_p = f(g_given, l_α, δ, l_extru)`. Lengths are in the units
/// of the geometry.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SpacingParams {
    /// `g_given`: the largest ratio between the lengths of neighbouring boundary segments.
    /// Must be > 1 (and at most 10); default 1.3.
    pub growth: f64,
    /// `α_refine`, degrees: the angle ∠ABC that three consecutive nodes on a circle of radius
    /// R may make, hence `l_α = 2R·cos(α_refine/2)`. In (90, 180); typical and default 165.
    /// The positive-Jacobian argument of the dissertation (§3.3.1) needs more than 135.
    pub refine_angle_deg: f64,
    /// `δ`: the maximum segment length. > 0; default 1.
    pub max_spacing: f64,
    /// `l_extru`: the first extrusion height of the layer mesh, used as the spacing at sharp
    /// corners (capped by `δ`). > 0; default 5e-5.
    pub first_height: f64,
    /// Whether to refine across narrow gaps (the optional medial-axis step): each point's
    /// spacing is capped by `l_b + (g − 1)·d` over the break points `b` of all loops, `d` the
    /// Euclidean distance. Default true.
    pub medial_axis: bool,
    /// Where the nodes go. Default [`NodePlacement::OnCurve`].
    pub placement: NodePlacement,
    /// The largest bulge `l²·κ/8` a segment may have off its chord (segment length `l`,
    /// curvature `κ`), in geometry units; infinite (the default) for no limit. A curving
    /// carries each wall edge's bulge up its stack of layers until the cells are tall enough
    /// to take it; where the whole stack is thinner than the bulge it cannot, so the meshing
    /// pipeline sets this to half the stack's height. > 0.
    #[serde(default = "no_bulge_limit")]
    pub max_bulge: f64,
}

fn no_bulge_limit() -> f64 {
    f64::INFINITY
}

impl Default for SpacingParams {
    fn default() -> Self {
        Self {
            growth: 1.3,
            refine_angle_deg: 165.0,
            max_spacing: 1.0,
            first_height: 5e-5,
            medial_axis: true,
            placement: NodePlacement::OnCurve,
            max_bulge: f64::INFINITY,
        }
    }
}

impl SpacingParams {
    /// Checks every field's range.
    ///
    /// # Errors
    /// [`Boundary1dError::InvalidParameter`] naming the first field out of range.
    pub fn validate(&self) -> Result<(), Boundary1dError> {
        let invalid = |name, value, reason| {
            Err(Boundary1dError::InvalidParameter {
                name,
                value,
                reason,
            })
        };
        if !(self.growth > 1.0 && self.growth <= 10.0) {
            return invalid("growth", self.growth, "must be > 1 and <= 10");
        }
        if !(self.refine_angle_deg > 90.0 && self.refine_angle_deg < 180.0) {
            return invalid(
                "refine_angle_deg",
                self.refine_angle_deg,
                "must be in (90, 180) degrees",
            );
        }
        if !(self.max_spacing > 0.0 && self.max_spacing.is_finite()) {
            return invalid(
                "max_spacing",
                self.max_spacing,
                "must be finite and positive",
            );
        }
        if !(self.first_height > 0.0 && self.first_height.is_finite()) {
            return invalid(
                "first_height",
                self.first_height,
                "must be finite and positive",
            );
        }
        if self.max_bulge.is_nan() || self.max_bulge <= 0.0 {
            return invalid("max_bulge", self.max_bulge, "must be positive");
        }
        Ok(())
    }
}

/// The nodes of one closed loop, in loop order (the last connects back to the first), starting
/// at the first node at or after `t = 0`, so that `t` increases strictly.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BoundaryNodes {
    /// Curve parameter of each node (see [`ClosedCurve`]: `t = i` is geometry point `i`).
    /// With [`NodePlacement::OnPolyline`], `t = i + f` means the fraction `f` along the
    /// straight edge from point `i` to point `i + 1`.
    pub t: Vec<f64>,
    /// Node positions.
    pub points: Vec<Point2<f64>>,
    /// Whether each node is a corner of the curve (every corner is a node).
    pub is_corner: Vec<bool>,
}

impl BoundaryNodes {
    /// Number of nodes (= number of boundary segments, the loop being closed).
    pub fn len(&self) -> usize {
        self.t.len()
    }

    /// Whether there are no nodes (never the case for a mesh returned by this crate).
    pub fn is_empty(&self) -> bool {
        self.t.is_empty()
    }
}

/// Meshes several loops together (the medial-axis step sees the break points of all of
/// them). Returns one [`BoundaryNodes`] per curve, in the same order.
///
/// # Errors
/// [`Boundary1dError::InvalidParameter`] for bad `params`;
/// [`Boundary1dError::SpacingBelowResolution`] when a spacing is too small for the
/// coordinates; [`Boundary1dError::TooManyNodes`] beyond [`MAX_BOUNDARY_NODES`];
/// [`Boundary1dError::SplinesCross`], [`Boundary1dError::NodesCross`],
/// [`Boundary1dError::NodesCrossThemselves`] or
/// [`Boundary1dError::NodesCoincide`] when the nodes would not make simple, disjoint
/// polygons; [`Boundary1dError::CornerSpacingDidNotSettle`] in the pathological case
/// described there.
pub fn mesh_loops(
    curves: &[ClosedCurve],
    params: &SpacingParams,
) -> Result<Vec<BoundaryNodes>, Boundary1dError> {
    let spacings = spacing_limits(curves, params)?;
    place_all(curves, spacings, &vec![*params; curves.len()])
}

/// [`mesh_loops`] where each loop has its own largest spacing `caps[i]` (a far field coarser
/// than the bodies, say); everything else comes from `params`.
///
/// # Errors
/// As [`mesh_loops`], and [`Boundary1dError::InvalidParameter`] when `caps` does not have one
/// finite positive value per curve.
pub fn mesh_loops_with_caps(
    curves: &[ClosedCurve],
    params: &SpacingParams,
    caps: &[f64],
) -> Result<Vec<BoundaryNodes>, Boundary1dError> {
    let spacings = spacing_limits_with_caps(curves, params, caps)?;
    place_all(
        curves,
        spacings,
        &spacing::per_loop(curves.len(), params, Some(caps))?,
    )
}

/// Plans every loop (node counts bounded by [`MAX_BOUNDARY_NODES`] in total before any node
/// is allocated), places the nodes and checks the result.
fn place_all(
    curves: &[ClosedCurve],
    spacings: Vec<LoopSpacing>,
    params: &[SpacingParams],
) -> Result<Vec<BoundaryNodes>, Boundary1dError> {
    for (loop_index, (curve, spacing)) in curves.iter().zip(&spacings).enumerate() {
        check::resolution(curve, spacing, loop_index)?;
    }
    let mut plans = Vec::with_capacity(curves.len());
    let mut total = 0usize;
    for (loop_index, (spacing, p)) in spacings.into_iter().zip(params).enumerate() {
        let plan = grading::plan_nodes(spacing, p, loop_index, MAX_BOUNDARY_NODES - total)
            .map_err(|e| match e {
                Boundary1dError::TooManyNodes {
                    loop_index,
                    estimate,
                    limit,
                } => Boundary1dError::TooManyNodes {
                    loop_index,
                    estimate: estimate + total as f64,
                    limit: limit + total,
                },
                other => other,
            })?;
        total += plan.node_count();
        plans.push(plan);
    }
    let meshes: Vec<BoundaryNodes> = curves
        .iter()
        .zip(&plans)
        .zip(params)
        .map(|((curve, plan), p)| grading::place_nodes(curve, plan, p))
        .collect();
    check::nodes(curves, &meshes)?;
    Ok(meshes)
}

/// Meshes one loop on its own ([`mesh_loops`] with a single curve).
///
/// # Errors
/// As [`mesh_loops`].
pub fn mesh_loop(
    curve: &ClosedCurve,
    params: &SpacingParams,
) -> Result<BoundaryNodes, Boundary1dError> {
    let mut all = mesh_loops(std::slice::from_ref(curve), params)?;
    Ok(all.remove(0))
}
