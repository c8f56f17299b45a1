//! Geometry curves for the boundary of a 2D domain: reading loops of points (Selig and
//! Lednicer `.dat` text, NACA 4-digit sections, circles), checking that a loop is a simple closed polygon and
//! that loops do not cross, the approximate (circumcircle) curvature of the dissertation
//! (§3.1.1), and the C2 piecewise quintic Hermite curve through the points with C0 breaks at
//! sharp corners (§3.1.2), with evaluation, arc length, its inverse and the closest point.
//!
//! It owns geometry only: no file IO (parsers take `&str`), no mesh spacing (that is
//! `boundary1d`), no knowledge of roles such as wall or far field. Points are
//! [`nalgebra::Point2<f64>`] and vectors [`nalgebra::Vector2<f64>`], re-exported here as
//! [`Point2`] and [`Vector2`] so that callers need not depend on nalgebra themselves.
//!
//! Conventions used throughout: a loop is a slice of `n` points, closed implicitly (the first
//! point is not repeated); edge `i` runs from point `i` to point `(i + 1) % n`, so edge `n - 1`
//! is the closing edge. Counter-clockwise loops have positive signed area.
//!
//! # Example
//!
//! A NACA 0012 section from its Selig `.dat` file (a title line, then `x y` from the upper
//! trailing edge over the upper surface and back under the lower one; this one has a blunt
//! trailing edge, 0.25 % of the chord thick), fitted by a C2 curve whose only corners are the
//! two ends of the trailing-edge base, and its curvature (1/chord) at the leading edge and at
//! mid-chord. The caller reads the file; the crate takes the text.
//!
//! ```
//! use geom_curve::{ClosedCurve, CurveParams, loops, selig};
//!
//! let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/data/naca0012.dat"))?;
//! let mut points = selig::parse(&text)?;
//! let n = points.len(); // 131
//! loops::validate_loop(&points, &CurveParams::default().loop_checks)?; // simple, closed
//! loops::make_counter_clockwise(&mut points); // Selig files are; other sources may not be
//!
//! let curve = ClosedCurve::new(&points, &CurveParams::default())?;
//! assert_eq!(curve.corners(), &[0, n - 1]); // the base's ends; the leading edge is smooth
//! // the curve interpolates its points: parameter t = i is point i
//! let le = (0..n).min_by(|&a, &b| points[a].x.total_cmp(&points[b].x)).unwrap();
//! assert_eq!(curve.point(le as f64), points[le]);
//! // a NACA 0012's leading-edge radius is 1.1019 · 0.12² ≈ 0.0159 chords: κ ≈ 63
//! let k_le = curve.curvature(le as f64);
//! assert!((k_le - 63.0).abs() < 10.0, "{k_le}");
//! assert!(curve.curvature(le as f64 / 2.0).abs() < 1.0); // mid-chord, upper surface
//! // arc length and its inverse: the upper surface is a little longer than the chord
//! let upper = curve.arc_length(0.0, le as f64);
//! assert!(upper > 1.0 && upper < 1.05, "{upper}");
//! assert!((curve.t_at_arc_length(upper) - le as f64).abs() < 1e-9);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! [`naca::naca4`] makes the same section from its four digits, at any resolution.

pub mod curvature;
mod dat_lines;
pub mod hermite;
pub mod lednicer;
pub mod loops;
pub mod naca;
mod quadrature;
pub mod selig;
mod shapes;

pub use hermite::{ClosedCurve, CurveParams, HermiteSegment};
pub use loops::LoopCheckParams;
pub use nalgebra::{Point2, Vector2};
pub use shapes::circle_points;

/// Most points a generated loop (circle, NACA section) may have: the points define the
/// geometry, not the mesh spacing, and a million is far beyond any resolution a curve needs.
/// Checked before anything is allocated.
pub const MAX_GENERATED_POINTS: usize = 1_000_000;

