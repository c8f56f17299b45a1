//! Shared geometric predicates and spatial search for the curvemesh crates, in one place so
//! that every crate decides "left of", "crossing" and "inside" the same way: exact orientation
//! in 2D and 3D and the exact in-sphere test (Shewchuk's adaptive predicates from the `robust` crate), segment–segment
//! intersection (proper or touching) and segment/triangle–triangle intersection in 3D decided
//! on exact signs, point projection and distances to segments, polylines and loops, point in
//! loop by an exact winding number, polygon area, a sort-and-sweep broad phase over boxes, and a k-d tree
//! (over `kiddo`) for nearest-point and within-radius queries.
//!
//! Points are plain `[f64; D]`; functions are generic over `const D` where the geometry allows
//! it. Loop and polyline functions take any `P: Copy + Into<[f64; D]>` (so `nalgebra` points
//! work without a copy). No IO, no allocation except where a function returns a `Vec` (and
//! the sweep's sort order).
//!
//! ```
//! use geom_predicates::{Aabb, PointTree, Sign, SegmentMeet, orient2d_sign, point_in_loop,
//!     segment_meet, overlapping_pairs};
//!
//! // exact orientation: a left turn, and a collinear triple that floating point would blur
//! assert_eq!(orient2d_sign([0.0, 0.0], [1.0, 0.0], [0.0, 1.0]), Sign::Positive);
//! assert_eq!(orient2d_sign([0.1, 0.1], [0.2, 0.2], [0.3, 0.3]), Sign::Zero);
//!
//! // segments: a proper crossing and an end point touching
//! assert_eq!(segment_meet([0.0, 0.0], [2.0, 2.0], [0.0, 2.0], [2.0, 0.0]), SegmentMeet::Proper);
//! assert!(matches!(segment_meet([0.0, 0.0], [2.0, 0.0], [1.0, 0.0], [1.0, 1.0]),
//!     SegmentMeet::Touch(_)));
//!
//! // point in a clockwise square
//! let square = [[0.0, 0.0], [0.0, 1.0], [1.0, 1.0], [1.0, 0.0]];
//! assert!(point_in_loop([0.5, 0.5], &square));
//! assert!(!point_in_loop([1.5, 0.5], &square));
//!
//! // broad phase: only the first two boxes overlap
//! let boxes = [
//!     Aabb::of_segment([0.0, 0.0], [1.0, 1.0], 0.0),
//!     Aabb::of_segment([0.5, 0.5], [2.0, 0.5], 0.0),
//!     Aabb::of_segment([5.0, 0.0], [6.0, 1.0], 0.0),
//! ];
//! assert_eq!(overlapping_pairs(&boxes), vec![(0, 1)]);
//!
//! // nearest point
//! let tree = PointTree::new(&[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 3.0, 0.0]]);
//! assert_eq!(tree.nearest([0.9, 0.2, 0.0]).map(|(i, _)| i), Some(1));
//! ```

mod orient;
mod polygon;
mod segment;
mod sweep;
mod tree;
mod triangle;
pub mod vector;

pub use orient::{Sign, insphere, insphere_sign, orient2d, orient2d_sign, orient3d, orient3d_sign};
pub use polygon::{point_in_loop, polygon_area, winding_number};
pub use segment::{
    Endpoint, SegmentMeet, closest_on_segment, distance_to_loop, distance_to_polyline,
    point_segment_distance, project_on_segment, segment_distance, segment_intersection,
    segment_meet, segments_meet,
};
pub use sweep::{Aabb, find_overlapping_pair, for_each_overlapping_pair, overlapping_pairs};
pub use tree::PointTree;
pub use triangle::{segment_meets_triangle, triangles_meet};
