//! Polyhedral cells: what a 3D mesher hands on when its cells are not Gmsh's four solids (a
//! prism whose side was split into two triangles by its neighbour, a cell cut by a surface),
//! before a topological cut turns them into standard cells.
//!
//! A [`PolyMesh`] stores each face once, as its list of nodes, and each cell as a list of
//! faces, each with a flag telling whether the face's node order must be reversed to face out
//! of this cell (a face between two cells is outward for one and reversed for the other). Every
//! cell keeps a layer and a pipe, like [`crate::Mesh`]'s `cell_layer` and `cell_pipe`.
//! [`PolyMesh::validate`] checks indices, that every cell is closed and consistently oriented
//! (each edge of a cell on exactly two of its faces, once in each direction), that no face is
//! in more than two cells, and that every cell has a positive volume (by the divergence
//! theorem, [`PolyMesh::cell_volume`]).

use std::fmt;

/// One face of a cell.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CellFace {
    /// The face's index.
    pub face: u32,
    /// True when the face's nodes run clockwise seen from outside this cell (the face is
    /// stored as its other cell sees it).
    pub reversed: bool,
}

/// A mesh of polyhedral cells, faces stored once (compressed-row layout).
#[derive(Debug, Clone, PartialEq)]
pub struct PolyMesh {
    /// Node coordinates.
    pub nodes: Vec<[f64; 3]>,
    face_start: Vec<u32>,
    face_nodes: Vec<u32>,
    cell_start: Vec<u32>,
    cell_faces: Vec<CellFace>,
    /// For each cell, its layer index (0 = touching the wall it grew from), or [`crate::NONE`].
    pub cell_layer: Vec<u32>,
    /// For each cell, the boundary facet whose pipe it belongs to, or [`crate::NONE`].
    pub cell_pipe: Vec<u32>,
}

impl Default for PolyMesh {
    fn default() -> Self {
        PolyMesh::new()
    }
}

/// One thing wrong with a polyhedral mesh.
#[derive(Debug, Clone, PartialEq)]
pub enum PolyProblem {
    /// A node coordinate is NaN or infinite.
    NonFiniteNode {
        /// Node index.
        node: usize,
    },
    /// A face has fewer than three nodes, or names a node that does not exist.
    BadFace {
        /// Face index.
        face: usize,
    },
    /// A cell names a face that does not exist, or has fewer than four faces.
    BadCell {
        /// Cell index.
        cell: usize,
    },
    /// A face is used by more than two cells.
    FaceOverused {
        /// Face index.
        face: usize,
        /// How many cells use it.
        cells: usize,
    },
    /// `cell_layer` or `cell_pipe` is neither empty nor one entry per cell.
    LengthMismatch {
        /// Which array.
        what: &'static str,
        /// Its length.
        len: usize,
    },
    /// An edge of a cell is on a number of its faces other than two: the cell is not closed.
    OpenCell {
        /// Cell index.
        cell: usize,
        /// The edge's end nodes, increasing.
        edge: [u32; 2],
        /// How many of the cell's faces have it.
        faces: usize,
    },
    /// Two faces of a cell run along a shared edge in the same direction: one of them faces
    /// inward.
    Misoriented {
        /// Cell index.
        cell: usize,
        /// The edge's end nodes, increasing.
        edge: [u32; 2],
    },
    /// A closed cell's volume is not positive.
    NotPositive {
        /// Cell index.
        cell: usize,
        /// Its signed volume.
        volume: f64,
    },
}

impl fmt::Display for PolyProblem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PolyProblem::NonFiniteNode { node } => {
                write!(f, "node {node} has a non-finite coordinate")
            }
            PolyProblem::BadFace { face } => write!(
                f,
                "face {face} has fewer than three nodes or names a node that does not exist"
            ),
            PolyProblem::BadCell { cell } => write!(
                f,
                "cell {cell} has fewer than four faces or names a face that does not exist"
            ),
            PolyProblem::FaceOverused { face, cells } => {
                write!(f, "face {face} is used by {cells} cells")
            }
            PolyProblem::LengthMismatch { what, len } => {
                write!(f, "{what} has {len} entries, neither none nor one per cell")
            }
            PolyProblem::OpenCell { cell, edge, faces } => {
                write!(
                    f,
                    "cell {cell} is not closed: edge {edge:?} is on {faces} of its faces"
                )
            }
            PolyProblem::Misoriented { cell, edge } => write!(
                f,
                "cell {cell} has a face turned inward (along edge {edge:?})"
            ),
            PolyProblem::NotPositive { cell, volume } => {
                write!(f, "cell {cell} has a non-positive volume {volume:e}")
            }
        }
    }
}

