//! The topology of a mesh, built once: its unique edges (2D and 3D) and unique faces (3D),
//! each with the cells that use it (and at which local index, in Gmsh's order), the boundary
//! facets that lie on it, and the reverse map from a cell to its edges or faces.
//!
//! Built by a sort, without hashing: every cell's local edges (faces) become keys of sorted
//! corner nodes, sorted in place; equal keys are one entity. **Order:** entities are numbered in increasing order of their sorted
//! corner nodes (lexicographic; a triangle face sorts before a quadrilateral face with the same
//! three lowest corners), so that [`Entities::find`] is a binary search; the cells of an entity
//! are listed by increasing cell index. The high-order node numbering of the curving follows
//! this edge order.
//!
//! ```
//! use mesh_model::{CellType, Shape, topology::Edges};
//!
//! // two triangles sharing the diagonal 0–2 of the unit square
//! let tri = Shape::Tri;
//! let edges = Edges::build([(tri, &[0, 1, 2][..]), (tri, &[0, 2, 3][..])], []);
//! assert_eq!(edges.len(), 5);
//! let diagonal = edges.find(&[2, 0]).unwrap();
//! assert_eq!(edges.cells(diagonal).len(), 2);
//! assert_eq!(edges.of_cell(1), &[diagonal, edges.find(&[2, 3]).unwrap(), edges.find(&[3, 0]).unwrap()]);
//! ```

use std::ops::ControlFlow;

use crate::cell::Shape;
use crate::mesh::{Dim, Mesh, NONE};

/// One use of an edge or a face by a cell.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Use {
    /// The cell (its index in the list the topology was built from).
    pub cell: u32,
    /// The local index of the edge (face) in the cell's shape, Gmsh's order
    /// ([`Shape::edges`], [`Shape::faces`]).
    pub local: u8,
}

/// Unique entities of `N` corners at most (edges: `N = 2`; faces: `N = 4`, a triangle's key
/// padded with [`NONE`]), in compressed-row layout.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Entities<const N: usize> {
    keys: Vec<[u32; N]>,
    use_start: Vec<u32>,
    uses: Vec<Use>,
    facet_start: Vec<u32>,
    facets: Vec<u32>,
    of_cell_start: Vec<u32>,
    of_cell: Vec<u32>,
}

/// The unique edges of a mesh.
pub type Edges = Entities<2>;
/// The unique faces of a 3D mesh.
pub type Faces = Entities<4>;

/// The edges and the faces of a mesh.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Topology {
    /// Unique edges of the cells; in 2D the boundary facets are listed on theirs.
    pub edges: Edges,
    /// Unique faces of the cells (empty in 2D); the boundary facets are listed on theirs.
    pub faces: Faces,
}

impl Topology {
    /// The edges and faces of `mesh`'s cells (corners only), with its boundary facets: lines
    /// on the edges in 2D, triangles and quadrilaterals on the faces in 3D.
    ///
    /// # Panics
    /// Never for a mesh without structural problems ([`crate::first_structural_problem`]);
    /// a corner index is only used as a number, so out-of-range nodes do not panic either.
    pub fn new(mesh: &Mesh) -> Self {
        let cells = || mesh.cells.shapes_and_corners();
        let facets = || mesh.boundary.iter().map(|f| f.corners());
        match mesh.dim {
            Dim::Two => Topology {
                edges: Edges::build(cells(), facets()),
                faces: Faces::default(),
            },
            Dim::Three => Topology {
                edges: Edges::build(cells(), []),
                faces: Faces::build(cells(), facets()),
            },
        }
    }
}

/// One local entity of a cell or a facet, before the sort.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
struct Raw<const N: usize> {
    key: [u32; N],
    /// Cells (false) before facets (true) within one key.
    facet: bool,
    index: u32,
    local: u8,
}

