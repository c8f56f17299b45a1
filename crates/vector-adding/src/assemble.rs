//! Builds the high-order mesh from the linear one, the edge table and the output cells: the
//! linear nodes keep their indices, then come the inner nodes of every edge, then the
//! interior nodes of every cell; cells and boundary lines list their nodes in Gmsh order.
//!
//! The cells are assembled in chunks on every thread: a first pass counts each chunk's
//! interior nodes and cell nodes, so that every chunk knows where its nodes and its cells'
//! node lists go, then each chunk fills its own ranges. The numbering is the sequential one
//! (interior nodes in cell order), whatever the number of threads.

use mesh_model::{CellType, Cells, Mesh, Shape};
use rayon::prelude::*;

use crate::cellmap::{Interiors, cell_nodes};
use crate::edges::EdgeTable;
use crate::split::OutCell;

/// Cells per chunk of the assembly.
const CHUNK: usize = 8192;

/// The mesh of order `edges.p` over the `count` output cells `cell(0..count)`;
/// `sorted_edges` is how many leading edges of the table are in sorted order (the linear
/// mesh's own, before any diagonal). `nodes` is the table's node array (`edges.nodes`, taken
/// out of it: the linear nodes, then the edges' inner points), which becomes the mesh's: it
/// grows once, by exactly the cells' interior nodes, and nothing in it is copied. The linear
/// nodes are read from it and the cells from `cell`: `linear.nodes` and `linear.cells` may
/// have been let go. The per-cell records (layer, pipe) of `linear` go with each cell when it
/// has them.
pub(crate) fn assemble<C>(
    linear: &Mesh,
    edges: &EdgeTable,
    nodes: Vec<[f64; 3]>,
    sorted_edges: usize,
    (count, cell): (usize, C),
    interiors: &Interiors,
) -> Mesh
where
    C: Fn(usize) -> OutCell + Sync,
{
    let p = edges.p;
    let mut mesh = Mesh::new(linear.dim, p as u8);
    let chunk = |k: usize| k * CHUNK..((k + 1) * CHUNK).min(count);
    // per chunk: its cells' interior nodes, and their nodes in all
    let sizes: Vec<(usize, usize)> = (0..count.div_ceil(CHUNK))
        .into_par_iter()
        .map(|k| {
            chunk(k).map(&cell).fold((0, 0), |(i, n), c| {
                let ty = CellType::new(c.shape, p as u8);
                (i + interiors.count(c.len(), p), n + ty.node_count())
            })
        })
        .collect();
    let first_interior = nodes.len();
    let interior_nodes: usize = sizes.iter().map(|s| s.0).sum();
    let cell_nodes_count: usize = sizes.iter().map(|s| s.1).sum();
    mesh.nodes = nodes;
    // (a no-op when the table reserved the room; the zeros are written on every thread)
    mesh.nodes.reserve_exact(interior_nodes);
    mesh.nodes
        .par_extend((0..interior_nodes).into_par_iter().map(|_| [0.0; 3]));
    let mut flat = Vec::with_capacity(cell_nodes_count);
    flat.par_extend((0..cell_nodes_count).into_par_iter().map(|_| 0u32));
    let mut offsets = vec![0u32; count + 1];
    // (each chunk sets its cells' types; the value here is only a start)
    let mut types = vec![CellType::new(Shape::Tri, p as u8); count];
    {
        let (head, mut interior) = mesh.nodes.split_at_mut(first_interior);
        let (mut ids, mut ends) = (&mut flat[..], &mut offsets[1..]);
        let mut kinds = &mut types[..];
        let (mut node, mut at) = (first_interior, 0);
        let mut jobs = Vec::with_capacity(sizes.len());
        for (k, &(n_interior, n_nodes)) in sizes.iter().enumerate() {
            let job = Chunk {
                cells: chunk(k),
                interior: take_front(&mut interior, n_interior),
                ids: take_front(&mut ids, n_nodes),
                ends: take_front(&mut ends, chunk(k).len()),
                types: take_front(&mut kinds, chunk(k).len()),
                first_node: node as u32,
                first_id: at as u32,
            };
            (node, at) = (node + n_interior, at + n_nodes);
            jobs.push(job);
        }
        let shared = Shared {
            p,
            nodes: head,
            edges,
            interiors,
        };
        jobs.into_par_iter().for_each(|job| shared.fill(job, &cell));
    }
    mesh.cells = Cells::from_parts(types, offsets, flat);
    let record = |of: &[u32]| -> Vec<u32> {
        (0..count)
            .into_par_iter()
            .map(|i| of[cell(i).source as usize])
            .collect()
    };
    if !linear.cell_layer.is_empty() {
        mesh.cell_layer = record(&linear.cell_layer);
    }
    if !linear.cell_pipe.is_empty() {
        mesh.cell_pipe = record(&linear.cell_pipe);
    }
    boundary_lines(&mut mesh, linear, edges, sorted_edges);
    mesh
}

