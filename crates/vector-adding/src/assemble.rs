//! Builds the high-order mesh from the linear one, the edge table and the output cells: the
//! linear nodes keep their indices, then come the inner nodes of every edge, then the
//! interior nodes of every cell; cells and boundary lines list their nodes in Gmsh order.

use mesh_model::{CellType, Cells, Mesh, Shape};
use rayon::prelude::*;

use crate::cellmap::{Interiors, cell_nodes};
use crate::edges::EdgeTable;
use crate::split::OutCell;

/// The mesh of order `edges.p` over the `count` cells `cells(0..count)`; `sorted_edges` is how
/// many leading edges of the table are in sorted order (the linear mesh's own, before any
/// diagonal). `nodes` is the table's node array (`edges.nodes`, taken out of it: the linear
/// nodes, then the edges' inner points), which becomes the mesh's: it grows once, by exactly
/// the cells' interior nodes (the cells are walked twice: once to count them and their
/// nodes), and nothing in it is copied. The linear nodes are read from it and the cells from
/// `cells`: `linear.nodes` and `linear.cells` may have been let go. The per-cell records
/// (layer, pipe) of `linear` go with each cell when it has them.
///
/// The cells are assembled in chunks on every thread, a batch of chunks at a time, each
/// chunk's interior nodes numbered from where the chunks before it end (known from the
/// count), then appended in order: the same mesh, to the last bit, whatever the threads.
pub(crate) fn assemble(
    linear: &Mesh,
    edges: &EdgeTable,
    nodes: Vec<[f64; 3]>,
    sorted_edges: usize,
    cells: &(impl Fn(usize) -> OutCell + Sync),
    count: usize,
    interiors: &Interiors,
) -> Mesh {
    let p = edges.p;
    let mut mesh = Mesh::new(linear.dim, p as u8);
    let base = edges.base() as u32;
    // per chunk of cells, its interior nodes and its cells' nodes
    let chunks = count.div_ceil(CHUNK);
    let sizes: Vec<(usize, usize)> = (0..chunks)
        .into_par_iter()
        .map(|k| {
            chunk(k, count).fold((0, 0), |(interior, all), i| {
                let c = cells(i);
                (
                    interior + interiors.count(c.len(), p),
                    all + CellType::new(c.shape, p as u8).node_count(),
                )
            })
        })
        .collect();
    let interior_nodes = sizes.iter().map(|s| s.0).sum();
    let cell_nodes_count = sizes.iter().map(|s| s.1).sum();
    mesh.nodes = nodes;
    mesh.nodes.reserve_exact(interior_nodes);
    mesh.cells = Cells::with_capacity_for(count, cell_nodes_count);
    let has_layers = !linear.cell_layer.is_empty();
    let has_pipes = !linear.cell_pipe.is_empty();
    if has_layers {
        mesh.cell_layer.reserve_exact(count);
    }
    if has_pipes {
        mesh.cell_pipe.reserve_exact(count);
    }
    let mut first_interior = Vec::with_capacity(chunks);
    let mut next = mesh.nodes.len() as u32;
    for s in &sizes {
        first_interior.push(next);
        next += s.0 as u32;
    }
    let ty = |shape| CellType::new(shape, p as u8);
    // a batch of chunks at a time on every thread, then appended in order (the buffers of a
    // batch stay small next to the mesh: the assembly is at the run's memory peak)
    for batch in (0..chunks).step_by(BATCH) {
        let at = Assembly {
            edges,
            base,
            nodes: &mesh.nodes,
            interiors,
        };
        let built: Vec<Built> = (batch..chunks.min(batch + BATCH))
            .into_par_iter()
            .map(|k| at.chunk(chunk(k, count).map(cells), first_interior[k]))
            .collect();
        for b in built {
            let mut ids = &b.ids[..];
            for (&shape, &source) in b.shapes.iter().zip(&b.sources) {
                let (cell, rest) = ids.split_at(ty(shape).node_count());
                mesh.cells.push(ty(shape), cell);
                ids = rest;
                if has_layers {
                    mesh.cell_layer.push(linear.cell_layer[source as usize]);
                }
                if has_pipes {
                    mesh.cell_pipe.push(linear.cell_pipe[source as usize]);
                }
            }
            mesh.nodes.extend_from_slice(&b.interior);
        }
    }
    debug_assert_eq!(mesh.nodes.len() as u32, next);
    let q = p - 1;
    let mut ids = Vec::new();
    let line = CellType::new(Shape::Line, p as u8);
    mesh.boundary = Cells::with_capacity(linear.boundary.len(), p + 1);
    for b in linear.boundary.iter() {
        let (a, z) = (b.nodes[0], b.nodes[1]);
        let key = [a.min(z), a.max(z)];
        let e = edges.ends[..sorted_edges]
            .binary_search(&key)
            .expect("every boundary facet is an edge of a cell (checked when curving)")
            as u32;
        ids.clear();
        ids.extend([a, z]);
        ids.extend((0..q).map(|i| edge_node(edges, base, e, a, i)));
        mesh.boundary.push(line, &ids);
    }
    mesh.boundary_patch = linear.boundary_patch.clone();
    mesh.patches = linear.patches.clone();
    mesh
}