impl<const N: usize> Entities<N> {
    /// The local entities of `shape`: its edges when `N == 2`, its faces otherwise.
    fn locals(shape: Shape) -> impl ExactSizeIterator<Item = &'static [usize]> {
        let (edges, faces) = if N == 2 {
            (shape.edges(), &[][..])
        } else {
            (&[][..], shape.faces())
        };
        let n = edges.len() + faces.len();
        (0..n).map(move |j| if N == 2 { &edges[j][..] } else { faces[j] })
    }

    /// The entities of `cells` (each a shape and at least its corner nodes, in Gmsh order),
    /// with the facets `facets` (each its corner nodes, at most `N`) listed on theirs; a facet
    /// that no cell has is an entity of its own, without cells.
    pub fn build<'a>(
        cells: impl IntoIterator<Item = (Shape, &'a [u32])>,
        facets: impl IntoIterator<Item = &'a [u32]>,
    ) -> Self {
        let mut raw: Vec<Raw<N>> = Vec::new();
        let mut of_cell_start = vec![0u32];
        for (i, (shape, nodes)) in cells.into_iter().enumerate() {
            let locals = Self::locals(shape);
            of_cell_start.push(of_cell_start[i] + locals.len() as u32);
            for (j, local) in locals.enumerate() {
                raw.push(Raw {
                    key: key(local.iter().map(|&c| nodes[c])),
                    facet: false,
                    index: i as u32,
                    local: j as u8,
                });
            }
        }
        for (i, nodes) in facets.into_iter().enumerate() {
            raw.push(Raw {
                key: key(nodes.iter().copied()),
                facet: true,
                index: i as u32,
                local: 0,
            });
        }
        let raw = sorted(raw);
        let mut out = Entities {
            keys: Vec::with_capacity(raw.len() / 2 + 1),
            use_start: vec![0],
            uses: Vec::with_capacity(raw.len()),
            facet_start: vec![0],
            facets: Vec::new(),
            of_cell: vec![NONE; *of_cell_start.last().unwrap_or(&0) as usize],
            of_cell_start,
        };
        let mut at = 0;
        while at < raw.len() {
            let id = out.keys.len() as u32;
            let key = raw[at].key;
            out.keys.push(key);
            while at < raw.len() && raw[at].key == key {
                let r = raw[at];
                if r.facet {
                    out.facets.push(r.index);
                } else {
                    out.uses.push(Use {
                        cell: r.index,
                        local: r.local,
                    });
                    out.of_cell[(out.of_cell_start[r.index as usize] + r.local as u32) as usize] =
                        id;
                }
                at += 1;
            }
            out.use_start.push(out.uses.len() as u32);
            out.facet_start.push(out.facets.len() as u32);
        }
        out
    }

    /// Number of entities.
    pub fn len(&self) -> usize {
        self.keys.len()
    }

    /// True when there is none.
    pub fn is_empty(&self) -> bool {
        self.keys.is_empty()
    }

    /// The corner nodes of entity `e`, in increasing order.
    pub fn nodes(&self, e: u32) -> &[u32] {
        let k = &self.keys[e as usize];
        let n = k.iter().position(|&v| v == NONE).unwrap_or(N);
        &k[..n]
    }

    /// The key of entity `e`: its sorted corner nodes, padded with [`NONE`].
    pub fn key(&self, e: u32) -> [u32; N] {
        self.keys[e as usize]
    }

    /// The cells that use entity `e`, by increasing cell index.
    pub fn cells(&self, e: u32) -> &[Use] {
        let e = e as usize;
        &self.uses[self.use_start[e] as usize..self.use_start[e + 1] as usize]
    }

    /// The boundary facets that lie on entity `e` (one on a sound boundary, none inside).
    pub fn facets(&self, e: u32) -> &[u32] {
        let e = e as usize;
        &self.facets[self.facet_start[e] as usize..self.facet_start[e + 1] as usize]
    }

    /// Whether a boundary facet lies on entity `e`.
    pub fn is_boundary(&self, e: u32) -> bool {
        !self.facets(e).is_empty()
    }

    /// The entities of cell `cell`, in its shape's local order.
    pub fn of_cell(&self, cell: usize) -> &[u32] {
        &self.of_cell[self.of_cell_start[cell] as usize..self.of_cell_start[cell + 1] as usize]
    }

    /// The entity with corner nodes `nodes` (in any order), if there is one.
    pub fn find(&self, nodes: &[u32]) -> Option<u32> {
        self.keys
            .binary_search(&key(nodes.iter().copied()))
            .ok()
            .map(|e| e as u32)
    }
}

