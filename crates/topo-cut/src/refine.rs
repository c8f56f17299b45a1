//! The cut refined cell by cell: a cut is one apex per cell and one diagonal per
//! quadrilateral face ([`Cut`]); the sweep gives a first one ([`Cut::from_ranks`]), then
//! [`refine`] re-cuts the cells worse than the target one at a time.
//!
//! A cut is conforming when both cells of a face split it by the same diagonal, and a cell's
//! cone is a cut of it when every quadrilateral through its apex is split through the apex.
//! So a bad cell may take any apex and any diagonals on its quadrilaterals away from it, as
//! long as each neighbour across a changed face still has an apex on all its split diagonals
//! (the neighbour then takes the best such apex). Unlike a swap of two nodes' ranks, which
//! re-cuts every cell around both nodes, this changes one cell and its face neighbours only,
//! and reaches the diagonal patterns no single order gives around it. A change is kept when it
//! lowers the largest dihedral angle over the cell and its neighbours (then the cell's own).
//! Faces kept whole (a kept cell's quadrilateral in the mixed cut) stay whole. In the mixed
//! cut ([`refine_mixed`]) a quadrilateral between two cut cells (or on the boundary) may be
//! kept whole as well, or split where it was whole: each cell then cones it from an apex off
//! it (a pyramid), so the two cells no longer have to agree on a diagonal.

use mesh_model::poly::PolyMesh;

use crate::cone::{CellFaces, Piece, UNRANKED, face_cone, first_ranked};
use crate::improve::worst_piece;

/// One apex per cell ([`UNRANKED`]: kept whole) and for each face the node its diagonal runs
/// through ([`UNRANKED`]: a triangle, or a quadrilateral kept whole).
#[derive(Debug, Clone, PartialEq)]
pub struct Cut {
    /// The apex of each cell's cone.
    pub apex: Vec<u32>,
    /// The node of each face its diagonal runs through (one of its first two nodes).
    pub split: Vec<u32>,
}

/// Normalises the node a quadrilateral's diagonal runs through to one of its first two.
pub(crate) fn normal_split(k: &[u32], w: u32) -> u32 {
    match k.iter().position(|&x| x == w) {
        Some(at) => k[at % 2],
        None => UNRANKED,
    }
}

/// Whether quadrilateral `k`'s diagonal through `s` runs through `a` (a node of `k`).
pub(crate) fn through(k: &[u32], s: u32, a: u32) -> bool {
    let (Some(i), Some(j)) = (
        k.iter().position(|&x| x == s),
        k.iter().position(|&x| x == a),
    ) else {
        return false;
    };
    i % 2 == j % 2
}

impl Cut {
    /// The cut of the sweep: each cell's first ranked node, each quadrilateral split through
    /// its first ranked node.
    pub fn from_ranks(poly: &PolyMesh, rank: &[u32]) -> Cut {
        let mut faces = CellFaces::default();
        let apex = (0..poly.cell_count())
            .map(|c| {
                faces.load(poly, c);
                faces.first_ranked(rank).unwrap_or(UNRANKED)
            })
            .collect();
        let split = (0..poly.face_count())
            .map(|f| {
                let k = poly.face(f);
                match (k.len(), first_ranked(k, rank)) {
                    (4, Some(w)) => normal_split(k, w),
                    _ => UNRANKED,
                }
            })
            .collect();
        Cut { apex, split }
    }

    /// The split node of face `i` of the loaded cell, if it is split.
    fn split_of(&self, faces: &CellFaces, i: usize) -> Option<u32> {
        Some(self.split[faces.id(i) as usize]).filter(|&s| s != UNRANKED)
    }

    /// Cuts the loaded cell into `out` (nothing when it is kept whole).
    pub fn pieces(&self, faces: &CellFaces, c: usize, out: &mut Vec<Piece>) {
        let apex = self.apex[c];
        if apex != UNRANKED {
            faces.cone_split(apex, |i, _| self.split_of(faces, i), out);
        }
    }
}

/// The worst piece of the loaded cell's cone from `apex` with the diagonals `split` (by face
/// of the cell), or `None` when a quadrilateral through the apex is not split through it.
fn cone_quality(
    nodes: &[[f64; 3]],
    faces: &CellFaces,
    apex: u32,
    split: &[u32],
    pieces: &mut Vec<Piece>,
) -> Option<f64> {
    let fits = faces
        .faces()
        .enumerate()
        .all(|(i, k)| k.len() != 4 || !k.contains(&apex) || through(k, split[i], apex));
    if !fits {
        return None;
    }
    pieces.clear();
    faces.cone_split(
        apex,
        |i, _| Some(split[i]).filter(|&s| s != UNRANKED),
        pieces,
    );
    Some(worst_piece(nodes, pieces))
}

