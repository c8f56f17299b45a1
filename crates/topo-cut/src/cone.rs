//! One cell at a time: the outward faces of a polyhedral cell, what standard shape it is (in
//! Gmsh's node order), and its cut, the cone from its first node to cut around.

use mesh_model::Shape;
use mesh_model::poly::PolyMesh;

/// Marks a node that is not cut around.
pub const UNRANKED: u32 = u32::MAX;

/// A standard cell: its shape and its corners in Gmsh's order (the first `shape.corners()`).
pub type Piece = (Shape, [u32; 8]);

/// The faces of one cell, each turned outward (a buffer reused from cell to cell).
#[derive(Debug, Default, Clone)]
pub struct CellFaces {
    nodes: Vec<u32>,
    start: Vec<usize>,
    ids: Vec<u32>,
}

impl CellFaces {
    /// Loads cell `c` of `poly`, its faces turned outward.
    pub fn load(&mut self, poly: &PolyMesh, c: usize) {
        self.nodes.clear();
        self.start.clear();
        self.ids.clear();
        self.start.push(0);
        for cf in poly.cell(c) {
            self.ids.push(cf.face);
            let k = poly.face(cf.face as usize);
            if cf.reversed {
                self.nodes.extend(k.iter().rev());
            } else {
                self.nodes.extend_from_slice(k);
            }
            self.start.push(self.nodes.len());
        }
    }

    /// Number of faces.
    pub fn len(&self) -> usize {
        self.start.len() - 1
    }

    /// Whether the cell has no face.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Face `i`, turned outward.
    pub fn face(&self, i: usize) -> &[u32] {
        &self.nodes[self.start[i]..self.start[i + 1]]
    }

    /// The index in the polyhedral mesh of face `i`.
    pub fn id(&self, i: usize) -> u32 {
        self.ids[i]
    }

    /// The faces, turned outward.
    pub fn faces(&self) -> impl Iterator<Item = &[u32]> + '_ {
        (0..self.len()).map(|i| self.face(i))
    }

    /// The index of the first face with more than four nodes, if any.
    pub fn long_face(&self) -> Option<usize> {
        self.faces().position(|k| k.len() > 4)
    }

    /// The distinct nodes of the cell, in order of first appearance.
    pub fn distinct_nodes(&self, out: &mut Vec<u32>) {
        out.clear();
        for &v in &self.nodes {
            if !out.contains(&v) {
                out.push(v);
            }
        }
    }

    /// The node of the cell with the lowest rank, if any is ranked.
    pub fn first_ranked(&self, rank: &[u32]) -> Option<u32> {
        first_ranked(&self.nodes, rank)
    }

    /// The standard shape of the cell and its corners in Gmsh's order, or `None` when it is
    /// none of tetrahedron, pyramid, prism, hexahedron. A closed cell's face sizes decide its
    /// combinatorial type (four triangles; one quadrilateral and four triangles; two triangles
    /// and three quadrilaterals; six quadrilaterals).
    pub fn standard(&self) -> Option<Piece> {
        let (mut tris, mut quads) = (Vec::new(), Vec::new());
        for (i, k) in self.faces().enumerate() {
            match k.len() {
                3 => tris.push(i),
                4 => quads.push(i),
                _ => return None,
            }
        }
        let mut out = [0u32; 8];
        let shape = match (tris.len(), quads.len()) {
            (4, 0) => {
                let k = self.face(tris[0]);
                let apex = self.nodes.iter().copied().find(|v| !k.contains(v))?;
                out[..4].copy_from_slice(&[k[0], k[2], k[1], apex]);
                Shape::Tet
            }
            (4, 1) => {
                let k = self.face(quads[0]);
                let apex = self.nodes.iter().copied().find(|v| !k.contains(v))?;
                out[..5].copy_from_slice(&[k[0], k[3], k[2], k[1], apex]);
                Shape::Pyramid
            }
            (2, 3) => {
                let k = self.face(tris[0]);
                let base = [k[0], k[2], k[1]];
                out[..3].copy_from_slice(&base);
                for (j, &v) in base.iter().enumerate() {
                    out[3 + j] = self.partner(v, &base)?;
                }
                Shape::Prism
            }
            (0, 6) => {
                let k = self.face(quads[0]);
                let base = [k[0], k[3], k[2], k[1]];
                out[..4].copy_from_slice(&base);
                for (j, &v) in base.iter().enumerate() {
                    out[4 + j] = self.partner(v, &base)?;
                }
                Shape::Hex
            }
            _ => return None,
        };
        Some((shape, out))
    }

    /// The node joined to `v` by an edge of the cell and not in `base`.
    fn partner(&self, v: u32, base: &[u32]) -> Option<u32> {
        self.faces().find_map(|k| {
            let at = k.iter().position(|&x| x == v)?;
            let next = k[(at + 1) % k.len()];
            let prev = k[(at + k.len() - 1) % k.len()];
            [next, prev].into_iter().find(|x| !base.contains(x))
        })
    }

    /// Cuts the cell: the cone from its first ranked node `apex` over each face that does not
    /// contain it (a triangle gives a tetrahedron; a quadrilateral a pyramid, or two
    /// tetrahedra when it has a ranked node, split by the diagonal through its first one).
    /// Faces through the apex are fanned from it, which is how the neighbour across them cuts
    /// them too. Every face must be a triangle or a quadrilateral.
    pub fn cone(&self, apex: u32, rank: &[u32], out: &mut Vec<Piece>) {
        self.cone_split(apex, |_, k| first_ranked(k, rank), out);
    }

    /// The cone from `apex` over each face that does not contain it, a quadrilateral face
    /// `i` split by the diagonal through node `split(i, face)`, or kept whole (a pyramid's
    /// base) when that is `None`. The faces through the apex must be split through it.
    pub fn cone_split(
        &self,
        apex: u32,
        split: impl Fn(usize, &[u32]) -> Option<u32>,
        out: &mut Vec<Piece>,
    ) {
        for (i, k) in self.faces().enumerate().filter(|(_, k)| !k.contains(&apex)) {
            face_cone(k, split(i, k), apex, out);
        }
    }
}

