//! The sweep: one global order of the nodes to cut around.
//!
//! Lower fronts come first (a node's level is its cell's layer when it is on the bottom, one
//! more when it is a child). Within a front, the order is the wall's: the wall nodes sorted by
//! the deviation of their extrusion edge from the wall normal (the dissertation's "start with
//! the extrusion edge which has the smallest deviation angle from its ideal extruding
//! direction"), every child inheriting its parent's key, a merged child the smallest of its
//! parents' (a merging group is swept at once). Inheriting keeps a hexahedron's first bottom
//! node under its first top node, so the top's diagonal passes over the bottom's and no
//! tetrahedron lies flat in a thin layer. Ties are broken by node index. A node on both the
//! bottom and the top of a cell (its column stopped, `afsf3d`) comes first in its level: the
//! cells beside a stopped column are thin where their top and bottom meet, and only the cones
//! from the stopped node are sure.

use mesh_model::NONE;
use mesh_model::poly::PolyMesh;

use crate::cone::{CellFaces, UNRANKED};
use crate::improve::{Around, INVERTED, Scratch, piece_quality};
use crate::{CutError, TARGET_DIHEDRAL_DEG};

/// The cells in the order of their layers (cells without a layer last), then by index.
pub fn cells_by_layer(poly: &PolyMesh) -> Vec<u32> {
    let layer = |c: u32| poly.cell_layer.get(c as usize).copied().unwrap_or(NONE);
    let mut cells: Vec<u32> = (0..poly.cell_count() as u32).collect();
    cells.sort_by_key(|&c| (layer(c), c));
    cells
}

/// Whether bottom node `v` of a cell is kept: on its top (face 1) as well, its column
/// stopped (`afsf3d`), so it has no child in the cell.
fn kept(faces: &CellFaces, v: u32) -> bool {
    faces.len() > 1 && faces.face(1).contains(&v)
}

/// The child of bottom node `v` in a cell: the node joined to it by an edge of the cell and
/// not on the bottom (face 0); none for a kept node ([`kept`]).
pub(crate) fn child(faces: &CellFaces, v: u32) -> Option<u32> {
    let bottom = faces.face(0);
    if kept(faces, v) {
        return None;
    }
    faces.faces().skip(1).find_map(|k| {
        let at = k.iter().position(|&x| x == v)?;
        let next = k[(at + 1) % k.len()];
        let prev = k[(at + k.len() - 1) % k.len()];
        [next, prev].into_iter().find(|x| !bottom.contains(x))
    })
}

/// Newell's normal of the polygon `k` (twice its vector area).
fn newell(nodes: &[[f64; 3]], k: &[u32]) -> [f64; 3] {
    let mut n = [0.0; 3];
    for i in 0..k.len() {
        let (p, q) = (nodes[k[i] as usize], nodes[k[(i + 1) % k.len()] as usize]);
        n[0] += (p[1] - q[1]) * (p[2] + q[2]);
        n[1] += (p[2] - q[2]) * (p[0] + q[0]);
        n[2] += (p[0] - q[0]) * (p[1] + q[1]);
    }
    n
}

fn angle(a: [f64; 3], b: [f64; 3]) -> f64 {
    let dot: f64 = (0..3).map(|d| a[d] * b[d]).sum();
    let na = a.iter().map(|x| x * x).sum::<f64>().sqrt();
    let nb = b.iter().map(|x| x * x).sum::<f64>().sqrt();
    let c = dot / (na * nb);
    if c.is_finite() {
        c.clamp(-1.0, 1.0).acos()
    } else {
        std::f64::consts::PI
    }
}

/// The sweep rank of every node (0 = first); every node is ranked.
pub fn sweep_ranks(poly: &PolyMesh) -> Vec<u32> {
    let n = poly.nodes.len();
    let cells = cells_by_layer(poly);
    let mut faces = CellFaces::default();
    // the normal of the front at each bottom node: the bottoms around it, turned away from
    // the wall (a bottom faces out of its cell, toward the wall)
    let mut normal = vec![[0.0f64; 3]; n];
    for &c in &cells {
        faces.load(poly, c as usize);
        let m = newell(&poly.nodes, faces.face(0));
        for &v in faces.face(0) {
            (0..3).for_each(|d| normal[v as usize][d] -= m[d]);
        }
    }
    let mut level = vec![u32::MAX; n];
    let mut key = vec![f64::INFINITY; n];
    for &c in &cells {
        faces.load(poly, c as usize);
        let layer = poly.cell_layer.get(c as usize).copied().unwrap_or(NONE);
        let layer = if layer == NONE { u32::MAX - 1 } else { layer };
        for i in 0..faces.face(0).len() {
            let v = faces.face(0)[i] as usize;
            let ch = child(&faces, v as u32);
            if level[v] == u32::MAX && kept(&faces, v as u32) {
                // a stopped column's node first in its level: the apex of the cells beside
                // it, whose cones from it `afsf3d` checked (their other cones may fold)
                level[v] = layer;
                key[v] = f64::NEG_INFINITY;
            } else if level[v] == u32::MAX {
                level[v] = layer;
                key[v] = ch.map_or(f64::INFINITY, |u| {
                    let p = poly.nodes[u as usize];
                    let q = poly.nodes[v];
                    angle([p[0] - q[0], p[1] - q[1], p[2] - q[2]], normal[v])
                });
            }
            if let Some(u) = ch {
                let u = u as usize;
                level[u] = level[u].min(level[v].saturating_add(1));
                key[u] = key[u].min(key[v]);
            }
        }
    }
    let mut order: Vec<u32> = (0..n as u32).collect();
    order.sort_by(|&a, &b| {
        let (a, b) = (a as usize, b as usize);
        level[a]
            .cmp(&level[b])
            .then(key[a].total_cmp(&key[b]))
            .then(a.cmp(&b))
    });
    let mut rank = vec![0u32; n];
    for (r, &v) in order.iter().enumerate() {
        rank[v as usize] = r as u32;
    }
    rank
}