/// The best apex of the loaded cell for the diagonals `split` (by face of the cell), and its
/// worst piece; `None` when no node is on every split diagonal through it.
fn best_apex(
    nodes: &[[f64; 3]],
    faces: &CellFaces,
    split: &[u32],
    buf: &mut (Vec<u32>, Vec<Piece>),
) -> Option<(f64, u32)> {
    faces.distinct_nodes(&mut buf.0);
    let mut best: Option<(f64, u32)> = None;
    for j in 0..buf.0.len() {
        let a = buf.0[j];
        let q = cone_quality(nodes, faces, a, split, &mut buf.1);
        if let Some(q) = q.filter(|&q| best.is_none_or(|b| q < b.0)) {
            best = Some((q, a));
        }
    }
    best
}

/// How face `free[b]` is cut under the code `bits` of [`cell_cuts`]: split through its first
/// node (0), its second (1), or kept whole (2).
fn face_code(bits: u32, b: usize) -> u32 {
    (bits >> (2 * b)) & 3
}

/// The cone cuts of the loaded cell under `bound` into `out`, as (worst piece, apex, code):
/// every apex, and the diagonals of the faces `free` (by face of the cell; the others keep
/// `current`) set by the code ([`face_code`]; kept whole only when `whole`, and never a face
/// through the apex). Only the admissible cuts are listed (each quadrilateral through the
/// apex split through it: 8 of a hexahedron's 64 diagonal sets per apex, 2 of a prism's 8),
/// in the order of apex, then the far faces' choices; each face's pieces are measured once
/// per apex, a cut's worst piece being the worst of its faces'.
fn cell_cuts(
    nodes: &[[f64; 3]],
    faces: &CellFaces,
    (free, current, whole): (&[usize], &[u32], bool),
    bound: f64,
    pieces: &mut Vec<Piece>,
    out: &mut Vec<(f64, u32, u32)>,
) {
    let mut apices = Vec::new();
    faces.distinct_nodes(&mut apices);
    let mut worst = |k: &[u32], w: Option<u32>, a: u32| {
        pieces.clear();
        face_cone(k, w, a, pieces);
        worst_piece(nodes, pieces)
    };
    // the free faces away from the apex: (face, worst piece with each diagonal, kept whole)
    let mut far: Vec<(usize, [f64; 3])> = Vec::new();
    let choices: u32 = if whole { 3 } else { 2 };
    'apex: for &a in &apices {
        far.clear();
        let (mut forced, mut fixed) = (0u32, 0.0f64);
        for (i, k) in faces.faces().enumerate() {
            let bit = free.iter().position(|&j| j == i);
            match (k.iter().position(|&x| x == a), bit) {
                (Some(at), Some(b)) if k.len() == 4 => forced |= ((at % 2) as u32) << (2 * b),
                (Some(_), None) if k.len() == 4 && !through(k, current[i], a) => continue 'apex,
                (Some(_), _) => {}
                (None, Some(b)) => {
                    let kept = if whole {
                        worst(k, None, a)
                    } else {
                        f64::INFINITY
                    };
                    far.push((b, [worst(k, Some(k[0]), a), worst(k, Some(k[1]), a), kept]))
                }
                (None, None) => {
                    let w = Some(current[i]).filter(|&s| s != UNRANKED);
                    fixed = fixed.max(worst(k, w, a));
                }
            }
            if fixed >= bound {
                continue 'apex;
            }
        }
        for m in 0..choices.pow(far.len() as u32) {
            let (mut bits, mut q, mut rest) = (forced, fixed, m);
            for &(b, x) in &far {
                let s = rest % choices;
                rest /= choices;
                bits |= s << (2 * b);
                q = q.max(x[s as usize]);
            }
            if q < bound {
                out.push((q, a, bits));
            }
        }
    }
}

/// The worst piece of cell `c` (loaded in `faces`) as `cut` cuts it (0 when kept whole).
fn cut_quality(
    nodes: &[[f64; 3]],
    cut: &Cut,
    faces: &CellFaces,
    c: usize,
    pieces: &mut Vec<Piece>,
) -> f64 {
    pieces.clear();
    cut.pieces(faces, c, pieces);
    worst_piece(nodes, pieces)
}

/// The two cells of each face (the second [`UNRANKED`] on the boundary).
pub(crate) fn face_cells(poly: &PolyMesh) -> Vec<[u32; 2]> {
    let mut out = vec![[UNRANKED; 2]; poly.face_count()];
    for c in 0..poly.cell_count() {
        for cf in poly.cell(c) {
            let e = &mut out[cf.face as usize];
            let slot = if e[0] == UNRANKED { 0 } else { 1 };
            e[slot] = c as u32;
        }
    }
    out
}

