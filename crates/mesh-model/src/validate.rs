//! The checks of a mesh, as one walk over it that hands each problem found to a sink: the
//! sink decides whether to go on ([`validate()`]: every problem, for tests and reports) or to
//! stop at the first ([`first_problem`]; [`first_structural_problem`] for the writers, the
//! drawer and the curving, which need sound indices but not sound geometry).
//!
//! Structural checks come first (finite coordinates, cell shapes and orders that fit the
//! dimension, node, patch and pipe indices, array lengths); the geometric ones run only on a
//! structurally sound mesh: positive linear cells (2D: every corner turns left, exactly; 3D:
//! the Jacobian at every corner of a tet, pyramid, prism or hex is positive, decided by the
//! exact `orient3d`) and conformity (2D: each edge in two cells, or in one cell and one
//! boundary facet; 3D: the same for faces), read from the [`crate::topology`] tables.

use std::fmt;
use std::ops::ControlFlow;

use crate::cell::Shape;
use crate::mesh::{Dim, Mesh, NONE};
use crate::topology::{for_each_edge_use_count, for_each_use_count};

/// One thing wrong with a mesh.
#[derive(Debug, Clone, PartialEq)]
pub enum Problem {
    /// A node coordinate is NaN or infinite.
    NonFiniteNode {
        /// Node index.
        node: usize,
        /// Its coordinates.
        coords: [f64; 3],
    },
    /// A cell's shape does not fit the mesh's dimension (a tet in a 2D mesh, a line as a
    /// domain cell), or a facet's does not fit one dimension less.
    WrongShape {
        /// Cell index (or facet index when `facet` is true).
        cell: usize,
        /// True for a boundary facet.
        facet: bool,
        /// Its shape.
        shape: Shape,
        /// The mesh's dimension.
        dim: u8,
    },
    /// A cell's polynomial order is not 1, 2 or 3.
    BadOrder {
        /// Cell index (or facet index when `facet` is true).
        cell: usize,
        /// True for a boundary facet.
        facet: bool,
        /// Its order.
        order: u8,
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
    /// A linear 3D cell's Jacobian is not positive at one of its corners (decided exactly):
    /// the cell is inverted or degenerate there.
    NotPositiveCorner {
        /// Cell index.
        cell: usize,
        /// The local corner (Gmsh order) where the Jacobian is not positive.
        corner: usize,
    },
    /// A face of a 3D mesh is shared by a number of cells other than two (interior) or one
    /// (on a boundary facet), or lies on several boundary facets.
    NonConformingFace {
        /// The face's corner nodes, increasing.
        face: Vec<u32>,
        /// How many cells use it.
        cells: usize,
        /// Whether a boundary facet lies on it.
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

impl Problem {
    /// Whether the problem breaks the mesh's structure (an index, a length, a shape, a
    /// coordinate) rather than its geometry (orientation, conformity): a mesh with only
    /// geometric problems can still be measured, drawn and written.
    pub fn is_structural(&self) -> bool {
        !matches!(
            self,
            Problem::NotPositive { .. }
                | Problem::NotPositiveCorner { .. }
                | Problem::NonConforming { .. }
                | Problem::NonConformingFace { .. }
        )
    }
}

impl fmt::Display for Problem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Problem::NonFiniteNode { node, coords } => {
                write!(f, "node {node} has a non-finite coordinate {coords:?}")
            }
            Problem::WrongShape {
                cell,
                facet,
                shape,
                dim,
            } => {
                let what = if *facet { "boundary facet" } else { "cell" };
                write!(f, "{what} {cell} is a {} in a {dim}D mesh", shape.name())
            }
            Problem::BadOrder { cell, facet, order } => {
                let what = if *facet { "boundary facet" } else { "cell" };
                write!(f, "{what} {cell} has order {order} (supported: 1 to 3)")
            }
            Problem::NotPositiveCorner { cell, corner } => write!(
                f,
                "cell {cell} is inverted or degenerate at its corner {corner} (Jacobian not positive)"
            ),
            Problem::NonConformingFace {
                face,
                cells,
                on_boundary,
            } => write!(
                f,
                "face {face:?} ({}) is used by {cells} cells",
                if *on_boundary { "boundary" } else { "interior" }
            ),
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

/// Every problem of `mesh`, structural and geometric, in the order of the walk (structural
/// problems first; geometric checks run only when there is none).
pub fn validate(mesh: &Mesh) -> Vec<Problem> {
    let mut problems = Vec::new();
    let _ = walk(mesh, true, &mut |p| {
        problems.push(p);
        ControlFlow::Continue(())
    });
    problems
}

/// The first problem of `mesh` that [`validate()`] would report, found without looking
/// further.
pub fn first_problem(mesh: &Mesh) -> Option<Problem> {
    first(mesh, true)
}

/// The first structural problem of `mesh` (finiteness, shapes and orders, indices, lengths):
/// what writers and drawers need before they index anything. Orientation and conformity are
/// not checked, so that a tangled mesh can still be written and looked at.
pub fn first_structural_problem(mesh: &Mesh) -> Option<Problem> {
    first(mesh, false)
}

fn first(mesh: &Mesh, geometry: bool) -> Option<Problem> {
    match walk(mesh, geometry, &mut ControlFlow::Break) {
        ControlFlow::Break(p) => Some(p),
        ControlFlow::Continue(()) => None,
    }
}

/// What a sink says after each problem: go on, or stop with this value.
type Sink<'a> = &'a mut dyn FnMut(Problem) -> ControlFlow<Problem>;

/// The one walk: structural checks, then (when `geometry` and the structure is sound) the
/// orientation and conformity checks.
fn walk(mesh: &Mesh, geometry: bool, sink: Sink<'_>) -> ControlFlow<Problem> {
    let mut sound = true;
    let mut report = |p| {
        sound = false;
        sink(p)
    };
    structure(mesh, &mut report)?;
    if !geometry || !sound {
        return ControlFlow::Continue(());
    }
    orientation(mesh, sink)?;
    conformity(mesh, sink)
}

fn structure(mesh: &Mesh, sink: Sink<'_>) -> ControlFlow<Problem> {
    for (i, p) in mesh.nodes.iter().enumerate() {
        if !p.iter().all(|c| c.is_finite()) {
            sink(Problem::NonFiniteNode {
                node: i,
                coords: *p,
            })?;
        }
    }
    let cell_dim = mesh.dim.as_u8();
    let n = mesh.nodes.len() as u32;
    for (facet, cells, dim) in [
        (false, &mesh.cells, cell_dim),
        (true, &mesh.boundary, cell_dim - 1),
    ] {
        for (i, c) in cells.iter().enumerate() {
            if c.ty.shape.dim() != dim {
                sink(Problem::WrongShape {
                    cell: i,
                    facet,
                    shape: c.ty.shape,
                    dim: cell_dim,
                })?;
            } else if !(1..=3).contains(&c.ty.order) {
                sink(Problem::BadOrder {
                    cell: i,
                    facet,
                    order: c.ty.order,
                })?;
            } else if let Some(&bad) = c.nodes.iter().find(|&&v| v >= n) {
                sink(Problem::NodeOutOfRange {
                    cell: i,
                    facet,
                    node: bad,
                })?;
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
            sink(Problem::LengthMismatch {
                what,
                len,
                expected,
            })?;
        }
    }
    for (facet, &patch) in mesh.boundary_patch.iter().enumerate() {
        if patch as usize >= mesh.patches.len() {
            sink(Problem::PatchOutOfRange { facet, patch })?;
        }
    }
    for (cell, &pipe) in mesh.cell_pipe.iter().enumerate() {
        if pipe != NONE && pipe as usize >= mesh.boundary.len() {
            sink(Problem::PipeOutOfRange { cell, pipe })?;
        }
    }
    ControlFlow::Continue(())
}

/// Positive linear cells: 2D corners turning left (exactly), 3D corner Jacobians positive.
fn orientation(mesh: &Mesh, sink: Sink<'_>) -> ControlFlow<Problem> {
    for cell in 0..mesh.cells.len() {
        let c = mesh.cells.get(cell);
        let k = c.corners();
        match mesh.dim {
            Dim::Two => {
                // a 2D linear cell has at most four corners: no allocation per cell
                let mut corners = [[0.0; 2]; 4];
                for (x, &v) in corners.iter_mut().zip(k) {
                    *x = mesh.xy(v);
                }
                if !crate::mesh::is_positive_polygon(&corners[..k.len().min(4)]) {
                    let area = mesh.linear_cell_area(cell);
                    sink(Problem::NotPositive { cell, area })?;
                }
            }
            Dim::Three => {
                let at = |j: usize| mesh.nodes[k[j] as usize];
                if let Some(t) = c.ty.shape.corner_tets().find(|t| {
                    let [o, a, b, d] = t.map(at);
                    !is_positive_tet(o, a, b, d)
                }) {
                    sink(Problem::NotPositiveCorner { cell, corner: t[0] })?;
                }
            }
        }
    }
    ControlFlow::Continue(())
}

/// Whether the tetrahedron `o a b c` has a positive signed volume (`(a−o)×(b−o)·(c−o) > 0`),
/// decided exactly (`geom_predicates::orient3d`, which is positive for the opposite
/// orientation).
pub fn is_positive_tet(o: [f64; 3], a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> bool {
    geom_predicates::orient3d(o, a, b, c) < 0.0
}

/// Each edge (2D) or face (3D) in two cells, or in one cell and one boundary facet: only
/// the counts of the uses ([`crate::topology::for_each_edge_use_count`] in 2D,
/// [`crate::topology::for_each_use_count`] in 3D), not the whole topology.
fn conformity(mesh: &Mesh, sink: Sink<'_>) -> ControlFlow<Problem> {
    let cells = mesh.cells.shapes_and_corners();
    let facets = mesh.boundary.iter().map(|f| f.corners());
    let conforming = |cells: usize, facets: usize| matches!((cells, facets), (2, 0) | (1, 1));
    match mesh.dim {
        Dim::Two => for_each_edge_use_count(cells, facets, |e, cells, facets| {
            if conforming(cells, facets) {
                return ControlFlow::Continue(());
            }
            sink(Problem::NonConforming {
                edge: [e[0], e[1]],
                cells,
                on_boundary: facets > 0,
            })
        }),
        Dim::Three => for_each_use_count::<4, _>(cells, facets, |f, cells, facets| {
            if conforming(cells, facets) {
                return ControlFlow::Continue(());
            }
            sink(Problem::NonConformingFace {
                face: f.to_vec(),
                cells,
                on_boundary: facets > 0,
            })
        }),
    }
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

    #[test]
    fn a_tet_is_positive_by_the_right_hand_rule_and_a_flat_one_is_not() {
        let (o, x, y, z) = ([0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]);
        assert!(is_positive_tet(o, x, y, z));
        assert!(!is_positive_tet(o, y, x, z));
        assert!(!is_positive_tet(o, x, y, [0.3, 0.3, 0.0]));
    }

    #[test]
    fn a_flipped_tet_and_a_tet_in_a_2d_mesh_are_named() {
        let mut m = Mesh::new(Dim::Three, 1);
        m.nodes = vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let tet = CellType::new(Shape::Tet, 1);
        m.cells.push(tet, &[0, 2, 1, 3]);
        let p = validate(&m);
        assert_eq!(p[0], Problem::NotPositiveCorner { cell: 0, corner: 0 });
        // no boundary facets: each of its four faces is in one cell and on no facet
        assert_eq!(p.len(), 5, "{p:?}");
        m.dim = Dim::Two;
        let first = first_problem(&m).unwrap();
        assert!(first.is_structural());
        assert_eq!(first.to_string(), "cell 0 is a tet in a 2D mesh");
    }
}