impl PolyMesh {
    /// An empty mesh.
    pub fn new() -> Self {
        PolyMesh {
            nodes: Vec::new(),
            face_start: vec![0],
            face_nodes: Vec::new(),
            cell_start: vec![0],
            cell_faces: Vec::new(),
            cell_layer: Vec::new(),
            cell_pipe: Vec::new(),
        }
    }

    /// Appends a face (its nodes in order around it) and returns its index.
    pub fn push_face(&mut self, nodes: &[u32]) -> u32 {
        self.face_nodes.extend_from_slice(nodes);
        self.face_start.push(self.face_nodes.len() as u32);
        self.face_count() as u32 - 1
    }

    /// Appends a cell bounded by `faces`, of layer `layer` in pipe `pipe` ([`crate::NONE`] for
    /// none), and returns its index.
    pub fn push_cell(&mut self, faces: &[CellFace], layer: u32, pipe: u32) -> u32 {
        self.cell_faces.extend_from_slice(faces);
        self.cell_start.push(self.cell_faces.len() as u32);
        self.cell_layer.push(layer);
        self.cell_pipe.push(pipe);
        self.cell_count() as u32 - 1
    }

    /// Number of faces.
    pub fn face_count(&self) -> usize {
        self.face_start.len() - 1
    }

    /// Number of cells.
    pub fn cell_count(&self) -> usize {
        self.cell_start.len() - 1
    }

    /// The nodes of face `f`, in order around it.
    pub fn face(&self, f: usize) -> &[u32] {
        &self.face_nodes[self.face_start[f] as usize..self.face_start[f + 1] as usize]
    }

    /// The faces of cell `c`.
    pub fn cell(&self, c: usize) -> &[CellFace] {
        &self.cell_faces[self.cell_start[c] as usize..self.cell_start[c + 1] as usize]
    }

    /// The directed edges of cell `c`'s faces, each face turned outward.
    fn outward_edges(&self, c: usize) -> impl Iterator<Item = (u32, u32)> + '_ {
        self.cell(c).iter().flat_map(move |cf| {
            let k = self.face(cf.face as usize);
            (0..k.len()).map(move |i| {
                let (a, b) = (k[i], k[(i + 1) % k.len()]);
                if cf.reversed { (b, a) } else { (a, b) }
            })
        })
    }

    /// The signed volume of cell `c` by the divergence theorem: each face, turned outward,
    /// is fanned into triangles from its centroid (exact for planar faces, and for a warped
    /// face the volume of the fanned surface), and the cell's volume is the sum of the
    /// tetrahedra these triangles make with the cell's first node. Positive for a closed,
    /// outward-oriented cell.
    pub fn cell_volume(&self, c: usize) -> f64 {
        let Some(first) = self.cell(c).first() else {
            return 0.0;
        };
        let o = self.nodes[self.face(first.face as usize)[0] as usize];
        let rel = |v: u32| {
            let p = self.nodes[v as usize];
            [p[0] - o[0], p[1] - o[1], p[2] - o[2]]
        };
        let mut six = 0.0;
        for cf in self.cell(c) {
            let k = self.face(cf.face as usize);
            let mut centre = [0.0; 3];
            for &v in k {
                let p = rel(v);
                (0..3).for_each(|d| centre[d] += p[d] / k.len() as f64);
            }
            for i in 0..k.len() {
                let (mut a, mut b) = (rel(k[i]), rel(k[(i + 1) % k.len()]));
                if cf.reversed {
                    std::mem::swap(&mut a, &mut b);
                }
                six += triple(centre, a, b);
            }
        }
        six / 6.0
    }

    /// Every problem of the mesh: indices and lengths first; closure, orientation and volume
    /// only when those are sound.
    pub fn validate(&self) -> Vec<PolyProblem> {
        let mut problems = self.structure();
        if !problems.is_empty() {
            return problems;
        }
        let mut edges = Vec::new();
        for c in 0..self.cell_count() {
            edges.clear();
            edges.extend(
                self.outward_edges(c)
                    .map(|(a, b)| ([a.min(b), a.max(b)], a < b)),
            );
            edges.sort_unstable();
            let before = problems.len();
            for group in edges.chunk_by(|x, y| x.0 == y.0) {
                let edge = group[0].0;
                if group.len() != 2 {
                    problems.push(PolyProblem::OpenCell {
                        cell: c,
                        edge,
                        faces: group.len(),
                    });
                } else if group[0].1 == group[1].1 {
                    problems.push(PolyProblem::Misoriented { cell: c, edge });
                }
            }
            let volume = self.cell_volume(c);
            if problems.len() == before
                && volume.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater)
            {
                problems.push(PolyProblem::NotPositive { cell: c, volume });
            }
        }
        problems
    }

    /// Indices, lengths, finiteness and the number of cells of each face.
    fn structure(&self) -> Vec<PolyProblem> {
        let mut problems = Vec::new();
        for (node, p) in self.nodes.iter().enumerate() {
            if !p.iter().all(|x| x.is_finite()) {
                problems.push(PolyProblem::NonFiniteNode { node });
            }
        }
        let n = self.nodes.len() as u32;
        for face in 0..self.face_count() {
            let k = self.face(face);
            if k.len() < 3 || k.iter().any(|&v| v >= n) {
                problems.push(PolyProblem::BadFace { face });
            }
        }
        let mut uses = vec![0usize; self.face_count()];
        for cell in 0..self.cell_count() {
            let faces = self.cell(cell);
            if faces.len() < 4 || faces.iter().any(|f| f.face as usize >= uses.len()) {
                problems.push(PolyProblem::BadCell { cell });
                continue;
            }
            faces.iter().for_each(|f| uses[f.face as usize] += 1);
        }
        for (face, &cells) in uses.iter().enumerate() {
            if cells > 2 {
                problems.push(PolyProblem::FaceOverused { face, cells });
            }
        }
        for (what, len) in [
            ("cell_layer", self.cell_layer.len()),
            ("cell_pipe", self.cell_pipe.len()),
        ] {
            if len != 0 && len != self.cell_count() {
                problems.push(PolyProblem::LengthMismatch { what, len });
            }
        }
        problems
    }
}

