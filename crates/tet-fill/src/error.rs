//! The errors of the fill: one line each, naming the point or facet and where it is.

/// Why a fill (or a Delaunay tetrahedralisation) failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FillError {
    /// A coordinate is NaN or infinite.
    #[error("point {index} is not finite: {point:?}")]
    NonFinitePoint {
        /// The point's index in the input.
        index: usize,
        /// Its coordinates.
        point: [f64; 3],
    },
    /// Two input points have identical coordinates.
    #[error("points {first} and {second} are the same point {point:?}")]
    DuplicatePoint {
        /// The lower index.
        first: usize,
        /// The higher index.
        second: usize,
        /// The coordinates they share.
        point: [f64; 3],
    },
    /// A facet names a point that does not exist.
    #[error("facet {facet} names point {index}, but there are only {points} points")]
    FacetIndexOutOfRange {
        /// The facet's index.
        facet: usize,
        /// The index out of range.
        index: u32,
        /// How many points there are.
        points: usize,
    },
    /// A facet's corners are not three distinct non-collinear points.
    #[error("facet {facet} {corners:?} is degenerate (repeated or collinear corners)")]
    DegenerateFacet {
        /// The facet's index.
        facet: usize,
        /// Its corners.
        corners: [[f64; 3]; 3],
    },
    /// Every point lies in one plane: there is no volume to fill.
    #[error("all {points} points lie in one plane: nothing to tetrahedralise")]
    Flat {
        /// How many points there are.
        points: usize,
    },
    /// A facet is missing from the tetrahedralisation and neither flips nor Steiner points off
    /// the surfaces brought it back.
    #[error("facet {facet} {corners:?} cannot be recovered: {why}")]
    Unrecoverable {
        /// The facet's index.
        facet: usize,
        /// Its corners.
        corners: Box<[[f64; 3]; 3]>,
        /// What was missing (an edge, the facet itself) and why.
        why: String,
        /// The facet's edge missing from the tetrahedralisation (input point indices), when
        /// an edge is what could not be recovered: a caller may change its surfaces there
        /// (e.g. cap the two facets on that edge) and try again.
        edge: Option<[u32; 2]>,
        /// Every input edge missing from the tetrahedralisation when the fill gave up (input
        /// point indices, each once): a caller changing its surfaces can mend them all before
        /// trying again.
        missing_edges: Vec<[u32; 2]>,
    },
    /// The region is inconsistently oriented: a facet has the fill on both sides or on none
    /// (normals pointing into the fill on one surface and out of it on another, or a surface
    /// that is not closed).
    #[error(
        "region inconsistently oriented at facet {facet} {corners:?}: both its sides classify as {side}"
    )]
    InconsistentOrientation {
        /// The facet's index.
        facet: usize,
        /// Its corners.
        corners: [[f64; 3]; 3],
        /// "inside" or "outside".
        side: &'static str,
    },
    /// Refinement or recovery would add more points than [`crate::FillOptions::max_points`].
    #[error("more than {limit} points would be inserted (max_points)")]
    TooManyPoints {
        /// The cap.
        limit: usize,
    },
    /// A point the Delaunay insertion could not place (its cavity came out empty): with exact
    /// predicates it does not happen, but a lost input point would leave its facets
    /// unrecoverable, so it is said rather than skipped.
    #[error("point {index} {point:?} could not be inserted (an empty cavity): an internal fault")]
    PointNotInserted {
        /// The point's index.
        index: usize,
        /// Its coordinates.
        point: [f64; 3],
    },
}
