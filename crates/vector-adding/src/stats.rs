//! The figures of one curving run, for reports and tests.

use serde::Serialize;

/// How the curved pipes ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
pub struct StopCounts {
    /// The cell was valid (and good enough) with a straight top edge.
    pub jacobian: usize,
    /// The two children of the curved edge merged: the last cell is a triangle.
    pub collapsed: usize,
    /// The top edge is not the bottom of a cell of the same pipe (the pipe met another
    /// pipe, the filled region or a frozen front), so it stays straight.
    pub pipe_ended: usize,
    /// Cells left invalid by the marching because no choice of top edge made them valid
    /// (the final certification names them).
    pub invalid: usize,
}

/// What [`crate::curve_mesh`] did.
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct CurvingStats {
    /// Edges of the output mesh (diagonals of cut quadrilaterals included).
    pub edges: usize,
    /// Of those, the edges whose high-order nodes are off their chord.
    pub curved_edges: usize,
    /// `curved_edges / edges`.
    pub curved_edge_fraction: f64,
    /// Boundary edges curved onto their curves.
    pub curved_boundary_edges: usize,
    /// Pipe ends, by cause.
    pub stops: StopCounts,
    /// Top edges given only part of the deviation below them, because the full one made
    /// the cell invalid.
    pub reduced_tops: usize,
    /// Pipes that ended in the filled region and bent the edge they share with its triangle,
    /// because that left both cells better than a straight top.
    pub handed_to_fill: usize,
    /// The highest layer with a curved bottom edge, counting the boundary as layer 1.
    pub deepest_curved_layer: u32,
    /// Invalid cells made valid by bending their straight edges after the marching.
    pub repaired_cells: usize,
    /// Cells still invalid after the repair.
    pub unrepaired_cells: usize,
    /// Diagonals of cut quadrilaterals that had to be curved.
    pub curved_diagonals: usize,
    /// Triangles of cut quadrilaterals left invalid even with a curved diagonal.
    pub invalid_after_cut: usize,
    /// Seconds spent in each phase: edges, boundary, march, repair, cut, assemble.
    pub timings_s: Vec<(&'static str, f64)>,
}

/// `part / whole`, 0 for an empty whole: the curved-edge fractions.
pub(crate) fn share(part: usize, whole: usize) -> f64 {
    part as f64 / whole.max(1) as f64
}