/// The sorted key of an entity with the given corners, padded with [`NONE`].
fn key<const N: usize>(corners: impl Iterator<Item = u32>) -> [u32; N] {
    let mut k = [NONE; N];
    for (slot, v) in k.iter_mut().zip(corners) {
        *slot = v;
    }
    k.sort_unstable();
    k
}

/// `raw` sorted, in place (no second array: at 1M cells a copy of the records sat at the
/// run's memory peak). A pattern-defeating quicksort: an in-place counting sort by the keys'
/// first node (each record swapped along a cycle into its bucket) was 4-7 times slower, every
/// swap a cache miss, and sorted the 2.6M edges of a 442k-tetrahedron wing in 1.6 s.
fn sorted<T: Ord>(mut raw: Vec<T>) -> Vec<T> {
    raw.sort_unstable();
    raw
}

/// What [`edge_table_2d`] gives: each edge's ends, each edge's first two cells, each cell's
/// edges.
pub type EdgeTable2d = (Vec<[u32; 2]>, Vec<[u32; 2]>, Vec<[u32; 4]>);

/// The unique edges of the 2D `cells` (each a shape and at least its corner nodes, in Gmsh
/// order), in the order of [`Edges::build`], as three arrays and nothing more: each edge's
/// ends (lower node first); the first two cells of each edge (lower cell index first,
/// [`NONE`] when missing); each cell's edge at each local edge ([`NONE`] past its last). What
/// the curving's edge table keeps, without the tables of [`Edges`] (on a large mesh, built,
/// copied and dropped, they stayed with the allocator at the run's memory peak): the records
/// are sorted in one array that is let go whole.
pub fn edge_table_2d<'a>(cells: impl ExactSizeIterator<Item = (Shape, &'a [u32])>) -> EdgeTable2d {
    let mut of_cell = vec![[NONE; 4]; cells.len()];
    // (key, cell, local edge): sorted, the order of `Raw` without facets
    let mut raw: Vec<([u32; 2], u32, u8)> = Vec::with_capacity(cells.len() * 4);
    for (i, (shape, nodes)) in cells.enumerate() {
        for (j, e) in shape.edges().iter().enumerate() {
            raw.push((key(e.iter().map(|&c| nodes[c])), i as u32, j as u8));
        }
    }
    let raw = sorted(raw);
    let unique = raw.windows(2).filter(|w| w[0].0 != w[1].0).count() + usize::from(!raw.is_empty());
    let (mut ends, mut cells_of) = (Vec::with_capacity(unique), Vec::with_capacity(unique));
    for (k, cell, local) in raw {
        if ends.last() != Some(&k) {
            ends.push(k);
            cells_of.push([NONE; 2]);
        }
        let e = ends.len() - 1;
        if let Some(slot) = cells_of[e].iter_mut().find(|c| **c == NONE) {
            *slot = cell;
        }
        of_cell[cell as usize][usize::from(local)] = e as u32;
    }
    (ends, cells_of, of_cell)
}

/// Calls `f` with the corner nodes (increasing), the number of cells and the number of
/// facets of every entity of `cells` and `facets`, in the order of [`Entities::build`],
/// until `f` breaks. What a conformity check needs, without the tables of [`Entities`]: the
/// sorted keys alone, an eighth of their memory on a large mesh.
pub fn for_each_use_count<'a, const N: usize, B>(
    cells: impl IntoIterator<Item = (Shape, &'a [u32])>,
    facets: impl IntoIterator<Item = &'a [u32]>,
    mut f: impl FnMut(&[u32], usize, usize) -> ControlFlow<B>,
) -> ControlFlow<B> {
    let cells = cells.into_iter();
    let mut of_cells: Vec<[u32; N]> = Vec::with_capacity(cells.size_hint().0 * N.min(4));
    for (shape, nodes) in cells {
        let locals = Entities::<N>::locals(shape);
        of_cells.extend(locals.map(|local| key(local.iter().map(|&c| nodes[c]))));
    }
    let of_cells = sorted(of_cells);
    let of_facets: Vec<[u32; N]> =
        sorted(facets.into_iter().map(|n| key(n.iter().copied())).collect());
    merged_counts(&of_cells, &of_facets, |k, cells, facets| {
        let n = k.iter().position(|&v| v == NONE).unwrap_or(N);
        f(&k[..n], cells, facets)
    })
}