/// The pieces of the cone from `apex` over the outward face `k` (not through it): a
/// triangle's tetrahedron, a quadrilateral's two split by the diagonal through node `w`, or
/// its pyramid when `w` is `None`.
pub fn face_cone(k: &[u32], w: Option<u32>, apex: u32, out: &mut Vec<Piece>) {
    match (k.len(), w) {
        (3, _) => out.push(tet([k[0], k[1], k[2]], apex)),
        (_, None) => {
            let mut c = [0u32; 8];
            c[..5].copy_from_slice(&[k[0], k[3], k[2], k[1], apex]);
            out.push((Shape::Pyramid, c));
        }
        (_, Some(w)) => {
            let at = k.iter().position(|&x| x == w).unwrap_or(0);
            let r = |j: usize| k[(at + j) % 4];
            out.push(tet([r(0), r(1), r(2)], apex));
            out.push(tet([r(0), r(2), r(3)], apex));
        }
    }
}

/// The node of `nodes` with the lowest rank, if any is ranked.
pub fn first_ranked(nodes: &[u32], rank: &[u32]) -> Option<u32> {
    nodes
        .iter()
        .copied()
        .filter(|&v| rank[v as usize] != UNRANKED)
        .min_by_key(|&v| rank[v as usize])
}

/// The tetrahedron over the outward triangle `k` with its apex inside, in Gmsh's order (its
/// face `[0, 2, 1]` is `k`).
fn tet(k: [u32; 3], apex: u32) -> Piece {
    let mut c = [0u32; 8];
    c[..4].copy_from_slice(&[k[0], k[2], k[1], apex]);
    (Shape::Tet, c)
}

/// The outward triangles of face `k` split as its two cells see it: a triangle itself, a
/// quadrilateral by the diagonal through node `w`, else whole.
pub fn split_face(k: &[u32], w: Option<u32>, out: &mut Vec<Vec<u32>>) {
    match (k.len(), w) {
        (4, Some(w)) => {
            let at = k.iter().position(|&x| x == w).unwrap_or(0);
            let r = |j: usize| k[(at + j) % 4];
            out.push(vec![r(0), r(1), r(2)]);
            out.push(vec![r(0), r(2), r(3)]);
        }
        _ => out.push(k.to_vec()),
    }
}