/// `a · (b × c)`.
fn triple(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> f64 {
    a[0] * (b[1] * c[2] - b[2] * c[1])
        + a[1] * (b[2] * c[0] - b[0] * c[2])
        + a[2] * (b[0] * c[1] - b[1] * c[0])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::NONE;

    /// The faces of the unit right prism (Gmsh's corner order), its side quad 0-1-4-3 split
    /// into two triangles, and of a tetrahedron on that side sharing the triangle 0-1-4: the
    /// mesh without cells, the prism's faces and the tet's.
    fn split_prism() -> (PolyMesh, Vec<CellFace>, Vec<CellFace>) {
        let mut m = PolyMesh::new();
        m.nodes = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [1.0, 0.0, 1.0],
            [0.0, 1.0, 1.0],
            [0.5, -1.0, 0.5],
        ];
        let out = |face| CellFace {
            face,
            reversed: false,
        };
        let prism: Vec<CellFace> = [
            &[0, 2, 1][..],
            &[3, 4, 5],
            &[0, 1, 4],
            &[0, 4, 3],
            &[0, 3, 5, 2],
            &[1, 2, 5, 4],
        ]
        .iter()
        .map(|f| out(m.push_face(f)))
        .collect();
        let mut tet = vec![CellFace {
            face: prism[2].face,
            reversed: true,
        }];
        for f in [[4, 0, 6], [1, 4, 6], [0, 1, 6]] {
            tet.push(out(m.push_face(&f)));
        }
        (m, prism, tet)
    }

    #[test]
    fn a_prism_with_a_split_side_is_closed_and_has_its_volume() {
        let (mut m, prism, tet) = split_prism();
        m.push_cell(&prism, 0, 0);
        m.push_cell(&tet, 1, NONE);
        assert_eq!(m.validate(), vec![]);
        assert!((m.cell_volume(0) - 0.5).abs() < 1e-15);
        // base triangle 0-1-4 of area 1/2, apex 1 away from its plane
        assert!((m.cell_volume(1) - 1.0 / 6.0).abs() < 1e-15);
    }

    #[test]
    fn open_misoriented_inside_out_and_overused_are_found() {
        let (mut m, prism, _) = split_prism();
        m.push_cell(&prism[..5], 0, 0); // the last side left out
        let p = m.validate();
        assert_eq!(p.len(), 4, "{p:?}"); // its four edges
        assert!(
            matches!(
                p[0],
                PolyProblem::OpenCell {
                    cell: 0,
                    faces: 1,
                    ..
                }
            ),
            "{p:?}"
        );

        let (mut m, mut prism, _) = split_prism();
        prism[4].reversed = true;
        m.push_cell(&prism, 0, 0);
        let p = m.validate();
        assert!(
            p.iter()
                .all(|p| matches!(p, PolyProblem::Misoriented { cell: 0, .. })),
            "{p:?}"
        );

        let (mut m, mut prism, _) = split_prism();
        prism.iter_mut().for_each(|f| f.reversed = true);
        m.push_cell(&prism, 0, 0);
        let volume = m.cell_volume(0);
        assert!((volume + 0.5).abs() < 1e-15);
        assert_eq!(
            m.validate(),
            vec![PolyProblem::NotPositive { cell: 0, volume }]
        );

        let (mut m, prism, tet) = split_prism();
        for faces in [&prism, &tet, &prism] {
            m.push_cell(faces, 0, NONE);
        }
        assert_eq!(
            m.validate(),
            vec![PolyProblem::FaceOverused { face: 2, cells: 3 }]
        );
    }
}
