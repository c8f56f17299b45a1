//! The layers of a layered mesh, as every stage after the mesher needs them (curving, moving,
//! 3D extrusion): each node's layer and parents, the count of layered cells, and the pipe
//! columns — for each boundary facet, the cells above it from the wall up. [`LayeredMesh`] is
//! the one record of "the linear mesh with its layers" that the stages pass on.
//!
//! The per-cell layer and pipe stay on [`Mesh`] (`cell_layer`, `cell_pipe`): they travel with
//! the cells through every later stage (curving keeps them, cutting quads into triangles
//! copies them to both halves), which node data and columns do not. [`Layering::check`]
//! checks them together with the rest.

use serde::{Deserialize, Serialize};

use crate::mesh::{Mesh, NONE};

/// The layers of a mesh (see the module documentation). Cells `0..layered_cells` are layered
/// cells; the rest are the filled region's triangles, in no pipe column.
#[derive(Debug, Clone, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct Layering {
    /// For each node, its layer (0 on the boundary), or [`NONE`] for a node of the filled
    /// region (grown in no layer).
    pub node_layer: Vec<u32>,
    /// For each node, the nodes it was extruded from, [`NONE`] when absent: boundary and fill
    /// nodes have none, a layer node one; the second is the other parent of a node made by
    /// merging two children.
    pub node_parents: Vec<[u32; 2]>,
    /// Cells `0..layered_cells` are layered cells; the rest are fill triangles.
    pub layered_cells: usize,
    /// CSR offsets of the pipe columns: the column of boundary facet `f` is
    /// `pipe_cells[pipe_start[f]..pipe_start[f + 1]]`; one entry per facet plus one.
    pub pipe_start: Vec<u32>,
    /// The layered cells of every column, each column bottom-up (by layer, then by index).
    pub pipe_cells: Vec<u32>,
}

/// The one record of a linear mesh with its layers, passed from the mesher to every later
/// stage (and saved in snapshots).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LayeredMesh {
    /// The linear mesh, with `cell_layer` and `cell_pipe`.
    pub mesh: Mesh,
    /// Its layers.
    pub layering: Layering,
}

impl Layering {
    /// The layering of `mesh` from its nodes' layers and parents: the pipe columns are built
    /// from `mesh.cell_layer` and `mesh.cell_pipe` of the first `layered_cells` cells (a cell
    /// whose pipe is [`NONE`] or not a boundary facet is in no column).
    ///
    /// # Panics
    /// When `mesh.cell_layer` or `mesh.cell_pipe` has fewer than `layered_cells` entries.
    pub fn new(
        mesh: &Mesh,
        node_layer: Vec<u32>,
        node_parents: Vec<[u32; 2]>,
        layered_cells: usize,
    ) -> Self {
        let facets = mesh.boundary.len();
        let in_column = |c: usize| {
            let pipe = mesh.cell_pipe[c] as usize;
            (pipe < facets).then_some(pipe)
        };
        // counting sort by pipe; within a pipe cells come by index, then are sorted by layer
        let mut pipe_start = vec![0u32; facets + 1];
        for c in 0..layered_cells {
            if let Some(p) = in_column(c) {
                pipe_start[p + 1] += 1;
            }
        }
        for f in 0..facets {
            pipe_start[f + 1] += pipe_start[f];
        }
        let mut next = pipe_start.clone();
        let mut pipe_cells = vec![0u32; pipe_start[facets] as usize];
        for c in 0..layered_cells {
            if let Some(p) = in_column(c) {
                pipe_cells[next[p] as usize] = c as u32;
                next[p] += 1;
            }
        }
        for f in 0..facets {
            let column = &mut pipe_cells[pipe_start[f] as usize..pipe_start[f + 1] as usize];
            column.sort_by_key(|&c| mesh.cell_layer[c as usize]);
        }
        Layering {
            node_layer,
            node_parents,
            layered_cells,
            pipe_start,
            pipe_cells,
        }
    }

    /// The cells of boundary facet `facet`'s pipe, from the wall up.
    pub fn column(&self, facet: usize) -> &[u32] {
        &self.pipe_cells[self.pipe_start[facet] as usize..self.pipe_start[facet + 1] as usize]
    }

    /// The first thing wrong with this layering of `mesh`, or `None`: lengths (one entry per
    /// node, per cell, per facet), indices in range, every layered cell in the column of its
    /// pipe, layers never falling up a column, and each parent one layer below its child.
    pub fn check(&self, mesh: &Mesh) -> Option<String> {
        let (nodes, cells, facets) = (mesh.nodes.len(), mesh.cells.len(), mesh.boundary.len());
        let lengths = [
            ("node_layer", self.node_layer.len(), nodes),
            ("node_parents", self.node_parents.len(), nodes),
            ("cell_layer", mesh.cell_layer.len(), cells),
            ("cell_pipe", mesh.cell_pipe.len(), cells),
            ("pipe_start", self.pipe_start.len(), facets + 1),
        ];
        for (what, have, want) in lengths {
            if have != want {
                return Some(format!("{what} has {have} entries, not {want}"));
            }
        }
        if self.layered_cells > cells {
            return Some(format!("{} layered cells of {cells}", self.layered_cells));
        }
        if self.pipe_start.windows(2).any(|w| w[0] > w[1])
            || self.pipe_start.first() != Some(&0)
            || self.pipe_start.last().map(|&e| e as usize) != Some(self.pipe_cells.len())
        {
            return Some("pipe_start is not a run of offsets into pipe_cells".into());
        }
        self.check_parents()
            .or_else(|| self.check_columns(mesh, facets))
    }

