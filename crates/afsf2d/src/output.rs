//! The linear mesh out of what the layer loop and the fill made: the alive nodes compacted
//! (boundary first, then the layer nodes, then the fill's added nodes), the layered cells in
//! the layer loop's order, then the fill triangles with the layer and pipe of a neighbour.
//!
//! The layered part ([`LayeredPart`]) reads only what the layer loop left, so it is made
//! beside the fill, on the cells as they are before the fill peels any; [`output_cells`] then
//! takes the peeled cells out of it and adds the fill's nodes and triangles. The mesh is the
//! same, to the last entry, as one made after the fill from the cells left.

use mesh_model::cells::remove_sorted;
use mesh_model::{CellType, Cells, Mesh, NONE, Shape};

use crate::grow::Cell;
use crate::nodes::NodeStore;

/// The layered part of the mesh, made from the cells and nodes as the layer loop left them.
#[cfg_attr(test, derive(Debug, PartialEq))]
pub(crate) struct LayeredPart {
    /// The mesh number of each node of the layer loop (NONE: not alive).
    new_index: Vec<u32>,
    /// The alive nodes, in their new order.
    nodes: Vec<[f64; 3]>,
    /// Their parents and layers, in mesh numbers.
    node_parents: Vec<[u32; 2]>,
    node_layer: Vec<u32>,
    /// Each node's pipe, for the fill triangles: a boundary node the facet that starts at it,
    /// a layer node that of the first cell it is a corner of (NONE: none).
    node_pipe: Vec<u32>,
    /// The place among `cells` of the cell that gave each node its pipe (NONE: none did).
    first: Vec<u32>,
    /// The cells with corners (`len` > 0), their layers and pipes.
    cells: Cells,
    cell_layer: Vec<u32>,
    cell_pipe: Vec<u32>,
    /// The layer loop's index of each cell of `cells` (increasing).
    source: Vec<u32>,
}

impl LayeredPart {
    /// The part of `cells` over `nodes` (the first `n_boundary` of them the boundary's).
    pub(crate) fn new(cells: &[Cell], nodes: &NodeStore, n_boundary: usize) -> Self {
        let n = nodes.pos.len();
        // room for the nodes the fill adds too (about one for every sixteen layered nodes on
        // the built-in cases): the arrays are not moved when they come, and room not filled
        // is never touched
        let room = |k: usize| k + k / 4;
        let unset = |k: usize| {
            let mut v = Vec::with_capacity(room(k));
            v.resize(k, NONE);
            v
        };
        let mut new_index = unset(n);
        let mut next = 0u32;
        for (g, slot) in new_index.iter_mut().enumerate() {
            if nodes.alive[g] {
                *slot = next;
                next += 1;
            }
        }
        let mut part = LayeredPart {
            nodes: Vec::with_capacity(room(next as usize)),
            node_parents: Vec::with_capacity(room(next as usize)),
            node_layer: Vec::with_capacity(room(next as usize)),
            node_pipe: unset(n),
            first: vec![NONE; n],
            cells: Cells::new(),
            cell_layer: Vec::new(),
            cell_pipe: Vec::new(),
            source: Vec::new(),
            new_index,
        };
        for g in (0..n).filter(|&g| nodes.alive[g]) {
            part.push_node(nodes, g, nodes.layer[g]);
        }
        for (g, slot) in part.node_pipe.iter_mut().enumerate().take(n_boundary) {
            *slot = g as u32;
        }
        part.push_cells(cells);
        part
    }

    /// The layered cells, in mesh numbers.
    pub(crate) fn cells(&self) -> &Cells {
        &self.cells
    }

    /// How many nodes the part has (the mesh's first nodes).
    pub(crate) fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// Appends alive node `g` of `nodes`, of layer `layer`.
    fn push_node(&mut self, nodes: &NodeStore, g: usize, layer: u32) {
        let p = nodes.pos[g];
        self.nodes.push([p[0], p[1], 0.0]);
        let index = &self.new_index;
        self.node_parents.push(
            nodes
                .parents(g)
                .map(|p| if p == NONE { NONE } else { index[p as usize] }),
        );
        self.node_layer.push(layer);
    }

