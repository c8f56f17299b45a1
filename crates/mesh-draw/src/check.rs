//! The checks a mesh must pass before it is drawn, so that drawing never indexes out of range
//! or computes with NaN. It is not a mesh validator (that is `mesh_model::validate`): a
//! tangled or non-conforming mesh is drawn as it is, which is often why one wants a picture.

use mesh_model::{Dim, Mesh, Shape};

use crate::error::DrawError;

/// `Ok` when the mesh is 2D, non-empty, has triangles and quads as cells and lines as facets,
/// valid node and patch indices, finite coordinates and one patch per boundary facet.
pub(crate) fn check_mesh(mesh: &Mesh) -> Result<(), DrawError> {
    if mesh.dim != Dim::Two {
        return Err(DrawError::NotPlanar);
    }
    if mesh.cells.is_empty() && mesh.boundary.is_empty() {
        return Err(DrawError::EmptyMesh);
    }
    let node_count = mesh.nodes.len();
    for (what, store, allowed) in [
        ("cell", &mesh.cells, &[Shape::Tri, Shape::Quad][..]),
        ("boundary facet", &mesh.boundary, &[Shape::Line][..]),
    ] {
        for (index, cell) in store.iter().enumerate() {
            if !allowed.contains(&cell.ty.shape) {
                return Err(DrawError::UnsupportedShape {
                    what,
                    index,
                    shape: cell.ty.shape.name(),
                });
            }
            if let Some(&node) = cell.nodes.iter().find(|&&n| n as usize >= node_count) {
                return Err(DrawError::NodeOutOfRange {
                    what,
                    index,
                    node,
                    node_count,
                });
            }
        }
    }
    if let Some((node, coords)) = mesh
        .nodes
        .iter()
        .enumerate()
        .find(|(_, p)| !(p[0].is_finite() && p[1].is_finite()))
    {
        return Err(DrawError::NonFiniteNode {
            node,
            coords: *coords,
        });
    }
    if mesh.boundary_patch.len() != mesh.boundary.len() {
        return Err(DrawError::LengthMismatch {
            what: "mesh.boundary_patch",
            len: mesh.boundary_patch.len(),
            expected: mesh.boundary.len(),
            per: "boundary facet",
        });
    }
    if let Some((facet, &patch)) = mesh
        .boundary_patch
        .iter()
        .enumerate()
        .find(|(_, p)| **p as usize >= mesh.patches.len())
    {
        return Err(DrawError::PatchOutOfRange {
            facet,
            patch,
            patch_count: mesh.patches.len(),
        });
    }
    Ok(())
}