/// Cells per chunk of the assembly.
const CHUNK: usize = 2048;
/// Chunks assembled at once, on every thread.
const BATCH: usize = 32;

/// The cells of chunk `k` of `count` cells.
fn chunk(k: usize, count: usize) -> std::ops::Range<usize> {
    k * CHUNK..count.min((k + 1) * CHUNK)
}

/// The id of the `i`-th inner node of edge `e` counted from its end `from`.
fn edge_node(edges: &EdgeTable, base: u32, e: u32, from: u32, i: usize) -> u32 {
    let q = edges.p - 1;
    let j = if edges.ends[e as usize][0] == from {
        i
    } else {
        q - 1 - i
    };
    base + e * q as u32 + j as u32
}

/// What the chunks of the assembly read.
struct Assembly<'a> {
    edges: &'a EdgeTable,
    /// The first edge node's id.
    base: u32,
    /// The mesh's nodes as far as the edges' points go.
    nodes: &'a [[f64; 3]],
    interiors: &'a Interiors,
}

/// A chunk of assembled cells.
struct Built {
    /// Each cell's shape.
    shapes: Vec<Shape>,
    /// Each cell's linear source cell.
    sources: Vec<u32>,
    /// Every cell's nodes, one cell after the other, in Gmsh order.
    ids: Vec<u32>,
    /// The chunk's interior nodes, numbered from the chunk's first.
    interior: Vec<[f64; 3]>,
}

impl Assembly<'_> {
    /// The nodes of `cells`, their interior nodes numbered from `first`.
    fn chunk(&self, cells: impl Iterator<Item = OutCell>, first: u32) -> Built {
        let p = self.edges.p;
        let q = p - 1;
        let mut out = Built {
            shapes: Vec::with_capacity(CHUNK),
            sources: Vec::with_capacity(CHUNK),
            ids: Vec::new(),
            interior: Vec::new(),
        };
        let (mut corners, mut pts, mut coords) = (Vec::new(), Vec::new(), Vec::new());
        for c in cells {
            let n = c.len();
            let local = c.shape.edges();
            corners.clear();
            pts.clear();
            let start = out.ids.len();
            for &v in &c.corners[..n] {
                let x = self.nodes[v as usize];
                corners.push([x[0], x[1]]);
                out.ids.push(v);
            }
            for (j, e) in local.iter().enumerate() {
                let from = c.corners[e[0]];
                for i in 0..q {
                    let id = edge_node(self.edges, self.base, c.edges[j], from, i);
                    out.ids.push(id);
                    let v = self.nodes[id as usize];
                    pts.push([v[0], v[1]]);
                }
            }
            cell_nodes(p, &corners, &pts, self.interiors, &mut coords);
            let known = out.ids.len() - start;
            if let Some(x) = c.interior {
                coords[known] = x;
            }
            for x in &coords[known..] {
                out.ids.push(first + out.interior.len() as u32);
                out.interior.push([x[0], x[1], 0.0]);
            }
            out.shapes.push(c.shape);
            out.sources.push(c.source);
        }
        out
    }
}