/// Working state of [`refine`].
struct Refiner<'a> {
    poly: &'a PolyMesh,
    cut: &'a mut Cut,
    q: Vec<f64>,
    across: Vec<[u32; 2]>,
    buf: (Vec<u32>, Vec<Piece>),
    /// Whether a quadrilateral between two cut cells may be kept whole (the mixed cut).
    whole: bool,
}

/// A re-cut of a few cells: the new diagonals by face (with the faces of the re-cut cells that
/// keep theirs), and (cell, apex, worst piece) of each re-cut cell.
#[derive(Default)]
struct Change {
    faces: Vec<(u32, u32)>,
    cells: Vec<(u32, u32, f64)>,
}

impl Change {
    fn split(&self, cut: &Cut, f: u32) -> u32 {
        match self.faces.iter().rev().find(|x| x.0 == f) {
            Some(x) => x.1,
            None => cut.split[f as usize],
        }
    }

    fn worst(&self) -> f64 {
        self.cells.iter().map(|x| x.2).fold(0.0, f64::max)
    }
}

impl Refiner<'_> {
    /// The neighbour across face `f` of cell `c`.
    fn neighbour(&self, c: u32, f: u32) -> Option<u32> {
        let e = self.across[f as usize];
        let n = if e[0] == c { e[1] } else { e[0] };
        (n != UNRANKED).then_some(n)
    }

    /// The best re-cut of cell `c` under the diagonals `change` already fixes, every re-cut
    /// cell's worst piece under `bound`: `c` takes any apex and any diagonals on its other
    /// split faces; each neighbour across a changed face takes its best apex, or, `depth`
    /// levels down, is re-cut the same way.
    fn recut(&mut self, c: u32, change: &mut Change, depth: usize, bound: f64) -> Option<Change> {
        let mut faces = CellFaces::default();
        faces.load(self.poly, c as usize);
        let ids: Vec<u32> = (0..faces.len()).map(|i| faces.id(i)).collect();
        let current: Vec<u32> = ids.iter().map(|&f| change.split(self.cut, f)).collect();
        let fixed = |f: u32, change: &Change| change.faces.iter().any(|x| x.0 == f);
        // a face free to change: split, or (mixed) a quadrilateral whose cells are both cut
        let open = |i: usize| {
            let cut_across = self
                .neighbour(c, ids[i])
                .is_none_or(|n| self.cut.apex[n as usize] != UNRANKED);
            self.whole && faces.face(i).len() == 4 && cut_across
        };
        let free: Vec<usize> = (0..ids.len())
            .filter(|&i| (current[i] != UNRANKED || open(i)) && !fixed(ids[i], change))
            .collect();
        let mut split = current.clone();
        let set = |split: &mut [u32], bits: u32| {
            for (b, &i) in free.iter().enumerate() {
                let k = faces.face(i);
                split[i] = match face_code(bits, b) {
                    2 => UNRANKED,
                    s => normal_split(k, k[s as usize]),
                };
            }
        };
        // the cuts of the cell alone under the bound, best first: the neighbours only make
        // a candidate worse, so the search stops at the first no better than the best found
        let mut candidates: Vec<(f64, u32, u32)> = Vec::new();
        cell_cuts(
            &self.poly.nodes,
            &faces,
            (&free, &current, self.whole),
            bound,
            &mut self.buf.1,
            &mut candidates,
        );
        candidates.sort_by(|x, y| x.0.total_cmp(&y.0));
        let mut best: Option<Change> = None;
        let (faces_mark, cells_mark) = (change.faces.len(), change.cells.len());
        for (qc, a, bits) in candidates {
            let limit = best.as_ref().map_or(bound, |x| x.worst());
            if qc >= limit {
                break;
            }
            set(&mut split, bits);
            change
                .faces
                .extend(ids.iter().copied().zip(split.iter().copied()));
            change.cells.push((c, a, qc));
            let ok = free
                .iter()
                .filter(|&&i| split[i] != current[i])
                .all(|&i| self.settle(c, ids[i], change, depth, limit));
            if ok && change.worst() < limit {
                best = Some(Change {
                    faces: change.faces[faces_mark..].to_vec(),
                    cells: change.cells[cells_mark..].to_vec(),
                });
            }
            change.faces.truncate(faces_mark);
            change.cells.truncate(cells_mark);
        }
        best
    }

    /// Settles the neighbour of `c` across the re-split face `f` into `change`: its best apex
    /// under the diagonals so far, else (`depth` > 0) a re-cut of it; false when neither stays
    /// under `bound`.
    fn settle(&mut self, c: u32, f: u32, change: &mut Change, depth: usize, bound: f64) -> bool {
        let Some(n) = self.neighbour(c, f) else {
            return true;
        };
        if change.cells.iter().any(|x| x.0 == n) {
            return false;
        }
        let mut other = CellFaces::default();
        other.load(self.poly, n as usize);
        let theirs: Vec<u32> = (0..other.len())
            .map(|j| change.split(self.cut, other.id(j)))
            .collect();
        let apex = best_apex(&self.poly.nodes, &other, &theirs, &mut self.buf);
        if let Some((q, a)) = apex.filter(|x| x.0 < bound) {
            change.cells.push((n, a, q));
            return true;
        }
        if depth == 0 {
            return false;
        }
        match self.recut(n, change, depth - 1, bound) {
            Some(x) => {
                change.faces.extend(x.faces);
                change.cells.extend(x.cells);
                true
            }
            None => false,
        }
    }

    fn apply(&mut self, x: Change) {
        for (f, s) in x.faces {
            self.cut.split[f as usize] = s;
        }
        for (c, a, q) in x.cells {
            self.cut.apex[c as usize] = a;
            self.q[c as usize] = q;
        }
    }
}