/// The ranks restricted to the nodes round-cut for the mixed mesh (the others
/// [`UNRANKED`]): for each non-standard cell (or standard one with a corner not positive), in
/// layer order, that has no such node yet, the
/// node of it whose cut keeps the cells around it under the target dihedral angle, then
/// touches the fewest standard cells still untouched, then cuts best (ties: first in the
/// sweep). The cells `cut_anyway` flags (one flag per cell, or none) count as non-standard.
pub fn round_cut_ranks(
    poly: &PolyMesh,
    sweep: &[u32],
    cut_anyway: &[bool],
) -> Result<Vec<u32>, CutError> {
    let cc = poly.cell_count();
    let mut faces = CellFaces::default();
    let mut cell_nodes: Vec<Vec<u32>> = Vec::with_capacity(cc);
    let mut standard = vec![false; cc];
    for (c, is_standard) in standard.iter_mut().enumerate() {
        crate::load_checked(&mut faces, poly, c)?;
        // a standard cell with a corner not positive (a warped merged cell) is cut as well
        *is_standard = !cut_anyway.get(c).copied().unwrap_or(false)
            && faces
                .standard()
                .is_some_and(|p| piece_quality(&poly.nodes, &p) < INVERTED);
        let mut nodes = Vec::new();
        faces.distinct_nodes(&mut nodes);
        cell_nodes.push(nodes);
    }
    let around = Around::new(poly);
    let mut scratch = Scratch::default();
    let mut rank = vec![UNRANKED; poly.nodes.len()];
    let mut touched = vec![false; cc];
    for c in cells_by_layer(poly) {
        let c = c as usize;
        if standard[c] || touched[c] {
            continue;
        }
        let mut best: Option<((bool, usize, f64, u32), u32)> = None;
        for &v in &cell_nodes[c] {
            let cells = around.of(v);
            let disturbed = cells
                .iter()
                .filter(|&&d| standard[d as usize] && !touched[d as usize])
                .count();
            rank[v as usize] = sweep[v as usize];
            let worst = cells
                .iter()
                .map(|&d| scratch.quality(poly, d, &rank))
                .fold(0.0, f64::max);
            rank[v as usize] = UNRANKED;
            let key = (
                worst > TARGET_DIHEDRAL_DEG,
                disturbed,
                worst,
                sweep[v as usize],
            );
            if best.is_none_or(|b| key < b.0) {
                best = Some((key, v));
            }
        }
        if let Some((_, v)) = best {
            rank[v as usize] = sweep[v as usize];
            around
                .of(v)
                .iter()
                .for_each(|&d| touched[d as usize] = true);
        }
    }
    uncover_inverted(poly, sweep, &around, &mut rank);
    Ok(rank)
}

/// The most rounds of [`uncover_inverted`]: each splits one more quadrilateral per inverted
/// piece, and a chain of warped quadrilaterals takes one round a link (the slot of `afsf3d`'s
/// `tests/integration/stop.rs`, whose layers outgrow its width, needs 17; 8 left it inverted).
const UNCOVER_ROUNDS: usize = 64;

/// Where a round-cut cell still has a piece that is not positive (a pyramid over a warped
/// quadrilateral of a kept neighbour), ranks one more node of it, the one whose cut keeps
/// the cells around it best, so that the quadrilateral is split and the neighbour cut too;
/// round after round while one ranks a node, at most [`UNCOVER_ROUNDS`] (every node ranked
/// is the pure tetrahedral cut).
fn uncover_inverted(poly: &PolyMesh, sweep: &[u32], around: &Around, rank: &mut [u32]) {
    let mut scratch = Scratch::default();
    let mut faces = CellFaces::default();
    let mut nodes = Vec::new();
    for _ in 0..UNCOVER_ROUNDS {
        let mut changed = false;
        for c in 0..poly.cell_count() as u32 {
            if scratch.quality(poly, c, rank) < INVERTED {
                continue;
            }
            faces.load(poly, c as usize);
            faces.distinct_nodes(&mut nodes);
            nodes.retain(|&v| rank[v as usize] == UNRANKED);
            let mut best: Option<(f64, u32)> = None;
            for &v in &nodes {
                rank[v as usize] = sweep[v as usize];
                let worst = around
                    .of(v)
                    .iter()
                    .map(|&d| scratch.quality(poly, d, rank))
                    .fold(0.0, f64::max);
                rank[v as usize] = UNRANKED;
                if best.is_none_or(|b| worst < b.0) {
                    best = Some((worst, v));
                }
            }
            if let Some((_, v)) = best {
                rank[v as usize] = sweep[v as usize];
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
}
