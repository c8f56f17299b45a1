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
//! use tet_fill::delaunay;
//!
//! // Delaunay of the unit cube's corners (co-spherical: any valid split will do)
//! let cube: Vec<[f64; 3]> = (0..8)
//!     .map(|i| [(i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64])
//!     .collect();
//! let tets = delaunay(&cube).unwrap();
//! assert!(tets.len() >= 5);
//! ```

mod build;
mod error;
mod insert;
mod mesh;
mod order;

pub use build::delaunay;
pub use error::FillError;