/// Walks the sorted lists `a` and `b` together: each value either holds, once and increasing,
/// with how many times `a` and `b` hold it.
fn merged_counts<T: Copy + Ord, B>(
    a: &[T],
    b: &[T],
    mut f: impl FnMut(T, usize, usize) -> ControlFlow<B>,
) -> ControlFlow<B> {
    let (mut i, mut j) = (0, 0);
    while i < a.len() || j < b.len() {
        let k = match (a.get(i), b.get(j)) {
            (Some(&x), Some(&y)) => x.min(y),
            (Some(&x), None) => x,
            (None, Some(&y)) => y,
            (None, None) => unreachable!("one of the lists has values left"),
        };
        let (i0, j0) = (i, j);
        while a.get(i) == Some(&k) {
            i += 1;
        }
        while b.get(j) == Some(&k) {
            j += 1;
        }
        f(k, i - i0, j - j0)?;
    }
    ControlFlow::Continue(())
}

/// [`for_each_use_count`] for the edges of 2D `cells` and the lines of `facets` (their
/// first two nodes each): the same calls in the same order, with less memory and time. Each
/// use is a node's higher neighbour scattered into the bucket of its lower node (half the
/// bytes of a key, no chain of dependent swaps), and each node's few neighbours are sorted
/// when its bucket comes.
pub fn for_each_edge_use_count<'a, B>(
    cells: impl Iterator<Item = (Shape, &'a [u32])> + Clone,
    facets: impl Iterator<Item = &'a [u32]> + Clone,
    mut f: impl FnMut(&[u32], usize, usize) -> ControlFlow<B>,
) -> ControlFlow<B> {
    let cell_edges = cells.flat_map(|(shape, nodes)| {
        shape
            .edges()
            .iter()
            .map(move |e| (nodes[e[0]], nodes[e[1]]))
    });
    let (cell_start, mut cell_hi) = by_lower_node(cell_edges);
    let (facet_start, mut facet_hi) = by_lower_node(facets.map(|n| (n[0], n[1])));
    let last = cell_start.len().max(facet_start.len());
    let range = |start: &[u32], v: usize| match (start.get(v), start.get(v + 1)) {
        (Some(&a), Some(&b)) => a as usize..b as usize,
        _ => 0..0,
    };
    for v in 0..last.saturating_sub(1) {
        let of_cells = &mut cell_hi[range(&cell_start, v)];
        let of_facets = &mut facet_hi[range(&facet_start, v)];
        of_cells.sort_unstable();
        of_facets.sort_unstable();
        merged_counts(of_cells, of_facets, |w, cells, facets| {
            f(&[v as u32, w], cells, facets)
        })?;
    }
    ControlFlow::Continue(())
}

