//! The edges of a 2D mesh, each stored once with its high-order points: the table the
//! marching writes into and the assembly reads from, so that a curved edge is curved the same
//! way in both cells that share it.

use mesh_model::{Mesh, NONE};

/// Every edge of the mesh, with the `p − 1` inner points of each, from its lower-numbered end
/// to its higher-numbered one.
#[derive(Debug, Clone)]
pub(crate) struct EdgeTable {
    /// Order of the cells.
    pub p: usize,
    /// Ends of each edge, lower node first.
    pub ends: Vec<[u32; 2]>,
    /// The (at most) two cells of each edge, NONE when missing; the lower cell index first.
    pub cells: Vec<[u32; 2]>,
    /// Per cell, the edge of each local edge (Gmsh order; NONE in the fourth slot of a
    /// triangle).
    pub cell_edges: Vec<[u32; 4]>,
    /// `p − 1` points per edge, from `ends[0]` to `ends[1]`.
    pub points: Vec<[f64; 2]>,
    /// Whether an edge's points were moved off its chord.
    pub curved: Vec<bool>,
}

impl EdgeTable {
    /// The edges of the linear mesh `mesh`, every one straight, for order `p`.
    pub fn new(mesh: &Mesh, p: usize) -> Self {
        // bucket every cell edge by its lower node (a counting sort), then group each
        // bucket's few entries by the higher node: edges come out sorted by (lower, higher)
        let n = mesh.nodes.len();
        let mut start = vec![0u32; n + 1];
        for cell in mesh.cells.iter() {
            let k = cell.corners();
            for e in cell.ty.shape.edges() {
                start[k[e[0]].min(k[e[1]]) as usize + 1] += 1;
            }
        }
        for v in 0..n {
            start[v + 1] += start[v];
        }
        let mut fill = start.clone();
        let mut entries = vec![(0u32, 0u32); start[n] as usize];
        for (i, cell) in mesh.cells.iter().enumerate() {
            let k = cell.corners();
            for (j, e) in cell.ty.shape.edges().iter().enumerate() {
                let (a, b) = (k[e[0]], k[e[1]]);
                let slot = &mut fill[a.min(b) as usize];
                entries[*slot as usize] = (a.max(b), (i as u32) << 2 | j as u32);
                *slot += 1;
            }
        }
        let mut table = EdgeTable {
            p,
            ends: Vec::with_capacity(entries.len() / 2 + 8),
            cells: Vec::with_capacity(entries.len() / 2 + 8),
            cell_edges: vec![[NONE; 4]; mesh.cells.len()],
            points: Vec::new(),
            curved: Vec::new(),
        };
        for lo in 0..n {
            let bucket = &mut entries[start[lo] as usize..start[lo + 1] as usize];
            bucket.sort_unstable();
            let mut at = 0;
            while at < bucket.len() {
                let hi = bucket[at].0;
                let id = table.ends.len() as u32;
                table.ends.push([lo as u32, hi]);
                let mut cells = [NONE; 2];
                let mut count = 0;
                while at < bucket.len() && bucket[at].0 == hi {
                    let slot = bucket[at].1;
                    let (cell, local) = ((slot >> 2) as usize, (slot & 3) as usize);
                    table.cell_edges[cell][local] = id;
                    if count < 2 {
                        cells[count] = cell as u32;
                    }
                    count += 1;
                    at += 1;
                }
                table.cells.push(cells);
            }
        }
        let nodes: Vec<[f64; 2]> = mesh.nodes.iter().map(|v| [v[0], v[1]]).collect();
        table.points = Vec::with_capacity(table.ends.len() * (p - 1));
        for e in 0..table.ends.len() {
            let [a, b] = table.ends[e];
            for i in 1..p {
                table.points.push(lerp(
                    nodes[a as usize],
                    nodes[b as usize],
                    i as f64 / p as f64,
                ));
            }
        }
        table.curved = vec![false; table.ends.len()];
        table
    }

    /// Number of edges.
    pub fn len(&self) -> usize {
        self.ends.len()
    }

    /// The other cell of edge `e` than `cell`, or NONE.
    pub fn other_cell(&self, e: u32, cell: u32) -> u32 {
        let [c0, c1] = self.cells[e as usize];
        if c0 == cell { c1 } else { c0 }
    }

    /// The inner points of edge `e` listed from node `from` to the other end.
    pub fn points_from(&self, e: u32, from: u32, out: &mut [[f64; 2]]) {
        let q = self.p - 1;
        let pts = &self.points[e as usize * q..(e as usize + 1) * q];
        if self.ends[e as usize][0] == from {
            out[..q].copy_from_slice(pts);
        } else {
            for (o, v) in out[..q].iter_mut().zip(pts.iter().rev()) {
                *o = *v;
            }
        }
    }

    /// Sets the inner points of edge `e`, given from node `from` to the other end.
    pub fn set_points_from(&mut self, e: u32, from: u32, pts: &[[f64; 2]], curved: bool) {
        let q = self.p - 1;
        let forward = self.ends[e as usize][0] == from;
        let dst = &mut self.points[e as usize * q..(e as usize + 1) * q];
        for i in 0..q {
            dst[i] = if forward { pts[i] } else { pts[q - 1 - i] };
        }
        self.curved[e as usize] = curved;
    }

    /// The deviation of edge `e`'s inner points from their places on its chord, listed from
    /// node `from`; returns the largest deviation's length.
    pub fn deviation(&self, mesh: &Mesh, e: u32, from: u32, dev: &mut [[f64; 2]]) -> f64 {
        self.points_from(e, from, dev);
        let [u, w] = self.ends[e as usize];
        let to = if u == from { w } else { u };
        let (xf, xt) = (mesh.xy(from), mesh.xy(to));
        let mut most: f64 = 0.0;
        for (i, d) in dev.iter_mut().enumerate() {
            let l = lerp(xf, xt, (i + 1) as f64 / self.p as f64);
            *d = [d[0] - l[0], d[1] - l[1]];
            most = most.max(d[0].hypot(d[1]));
        }
        most
    }

    /// Adds an edge that no linear cell has (the diagonal of a cut quadrilateral); returns
    /// its index.
    pub fn push(&mut self, a: u32, b: u32, from_a: &[[f64; 2]], curved: bool) -> u32 {
        let id = self.ends.len() as u32;
        self.ends.push([a.min(b), a.max(b)]);
        self.cells.push([NONE; 2]);
        let q = self.p - 1;
        self.points.extend(std::iter::repeat_n([0.0; 2], q));
        self.curved.push(false);
        self.set_points_from(id, a, from_a, curved);
        id
    }
}

/// The point at fraction `s` from `a` to `b`.
pub(crate) fn lerp(a: [f64; 2], b: [f64; 2], s: f64) -> [f64; 2] {
    [a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1])]
}
