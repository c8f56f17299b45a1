//! The marching up the pipes: each layered cell whose bottom edge is curved decides its top
//! edge — the bottom's deviation from its chord laid onto the top chord (Vector-Adding), or
//! straight when the pipe stops. Cells are visited layer by layer, so a bottom edge is final
//! before the cell above reads it.

use jacobian_check::Certificate;
use mesh_model::{Mesh, NONE, Role, Shape};

use crate::cellcheck::{Ctx, Scratch, check, quality};
use crate::cellmap::Interiors;
use crate::decisions::{Carry, lay};
use crate::edges::EdgeTable;
use crate::error::CurvingError;
use crate::params::CurvingParams;
use crate::stats::StopCounts;

/// No local edge.
pub(crate) const NO_EDGE: u8 = u8::MAX;

/// The bottom and top local edges of every cell (NO_EDGE where it has none): the bottom joins
/// two nodes of the cell's layer, the top two nodes of the layer above. Fill cells (from
/// `layered_cells` on) and cells that do not fit the pattern have neither.
pub(crate) fn classify(mesh: &Mesh, node_layer: &[u32], layered_cells: usize) -> Vec<[u8; 2]> {
    let mut out = vec![[NO_EDGE; 2]; mesh.cells.len()];
    for (i, cell) in mesh.cells.iter().enumerate().take(layered_cells) {
        let layer = mesh.cell_layer[i];
        if layer == NONE {
            continue;
        }
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
            continue;
        }
        // a quadrilateral's top must face its bottom, so that the chords correspond
        if cell.ty.shape == Shape::Quad
            && bottom != NO_EDGE
            && top != NO_EDGE
            && (bottom + 2) % 4 != top
        {
            continue;
        }
        out[i] = [bottom, top];
    }
    out
}

/// What the marching did.
#[derive(Debug, Clone, Default)]
pub(crate) struct MarchOutcome {
    pub stops: StopCounts,
    pub reduced_tops: usize,
    pub deepest_curved_layer: u32,
    /// Pipes that ended in the filled region and bent the edge they share with it.
    pub handed_to_fill: usize,
    /// Cells the marching proved valid as they are now (later steps only change edges of
    /// other cells).
    pub certified: Vec<bool>,
}

