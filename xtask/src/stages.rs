//! What `--snapshot FILE.bin` saves: the intermediate stages of a run, so that a later stage
//! (curving, movement) or a debugging session can start from them without meshing again.
//! The encoding is `mesh_io::snapshot`'s (the one place that knows it).

use boundary1d::BoundaryNodes;
use mesh_model::Mesh;
use serde::{Deserialize, Serialize};

/// The stages of one run of `cargo xtask mesh`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Snapshot {
    /// The case's name.
    pub case: String,
    /// The 1D boundary mesh of every loop, in the case's loop order (curves counter-clockwise).
    pub boundary: Vec<BoundaryNodes>,
    /// The layered linear mesh, with `cell_layer` and `cell_pipe`.
    pub mesh: Mesh,
    /// For every node, the node it was extruded from (`mesh_model::NONE` for boundary nodes
    /// and the nodes the hole filling added).
    pub node_parent: Vec<u32>,
    /// For every node, its layer (0 on the boundary, `NONE` for filling nodes).
    pub node_layer: Vec<u32>,
}
