//! Structural checks of a mesh that every stage's tests call at the end: they return every
//! problem found, with the values, instead of stopping at the first.

use std::collections::HashMap;
use std::fmt;

use crate::cell::Shape;
use crate::mesh::{Dim, Mesh, NONE};

/// One thing wrong with a mesh.
#[derive(Debug, Clone, PartialEq)]
pub enum Problem {
    /// A node coordinate is NaN or infinite.
    NonFiniteNode {
        /// Node index.
        node: usize,
    },
    /// A cell or facet names a node that does not exist.
    NodeOutOfRange {
        /// Cell index (or facet index when `facet` is true).
        cell: usize,
        /// True for a boundary facet.
        facet: bool,
        /// The bad node index.
        node: u32,
    },
    /// A per-cell or per-facet array has the wrong length.
    LengthMismatch {
        /// Which array.
        what: &'static str,
        /// Its length.
        len: usize,
        /// The length it should have.
        expected: usize,
    },
    /// A boundary facet names a patch that does not exist.
    PatchOutOfRange {
        /// Facet index.
        facet: usize,
        /// The bad patch index.
        patch: u32,
    },
    /// A linear 2D cell (corners) is not counter-clockwise (exactly), or a quadrilateral is
    /// not convex.
    NotPositive {
        /// Cell index.
        cell: usize,
        /// Its signed area.
        area: f64,
    },
    /// An edge is shared by a number of cells other than two (interior) or one (boundary).
    NonConforming {
        /// The edge's end nodes.
        edge: [u32; 2],
        /// How many cells use it.
        cells: usize,
        /// Whether it is a boundary facet.
        on_boundary: bool,
    },
    /// A cell names a pipe (boundary facet) that does not exist.
    PipeOutOfRange {
        /// Cell index.
        cell: usize,
        /// The bad pipe.
        pipe: u32,
    },
}

impl fmt::Display for Problem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Problem::NonFiniteNode { node } => write!(f, "node {node} has a non-finite coordinate"),
            Problem::NodeOutOfRange { cell, facet, node } => {
                let what = if *facet { "boundary facet" } else { "cell" };
                write!(f, "{what} {cell} names node {node}, which does not exist")
            }
            Problem::LengthMismatch {
                what,
                len,
                expected,
            } => {
                write!(f, "{what} has {len} entries, expected {expected}")
            }
            Problem::PatchOutOfRange { facet, patch } => {
                write!(
                    f,
                    "boundary facet {facet} names patch {patch}, which does not exist"
                )
            }
            Problem::NotPositive { cell, area } => {
                write!(
                    f,
                    "cell {cell} is not positively oriented or not convex (signed area {area:e})"
                )
            }
            Problem::NonConforming {
                edge,
                cells,
                on_boundary,
            } => write!(
                f,
                "edge {edge:?} ({}) is used by {cells} cells",
                if *on_boundary { "boundary" } else { "interior" }
            ),
            Problem::PipeOutOfRange { cell, pipe } => {
                write!(
                    f,
                    "cell {cell} names pipe {pipe}, which is not a boundary facet"
                )
            }
        }
    }
}

/// Checks indices, lengths and finiteness; in 2D also orientation of the linear cells and
/// conformity (each interior edge in exactly two cells, each boundary facet in exactly one).
pub fn validate(mesh: &Mesh) -> Vec<Problem> {
    let mut problems = Vec::new();
    let n = mesh.nodes.len() as u32;
    for (i, p) in mesh.nodes.iter().enumerate() {
        if !p.iter().all(|c| c.is_finite()) {
            problems.push(Problem::NonFiniteNode { node: i });
        }
    }
    for (facet, cells) in [(false, &mesh.cells), (true, &mesh.boundary)] {
        for (i, c) in cells.iter().enumerate() {
            if let Some(&bad) = c.nodes.iter().find(|&&v| v >= n) {
                problems.push(Problem::NodeOutOfRange {
                    cell: i,
                    facet,
                    node: bad,
                });
            }
        }
    }
    let lengths = [
        (
            "boundary_patch",
            mesh.boundary_patch.len(),
            mesh.boundary.len(),
            false,
        ),
        ("cell_layer", mesh.cell_layer.len(), mesh.cells.len(), true),
        ("cell_pipe", mesh.cell_pipe.len(), mesh.cells.len(), true),
    ];
    for (what, len, expected, may_be_empty) in lengths {
        if len != expected && !(may_be_empty && len == 0) {
            problems.push(Problem::LengthMismatch {
                what,
                len,
                expected,
            });
        }
    }
    for (facet, &patch) in mesh.boundary_patch.iter().enumerate() {
        if patch as usize >= mesh.patches.len() {
            problems.push(Problem::PatchOutOfRange { facet, patch });
        }
    }
    for (cell, &pipe) in mesh.cell_pipe.iter().enumerate() {
        if pipe != NONE && pipe as usize >= mesh.boundary.len() {
            problems.push(Problem::PipeOutOfRange { cell, pipe });
        }
    }
    if !problems.is_empty() || mesh.dim != Dim::Two {
        return problems;
    }
    for cell in 0..mesh.cells.len() {
        // a 2D linear cell has at most four corners: no allocation per cell
        let c = mesh.cells.get(cell);
        let k = c.corners();
        let mut corners = [[0.0; 2]; 4];
        for (x, &v) in corners.iter_mut().zip(k) {
            *x = mesh.xy(v);
        }
        if !crate::mesh::is_positive_polygon(&corners[..k.len().min(4)]) {
            let area = mesh.linear_cell_area(cell);
            problems.push(Problem::NotPositive { cell, area });
        }
    }
    problems.extend(edge_conformity_2d(mesh));
    problems
}