/// Everything that can go wrong when reading or checking geometry in this crate.
///
/// Each message is one line that names the fault (line number, point or edge index, value).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CurveError {
    /// A coordinate line of a Selig file is not exactly two numbers. Fix or delete that line
    /// (line 1 is always taken as the title).
    #[error("line {line}: expected two numbers \"x y\", found {content:?}")]
    MalformedLine {
        /// 1-based line number in the text.
        line: usize,
        /// The offending line, trimmed.
        content: String,
    },
    /// A coordinate in a Selig file is NaN or infinite. Replace it with a finite number.
    #[error("line {line}: coordinate is not finite in {content:?}")]
    NonFiniteCoordinate {
        /// 1-based line number in the text.
        line: usize,
        /// The offending line, trimmed.
        content: String,
    },
    /// A loop has fewer than three points (after dropping a repeated closing point). Give at
    /// least three distinct points.
    #[error("a closed loop needs at least 3 points, found {count}")]
    TooFewPoints {
        /// Number of points found.
        count: usize,
    },
    /// A point has a NaN or infinite coordinate. Fix the point.
    #[error("point {index} is not finite: ({x}, {y})")]
    NonFinitePoint {
        /// Index of the point in the loop.
        index: usize,
        /// Its x coordinate.
        x: f64,
        /// Its y coordinate.
        y: f64,
    },
    /// Two consecutive points (the last and the first included) coincide within the relative
    /// tolerance. Remove one of them.
    #[error(
        "points {index} and {next} coincide (distance {distance:.3e} <= tolerance {tolerance:.3e}); remove one of them"
    )]
    DuplicatePoint {
        /// Index of the first point.
        index: usize,
        /// Index of the following point (0 for the closing edge).
        next: usize,
        /// Their distance.
        distance: f64,
        /// The tolerance: the relative tolerance times the loop's bounding-box diagonal.
        tolerance: f64,
    },
    /// The implied closing edge is much longer than every other edge and a sizeable part of
    /// the perimeter: the points probably describe an open curve (for example a Lednicer
    /// file read as Selig, or a surface listed only once). Close the loop or add points.
    #[error(
        "the loop looks open: the gap between last and first point is {gap:.4e} (longest other edge {longest_edge:.4e}, perimeter {perimeter:.4e}); close the loop or add points"
    )]
    OpenLoop {
        /// Length of the closing edge.
        gap: f64,
        /// Length of the longest other edge.
        longest_edge: f64,
        /// Perimeter of the loop, closing edge included.
        perimeter: f64,
    },
    /// Two non-adjacent edges of a loop touch or cross, or two adjacent edges fold back onto
    /// each other. Fix the point order or remove the stray points.
    #[error("the loop intersects itself: edge {edge_a} and edge {edge_b} meet at ({x}, {y})")]
    SelfIntersection {
        /// Index of the first edge (edge i runs from point i to point i+1).
        edge_a: usize,
        /// Index of the second edge.
        edge_b: usize,
        /// x of a common point.
        x: f64,
        /// y of a common point.
        y: f64,
    },
    /// Two different loops touch or cross. Move or scale one of them.
    #[error("loop {loop_a} (edge {edge_a}) crosses loop {loop_b} (edge {edge_b}) at ({x}, {y})")]
    LoopsCross {
        /// Index of the first loop.
        loop_a: usize,
        /// Edge of the first loop.
        edge_a: usize,
        /// Index of the second loop.
        loop_b: usize,
        /// Edge of the second loop.
        edge_b: usize,
        /// x of a common point.
        x: f64,
        /// y of a common point.
        y: f64,
    },
    /// A coordinate is larger in magnitude than [`loops::MAX_COORDINATE`] (1e20): beyond it the
    /// squares and products of lengths that later stages form, and the Delaunay library's own
    /// limits, leave no margin. Scale the geometry down (change its units).
    #[error(
        "point {index} ({x:e}, {y:e}) is too large: coordinates must lie within ±1e20 (the supported range, see the README); scale the geometry down"
    )]
    CoordinateTooLarge {
        /// Index of the point in the loop.
        index: usize,
        /// Its x coordinate.
        x: f64,
        /// Its y coordinate.
        y: f64,
    },
    /// A loop spans less than [`loops::MIN_LOOP_SIZE`] (1e-20): the relative tolerances and the
    /// first heights of the mesh would reach the limits of floating point and of the Delaunay
    /// library. Scale the geometry up (change its units).
    #[error(
        "the loop is too small: it spans {size:.3e} (bounding-box diagonal), the supported range is 1e-20 to 1e20 (see the README); scale the geometry up"
    )]
    LoopTooSmall {
        /// The loop's bounding-box diagonal.
        size: f64,
    },
    /// One point lies so far from all the others that their own distances fall below the
    /// duplicate tolerance (relative to the whole loop's size). Fix or remove that point.
    #[error(
        "point {index} ({x:e}, {y:e}) lies {distance:.3e} away from the other points, which span only {rest:.3e}: a stray point? fix or remove it"
    )]
    OutlierPoint {
        /// Index of the point in the loop.
        index: usize,
        /// Its x coordinate.
        x: f64,
        /// Its y coordinate.
        y: f64,
        /// Its distance from the bounding box of the other points.
        distance: f64,
        /// The bounding-box diagonal of the other points.
        rest: f64,
    },
    /// The polygon through the points is simple, but the C2 spline fitted through them crosses
    /// itself (it overshoots where the points turn sharply without being a corner). Add
    /// points there, or make the turn sharp enough to be a corner.
    #[error(
        "the C2 spline through the points crosses itself near ({x:e}, {y:e}), between input points {from_a}-{to_a} and {from_b}-{to_b}: add points there or make that turn a sharp corner (more than 40 degrees)"
    )]
    SplineCrossesItself {
        /// Start of the first piece (input point index).
        from_a: usize,
        /// End of the first piece.
        to_a: usize,
        /// Start of the second piece.
        from_b: usize,
        /// End of the second piece.
        to_b: usize,
        /// x of a common point.
        x: f64,
        /// y of a common point.
        y: f64,
    },
    /// A NACA designation is not a valid 4-digit section. Give four digits `MPTT` with a
    /// camber position `P` > 0 when the camber `M` > 0, and a thickness `TT` > 0.
    #[error("invalid NACA 4-digit designation {digits:?}: {reason}")]
    InvalidNaca {
        /// The designation as given.
        digits: String,
        /// What is wrong with it.
        reason: &'static str,
    },
    /// A numeric parameter is out of its valid range. Use a value within the stated range.
    #[error("invalid parameter {name} = {value}: {reason}")]
    InvalidParameter {
        /// The parameter's name.
        name: &'static str,
        /// The value given.
        value: f64,
        /// The valid range or the reason.
        reason: &'static str,
    },
}
