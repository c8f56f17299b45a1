//! The crate's one error type: every way a cell or a mesh handed to this crate can be unusable.

use mesh_model::CellType;

/// Everything that can go wrong evaluating or certifying a cell.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum JacobianError {
    /// The cell type has no shape functions or no certified check here (order 0 or above 3,
    /// lines), or the operation does not apply to it (area of a 3D cell).
    /// Fix: use a supported type (see the crate documentation).
    #[error("cell type {shape} P{order} is not supported by {what}", shape = ty.shape.name(), order = ty.order)]
    Unsupported {
        /// The cell type asked for.
        ty: CellType,
        /// The operation that does not support it.
        what: &'static str,
    },

    /// The number of node coordinates given does not match the cell type.
    /// Fix: pass all nodes of the cell, in Gmsh order.
    #[error("cell type {shape} P{order} needs {expected} nodes, got {got}", shape = ty.shape.name(), order = ty.order)]
    NodeCount {
        /// The cell type.
        ty: CellType,
        /// Its node count.
        expected: usize,
        /// The number of coordinates given.
        got: usize,
    },

    /// A node coordinate is NaN or infinite.
    /// Fix: the stage that produced the cell is at fault.
    #[error("node {node} of the cell has a non-finite coordinate")]
    NonFiniteNode {
        /// Local index of the node in the cell.
        node: usize,
    },

    /// A 2D operation was given a cell of a 3D shape, or the reverse.
    /// Fix: pass node coordinates of the cell's own dimension (`[f64; 2]` for triangles and
    /// quadrilaterals, `[f64; 3]` for tetrahedra, pyramids, prisms and hexahedra).
    #[error("cell type {shape} has dimension {actual}, the operation needs dimension {needed}", shape = ty.shape.name())]
    WrongDimension {
        /// The cell type.
        ty: CellType,
        /// Its dimension.
        actual: u8,
        /// The dimension the operation works in.
        needed: u8,
    },

    /// A mesh cell names a node that does not exist.
    /// Fix: run `mesh_model::validate` on the mesh; the stage that built it is at fault.
    #[error("cell {cell} names node {node}, which does not exist")]
    NodeOutOfRange {
        /// Cell index in the mesh.
        cell: usize,
        /// The bad node index.
        node: u32,
    },

    /// A parameter is outside its documented range.
    /// Fix: see the documentation of the named field.
    #[error("parameter {name} = {value} is out of range ({rule})")]
    BadParameter {
        /// The field name.
        name: &'static str,
        /// Its value.
        value: f64,
        /// The documented range.
        rule: &'static str,
    },
}