fn edge_key(a: u32, b: u32) -> [u32; 2] {
    if a < b { [a, b] } else { [b, a] }
}

fn edge_conformity_2d(mesh: &Mesh) -> Vec<Problem> {
    let mut uses: HashMap<[u32; 2], usize> = HashMap::with_capacity(mesh.cells.len() * 2);
    for c in mesh.cells.iter() {
        let k = c.corners();
        for e in c.ty.shape.edges() {
            *uses.entry(edge_key(k[e[0]], k[e[1]])).or_default() += 1;
        }
    }
    let mut boundary: HashMap<[u32; 2], usize> = HashMap::with_capacity(mesh.boundary.len());
    for f in mesh.boundary.iter() {
        if f.ty.shape == Shape::Line {
            *boundary
                .entry(edge_key(f.nodes[0], f.nodes[1]))
                .or_default() += 1;
        }
    }
    let mut problems = Vec::new();
    for (&edge, &cells) in &uses {
        let on_boundary = boundary.contains_key(&edge);
        let expected = if on_boundary { 1 } else { 2 };
        if cells != expected {
            problems.push(Problem::NonConforming {
                edge,
                cells,
                on_boundary,
            });
        }
    }
    for (&edge, &facets) in &boundary {
        if !uses.contains_key(&edge) || facets > 1 {
            problems.push(Problem::NonConforming {
                edge,
                cells: uses.get(&edge).copied().unwrap_or(0),
                on_boundary: true,
            });
        }
    }
    problems.sort_by_key(|p| match p {
        Problem::NonConforming { edge, .. } => *edge,
        _ => [0, 0],
    });
    problems
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cell::CellType;
    use crate::mesh::{Patch, Role};

    fn square() -> Mesh {
        let mut m = Mesh::new(Dim::Two, 1);
        m.nodes = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        let tri = CellType::new(Shape::Tri, 1);
        m.cells.push(tri, &[0, 1, 2]);
        m.cells.push(tri, &[0, 2, 3]);
        let line = CellType::new(Shape::Line, 1);
        for i in 0..4u32 {
            m.boundary.push(line, &[i, (i + 1) % 4]);
            m.boundary_patch.push(0);
        }
        m.patches.push(Patch {
            name: "box".into(),
            role: Role::Farfield,
        });
        m
    }

    #[test]
    fn a_good_mesh_has_no_problem() {
        assert_eq!(validate(&square()), vec![]);
    }

    #[test]
    fn a_flipped_cell_and_a_missing_cell_are_both_reported() {
        let mut m = square();
        m.cells.nodes_mut(0).swap(1, 2);
        let p = validate(&m);
        assert!(
            p.iter()
                .any(|p| matches!(p, Problem::NotPositive { cell: 0, .. })),
            "{p:?}"
        );
        let mut m = square();
        m.cells = crate::cells::Cells::new();
        m.cells.push(CellType::new(Shape::Tri, 1), &[0, 1, 2]);
        let p = validate(&m);
        assert!(
            p.iter()
                .any(|p| matches!(p, Problem::NonConforming { cells: 0, .. })),
            "{p:?}"
        );
        assert!(
            p.iter().any(|p| matches!(
                p,
                Problem::NonConforming {
                    cells: 1,
                    on_boundary: false,
                    ..
                }
            )),
            "{p:?}"
        );
    }

    #[test]
    fn out_of_range_indices_are_reported_not_panicked_on() {
        let mut m = square();
        m.cells.nodes_mut(1)[2] = 99;
        m.boundary_patch[3] = 7;
        let p = validate(&m);
        assert!(p.contains(&Problem::NodeOutOfRange {
            cell: 1,
            facet: false,
            node: 99
        }));
        assert!(p.contains(&Problem::PatchOutOfRange { facet: 3, patch: 7 }));
    }
}
