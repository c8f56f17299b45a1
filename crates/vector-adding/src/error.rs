//! What can go wrong when curving: bad parameters, or an input that is not the layered
//! linear mesh and boundary curves this crate expects.

use thiserror::Error;

/// A curving failure. Each names the value or the cell at fault.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum CurvingError {
    /// A parameter outside its range.
    #[error("curving parameter {name} = {value}: {rule}")]
    BadParameter {
        /// The parameter's name.
        name: &'static str,
        /// The value given.
        value: f64,
        /// What it must satisfy.
        rule: &'static str,
    },
    /// The input mesh is not a linear 2D mesh of triangles and quadrilaterals.
    #[error("curving needs a linear 2D mesh of triangles and quadrilaterals: {0}")]
    NotLinear2d(String),
    /// The input of the 3D curving is not a linear 3D mesh of tetrahedra, pyramids, prisms
    /// and hexahedra.
    #[error("3D curving: {0}")]
    Unsupported3d(String),
    /// The input mesh breaks a structural invariant of the data model (a node index out of
    /// range, a non-finite coordinate, an array of the wrong length), found by
    /// `mesh_model::first_structural_problem`.
    #[error("the mesh to curve is not sound: {0}")]
    InvalidMesh(mesh_model::Problem),
    /// The per-node or per-cell layer data do not match the mesh.
    #[error("layer data do not match the mesh: {0}")]
    BadLayers(String),
    /// A boundary facet does not join two consecutive nodes of its loop's curve, or a
    /// boundary node is not on its curve.
    #[error("boundary facet {facet} (patch {patch}): {what}")]
    BoundaryMismatch {
        /// The facet's index in the mesh's boundary.
        facet: usize,
        /// Its patch.
        patch: u32,
        /// What is wrong.
        what: String,
    },
    /// The decisions given are not those of a mesh of the same topology and curving
    /// parameters (other edges, another order, cut or strategy).
    #[error("the decisions do not fit this mesh: {0}")]
    NotTheSameMesh(String),
    /// The certified check could not run on a cell (a non-finite node, say).
    #[error("cell {cell}: {source}")]
    Check {
        /// The cell.
        cell: usize,
        /// The checker's error.
        source: jacobian_check::JacobianError,
    },
}