/// The pairs of `pairs` by their lower node: where each node's bucket starts (one past the
/// highest lower node, plus one), and each pair's higher node in its lower node's bucket,
/// in the pairs' order. Two passes over `pairs`: the counts, then the scatter.
fn by_lower_node(pairs: impl Iterator<Item = (u32, u32)> + Clone) -> (Vec<u32>, Vec<u32>) {
    let mut start: Vec<u32> = Vec::new();
    let mut total = 0usize;
    for (a, b) in pairs.clone() {
        let lo = a.min(b) as usize;
        if start.len() < lo + 2 {
            start.resize(lo + 2, 0);
        }
        start[lo + 1] += 1;
        total += 1;
    }
    for v in 1..start.len() {
        start[v] += start[v - 1];
    }
    let mut fill = start.clone();
    let mut hi = vec![0u32; total];
    for (a, b) in pairs {
        let lo = a.min(b) as usize;
        hi[fill[lo] as usize] = a.max(b);
        fill[lo] += 1;
    }
    (start, hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_edge_use_counts_are_those_of_the_keys() {
        // a quad and a triangle sharing an edge, facets on some edges (one twice, one on no
        // cell's edge, one past every cell's nodes), an edge used by three cells
        let cells: Vec<(Shape, Vec<u32>)> = vec![
            (Shape::Quad, vec![0, 1, 4, 3]),
            (Shape::Tri, vec![3, 4, 6]),
            (Shape::Tri, vec![4, 3, 7]),
            (Shape::Tri, vec![8, 2, 5]),
        ];
        let facets: Vec<Vec<u32>> =
            vec![vec![1, 0], vec![0, 1], vec![2, 6], vec![12, 11], vec![6, 4]];
        let of = || cells.iter().map(|(s, n)| (*s, &n[..]));
        let mut want = Vec::new();
        let _ = for_each_use_count::<2, ()>(of(), facets.iter().map(|f| &f[..]), |k, c, f| {
            want.push((k.to_vec(), c, f));
            ControlFlow::Continue(())
        });
        let mut got = Vec::new();
        let _ = for_each_edge_use_count::<()>(of(), facets.iter().map(|f| &f[..]), |k, c, f| {
            got.push((k.to_vec(), c, f));
            ControlFlow::Continue(())
        });
        assert_eq!(got, want);
        assert!(got.contains(&(vec![3, 4], 3, 0)) && got.contains(&(vec![11, 12], 0, 1)));
        // stopping at the first break, as the keys do
        let first = for_each_edge_use_count(of(), facets.iter().map(|f| &f[..]), |k, c, _| {
            if c == 3 {
                ControlFlow::Break(k.to_vec())
            } else {
                ControlFlow::Continue(())
            }
        });
        assert_eq!(first, ControlFlow::Break(vec![3, 4]));
    }

    #[test]
    fn the_edge_table_is_that_of_the_edges() {
        // a quad, a triangle on its top and one on its right, and a quad beyond
        let cells: Vec<(Shape, Vec<u32>)> = vec![
            (Shape::Quad, vec![0, 1, 4, 3]),
            (Shape::Tri, vec![3, 4, 6]),
            (Shape::Tri, vec![1, 2, 4]),
            (Shape::Quad, vec![2, 5, 7, 4]),
        ];
        let of = || cells.iter().map(|(s, n)| (*s, &n[..]));
        let edges = Edges::build(of(), []);
        let (ends, cells_of, of_cell) = edge_table_2d(of());
        assert_eq!(ends.len(), edges.len());
        for e in 0..edges.len() as u32 {
            assert_eq!(ends[e as usize], edges.key(e));
            let mut two = [NONE; 2];
            for (slot, u) in two.iter_mut().zip(edges.cells(e)) {
                *slot = u.cell;
            }
            assert_eq!(cells_of[e as usize], two);
        }
        for (c, local) in of_cell.iter().enumerate() {
            let n = edges.of_cell(c).len();
            assert_eq!(&local[..n], edges.of_cell(c));
            assert!(local[n..].iter().all(|&e| e == NONE));
        }
        assert_eq!(edge_table_2d(std::iter::empty()).0.len(), 0);
    }

    #[test]
    fn two_tets_share_one_face_and_its_three_edges() {
        let t = Shape::Tet;
        let faces = Faces::build([(t, &[0, 1, 2, 3][..]), (t, &[1, 2, 3, 4][..])], []);
        assert_eq!(faces.len(), 7);
        let shared = faces.find(&[3, 2, 1]).unwrap();
        assert_eq!(
            faces.cells(shared),
            &[Use { cell: 0, local: 3 }, Use { cell: 1, local: 0 }]
        );
        assert_eq!(faces.nodes(shared), &[1, 2, 3]);
        let edges = Edges::build([(t, &[0, 1, 2, 3][..]), (t, &[1, 2, 3, 4][..])], []);
        assert_eq!(edges.len(), 9);
        assert_eq!((0..9).filter(|&e| edges.cells(e).len() == 2).count(), 3);
        assert_eq!(edges.of_cell(1).len(), 6);
    }

    #[test]
    fn a_facet_without_a_cell_is_an_entity_without_cells() {
        let edges = Edges::build([(Shape::Tri, &[0, 1, 2][..])], [&[1, 0][..], &[5, 6][..]]);
        assert_eq!(edges.len(), 4);
        let e = edges.find(&[0, 1]).unwrap();
        assert_eq!(edges.facets(e), &[0]);
        let lone = edges.find(&[6, 5]).unwrap();
        assert!(edges.cells(lone).is_empty() && edges.is_boundary(lone));
        assert_eq!(edges.find(&[0, 5]), None);
    }
}
