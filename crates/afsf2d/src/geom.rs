//! Planar names used across afsf2d: a point is `[f64; 2]` and a box is 2D. The predicates
//! themselves (exact orientation, segment crossing and distance, projection, sort-and-sweep)
//! and the polygon area are the shared ones of `geom-predicates`.

pub(crate) type P2 = [f64; 2];

/// An axis-aligned 2D box for the sort-and-sweep of `geom-predicates`.
pub(crate) type Aabb = geom_predicates::Aabb<2>;