/// The first `n` items of `rest`, taken off it.
fn take_front<'a, T>(rest: &mut &'a mut [T], n: usize) -> &'a mut [T] {
    let (front, back) = std::mem::take(rest).split_at_mut(n);
    *rest = back;
    front
}

/// What every chunk reads.
struct Shared<'a> {
    p: usize,
    /// The linear nodes, then the edges' inner points.
    nodes: &'a [[f64; 3]],
    edges: &'a EdgeTable,
    interiors: &'a Interiors,
}

/// One chunk of cells and the ranges it fills.
struct Chunk<'a> {
    cells: std::ops::Range<usize>,
    /// Its cells' interior nodes, in cell order.
    interior: &'a mut [[f64; 3]],
    /// Its cells' node lists, one after the other.
    ids: &'a mut [u32],
    /// Where each of its cells' node list ends in the whole list.
    ends: &'a mut [u32],
    /// Its cells' types.
    types: &'a mut [CellType],
    /// The number of its first interior node.
    first_node: u32,
    /// Where its first cell's node list starts in the whole list.
    first_id: u32,
}

impl Shared<'_> {
    /// Fills `job`'s ranges with the nodes and node lists of its cells.
    fn fill(&self, job: Chunk<'_>, cell: impl Fn(usize) -> OutCell) {
        let (p, q) = (self.p, self.p - 1);
        let (mut corners, mut pts, mut coords, mut ids) =
            (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        let (mut node, mut written, mut at) = (job.first_node, 0, 0);
        for (j, i) in job.cells.enumerate() {
            let c = cell(i);
            corners.clear();
            pts.clear();
            ids.clear();
            for &v in &c.corners[..c.len()] {
                let x = self.nodes[v as usize];
                corners.push([x[0], x[1]]);
                ids.push(v);
            }
            for (k, e) in c.shape.edges().iter().enumerate() {
                let from = c.corners[e[0]];
                for i in 0..q {
                    let id = edge_node(self.edges, c.edges[k], from, i);
                    ids.push(id);
                    let v = self.nodes[id as usize];
                    pts.push([v[0], v[1]]);
                }
            }
            cell_nodes(p, &corners, &pts, self.interiors, &mut coords);
            if let Some(x) = c.interior {
                coords[ids.len()] = x;
            }
            for x in &coords[ids.len()..] {
                ids.push(node);
                job.interior[written] = [x[0], x[1], 0.0];
                (node, written) = (node + 1, written + 1);
            }
            job.ids[at..at + ids.len()].copy_from_slice(&ids);
            at += ids.len();
            job.ends[j] = job.first_id + at as u32;
            job.types[j] = CellType::new(c.shape, p as u8);
        }
    }
}

/// The node of index `i` (0..p − 1, from `from`, one end of the edge) on edge `e`.
fn edge_node(edges: &EdgeTable, e: u32, from: u32, i: usize) -> u32 {
    let q = edges.p - 1;
    let j = if edges.ends[e as usize][0] == from {
        i
    } else {
        q - 1 - i
    };
    edges.base() as u32 + e * q as u32 + j as u32
}

/// The boundary lines of `linear` at the mesh's order, through their edges' points.
fn boundary_lines(mesh: &mut Mesh, linear: &Mesh, edges: &EdgeTable, sorted_edges: usize) {
    let p = edges.p;
    let line = CellType::new(Shape::Line, p as u8);
    mesh.boundary = Cells::with_capacity(linear.boundary.len(), p + 1);
    let mut ids = Vec::with_capacity(p + 1);
    for b in linear.boundary.iter() {
        let (a, z) = (b.nodes[0], b.nodes[1]);
        let key = [a.min(z), a.max(z)];
        let e = edges.ends[..sorted_edges]
            .binary_search(&key)
            .expect("every boundary facet is an edge of a cell (checked when curving)")
            as u32;
        ids.clear();
        ids.extend([a, z]);
        ids.extend((0..p - 1).map(|i| edge_node(edges, e, a, i)));
        mesh.boundary.push(line, &ids);
    }
    mesh.boundary_patch = linear.boundary_patch.clone();
    mesh.patches = linear.patches.clone();
}
