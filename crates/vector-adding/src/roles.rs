//! The roles of a cell's local edges in the marching: which one is its bottom (two nodes of
//! the cell's layer) and which its top (two nodes of the layer above), [`NO_EDGE`] where it
//! has none. Computed once per curving ([`classify`]) and read by the marching, the repair and
//! the cutting.

use mesh_model::{Mesh, NONE, Shape};
use rayon::prelude::*;

/// No local edge.
pub(crate) const NO_EDGE: u8 = u8::MAX;

/// The bottom and top local edges of every cell (NO_EDGE where it has none): the bottom joins
/// two nodes of the cell's layer, the top two nodes of the layer above. Fill cells (from
/// `layered_cells` on) and cells that do not fit the pattern have neither. Each cell on its
/// own, on every thread.
pub(crate) fn classify(mesh: &Mesh, node_layer: &[u32], layered_cells: usize) -> Vec<[u8; 2]> {
    (0..mesh.cells.len())
        .into_par_iter()
        .with_min_len(1 << 12)
        .map(|i| {
            if i < layered_cells {
                roles_of(mesh, node_layer, i)
            } else {
                [NO_EDGE; 2]
            }
        })
        .collect()
}

/// The bottom and top local edges of layered cell `i` ([`classify`]).
fn roles_of(mesh: &Mesh, node_layer: &[u32], i: usize) -> [u8; 2] {
    let layer = mesh.cell_layer[i];
    if layer == NONE {
        return [NO_EDGE; 2];
    }
    let cell = mesh.cells.get(i);
    let k = cell.corners();
    let (mut bottom, mut top, mut bottoms, mut tops) = (NO_EDGE, NO_EDGE, 0, 0);
    for (j, e) in cell.ty.shape.edges().iter().enumerate() {
        let (la, lb) = (node_layer[k[e[0]] as usize], node_layer[k[e[1]] as usize]);
        if la == layer && lb == layer {
            bottom = j as u8;
            bottoms += 1;
        } else if la == layer + 1 && lb == layer + 1 {
            top = j as u8;
            tops += 1;
        }
    }
    if bottoms > 1 || tops > 1 {
        return [NO_EDGE; 2];
    }
    // a quadrilateral's top must face its bottom, so that the chords correspond
    if cell.ty.shape == Shape::Quad
        && bottom != NO_EDGE
        && top != NO_EDGE
        && (bottom + 2) % 4 != top
    {
        return [NO_EDGE; 2];
    }
    [bottom, top]
}