    /// Parents in range and one layer below their child.
    fn check_parents(&self) -> Option<String> {
        let nodes = self.node_layer.len();
        for (n, parents) in self.node_parents.iter().enumerate() {
            for &p in parents.iter().filter(|&&p| p != NONE) {
                if p as usize >= nodes {
                    return Some(format!("node {n}: parent {p} out of range"));
                }
                let (lp, ln) = (self.node_layer[p as usize], self.node_layer[n]);
                if lp == NONE || ln != lp + 1 {
                    return Some(format!(
                        "node {n} of layer {ln}: parent {p} is of layer {lp}, not one below"
                    ));
                }
            }
        }
        None
    }

    /// Every layered cell of a pipe in its column, the columns bottom-up. A column may hold
    /// two cells of one layer (the triangles of a fan at a corner) and may skip layers (a pipe
    /// whose edge stopped, its children merged, is taken up higher by an edge the front
    /// inserted, which inherits a neighbour's pipe).
    fn check_columns(&self, mesh: &Mesh, facets: usize) -> Option<String> {
        let mut seen = vec![false; self.layered_cells];
        for f in 0..facets {
            let mut below: Option<u32> = None;
            for &c in self.column(f) {
                let Some(s) = seen.get_mut(c as usize).filter(|s| !**s) else {
                    return Some(format!("facet {f}: cell {c} is not a layered cell once"));
                };
                *s = true;
                if mesh.cell_pipe[c as usize] as usize != f {
                    return Some(format!("facet {f}: cell {c} is in another pipe"));
                }
                let layer = mesh.cell_layer[c as usize];
                if below.is_some_and(|b| layer < b) {
                    return Some(format!(
                        "facet {f}: cell {c} of layer {layer} above layer {below:?}"
                    ));
                }
                below = Some(layer);
            }
        }
        (0..self.layered_cells)
            .find(|&c| !seen[c] && (mesh.cell_pipe[c] as usize) < facets)
            .map(|c| format!("layered cell {c} is in no column"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cell::{CellType, Shape};
    use crate::mesh::Dim;

    /// A strip of two quads stacked on one wall facet, a fan triangle beside them on a second
    /// facet, and a fill triangle: nodes 0-2 on the wall, 3-5 layer 1, 6-7 layer 2, 8 fill.
    fn strip() -> (Mesh, Layering) {
        let mut m = Mesh::new(Dim::Two, 1);
        m.nodes = [
            [0.0, 0.0],
            [1.0, 0.0],
            [2.0, 0.0],
            [0.0, 1.0],
            [1.0, 1.0],
            [2.0, 1.0],
            [0.0, 2.0],
            [1.0, 2.0],
            [2.0, 2.0],
        ]
        .iter()
        .map(|p| [p[0], p[1], 0.0])
        .collect();
        let line = CellType::new(Shape::Line, 1);
        m.boundary.push(line, &[0, 1]);
        m.boundary.push(line, &[1, 2]);
        m.boundary_patch = vec![0, 0];
        let (quad, tri) = (CellType::new(Shape::Quad, 1), CellType::new(Shape::Tri, 1));
        m.cells.push(quad, &[3, 4, 7, 6]); // layer 1, pipe 0 (listed first on purpose)
        m.cells.push(quad, &[0, 1, 4, 3]); // layer 0, pipe 0
        m.cells.push(quad, &[1, 2, 5, 4]); // layer 0, pipe 1
        m.cells.push(tri, &[4, 5, 8]); // fill
        m.cell_layer = vec![1, 0, 0, 1];
        m.cell_pipe = vec![0, 0, 1, 1];
        let none = [NONE, NONE];
        let parents = vec![
            none,
            none,
            none,
            [0, NONE],
            [1, NONE],
            [2, NONE],
            [3, NONE],
            [4, NONE],
            none,
        ];
        let layers = vec![0, 0, 0, 1, 1, 1, 2, 2, NONE];
        let l = Layering::new(&m, layers, parents, 3);
        (m, l)
    }

    #[test]
    fn columns_run_bottom_up_and_the_checks_pass() {
        let (m, l) = strip();
        assert_eq!(l.column(0), &[1, 0]);
        assert_eq!(l.column(1), &[2]);
        assert_eq!(l.check(&m), None);
    }

    #[test]
    fn check_names_what_is_wrong() {
        let (m, l) = strip();
        let mut bad = l.clone();
        bad.node_parents[6] = [0, NONE]; // layer 2 under a layer-0 parent
        assert!(bad.check(&m).unwrap().contains("not one below"));
        let mut bad = l.clone();
        bad.node_layer.pop();
        assert!(bad.check(&m).unwrap().contains("node_layer"));
        let mut bad = l.clone();
        bad.pipe_cells.swap(0, 1); // layer 1 at the bottom of column 0
        assert!(bad.check(&m).unwrap().contains("above layer"));
        let mut bad = l.clone();
        bad.layered_cells = 9;
        assert!(bad.check(&m).unwrap().contains("layered cells"));
        let mut m2 = m.clone();
        m2.cell_pipe[2] = 0; // cell 2 now claims pipe 0 but sits in column 1
        assert!(l.check(&m2).unwrap().contains("another pipe"));
    }
}
