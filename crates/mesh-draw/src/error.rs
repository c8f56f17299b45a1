//! The one error type of the crate: every way a drawing request can be refused, each with a
//! one-line message that names the fault and the value at fault.

use thiserror::Error;

/// Why a mesh could not be drawn.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum DrawError {
    /// The requested picture is smaller than 16 px or larger than 16384 px on a side.
    /// Fix: ask for a size between those limits.
    #[error(
        "picture size {width_px}x{height_px} px is out of range (each side must be 16 to 16384 px)"
    )]
    InvalidSize {
        /// Requested width, pixels.
        width_px: u32,
        /// Requested height, pixels.
        height_px: u32,
    },
    /// The view is empty (x0 >= x1 or y0 >= y1), has a NaN or infinite corner, or is so small
    /// or so large that the mesh-to-pixel scale is not a finite positive number.
    /// Fix: give finite corners with x0 < x1 and y0 < y1.
    #[error("view x {x0}..{x1}, y {y0}..{y1} is not a valid rectangle: {reason}")]
    InvalidView {
        /// Left edge, mesh units.
        x0: f64,
        /// Bottom edge, mesh units.
        y0: f64,
        /// Right edge, mesh units.
        x1: f64,
        /// Top edge, mesh units.
        y1: f64,
        /// What is wrong with it.
        reason: &'static str,
    },
    /// The mesh has no cell and no boundary facet, so there is nothing to draw (an empty mesh is
    /// refused rather than drawn as a blank picture). Fix: draw a mesh that has cells.
    #[error("the mesh has no cell and no boundary facet: nothing to draw")]
    EmptyMesh,
    /// The mesh is 3D; only planar meshes are drawn. Fix: draw a 2D mesh (or a 2D slice of it).
    #[error("the mesh is 3D; mesh-draw draws only 2D meshes")]
    NotPlanar,
    /// The mesh breaks a structural invariant of the data model (a cell that is not a
    /// triangle or a quadrilateral, a facet that is not a line, a node or patch index out of
    /// range, a non-finite coordinate, an array of the wrong length): the first problem
    /// `mesh_model::first_structural_problem` finds. Fix: the stage that made the mesh is at
    /// fault; `mesh_model::validate` lists every problem.
    #[error("the mesh cannot be drawn: {0}")]
    InvalidMesh(mesh_model::Problem),
    /// A per-cell array has the wrong length: `mesh.cell_layer` when colouring by layer, the
    /// caller's value array when colouring by values.
    /// Fix: supply exactly one entry per cell (per facet).
    #[error("{what} has {len} entries, expected {expected} (one per {per})")]
    LengthMismatch {
        /// Which array.
        what: &'static str,
        /// Its length.
        len: usize,
        /// The length it should have.
        expected: usize,
        /// `cell` or `boundary facet`.
        per: &'static str,
    },
    /// A view was asked around boundary patches of a role the mesh does not have.
    /// Fix: ask for a role the mesh has, or give the view yourself.
    #[error("the mesh has no boundary facet of role {role}")]
    NoSuchRole {
        /// The role's name.
        role: &'static str,
    },
    /// A plane cut through a 3D mesh that cannot be made: not a 3D mesh, an axis other than
    /// x, y or z, a plane that is not finite or crosses no cell.
    /// Fix: put the plane through the mesh (see its bounding box).
    #[error("cannot cut the mesh by the plane {} = {at}: {reason}", ["x", "y", "z"].get(*axis).unwrap_or(&"?"))]
    BadSlice {
        /// 0, 1 or 2.
        axis: usize,
        /// Where the plane crosses the axis.
        at: f64,
        /// What is wrong.
        reason: &'static str,
    },
    /// The PNG encoder failed (out of memory, in practice).
    #[error("PNG encoding failed: {0}")]
    PngEncode(String),
}
