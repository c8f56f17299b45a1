//! The crate's one error type: what can be wrong with the boundary loops or the parameters,
//! and the one internal failure (the hole filling refused the fronts) reported instead of a
//! panic.

use thiserror::Error;

/// Why a mesh could not be made.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum AfsfError {
    /// No loop was given. Fix: give a far-field loop and wall loops, or one wall loop with
    /// `inside = true`.
    #[error("no boundary loop given")]
    NoLoop,
    /// A loop has fewer than three points. Fix: mesh the boundary curve first.
    #[error("loop {index} ({name}) has {points} points; a closed loop needs at least 3")]
    TooFewPoints {
        /// Loop index in the input.
        index: usize,
        /// Loop name.
        name: String,
        /// Number of points.
        points: usize,
    },
    /// `is_corner` does not have one flag per point. Fix: give one flag per point.
    #[error("loop {index} ({name}) has {points} points but {flags} corner flags")]
    CornerFlagsMismatch {
        /// Loop index.
        index: usize,
        /// Loop name.
        name: String,
        /// Number of points.
        points: usize,
        /// Number of flags.
        flags: usize,
    },
    /// A coordinate is NaN or infinite.
    #[error("loop {index} ({name}) point {point} is not finite")]
    NonFinitePoint {
        /// Loop index.
        index: usize,
        /// Loop name.
        name: String,
        /// Point index.
        point: usize,
    },
    /// Two consecutive points coincide (including the last and the first: do not repeat the
    /// first point at the end).
    #[error(
        "loop {index} ({name}) points {point} and the next coincide (do not repeat the first point at the end)"
    )]
    RepeatedPoint {
        /// Loop index.
        index: usize,
        /// Loop name.
        name: String,
        /// Point index.
        point: usize,
    },
    /// The loops do not describe a domain: the message says what was expected.
    #[error("bad loop set: {0}")]
    BadLoopSet(String),
    /// Two boundary edges cross or touch (in one loop or between loops).
    #[error("boundary edges cross: loop {loop_a} edge {edge_a} and loop {loop_b} edge {edge_b}")]
    LoopsCross {
        /// First loop.
        loop_a: usize,
        /// Its edge (from point `edge_a` to the next).
        edge_a: usize,
        /// Second loop.
        loop_b: usize,
        /// Its edge.
        edge_b: usize,
    },
    /// A wall loop is not inside the far-field loop, or one wall is inside another.
    #[error("loop {index} ({name}) is not placed as its role requires: {what}")]
    Misplaced {
        /// Loop index.
        index: usize,
        /// Loop name.
        name: String,
        /// What is wrong.
        what: &'static str,
    },
    /// A parameter is out of range (named in the message).
    #[error("parameter `{name}` = {value} is out of range: {expected}")]
    BadParameter {
        /// Parameter name.
        name: &'static str,
        /// Its value.
        value: f64,
        /// What it should be.
        expected: &'static str,
    },
    /// Two loops come so near each other that no cell across the gap can have all its angles
    /// below `gap_max_angle_deg` with these boundary nodes: the nodes of the two sides do
    /// not face each other and are spaced far wider than the gap. Fix: refine the boundary
    /// there (spacing at most about twice the gap), or widen the gap.
    #[error(
        "narrow gap between loop {loop_a} ({name_a}) and loop {loop_b} ({name_b}) at ({x:.6e}, {y:.6e}): width {width:.3e}, but the boundary nodes there are {spacing:.3e} apart and do not face each other (a cell across it would have an angle of {angle:.1}°); refine the boundary there to a spacing of at most {fits_spacing:.2e} (a first height of at most {fits_height:.2e} fits in the gap) or widen the gap"
    )]
    NarrowGap {
        /// Loop of the facet with no usable cell across the gap.
        loop_a: usize,
        /// Its name.
        name_a: String,
        /// The loop it faces.
        loop_b: usize,
        /// Its name.
        name_b: String,
        /// Width of the gap.
        width: f64,
        /// A point in the gap.
        x: f64,
        /// A point in the gap.
        y: f64,
        /// Boundary node spacing there.
        spacing: f64,
        /// The best largest angle of a triangle across the gap on that facet (degrees).
        angle: f64,
        /// A boundary spacing that resolves the gap.
        fits_spacing: f64,
        /// A first height that leaves room for layers from both sides.
        fits_height: f64,
    },
    /// The spring parameters are invalid.
    #[error(transparent)]
    Spring(#[from] springfield::SpringError),
    /// The region left between the fronts could not be triangulated (a bug: the fronts are
    /// kept simple and disjoint by construction). Please report it with the input loops.
    #[error("hole filling failed: {0}")]
    Fill(String),
}
