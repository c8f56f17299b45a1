//! The sweep improved where it cuts badly (dissertation §5.2.3: "if there is a tetrahedron
//! with a larger dihedral angle, switch the newest chosen extrusion edge with the related
//! extrusion edge which constructs this tetrahedron").
//!
//! A cell's cut depends only on the order of its own nodes, and any global order cuts
//! conforming, so the order may be changed freely: for each cell whose worst piece is worse
//! than the target, the swap of two of its nodes' ranks that most lowers the worst piece of
//! the cells around them is kept (only when it lowers it).

use mesh_model::poly::PolyMesh;
use mesh_model::{Shape, is_positive_tet};

use crate::cone::{CellFaces, Piece, UNRANKED};
use mesh_model::measure3d::tet_max_dihedral_deg_of;

/// The quality of a cell that is cut into a piece that is not positive.
pub const INVERTED: f64 = 360.0;

/// The cells around each node (compressed rows).
pub struct Around {
    start: Vec<u32>,
    cells: Vec<u32>,
}

impl Around {
    /// The cells of `poly` around each of its nodes.
    pub fn new(poly: &PolyMesh) -> Around {
        let n = poly.nodes.len();
        let mut faces = CellFaces::default();
        let mut nodes = Vec::new();
        let mut pairs: Vec<(u32, u32)> = Vec::new();
        for c in 0..poly.cell_count() {
            faces.load(poly, c);
            faces.distinct_nodes(&mut nodes);
            pairs.extend(nodes.iter().map(|&v| (v, c as u32)));
        }
        pairs.sort_unstable();
        let mut start = vec![0u32; n + 1];
        pairs.iter().for_each(|&(v, _)| start[v as usize + 1] += 1);
        for v in 0..n {
            start[v + 1] += start[v];
        }
        Around {
            start,
            cells: pairs.into_iter().map(|(_, c)| c).collect(),
        }
    }

    /// The cells around node `v`.
    pub fn of(&self, v: u32) -> &[u32] {
        &self.cells[self.start[v as usize] as usize..self.start[v as usize + 1] as usize]
    }
}

/// The worst of `pieces` ([`piece_quality`]), 0 when there are none.
pub(crate) fn worst_piece(nodes: &[[f64; 3]], pieces: &[Piece]) -> f64 {
    pieces
        .iter()
        .map(|p| piece_quality(nodes, p))
        .fold(0.0, f64::max)
}

/// The worst piece of a cut: the largest dihedral angle of a tetrahedron in degrees, 0 for
/// another positive piece, [`INVERTED`] when a corner is not positive.
pub fn piece_quality(nodes: &[[f64; 3]], (shape, k): &Piece) -> f64 {
    let at = |j: usize| nodes[k[j] as usize];
    if shape
        .corner_tets()
        .any(|t| !is_positive_tet(at(t[0]), at(t[1]), at(t[2]), at(t[3])))
    {
        return INVERTED;
    }
    if *shape == Shape::Tet {
        tet_max_dihedral_deg_of([at(0), at(1), at(2), at(3)])
    } else {
        0.0
    }
}

/// Reusable buffers for cutting one cell.
#[derive(Default)]
pub struct Scratch {
    faces: CellFaces,
    pieces: Vec<Piece>,
}

impl Scratch {
    /// The worst piece of cell `c` cut with `rank` (0 when the cell is kept).
    pub fn quality(&mut self, poly: &PolyMesh, c: u32, rank: &[u32]) -> f64 {
        self.faces.load(poly, c as usize);
        if self.faces.long_face().is_some() {
            return 0.0;
        }
        self.pieces.clear();
        match self.faces.first_ranked(rank) {
            Some(apex) => self.faces.cone(apex, rank, &mut self.pieces),
            None => return 0.0,
        }
        worst_piece(&poly.nodes, &self.pieces)
    }
}

/// Swaps ranks of nodes of the cells cut worse than `target` degrees while that lowers the
/// worst piece around them; at most `passes` passes.
pub fn improve(poly: &PolyMesh, rank: &mut [u32], target: f64, passes: usize) {
    let around = Around::new(poly);
    let mut s = Scratch::default();
    let mut q: Vec<f64> = (0..poly.cell_count() as u32)
        .map(|c| s.quality(poly, c, rank))
        .collect();
    let mut nodes = Vec::new();
    let mut affected = Vec::new();
    for _ in 0..passes {
        let mut bad: Vec<u32> = (0..q.len() as u32)
            .filter(|&c| q[c as usize] > target)
            .collect();
        bad.sort_by(|&a, &b| q[b as usize].total_cmp(&q[a as usize]));
        let mut changed = false;
        for c in bad {
            if q[c as usize] <= target {
                continue;
            }
            s.faces.load(poly, c as usize);
            s.faces.distinct_nodes(&mut nodes);
            nodes.retain(|&v| rank[v as usize] != UNRANKED);
            let mut best: Option<(f64, u32, u32)> = None;
            for i in 0..nodes.len() {
                for j in i + 1..nodes.len() {
                    let (v, w) = (nodes[i], nodes[j]);
                    affected.clear();
                    affected.extend_from_slice(around.of(v));
                    affected.extend_from_slice(around.of(w));
                    affected.sort_unstable();
                    affected.dedup();
                    let before = affected.iter().map(|&d| q[d as usize]).fold(0.0, f64::max);
                    let bound = best.map_or(before, |b| b.0.min(before));
                    rank.swap(v as usize, w as usize);
                    // the bad cell first, then its neighbours, stopping once no better
                    let mut after = s.quality(poly, c, rank);
                    for &d in affected.iter().filter(|&&d| d != c) {
                        if after >= bound - 1e-9 {
                            break;
                        }
                        after = after.max(s.quality(poly, d, rank));
                    }
                    rank.swap(v as usize, w as usize);
                    if after < bound - 1e-9 {
                        best = Some((after, v, w));
                    }
                }
            }
            if let Some((_, v, w)) = best {
                rank.swap(v as usize, w as usize);
                for &d in around.of(v).iter().chain(around.of(w)) {
                    q[d as usize] = s.quality(poly, d, rank);
                }
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
}