/// Re-cuts the cells cut worse than `target` degrees (worst first) while that lowers the
/// worst piece over them and their neighbours; at most `passes` passes. Cells kept whole stay
/// whole. A re-cut may re-cut the neighbours `depth` levels deep (one from a cell of more
/// than five faces when `depth` is 2). Every cell must have faces
/// of three or four nodes. Returns the worst piece of the cut (an inverted one counts 360°).
pub fn refine(poly: &PolyMesh, cut: &mut Cut, target: f64, passes: usize, depth: usize) -> f64 {
    refine_cut(poly, cut, (target, passes, depth), false)
}

/// [`refine`] for a mixed cut: a quadrilateral between two cut cells may also be kept whole,
/// a pyramid's base on both sides (or split where it was whole), which breaks the chains of
/// diagonals a prism's neighbours force on it (a prism cut into a pyramid and a tetrahedron
/// keeps the side away from its apex whole).
pub fn refine_mixed(
    poly: &PolyMesh,
    cut: &mut Cut,
    target: f64,
    passes: usize,
    depth: usize,
) -> f64 {
    refine_cut(poly, cut, (target, passes, depth), true)
}

fn refine_cut(
    poly: &PolyMesh,
    cut: &mut Cut,
    (target, passes, depth): (f64, usize, usize),
    whole: bool,
) -> f64 {
    let mut r = Refiner {
        poly,
        cut,
        q: Vec::new(),
        across: face_cells(poly),
        buf: Default::default(),
        whole,
    };
    let mut faces = CellFaces::default();
    r.q = (0..poly.cell_count())
        .map(|c| {
            faces.load(poly, c);
            cut_quality(&poly.nodes, r.cut, &faces, c, &mut r.buf.1)
        })
        .collect();
    // a cell is tried again only when a re-cut touched it or a neighbour since its last try
    let mut dirty = vec![true; poly.cell_count()];
    for _ in 0..passes {
        let mut bad: Vec<u32> = (0..r.q.len() as u32)
            .filter(|&c| r.q[c as usize] > target && r.cut.apex[c as usize] != UNRANKED)
            .filter(|&c| dirty[c as usize])
            .collect();
        bad.sort_by(|&a, &b| r.q[b as usize].total_cmp(&r.q[a as usize]));
        let mut changed = false;
        for c in bad {
            dirty[c as usize] = false;
            if r.q[c as usize] <= target {
                continue;
            }
            let bound = r.q[c as usize] - 1e-9;
            // a hexahedron's re-cut lists 48 cuts against a prism's 12: two levels from it
            // cost too much (16 s for the bench's 26k merged hexahedra), so one; the bar's
            // deep pass (three levels, few cells) is left as asked
            // (and the third pass, four levels from a prism, one from a hexahedron: three
            // took `cut_to_tets/hex` 1.1 s → 3.6 s)
            let deep = match (poly.cell(c as usize).len() > 5, depth) {
                (true, 2) | (true, 4..) => 1,
                (_, d) => d,
            };
            if let Some(x) = r.recut(c, &mut Change::default(), deep, bound) {
                for &(d, _, _) in &x.cells {
                    dirty[d as usize] = true;
                    for cf in poly.cell(d as usize) {
                        if let Some(n) = r.neighbour(d, cf.face) {
                            dirty[n as usize] = true;
                        }
                    }
                }
                r.apply(x);
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
    r.q.iter().copied().fold(0.0, f64::max)
}
