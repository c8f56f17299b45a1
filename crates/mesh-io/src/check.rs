//! The check every writer runs before it creates any file, so that a mesh that cannot be
//! written faithfully gives an error and no partial output: the data model's structural
//! checks (`mesh_model::first_structural_problem`: finite coordinates, cell types that fit
//! the dimension, orders 1 to 3, indices in range, array lengths). Geometric validity
//! (orientation, conformity) is not checked here: a mesh that fails `mesh_model::validate` is
//! still written, so that it can be looked at.

use std::path::Path;

use mesh_model::{Mesh, Problem};

use crate::IoError;

/// Checks that `mesh` can be written; `path` is only used to name the file in the error.
pub(crate) fn check_writable(mesh: &Mesh, path: &Path) -> Result<(), IoError> {
    match mesh_model::first_structural_problem(mesh) {
        None => Ok(()),
        Some(Problem::NonFiniteNode { node, coords }) => Err(IoError::NonFiniteNode {
            path: path.to_path_buf(),
            node,
            coords,
        }),
        Some(problem) => Err(IoError::InvalidMesh {
            path: path.to_path_buf(),
            message: problem.to_string(),
        }),
    }
}