    /// The cells with corners, with their layers and pipes; each corner without a pipe
    /// takes its cell's.
    fn push_cells(&mut self, cells: &[Cell]) {
        let (quad, tri) = (CellType::new(Shape::Quad, 1), CellType::new(Shape::Tri, 1));
        let (mut count, mut corners) = (0, 0);
        for c in cells.iter().filter(|c| c.len > 0) {
            (count, corners) = (count + 1, corners + c.len as usize);
        }
        // room for the fill triangles too (about one for every eight layered cells on the
        // built-in cases, one for four at most): room not filled is never touched
        let room = count / 4;
        self.cells = Cells::with_capacity_for(count + room, corners + 3 * room);
        self.cell_layer.reserve_exact(count + room);
        self.cell_pipe.reserve_exact(count + room);
        self.source.reserve_exact(count);
        for (i, c) in cells.iter().enumerate().filter(|(_, c)| c.len > 0) {
            let mut k = [0u32; 4];
            for (slot, &g) in k.iter_mut().zip(c.corners()) {
                *slot = self.new_index[g as usize];
            }
            let k = &k[..c.corners().len()];
            self.cells.push(if c.len == 4 { quad } else { tri }, k);
            self.cell_layer.push(c.layer);
            self.cell_pipe.push(c.pipe);
            self.source.push(i as u32);
            let place = self.cells.len() as u32 - 1;
            for &g in c.corners() {
                if self.node_pipe[g as usize] == NONE {
                    self.node_pipe[g as usize] = c.pipe;
                    self.first[g as usize] = place;
                }
            }
        }
    }

    /// Takes the cells `peeled` (the layer loop's indices, after this part was made) out,
    /// and gives each corner whose first cell went the pipe of the next cell that has it as a
    /// corner (the arrays after the first peeled cell move down; nothing else is read).
    /// Returns the positions of the cells taken out, increasing.
    fn take_out(&mut self, peeled: &[u32], cells: &[Cell]) -> Vec<u32> {
        let mut at = Vec::with_capacity(peeled.len());
        // the corners whose pipe came from a peeled cell, with where to look on from (a
        // peeled cell's `len` is 0 by now; its corners are still in `nodes`)
        let mut again: Vec<(u32, usize)> = Vec::new();
        for &c in peeled {
            let Ok(k) = self.source.binary_search(&c) else {
                continue;
            };
            at.push(k);
            for &g in cells[c as usize].nodes.iter().filter(|&&g| g != NONE) {
                if self.first[g as usize] == k as u32 {
                    again.push((g, k));
                }
            }
        }
        at.sort_unstable();
        at.dedup();
        self.cells.remove_sorted(&at);
        for list in [&mut self.cell_layer, &mut self.cell_pipe, &mut self.source] {
            remove_sorted(list, &at);
        }
        for (g, k) in again {
            // the cells after the k-th kept one are at k - (peeled before it) on
            let from = k - at.partition_point(|&a| a < k);
            let next = (from..self.cells.len()).find(|&i| {
                self.cells
                    .get(i)
                    .corners()
                    .contains(&self.new_index[g as usize])
            });
            self.node_pipe[g as usize] = next.map_or(NONE, |i| cells[self.source[i] as usize].pipe);
        }
        at.into_iter().map(|k| k as u32).collect()
    }
}

/// Writes the nodes and cells of the grown and filled mesh into `mesh`: `part` (made before
/// the fill) without the cells `peeled`, then the nodes the fill added (those of `nodes` from
/// `n_grown` on) and its triangles `fill`, each with the layer and pipe of its highest grown
/// corner. `cells` are the layer loop's cells. Returns both parents and the layer of every
/// node, the number of layered cells, and the positions among `part`'s cells of those taken
/// out (increasing).
pub(crate) fn output_cells(
    mesh: &mut Mesh,
    mut part: LayeredPart,
    (cells, nodes): (&[Cell], &NodeStore),
    fill: &[[u32; 3]],
    peeled: &[u32],
) -> (Vec<[u32; 2]>, Vec<u32>, usize, Vec<u32>) {
    let n_grown = part.new_index.len();
    let left_out = if peeled.is_empty() {
        Vec::new()
    } else {
        part.take_out(peeled, cells)
    };
    let mut next = part.nodes.len() as u32;
    for g in n_grown..nodes.pos.len() {
        if nodes.alive[g] {
            part.new_index.push(next);
            next += 1;
            part.push_node(nodes, g, NONE);
        } else {
            part.new_index.push(NONE);
        }
    }
    let n_all = nodes.pos.len();
    part.node_pipe.resize(n_all, NONE);
    // fill triangles take the layer and pipe of their highest grown corner; triangles whose
    // corners are all fill nodes take them from a neighbour, pass after pass
    let mut node_fill_layer: Vec<u32> = (0..n_all)
        .map(|g| if g < n_grown { nodes.layer[g] } else { NONE })
        .collect();
    let layered_cells = part.cells.len();
    let fill_tag = fill_tags(fill, &mut part.node_pipe, &mut node_fill_layer);
    let tri = CellType::new(Shape::Tri, 1);
    for (t, tag) in fill.iter().zip(&fill_tag) {
        let k = t.map(|g| part.new_index[g as usize]);
        part.cells.push(tri, &k);
        part.cell_layer.push(tag.0);
        part.cell_pipe.push(tag.1);
    }
    debug_assert!(mesh.nodes.is_empty() && mesh.cells.is_empty());
    mesh.nodes = part.nodes;
    mesh.cells = part.cells;
    mesh.cell_layer = part.cell_layer;
    mesh.cell_pipe = part.cell_pipe;
    (part.node_parents, part.node_layer, layered_cells, left_out)
}