/// Marches up every pipe whose boundary edge is curved.
pub(crate) fn march(
    mesh: &Mesh,
    roles: &[[u8; 2]],
    edges: &mut EdgeTable,
    interiors: &Interiors,
    params: &CurvingParams,
    layered_cells: usize,
) -> Result<MarchOutcome, CurvingError> {
    let p = edges.p;
    let q = p - 1;
    let mut order: Vec<u32> = (0..mesh.cells.len() as u32)
        .filter(|&i| roles[i as usize][0] != NO_EDGE)
        .collect();
    order.sort_by_key(|&i| mesh.cell_layer[i as usize]);
    let mut out = MarchOutcome {
        certified: vec![false; mesh.cells.len()],
        ..MarchOutcome::default()
    };
    let mut s = Scratch::default();
    let ctx = Ctx {
        mesh,
        interiors,
        params,
        roles,
    };
    let mut dev = vec![[0.0; 2]; q];
    let mut top_pts = vec![[0.0; 2]; q];
    for &i in &order {
        let ci = i as usize;
        let [bottom, top] = roles[ci];
        let cell = mesh.cells.get(ci);
        let k = cell.corners();
        let n = k.len();
        let be = edges.cell_edges[ci][bottom as usize];
        if !edges.curved[be as usize] {
            continue;
        }
        let layer = mesh.cell_layer[ci];
        out.deepest_curved_layer = out.deepest_curved_layer.max(layer + 1);
        if top == NO_EDGE {
            // the two children merged: the pipe ends in a triangle with a curved bottom
            out.stops.collapsed += 1;
            if check(&ctx, edges, ci, &[], &mut s)?.is_valid() {
                out.certified[ci] = true;
            } else {
                out.stops.invalid += 1;
            }
            continue;
        }
        // the deviation of the bottom edge from its chord, bottom corner b0 → b1
        let (b0, b1) = (k[bottom as usize], k[(bottom as usize + 1) % n]);
        let (t0, t1) = (k[(top as usize + 1) % n], k[top as usize]); // t0 above b0
        let bulge = edges.deviation(mesh, be, b0, &mut dev);
        let (xb0, xb1) = (mesh.xy(b0), mesh.xy(b1));
        let te = edges.cell_edges[ci][top as usize];
        let above = edges.other_cell(te, i);
        let continues = above != NONE
            && roles[above as usize][0] != NO_EDGE
            && edges.cell_edges[above as usize][roles[above as usize][0] as usize] == te
            && mesh.cell_layer[above as usize] == layer + 1;
        let (xt0, xt1) = (mesh.xy(t0), mesh.xy(t1));
        let top_with =
            |lambda: f64, pts: &mut [[f64; 2]]| lay(p, xt0, xt1, &dev, false, lambda, pts);
        // the record of a top laid with `fraction` of the bottom's deviation
        let rule = |fraction: f64| Carry {
            source: be,
            source_from: b0,
            from: t0,
            reversed: false,
            fraction,
        };
        // the straight top is judged only when it may be used: lazily
        let mut straight_cert: Option<Certificate> = None;
        let mut straight =
            |edges: &EdgeTable, s: &mut Scratch| -> Result<Certificate, CurvingError> {
                if let Some(c) = straight_cert {
                    return Ok(c);
                }
                let mut pts = vec![[0.0; 2]; q];
                top_with(0.0, &mut pts);
                let c = check(&ctx, edges, ci, &[(top, t0, &pts)], s)?;
                straight_cert = Some(c);
                Ok(c)
            };
        if !continues {
            out.stops.pipe_ended += 1;
            let flat = straight(edges, &mut s)?;
            // ending in the filled region below the threshold, the pipe may hand part of its
            // deviation to the fill triangle above, where that makes the worse of the two
            // cells better than the straight top does
            let mut best: Option<(f64, f64)> = None;
            if quality(&flat) < params.stop_min_scaled_jacobian
                && above != NONE
                && above as usize >= layered_cells
            {
                let l = edges.cell_edges[above as usize]
                    .iter()
                    .position(|&e| e == te);
                let l = l.expect("the cell above an edge has that edge") as u8;
                for lambda in [1.0, 0.5, 0.25] {
                    top_with(lambda, &mut top_pts);
                    let mine = check(&ctx, edges, ci, &[(top, t0, &top_pts)], &mut s)?;
                    if !mine.is_valid() {
                        continue;
                    }
                    let theirs = check(&ctx, edges, above as usize, &[(l, t0, &top_pts)], &mut s)?;
                    let worse = quality(&mine).min(quality(&theirs));
                    if theirs.is_valid() && worse > best.map_or(quality(&flat), |b| b.0) {
                        best = Some((worse, lambda));
                    }
                }
            }
            match best {
                Some((_, lambda)) => {
                    top_with(lambda, &mut top_pts);
                    edges.carry(te, rule(lambda), &top_pts);
                    out.certified[ci] = true;
                    out.handed_to_fill += 1;
                }
                None if flat.is_valid() => out.certified[ci] = true,
                None => out.stops.invalid += 1,
            }
            continue;
        }
        let may_stop = layer + 1 >= min_layers(mesh, ci, params);
        // A straight top over a bottom that bulges by d in a cell of height h leaves a scaled
        // Jacobian near (h − d)/h; where even twice that estimate misses the threshold, the
        // check is skipped and the pipe goes on (always safe: that cell is certified too).
        let height = dist(xb0, xt0).min(dist(xb1, xt1));
        let hopeless = height * (1.0 - params.stop_min_scaled_jacobian) < 0.5 * bulge;
        if may_stop && !hopeless {
            let good_straight = straight(edges, &mut s)?
                .scaled_jacobian_lower_bound()
                .is_some_and(|q| q >= params.stop_min_scaled_jacobian);
            if good_straight {
                out.stops.jacobian += 1;
                out.certified[ci] = true;
                continue;
            }
        }
        let mut chosen = None;
        for lambda in [1.0, 0.5, 0.25] {
            top_with(lambda, &mut top_pts);
            let c = check(&ctx, edges, ci, &[(top, t0, &top_pts)], &mut s)?;
            if c.is_valid() {
                chosen = Some(lambda);
                break;
            }
        }
        match chosen {
            Some(lambda) => {
                if lambda < 1.0 {
                    out.reduced_tops += 1;
                }
                out.certified[ci] = true;
                top_with(lambda, &mut top_pts);
                edges.carry(te, rule(lambda), &top_pts);
            }
            None if straight(edges, &mut s)?.is_valid() => {
                out.stops.jacobian += 1;
                out.certified[ci] = true;
            }
            None => {
                // nothing valid: keep the full deviation and let the repair or the final
                // certification deal with it
                out.stops.invalid += 1;
                top_with(1.0, &mut top_pts);
                edges.carry(te, rule(1.0), &top_pts);
            }
        }
    }
    Ok(out)
}

fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    (b[0] - a[0]).hypot(b[1] - a[1])
}

/// The least number of curved layers of the pipe cell `ci` belongs to: walls keep
/// `min_curved_layers`, the far field only its boundary edge.
fn min_layers(mesh: &Mesh, ci: usize, params: &CurvingParams) -> u32 {
    let pipe = mesh.cell_pipe.get(ci).copied().unwrap_or(NONE);
    let role = mesh
        .boundary_patch
        .get(pipe as usize)
        .and_then(|&patch| mesh.patches.get(patch as usize))
        .map(|p| p.role);
    match role {
        Some(Role::Farfield) => 1,
        _ => params.min_curved_layers.max(1),
    }
}
