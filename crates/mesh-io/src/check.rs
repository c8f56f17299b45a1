//! Structural checks every writer runs before it creates any file, so that a mesh that
//! cannot be written faithfully gives an error and no partial output. These are the
//! invariants a writer relies on (indices in range, array lengths, finite coordinates, cell
//! types that fit the dimension); geometric validity (orientation, conformity) is not checked
//! here: a mesh that fails `mesh_model::validate` is still written, so that it can be looked at.

use std::path::Path;

use mesh_model::{Dim, Mesh};

use crate::IoError;

/// Checks that `mesh` can be written; `path` is only used to name the file in the error.
pub(crate) fn check_writable(mesh: &Mesh, path: &Path) -> Result<(), IoError> {
    let invalid = |message: String| IoError::InvalidMesh {
        path: path.to_path_buf(),
        message,
    };
    for (node, p) in mesh.nodes.iter().enumerate() {
        if !p.iter().all(|c| c.is_finite()) {
            return Err(IoError::NonFiniteNode {
                path: path.to_path_buf(),
                node,
                coords: *p,
            });
        }
    }
    let (cell_dim, facet_dim) = match mesh.dim {
        Dim::Two => (2, 1),
        Dim::Three => (3, 2),
    };
    let n = mesh.nodes.len();
    for (what, cells, dim) in [
        ("cell", &mesh.cells, cell_dim),
        ("boundary facet", &mesh.boundary, facet_dim),
    ] {
        for (i, c) in cells.iter().enumerate() {
            if c.ty.shape.dim() != dim {
                return Err(invalid(format!(
                    "{what} {i} is a {} in a {}D mesh",
                    c.ty.shape.name(),
                    mesh.dim.as_u8()
                )));
            }
            if !(1..=3).contains(&c.ty.order) {
                return Err(invalid(format!(
                    "{what} {i} has order {} (supported: 1 to 3)",
                    c.ty.order
                )));
            }
            if let Some(&bad) = c.nodes.iter().find(|&&v| v as usize >= n) {
                return Err(invalid(format!(
                    "{what} {i} names node {bad}, but the mesh has {n} nodes"
                )));
            }
        }
    }
    if mesh.boundary_patch.len() != mesh.boundary.len() {
        return Err(invalid(format!(
            "boundary_patch has {} entries for {} boundary facets",
            mesh.boundary_patch.len(),
            mesh.boundary.len()
        )));
    }
    if let Some((facet, &p)) = mesh
        .boundary_patch
        .iter()
        .enumerate()
        .find(|(_, p)| **p as usize >= mesh.patches.len())
    {
        return Err(invalid(format!(
            "boundary facet {facet} names patch {p}, but the mesh has {} patches",
            mesh.patches.len()
        )));
    }
    for (what, len) in [
        ("cell_layer", mesh.cell_layer.len()),
        ("cell_pipe", mesh.cell_pipe.len()),
    ] {
        if len != 0 && len != mesh.cells.len() {
            return Err(invalid(format!(
                "{what} has {len} entries for {} cells",
                mesh.cells.len()
            )));
        }
    }
    Ok(())
}
