//! The edges of a 2D mesh, each stored once with its high-order points: the table the
//! marching writes into and the assembly reads from, so that a curved edge is curved the same
//! way in both cells that share it.

use mesh_model::{Mesh, NONE};
use rayon::prelude::*;

use crate::decisions::{Carry, EdgeRule, EdgeRules, lay};

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
    /// The high-order mesh's node array as far as the edges go: the linear mesh's nodes, then
    /// `p − 1` points per edge (from `ends[0]` to `ends[1]`), edge by edge. The assembly
    /// takes it and appends the cells' interior nodes, so the edges' points are never
    /// copied (at 1M cells, a copy would sit at the run's memory peak).
    pub nodes: Vec<[f64; 3]>,
    /// Where the edges' points start in `nodes`: the linear mesh's node count.
    base: usize,
    /// Whether an edge's points were moved off its chord.
    pub curved: Vec<bool>,
    /// How each edge got its points (the record of the decisions).
    pub rules: EdgeRules,
}

impl EdgeTable {
    /// The edges of the linear mesh `mesh`, every one straight, for order `p`.
    pub fn new(mesh: &Mesh, p: usize) -> Self {
        Self::with_room(mesh, p, 0, None)
    }

    /// [`EdgeTable::new`], its node array reserved for `room` more nodes than the edges need
    /// (the cells' interior nodes and any diagonals the assembly and the cut will add), so that
    /// it is never moved as it grows: a move of the array, then some 5M nodes, cost a copy and
    /// the faulting-in of a second array at the run's memory peak. `topology`: the mesh's
    /// edge table when it is already made (`mesh_model::topology::edge_table_2d`'s arrays).
    pub fn with_room(
        mesh: &Mesh,
        p: usize,
        room: usize,
        topology: Option<mesh_model::topology::EdgeTable2d>,
    ) -> Self {
        // the mesh's unique edges in the topology's order (sorted by their end nodes), which
        // the high-order node numbering follows; a 2D cell has at most four edges
        let (ends, cells, cell_edges) =
            topology.unwrap_or_else(|| crate::table::edge_table_2d(&mesh.cells, mesh.nodes.len()));
        let mut table = EdgeTable {
            p,
            ends,
            cells,
            cell_edges,
            nodes: Vec::new(),
            base: mesh.nodes.len(),
            curved: Vec::new(),
            rules: EdgeRules::default(),
        };
        table.nodes = Vec::with_capacity(table.base + table.ends.len() * (p - 1) + room);
        // (on every thread: the copy is the first touch of these pages of the array)
        table.nodes.par_extend(mesh.nodes.par_iter().copied());
        // the edges' points, on every thread, straight into the reserved array
        let (q, ends) = (p - 1, &table.ends);
        table
            .nodes
            .par_extend((0..ends.len() * q).into_par_iter().map(|k| {
                let [a, b] = ends[k / q];
                let x = lerp(mesh.xy(a), mesh.xy(b), (k % q + 1) as f64 / p as f64);
                [x[0], x[1], 0.0]
            }));
        table.curved = vec![false; table.ends.len()];
        table.rules = EdgeRules::straight(table.ends.len());
        table
    }

    /// Where the edges' points start in `nodes`: the linear mesh's node count.
    pub fn base(&self) -> usize {
        self.base
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
        let at = self.base + e as usize * q;
        let pts = self.nodes[at..at + q].iter().map(|v| [v[0], v[1]]);
        if self.ends[e as usize][0] == from {
            out[..q].iter_mut().zip(pts).for_each(|(o, v)| *o = v);
        } else {
            out[..q].iter_mut().zip(pts.rev()).for_each(|(o, v)| *o = v);
        }
    }

    /// Sets the inner points of edge `e`, given from node `from` to the other end.
    pub fn set_points_from(&mut self, e: u32, from: u32, pts: &[[f64; 2]], curved: bool) {
        let q = self.p - 1;
        let forward = self.ends[e as usize][0] == from;
        let at = self.base + e as usize * q;
        for (i, dst) in self.nodes[at..at + q].iter_mut().enumerate() {
            let v = if forward { pts[i] } else { pts[q - 1 - i] };
            *dst = [v[0], v[1], 0.0];
        }
        self.curved[e as usize] = curved;
    }

    /// Gives edge `e` the points `pts` (listed from `rule.from`) that `rule` made, and records
    /// the rule.
    pub fn carry(&mut self, e: u32, rule: Carry, pts: &[[f64; 2]]) {
        self.set_points_from(e, rule.from, pts, true);
        self.rules.set(e as usize, EdgeRule::Carried(rule));
    }

    /// Lays edge `e`'s points by `rule` from the current points of its source (`dev` is
    /// scratch of `p − 1` slots).
    pub fn apply(&mut self, mesh: &Mesh, e: u32, rule: Carry, dev: &mut [[f64; 2]]) {
        self.deviation(mesh, rule.source, rule.source_from, dev);
        let [u, w] = self.ends[e as usize];
        let to = if u == rule.from { w } else { u };
        let mut pts = vec![[0.0; 2]; self.p - 1];
        let (xf, xt) = (mesh.xy(rule.from), mesh.xy(to));
        lay(self.p, xf, xt, dev, rule.reversed, rule.fraction, &mut pts);
        self.carry(e, rule, &pts);
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
        self.nodes.extend(std::iter::repeat_n([0.0; 3], q));
        self.curved.push(false);
        self.rules.push(EdgeRule::Straight);
        self.set_points_from(id, a, from_a, curved);
        id
    }
}

/// The point at fraction `s` from `a` to `b`.
pub(crate) fn lerp(a: [f64; 2], b: [f64; 2], s: f64) -> [f64; 2] {
    [a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1])]
}
