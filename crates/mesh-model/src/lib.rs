//! The shared mesh data model: node coordinates, mixed linear and high-order cells in Gmsh's
//! node order, boundary facets grouped in patches with a role (wall, far field), and the
//! per-cell layer index and "pipe" that the curving and movement stages need.
//!
//! It owns the types and the structural checks ([`validate()`]) and nothing else: no file
//! formats (that is `mesh-io`), no geometry and no meshing algorithm.

pub mod cell;
pub mod cells;
pub mod measure;
pub mod mesh;
pub mod reference;
pub mod validate;

pub use cell::{CellType, Shape};
pub use cells::{CellRef, Cells};
pub use mesh::{Dim, Mesh, NONE, Patch, Role, is_positive_polygon, polygon_area};
pub use validate::{Problem, validate};
