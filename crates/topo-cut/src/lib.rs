//! Cuts the raw cells of a 3D layered mesh into standard cells, conforming between neighbours
//! and without Steiner points (dissertation §5.2.3 and §5.2.5, `method.md` §7).
//!
//! A 3D advancing-front mesher hands over a [`PolyMesh`]: in each cell face 0 is the bottom (on
//! the previous front), face 1 the top (the children of the bottom's nodes; left out when the
//! merged children leave fewer than three distinct nodes), then the side faces, triangles or
//! quadrilaterals. Merged children make cells no solver knows (a quadrilateral bottom under a
//! triangle top, a triangle under an edge, …).
//!
//! Both cuts rest on one rule. The nodes to cut around are put in one global order, the
//! *sweep* ([`order`]): lower fronts first, and within a front by the deviation of the pipe's
//! first extrusion edge from the wall normal (straightest first, the dissertation's order),
//! which every child inherits from its parent (a merged child from the first of its parents).
//! A quadrilateral face with a node to cut around is split by the diagonal through its first
//! such node, and a cell with such a node is replaced by the cone from its first one over its
//! faces that do not contain it: a triangle gives a tetrahedron, a kept quadrilateral a
//! pyramid, a split one two tetrahedra ([`cone`]). Both cells of a face see the same first
//! node, so they agree on the face; a face through the apex is fanned from it on both sides.
//! This is the dissertation's sweep: going over the nodes in order and cutting around each
//! the cells (or the pieces of cells) that contain it, the first node of a prism's three side
//! faces never makes a cyclic pattern of diagonals, and every cell is cut without a Steiner
//! point. A hexahedron's first node is a bottom node whose child is the first top node, so
//! every tetrahedron keeps an extrusion edge (no flat slivers in thin layers).
//!
//! Where a cell is cut worse than [`TARGET_DIHEDRAL_DEG`], it is re-cut on its own
//! ([`refine`]): any apex and any diagonals of its quadrilaterals, the neighbours across the
//! changed faces re-cut in turn (two levels, three above [`BAR_DIHEDRAL_DEG`], then four for
//! the cells still above the target), kept when the largest dihedral angle around it
//! drops — the dissertation's switching of extrusion edges, face by face rather than by
//! swapping two nodes in the global order ([`improve`], now only the fallback when a piece
//! stays inverted).
//!
//! - [`cut_to_tets`]: every node is cut around — pure tetrahedra (§5.2.3).
//! - [`cut_to_mixed`]: only a few nodes are cut around — round-cutting (§5.2.5): for each
//!   non-standard cell not yet touched, the node whose cut keeps the cells around it under
//!   the target dihedral angle and disturbs the fewest standard cells.
//!   Standard cells without such a node (prisms, hexahedra, pyramids, tetrahedra) are kept,
//!   and a quadrilateral they share stays a quadrilateral on the other side (a pyramid's base).
//!   Its refining ([`refine::refine_mixed`]) may also keep a quadrilateral between two cut
//!   cells whole, a pyramid's base on both sides (a prism cut into a pyramid and a
//!   tetrahedron), which breaks the chains of diagonals neighbours force on a cell.
//!   [`cut_to_mixed_cutting`] round-cuts the standard cells a caller flags as well (a
//!   judgement this crate cannot make, e.g. prisms leaning too far off the wall's normal).
//! - [`cut_to_prisms`]: tetrahedra and prisms only, no pyramid ([`prisms`]): the hexahedra
//!   halved, every cell joined by quadrilaterals to one that has to be cut cut too.
//!
//! - [`smooth::smooth_worst_tets`]: after a cut (and a fill), the tetrahedra that no cut
//!   mends (their cell's own shape flat) mended by moving their free nodes.
//!
//! Every output cell keeps the layer and pipe of the cell it comes from. The boundary facets
//! are the bottoms of layer-0 cells (patch `wall`) and the other faces of one cell (the outer
//! front, patch `farfield`), turned out of the domain; when the pipes number the wall facets
//! `0..n`, facet `p` is (the first part of) the wall facet of pipe `p`.
//!
//! # Example
//!
//! One layer of one cell: the unit cube grown from the wall square (0, 1, 2, 3), its nodes'
//! children 4 to 7; the bottom face first, then the top, then the sides, all turned out. The
//! tetrahedral cut makes six positive tetrahedra filling the cube; the mixed cut keeps the
//! hexahedron:
//!
//! ```
//! use mesh_model::poly::{CellFace, PolyMesh};
//! use mesh_model::{Shape, measure3d::cell_volume, validate};
//!
//! let mut poly = PolyMesh::new();
//! poly.nodes = [0.0, 1.0]
//!     .iter()
//!     .flat_map(|&z| [[0.0, 0.0, z], [1.0, 0.0, z], [1.0, 1.0, z], [0.0, 1.0, z]])
//!     .collect();
//! let faces: [&[u32]; 6] =
//!     [&[0, 3, 2, 1], &[4, 5, 6, 7], &[0, 1, 5, 4], &[1, 2, 6, 5], &[2, 3, 7, 6], &[3, 0, 4, 7]];
//! let faces: Vec<CellFace> =
//!     faces.iter().map(|k| CellFace { face: poly.push_face(k), reversed: false }).collect();
//! poly.push_cell(&faces, 0, 0); // layer 0, pipe 0
//!
//! let tets = topo_cut::cut_to_tets(&poly).unwrap();
//! assert!(validate(&tets).is_empty());
//! assert_eq!((tets.cells.len(), tets.count(Shape::Tet)), (6, 6));
//! assert!((0..6).all(|i| cell_volume(&tets, i) > 0.0));
//! let volume: f64 = (0..6).map(|i| cell_volume(&tets, i)).sum();
//! assert!((volume - 1.0).abs() < 1e-12);
//!
//! let mixed = topo_cut::cut_to_mixed(&poly).unwrap();
//! assert_eq!((mixed.cells.len(), mixed.count(Shape::Hex)), (1, 1));
//! ```

