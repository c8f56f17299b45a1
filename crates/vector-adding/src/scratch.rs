//! The reusable buffers in which one cell's nodes are built, shared by the checks, the
//! marching, the repair and the cutting.

/// Reusable buffers for building one cell's nodes.
#[derive(Debug, Default)]
pub(crate) struct Scratch {
    pub corners: Vec<[f64; 2]>,
    pub edge_pts: Vec<[f64; 2]>,
    pub nodes: Vec<[f64; 2]>,
    pub tri: Vec<[f64; 2]>,
    pub tri_pts: Vec<[f64; 2]>,
    pub diag: Vec<[f64; 2]>,
}
