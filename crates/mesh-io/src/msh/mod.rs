//! Gmsh MSH 4.1, ASCII and binary: the writers ([`write()`], [`write_to`], and
//! [`write_binary_to`] for binary) and the reader ([`read`], [`parse`]), which reads both.
//! A binary file (file type 1) holds the same sections, with `$Entities`, `$Nodes` and
//! `$Elements` as little-endian numbers (`int` 4 bytes, `size_t` 8, `double` 8) followed by
//! a newline, as Gmsh writes them; names and our patch section stay text.
//!
//! What is written, for a mesh of dimension `d`:
//! - `$PhysicalNames`: one group `fluid` of dimension `d` holding every domain cell, and one
//!   group of dimension `d − 1` per boundary group ([`crate::groups`]: each wall named after
//!   its patch, `slat`, `main`, `flap`; one `farfield`). Physical tags are unique across
//!   dimensions (`fluid` is 1, the boundary groups follow), as PyFR requires.
//! - `$Entities` (with bounding boxes): one entity of dimension `d − 1` per patch (a curve per
//!   boundary loop in 2D), tag = patch index + 1, in its group; one entity of
//!   dimension `d`, tag 1, in `fluid`, bounded by all the patch entities. No point entities.
//! - `$Nodes`: one block, every node classified on the domain entity, tag = index + 1, in the
//!   data model's order; coordinates in shortest round-trip form (never NaN: a non-finite node
//!   is an error and nothing is written).
//! - `$Elements`: one block per (entity, element type). Cell `i` gets element tag `i + 1`,
//!   boundary facet `j` gets tag `cells + j + 1`, so the reader restores the original order.
//!   Node order inside each element is the data model's, which is Gmsh's.
//! - `$MeshIoPatches` (a section of ours, which Gmsh and PyFR skip): `tag role "name"` for
//!   each boundary entity, so that names and roles survive a round trip (files written before
//!   roles were recorded, `tag "name"`, are still read).
//!
//! What survives a write → read round trip: dimension, order, nodes (bit for bit), cells with
//! their types and node order, boundary facets with their order, patches with names and roles.
//! What does not: `cell_layer` and `cell_pipe` (they live in snapshots, see
//! [`crate::snapshot`]).
//!
//! The reader accepts any MSH 4.1 ASCII file of complete Lagrange elements of order 1 to 3
//! (see [`read`] for how it decides the dimension, the domain cells, the boundary facets and
//! the patches), including linear triangle surface meshes (read as a 3D mesh with boundary
//! facets and no cells).

mod read;
mod write;

use mesh_model::{CellType, Shape};

pub use read::{parse, read};
pub use write::{write, write_binary_to, write_to};

/// Name of the custom section holding patch names.
pub(crate) const PATCH_SECTION: &str = "MeshIoPatches";

/// Physical group name of the domain cells.
pub const FLUID_GROUP: &str = "fluid";

/// Gmsh element type numbers of the complete Lagrange cells, as listed in Gmsh's
/// `GmshDefines.h` and reported by `gmsh.model.mesh.getElementProperties` (checked by the
/// test `element_types_match_gmsh_reference` against a table dumped from Gmsh itself).
const TYPE_TABLE: [(Shape, u8, u32); 21] = [
    (Shape::Line, 1, 1),
    (Shape::Line, 2, 8),
    (Shape::Line, 3, 26),
    (Shape::Tri, 1, 2),
    (Shape::Tri, 2, 9),
    (Shape::Tri, 3, 21),
    (Shape::Quad, 1, 3),
    (Shape::Quad, 2, 10),
    (Shape::Quad, 3, 36),
    (Shape::Tet, 1, 4),
    (Shape::Tet, 2, 11),
    (Shape::Tet, 3, 29),
    (Shape::Hex, 1, 5),
    (Shape::Hex, 2, 12),
    (Shape::Hex, 3, 92),
    (Shape::Prism, 1, 6),
    (Shape::Prism, 2, 13),
    (Shape::Prism, 3, 90),
    (Shape::Pyramid, 1, 7),
    (Shape::Pyramid, 2, 14),
    (Shape::Pyramid, 3, 118),
];

/// Gmsh's element type number for a point element, which the reader skips.
pub(crate) const GMSH_POINT: u32 = 15;

/// The Gmsh element type number of a cell type, if it has one (orders 1 to 3).
pub fn gmsh_type_id(ty: CellType) -> Option<u32> {
    TYPE_TABLE
        .iter()
        .find(|(s, o, _)| *s == ty.shape && *o == ty.order)
        .map(|t| t.2)
}

/// The cell type of a Gmsh element type number, if it is one this crate knows.
pub fn cell_type_of_gmsh(type_id: u32) -> Option<CellType> {
    TYPE_TABLE
        .iter()
        .find(|t| t.2 == type_id)
        .map(|&(s, o, _)| CellType::new(s, o))
}

#[cfg(test)]
mod tests;