/// The (layer, pipe) of each fill triangle: those of its highest corner that has a pipe;
/// corners without one take the triangle's, and triangles with no such corner wait for a
/// later pass.
fn fill_tags(
    fill: &[[u32; 3]],
    node_pipe: &mut [u32],
    node_fill_layer: &mut [u32],
) -> Vec<(u32, u32)> {
    let mut fill_tag = vec![(NONE, NONE); fill.len()];
    loop {
        let mut changed = false;
        let mut missing = false;
        for (t, tag) in fill.iter().zip(fill_tag.iter_mut()) {
            if tag.1 != NONE {
                continue;
            }
            let best = t
                .iter()
                .filter(|&&g| node_pipe[g as usize] != NONE)
                .max_by_key(|&&g| node_fill_layer[g as usize]);
            let Some(&top) = best else {
                missing = true;
                continue;
            };
            *tag = (node_fill_layer[top as usize], node_pipe[top as usize]);
            for &g in t {
                if node_pipe[g as usize] == NONE {
                    node_pipe[g as usize] = tag.1;
                    node_fill_layer[g as usize] = tag.0;
                }
            }
            changed = true;
        }
        if !missing || !changed {
            break;
        }
    }
    fill_tag
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nodes::NewNode;

    /// Rows of 7 nodes (the first row the boundary) joined by quads, a triangle at the end of
    /// each layer, a dead node in the second row; each node's parent the node below it.
    fn grid() -> (Vec<Cell>, NodeStore) {
        let mut nodes = NodeStore::boundary((0..7).map(|i| [i as f64, 0.0]).collect());
        for row in 1..4u32 {
            for i in 0..7u32 {
                let g = nodes.push_node(NewNode {
                    layer: row,
                    parent: (row - 1) * 7 + i,
                    ..NewNode::unlayered([i as f64 + 0.1 * row as f64, row as f64])
                });
                if row == 2 && i == 3 {
                    nodes.alive[g as usize] = false;
                }
            }
        }
        let mut cells = Vec::new();
        for row in 0..3u32 {
            for i in 0..5u32 {
                let a = row * 7 + i;
                cells.push(Cell {
                    nodes: [a, a + 1, a + 8, a + 7],
                    len: 4,
                    layer: row + 1,
                    pipe: i + 10 * row,
                    origin: [0, i, NONE],
                });
            }
            let a = row * 7 + 5;
            cells.push(Cell {
                nodes: [a, a + 1, a + 7, NONE],
                len: 3,
                layer: row + 1,
                pipe: 5 + row,
                origin: [0, 5, NONE],
            });
        }
        cells[4].len = 0; // a cell the layer loop left without corners
        (cells, nodes)
    }

    #[test]
    fn a_part_made_before_the_peel_is_the_part_made_after_it() {
        for peeled in [
            vec![],
            vec![7],
            vec![0, 6, 17],
            vec![12, 13, 14, 15, 16, 17],
        ] {
            let (mut cells, nodes) = grid();
            let mut before = LayeredPart::new(&cells, &nodes, 7);
            for &c in &peeled {
                cells[c as usize].len = 0;
            }
            let mut after = LayeredPart::new(&cells, &nodes, 7);
            if !peeled.is_empty() {
                assert_ne!(before, after, "peeling {peeled:?} changes the part");
                before.take_out(&peeled, &cells);
            }
            // (the places of the cells that gave the pipes are bookkeeping of the take-out)
            for part in [&mut before, &mut after] {
                part.first.clear();
            }
            assert_eq!(before, after, "peeling {peeled:?}");
        }
    }
}