pub mod cone;
pub mod improve;
pub mod order;
pub mod prisms;
pub mod quality;
pub mod refine;
pub mod smooth;

mod assemble;

use mesh_model::Mesh;
use mesh_model::poly::{PolyMesh, PolyProblem};

pub use quality::{max_dihedral_deg, tet_dihedral_angles_deg};

/// Why a polyhedral mesh could not be cut.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CutError {
    /// The polyhedral mesh fails its own check (first problem).
    #[error("the polyhedral mesh is invalid: {0}")]
    Invalid(PolyProblem),
    /// A face with more than four nodes: only triangles and quadrilaterals are cut.
    #[error(
        "cell {cell}: face {face} has {nodes} nodes, only triangles and quadrilaterals can be cut"
    )]
    LongFace {
        /// Cell index.
        cell: usize,
        /// Face index.
        face: usize,
        /// Its number of nodes.
        nodes: usize,
    },
    /// A cell none of whose nodes was cut around is not one of the standard shapes (a bug).
    #[error("cell {cell} is not a standard cell and was not cut")]
    NotStandard {
        /// Cell index.
        cell: usize,
    },
}

/// Cuts every cell into tetrahedra by the ordered extrusion-edge sweep (dissertation §5.2.3).
///
/// The result is a linear 3D [`Mesh`] on the same nodes, conforming, with the `wall` and
/// `farfield` boundary facets, each tetrahedron with its cell's layer and pipe.
pub fn cut_to_tets(poly: &PolyMesh) -> Result<Mesh, CutError> {
    check(poly)?;
    finish(poly, order::sweep_ranks(poly), false)
}

/// The largest tetrahedron dihedral angle the sweep tries to stay under, in degrees.
pub const TARGET_DIHEDRAL_DEG: f64 = 150.0;

/// Keeps the standard cells and round-cuts the others into tetrahedra and pyramids
/// (dissertation §5.2.5), conforming: a quadrilateral face of a kept cell stays a
/// quadrilateral (a pyramid's base) on the other side.
pub fn cut_to_mixed(poly: &PolyMesh) -> Result<Mesh, CutError> {
    cut_to_mixed_cutting(poly, &[])
}

/// [`cut_to_mixed`], with the cells `cut_anyway` flags (one flag per cell, or none) round-cut
/// as well even where they are standard cells: a caller's judgement this crate cannot make,
/// e.g. a prism whose side edges lean too far off the wall's normal.
pub fn cut_to_mixed_cutting(poly: &PolyMesh, cut_anyway: &[bool]) -> Result<Mesh, CutError> {
    check(poly)?;
    let rank = order::sweep_ranks(poly);
    finish(poly, order::round_cut_ranks(poly, &rank, cut_anyway)?, true)
}

