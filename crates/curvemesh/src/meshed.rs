//! What a caller asks of a run ([`Options`]) and what it gets ([`Meshed`]).

use mesh_model::Mesh;

use crate::estimate;
use crate::report::Report;
use crate::stages::Snapshot;

/// How to mesh a case, beyond what the case itself says.
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    /// The cells' order, 1 to 3; `None`: the case's `[curving] order`.
    pub order: Option<u8>,
    /// 2D: cut every quad along its shorter diagonal (all triangles).
    pub triangles: bool,
    /// Refuse a case expected to make more cells than this, before the expensive stages.
    pub max_cells: u64,
    /// 2D: keep the stages (boundary nodes, layered linear mesh) in [`Meshed::snapshot`].
    pub snapshot: bool,
}

impl Default for Options {
    fn default() -> Options {
        Options {
            order: None,
            triangles: false,
            max_cells: estimate::DEFAULT_MAX_CELLS,
            snapshot: false,
        }
    }
}

/// A meshed case: the mesh, certified, and its report.
#[derive(Debug)]
pub struct Meshed {
    /// The final mesh (curved at order 2 or 3).
    pub mesh: Mesh,
    /// What was made and how good it is; [`Report::is_valid`] tells whether it passed
    /// validation (every cell certified, conforming, positively oriented).
    pub report: Report,
    /// 2D: each cell's least scaled Jacobian (certified bound, corners for linear cells);
    /// empty in 3D.
    pub scaled_jacobian: Vec<f64>,
    /// With [`Options::snapshot`] (2D): the stages, to be saved and moved later.
    pub snapshot: Option<Snapshot>,
    /// 3D at order 2: the linear mesh under the curved one.
    pub linear: Option<Mesh>,
    /// 2D: how many of [`Meshed::mesh`]'s cells, the last ones, are the filled region's
    /// triangles rather than layers (their `cell_layer` and `cell_pipe` are a neighbour's,
    /// as `afsf2d` leaves them); 0 in 3D, whose fill cells have no layer.
    pub fill_cells: usize,
}

/// The filled region's triangles of a layered mesh: its cells after the layered ones, the
/// last ones of every mesh made from it (a cut quadrilateral's two triangles take its place,
/// so they stay last).
pub(crate) fn fill_cells(layered: &mesh_model::LayeredMesh) -> usize {
    layered.mesh.cells.len() - layered.layering.layered_cells
}
