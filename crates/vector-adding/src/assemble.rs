//! Builds the high-order mesh from the linear one, the edge table and the output cells: the
//! linear nodes keep their indices, then come the inner nodes of every edge, then the
//! interior nodes of every cell; cells and boundary lines list their nodes in Gmsh order.

use mesh_model::{CellType, Cells, Mesh, Shape};

use crate::cellmap::{Interiors, cell_nodes};
use crate::edges::EdgeTable;
use crate::split::OutCell;

/// The mesh of order `edges.p` over `cells`; `sorted_edges` is how many leading edges of the
/// table are in sorted order (the linear mesh's own, before any diagonal). `nodes` is the
/// table's node array (`edges.nodes`, taken out of it: the linear nodes, then the edges'
/// inner points), which becomes the mesh's: it grows once, by exactly the cells' interior
/// nodes (`cells` is walked twice: once to count them and their nodes), and nothing in it is
/// copied. The linear nodes are read from it and the cells from `cells`: `linear.nodes` and
/// `linear.cells` may have been let go. The per-cell records (layer, pipe) of `linear` go
/// with each cell when it has them.
pub(crate) fn assemble(
    linear: &Mesh,
    edges: &EdgeTable,
    nodes: Vec<[f64; 3]>,
    sorted_edges: usize,
    cells: impl Iterator<Item = OutCell> + Clone,
    interiors: &Interiors,
) -> Mesh {
    let p = edges.p;
    let q = p - 1;
    let mut mesh = Mesh::new(linear.dim, p as u8);
    let base = edges.base() as u32;
    let (mut cell_count, mut interior_nodes, mut cell_nodes_count) = (0, 0, 0);
    for c in cells.clone() {
        cell_count += 1;
        interior_nodes += interiors.count(c.len(), p);
        cell_nodes_count += CellType::new(c.shape, p as u8).node_count();
    }
    mesh.nodes = nodes;
    mesh.nodes.reserve_exact(interior_nodes);
    let edge_node = |e: u32, from: u32, i: usize| -> u32 {
        let j = if edges.ends[e as usize][0] == from {
            i
        } else {
            q - 1 - i
        };
        base + e * q as u32 + j as u32
    };
    mesh.cells = Cells::with_capacity_for(cell_count, cell_nodes_count);
    let (mut corners, mut pts, mut coords, mut ids) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let has_layers = !linear.cell_layer.is_empty();
    let has_pipes = !linear.cell_pipe.is_empty();
    if has_layers {
        mesh.cell_layer.reserve_exact(cell_count);
    }
    if has_pipes {
        mesh.cell_pipe.reserve_exact(cell_count);
    }
    for c in cells {
        let n = c.len();
        let local = c.shape.edges();
        corners.clear();
        pts.clear();
        ids.clear();
        for &v in &c.corners[..n] {
            let x = mesh.nodes[v as usize];
            corners.push([x[0], x[1]]);
            ids.push(v);
        }
        for (j, e) in local.iter().enumerate() {
            let from = c.corners[e[0]];
            for i in 0..q {
                let id = edge_node(c.edges[j], from, i);
                ids.push(id);
                let v = mesh.nodes[id as usize];
                pts.push([v[0], v[1]]);
            }
        }
        cell_nodes(p, &corners, &pts, interiors, &mut coords);
        if let Some(x) = c.interior {
            coords[ids.len()] = x;
        }
        for x in &coords[ids.len()..] {
            ids.push(mesh.nodes.len() as u32);
            mesh.nodes.push([x[0], x[1], 0.0]);
        }
        mesh.cells.push(CellType::new(c.shape, p as u8), &ids);
        if has_layers {
            mesh.cell_layer.push(linear.cell_layer[c.source as usize]);
        }
        if has_pipes {
            mesh.cell_pipe.push(linear.cell_pipe[c.source as usize]);
        }
    }
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
        ids.extend((0..q).map(|i| edge_node(e, a, i)));
        mesh.boundary.push(line, &ids);
    }
    mesh.boundary_patch = linear.boundary_patch.clone();
    mesh.patches = linear.patches.clone();
    mesh
}