/// [`cut_to_mixed_cutting`] without pyramids or hexahedra: tetrahedra and prisms only, for
/// solvers that take no others ([`prisms`]). Each hexahedron is halved into two prisms; the
/// cells joined by quadrilaterals to a cell that has to be cut (a layer of prisms, a shell of
/// hexahedral columns) are cut whole into tetrahedra, refined as [`cut_to_tets`] refines.
pub fn cut_to_prisms(poly: &PolyMesh, cut_anyway: &[bool]) -> Result<Mesh, CutError> {
    check(poly)?;
    let rank = order::sweep_ranks(poly);
    let mut cut = prisms::prism_cut(poly, cut_anyway, &rank);
    refine::refine(poly, &mut cut, TARGET_DIHEDRAL_DEG, REFINE_PASSES, 2);
    refine::refine(poly, &mut cut, BAR_DIHEDRAL_DEG, REFINE_PASSES, 3);
    refine::refine(poly, &mut cut, TARGET_DIHEDRAL_DEG, REFINE_PASSES, 4);
    assemble::cut(poly, &cut)
}

/// The cut of the ranks, refined cell by cell where it is worse than the target
/// ([`refine`]), assembled. Should a piece stay inverted, the ranks are first improved by
/// swaps ([`improve`]) and refined again, and the better of the two kept.
fn finish(poly: &PolyMesh, mut rank: Vec<u32>, mixed: bool) -> Result<Mesh, CutError> {
    let mut cut = refined(poly, &rank, mixed);
    if cut.1 >= improve::INVERTED {
        improve::improve(poly, &mut rank, TARGET_DIHEDRAL_DEG, 4);
        let second = refined(poly, &rank, mixed);
        if second.1 < cut.1 {
            cut = second;
        }
    }
    assemble::cut(poly, &cut.0)
}

/// The cut of the ranks refined: every cell worse than the target with its neighbours two
/// levels deep, then the cells still worse than [`BAR_DIHEDRAL_DEG`] three levels deep, then
/// those still worse than the target four levels deep (a deep search costs, so only where it
/// is needed); and its worst piece. Two levels, not one: in a
/// layer of prisms the side quadrilaterals' diagonals are shared along chains of cells, and
/// one level left the wing's case 2 a tetrahedron of 160.8° in a cell whose best cut alone
/// is 93° (case 1: 154.6° → 151.7°, case 2: 160.8° → 157.6°, case 3: 159.6° → 157.4°).
fn refined(poly: &PolyMesh, rank: &[u32], mixed: bool) -> (refine::Cut, f64) {
    let mut cut = refine::Cut::from_ranks(poly, rank);
    let refine = if mixed {
        refine::refine_mixed
    } else {
        refine::refine
    };
    refine(poly, &mut cut, TARGET_DIHEDRAL_DEG, REFINE_PASSES, 2);
    refine(poly, &mut cut, BAR_DIHEDRAL_DEG, REFINE_PASSES, 3);
    // the few cells still over the target, four levels deep: the wing's tets cut of case 2
    // has 42 tetrahedra in (150°, 160°] after the two passes, 8 after this one (case 3: 44,
    // 15), for about a second
    let worst = refine(poly, &mut cut, TARGET_DIHEDRAL_DEG, REFINE_PASSES, 4);
    (cut, worst)
}

/// The largest tetrahedron dihedral angle the cut must not exceed where the raw cells allow
/// (issue 13's bar, the dissertation's result), in degrees.
pub const BAR_DIHEDRAL_DEG: f64 = 160.0;

/// The mesh of a given cut of `poly` (every cell's cone, or the cell kept when it has no
/// apex), with its boundary facets; for diagnostics and tests of other cuts than the sweep's.
pub fn assemble_cut(poly: &PolyMesh, cut: &refine::Cut) -> Result<Mesh, CutError> {
    check(poly)?;
    assemble::cut(poly, cut)
}

/// How many passes of [`refine::refine`] the cuts make.
const REFINE_PASSES: usize = 8;

/// Loads cell `c` into `faces`; an error when it has a face of more than four nodes.
fn load_checked(faces: &mut cone::CellFaces, poly: &PolyMesh, c: usize) -> Result<(), CutError> {
    faces.load(poly, c);
    match faces.long_face() {
        Some(face) => Err(CutError::LongFace {
            cell: c,
            face: poly.cell(c)[face].face as usize,
            nodes: faces.face(face).len(),
        }),
        None => Ok(()),
    }
}

fn check(poly: &PolyMesh) -> Result<(), CutError> {
    match poly.validate().into_iter().next() {
        Some(p) => Err(CutError::Invalid(p)),
        None => Ok(()),
    }
}
