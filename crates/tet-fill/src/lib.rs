//! A constrained Delaunay tetrahedraliser: fills the region between closed triangulated
//! surfaces (a far field with its normals pointing in, bodies with theirs pointing out) with
//! positive tetrahedra whose boundary faces are exactly the input facets — never split, so the
//! fill conforms to meshes built around it. The stages: Bowyer–Watson insertion of the input
//! points with exact `orient3d` and `insphere` (BRIO order, visibility walk, ghost tets
//! closing the hull); recovery of the facets that are missing, by flips and then by Steiner
//! points off the surfaces; classification of the tets inside the region by a flood fill
//! from the facets; Delaunay refinement towards a graded size field and a radius–edge bound,
//! never encroaching a facet; sliver removal by flips and smoothing.
//!
//! ```
//! use tet_fill::{FillInput, FillOptions, delaunay, fill};
//!
//! // Delaunay of the unit cube's corners (co-spherical: any valid split will do)
//! let cube: Vec<[f64; 3]> = (0..8)
//!     .map(|i| [(i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64])
//!     .collect();
//! let tets = delaunay(&cube).unwrap();
//! assert!(tets.len() >= 5);
//!
//! // fill a tetrahedron's inside: its facets turn counter-clockwise seen from inside
//! let points = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
//! let facets = [[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]];
//! let input = FillInput { points: &points, facets: &facets };
//! let out = fill(&input, &FillOptions::default()).unwrap();
//! assert_eq!(out.tets.len(), 1);
//! assert_eq!(out.points.len(), 4);
//! ```

mod build;
mod cavity;
mod error;
mod fill;
mod flip;
mod insert;
mod insphere;
mod intersect;
mod mesh;
mod order;
mod quality;
mod recover;
mod refine;
mod region;
mod sliver;

pub use build::delaunay;
pub use error::FillError;

/// Options of the fill.
#[derive(Debug, Clone, PartialEq)]
pub struct FillOptions {
    /// Refine until every tet's circumradius over its shortest edge is at most this (default
    /// 2.0); 0 or infinite: no radius–edge refinement.
    pub max_radius_edge: f64,
    /// No tet edge longer than this where the size field allows (default infinite).
    pub max_size: f64,
    /// Growth of the size field away from the facets: a point's size is at most the nearest
    /// facet point's size plus `(grading - 1)` times the distance to it (default 1.3); a
    /// facet point's size is the mean length of its facets' edges. Infinite: no refinement
    /// for size.
    pub grading: f64,
    /// Sliver removal target: the largest dihedral angle in degrees (default 150).
    pub max_dihedral_deg: f64,
    /// The cap on the points of the fill, input ones included (default 10 000 000): beyond it,
    /// an error.
    pub max_points: usize,
}

impl Default for FillOptions {
    fn default() -> Self {
        Self {
            max_radius_edge: 2.0,
            max_size: f64::INFINITY,
            grading: 1.3,
            max_dihedral_deg: 150.0,
            max_points: 10_000_000,
        }
    }
}

/// The region to fill: closed triangulated surfaces (any number of components), each facet's
/// corners counter-clockwise seen from inside the region to fill (its normal points into the
/// fill) — e.g. a far-field sphere with inward normals plus bodies with outward normals.
#[derive(Debug, Clone, Copy)]
pub struct FillInput<'a> {
    /// The surfaces' points (distinct, finite).
    pub points: &'a [[f64; 3]],
    /// The facets, three point indices each.
    pub facets: &'a [[u32; 3]],
}

/// The tetrahedra filling the region.
#[derive(Debug, Clone, PartialEq)]
pub struct Fill {
    /// The input points first, in order and bit-identical; Steiner and refinement points after.
    pub points: Vec<[f64; 3]>,
    /// The region's tets, each positive (`geom_predicates::orient3d > 0` of its corners in
    /// order). Every input facet is a face of exactly one of them, on its normal's side; every
    /// other face is shared by two.
    pub tets: Vec<[u32; 4]>,
    /// Points added off the input facets to recover them (never on an input facet or edge).
    pub steiner_points: usize,
    /// Points added by refinement.
    pub refinement_points: usize,
    /// The largest dihedral angle of the tets, in degrees.
    pub max_dihedral_deg: f64,
}

/// Fills the region bounded by the input facets with tetrahedra conforming to every facet
/// (never split): Delaunay of the points, facets recovered, region kept, refined, slivers
/// removed. Errors name the point or facet at fault.
pub fn fill(input: &FillInput, options: &FillOptions) -> Result<Fill, FillError> {
    fill::run(input, options)
}
