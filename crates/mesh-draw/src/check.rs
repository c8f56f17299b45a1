//! The checks a mesh must pass before it is drawn, so that drawing never indexes out of range
//! or computes with NaN: a planar, non-empty mesh without structural problems
//! (`mesh_model::first_structural_problem`). Orientation and conformity are not checked: a
//! tangled or non-conforming mesh is drawn as it is, which is often why one wants a picture.

use mesh_model::{Dim, Mesh};

use crate::error::DrawError;

/// `Ok` when the mesh is 2D, non-empty and structurally sound: triangles and quads as cells,
/// lines as facets, valid node, patch and pipe indices, finite coordinates, per-cell and
/// per-facet arrays of the right lengths.
pub(crate) fn check_mesh(mesh: &Mesh) -> Result<(), DrawError> {
    if mesh.dim != Dim::Two {
        return Err(DrawError::NotPlanar);
    }
    if mesh.cells.is_empty() && mesh.boundary.is_empty() {
        return Err(DrawError::EmptyMesh);
    }
    match mesh_model::first_structural_problem(mesh) {
        Some(problem) => Err(DrawError::InvalidMesh(problem)),
        None => Ok(()),
    }
}
