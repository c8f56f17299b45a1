//! The quality measures of the cut: dihedral angles of tetrahedra, kept in
//! `mesh_model::measure3d` (one copy for the cut, the report and the tests) and re-exported
//! here; and the layer cells whose corners fall below a scaled Jacobian
//! ([`low_corner_cells`]), which a mixed cut can be asked to cut rather than keep.

pub use mesh_model::measure3d::{max_dihedral_deg, tet_dihedral_angles_deg};

use mesh_model::Shape;
use mesh_model::measure3d::corner_determinants;
use mesh_model::poly::PolyMesh;

use crate::cone::CellFaces;

/// One flag per cell of `poly`: whether it is a standard prism or hexahedron with a corner
/// whose edge-normalised scaled Jacobian ([`corner_determinants`]) is below `limit` — the
/// cells a mixed cut should round-cut rather than keep ([`crate::cut_to_mixed_cutting`]).
/// Empty (none flagged) when no cell is below.
pub fn low_corner_cells(poly: &PolyMesh, limit: f64) -> Vec<bool> {
    let mut faces = CellFaces::default();
    let mut corners = Vec::with_capacity(8);
    let flags: Vec<bool> = (0..poly.cell_count())
        .map(|c| {
            let Some((shape, ids)) = layer_shape(poly, c, &mut faces) else {
                return false;
            };
            corners.clear();
            corners.extend(
                ids[..shape.corners()]
                    .iter()
                    .map(|&v| poly.nodes[v as usize]),
            );
            corner_determinants(&corners, true)
                .into_iter()
                .any(|q| q < limit)
        })
        .collect();
    if flags.iter().any(|&f| f) {
        flags
    } else {
        Vec::new()
    }
}

/// How many of the `flags`ged cells of `poly` (one flag per cell, or none) are standard
/// prisms or hexahedra — the cells a mixed cut would otherwise keep.
pub fn flagged_layer_shapes(poly: &PolyMesh, flags: &[bool]) -> usize {
    let mut faces = CellFaces::default();
    flags
        .iter()
        .enumerate()
        .filter(|&(c, &f)| f && layer_shape(poly, c, &mut faces).is_some())
        .count()
}

/// Cell `c` of `poly` as a standard prism or hexahedron, its corners in Gmsh's order, or
/// `None` when it is anything else.
fn layer_shape(poly: &PolyMesh, c: usize, faces: &mut CellFaces) -> Option<(Shape, [u32; 8])> {
    faces.load(poly, c);
    faces
        .standard()
        .filter(|(shape, _)| matches!(shape, Shape::Prism | Shape::Hex))
}
