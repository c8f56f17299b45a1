//! What `--snapshot FILE.bin` saves: the intermediate stages of a run, so that a later stage
//! (curving, movement) or an inspection can start from them without meshing again.
//! The encoding is `mesh_io::snapshot`'s (the one place that knows it).

use boundary1d::BoundaryNodes;
use mesh_model::LayeredMesh;
use serde::{Deserialize, Serialize};

/// The stages of one run of `cargo xtask mesh`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Snapshot {
    /// The case's name.
    pub case: String,
    /// The 1D boundary mesh of every loop, in the case's loop order (curves counter-clockwise).
    pub boundary: Vec<BoundaryNodes>,
    /// The layered linear mesh with its layers (node layers and parents, pipe columns).
    pub layered: LayeredMesh,
}
