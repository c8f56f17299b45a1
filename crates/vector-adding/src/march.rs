//! The marching up the pipes: each layered cell whose bottom edge is curved decides its top
//! edge — the bottom's deviation from its chord laid onto the top chord (Vector-Adding), or
//! straight when the pipe stops. Cells are visited layer by layer, so a bottom edge is final
//! before the cell above reads it.

use jacobian_check::Certificate;
use mesh_model::{Mesh, NONE, Role};

use crate::cellcheck::{Ctx, check};
use crate::cellmap::Interiors;
use crate::decisions::{Carry, EdgeRule, lay};
use crate::edges::EdgeTable;
use crate::error::CurvingError;
use crate::params::CurvingParams;
use crate::quality::quality;
use crate::roles::NO_EDGE;
use crate::scratch::Scratch;
use crate::stats::StopCounts;

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
        let te = edges.cell_edges[ci][top as usize];
        let (above, continues) = next_in_pipe(mesh, roles, edges, i, te);
        let mut t = Top {
            p,
            ci,
            top,
            te,
            be,
            b0,
            t0,
            xt: [mesh.xy(t0), mesh.xy(t1)],
            dev: &dev,
            straight: None,
        };
        if !continues {
            out.stops.pipe_ended += 1;
            let to_fill = (above != NONE && above as usize >= layered_cells).then_some(above);
            end_pipe(
                &ctx,
                edges,
                &mut t,
                to_fill,
                (&mut s, &mut top_pts),
                &mut out,
            )?;
            continue;
        }
        let may_stop = layer + 1 >= min_layers(mesh, ci, params);
        // A straight top over a bottom that bulges by d in a cell of height h leaves a scaled
        // Jacobian near (h − d)/h; where even twice that estimate misses the threshold, the
        // check is skipped and the pipe goes on (always safe: that cell is certified too).
        let height = dist(mesh.xy(b0), t.xt[0]).min(dist(mesh.xy(b1), t.xt[1]));
        let hopeless = height * (1.0 - params.stop_min_scaled_jacobian) < 0.5 * bulge;
        go_on(
            &ctx,
            edges,
            &mut t,
            may_stop && !hopeless,
            (&mut s, &mut top_pts),
            &mut out,
        )?;
    }
    Ok(out)
}

/// The top edge of one pipe cell being decided: local edge `top` (topology edge `te`) from
/// corner `t0`, above the bottom edge `be` from its corner `b0`, whose deviation from its
/// chord is `dev`; the straight top's certificate once it has been judged.
struct Top<'a> {
    p: usize,
    ci: usize,
    top: u8,
    te: u32,
    be: u32,
    b0: u32,
    t0: u32,
    /// The top's corners, `t0` first.
    xt: [[f64; 2]; 2],
    dev: &'a [[f64; 2]],
    straight: Option<Certificate>,
}

impl Top<'_> {
    /// The top's points with `lambda` times the bottom's deviation laid on its chord.
    fn lay(&self, lambda: f64, pts: &mut [[f64; 2]]) {
        lay(self.p, self.xt[0], self.xt[1], self.dev, false, lambda, pts);
    }

    /// The record of a top laid with `fraction` of the bottom's deviation.
    fn rule(&self, fraction: f64) -> Carry {
        Carry {
            source: self.be,
            source_from: self.b0,
            from: self.t0,
            reversed: false,
            fraction,
        }
    }

    /// The cell certified with the top laid with `lambda` (its points left in `pts`).
    fn check(
        &self,
        ctx: &Ctx<'_>,
        edges: &EdgeTable,
        lambda: f64,
        (s, pts): (&mut Scratch, &mut [[f64; 2]]),
    ) -> Result<Certificate, CurvingError> {
        self.lay(lambda, pts);
        check(ctx, edges, self.ci, &[(self.top, self.t0, pts)], s)
    }

    /// The cell certified with a straight top, judged once: only where it may be used.
    fn straight(
        &mut self,
        ctx: &Ctx<'_>,
        edges: &EdgeTable,
        s: &mut Scratch,
    ) -> Result<Certificate, CurvingError> {
        if let Some(c) = self.straight {
            return Ok(c);
        }
        let mut pts = vec![[0.0; 2]; self.p - 1];
        let c = self.check(ctx, edges, 0.0, (s, &mut pts))?;
        self.straight = Some(c);
        Ok(c)
    }

    /// Lays `lambda` of the deviation on the top edge and records the rule.
    fn carry(&self, edges: &mut EdgeTable, lambda: f64, pts: &mut [[f64; 2]]) {
        self.lay(lambda, pts);
        edges.carry(self.te, self.rule(lambda), pts);
    }
}

/// A pipe that ends at this cell: its top stays straight, unless the cell above is a fill
/// cell (`to_fill`) and the straight top is below the stop threshold — then the pipe may hand
/// part of its deviation to that triangle, where that makes the worse of the two cells better
/// than the straight top does.
fn end_pipe(
    ctx: &Ctx<'_>,
    edges: &mut EdgeTable,
    t: &mut Top<'_>,
    to_fill: Option<u32>,
    (s, top_pts): (&mut Scratch, &mut [[f64; 2]]),
    out: &mut MarchOutcome,
) -> Result<(), CurvingError> {
    let flat = t.straight(ctx, edges, s)?;
    let mut best: Option<(f64, f64)> = None;
    if let Some(above) = to_fill.filter(|_| quality(&flat) < ctx.params.stop_min_scaled_jacobian) {
        let l = edges.cell_edges[above as usize]
            .iter()
            .position(|&e| e == t.te);
        let l = l.expect("the cell above an edge has that edge") as u8;
        for lambda in [1.0, 0.5, 0.25] {
            let mine = t.check(ctx, edges, lambda, (s, top_pts))?;
            if !mine.is_valid() {
                continue;
            }
            let theirs = check(ctx, edges, above as usize, &[(l, t.t0, top_pts)], s)?;
            let worse = quality(&mine).min(quality(&theirs));
            if theirs.is_valid() && worse > best.map_or(quality(&flat), |b| b.0) {
                best = Some((worse, lambda));
            }
        }
    }
    match best {
        Some((_, lambda)) => {
            t.carry(edges, lambda, top_pts);
            out.certified[t.ci] = true;
            out.handed_to_fill += 1;
        }
        None if flat.is_valid() => out.certified[t.ci] = true,
        None => out.stops.invalid += 1,
    }
    Ok(())
}

/// A pipe that goes on: it stops with a straight top where it may (`may_stop`) and that top
/// keeps the stop threshold, else the top takes the bottom's deviation, or half or a quarter
/// of it, whichever first leaves the cell valid.
fn go_on(
    ctx: &Ctx<'_>,
    edges: &mut EdgeTable,
    t: &mut Top<'_>,
    may_stop: bool,
    (s, top_pts): (&mut Scratch, &mut [[f64; 2]]),
    out: &mut MarchOutcome,
) -> Result<(), CurvingError> {
    if may_stop {
        let good_straight = t
            .straight(ctx, edges, s)?
            .scaled_jacobian_lower_bound()
            .is_some_and(|q| q >= ctx.params.stop_min_scaled_jacobian);
        if good_straight {
            out.stops.jacobian += 1;
            out.certified[t.ci] = true;
            return Ok(());
        }
    }
    let mut chosen = None;
    for lambda in [1.0, 0.5, 0.25] {
        if t.check(ctx, edges, lambda, (s, top_pts))?.is_valid() {
            chosen = Some(lambda);
            break;
        }
    }
    match chosen {
        Some(lambda) => {
            if lambda < 1.0 {
                out.reduced_tops += 1;
            }
            out.certified[t.ci] = true;
            t.carry(edges, lambda, top_pts);
        }
        None if t.straight(ctx, edges, s)?.is_valid() => {
            out.stops.jacobian += 1;
            out.certified[t.ci] = true;
        }
        None => {
            // nothing valid: keep the full deviation and let the repair or the final
            // certification deal with it
            out.stops.invalid += 1;
            t.carry(edges, 1.0, top_pts);
        }
    }
    Ok(())
}

/// The cell above pipe cell `i` across its top edge `te` (NONE at the boundary) and whether
/// it is the next cell of the same pipe: a layered cell of the next layer whose bottom is `te`.
fn next_in_pipe(mesh: &Mesh, roles: &[[u8; 2]], edges: &EdgeTable, i: u32, te: u32) -> (u32, bool) {
    let above = edges.other_cell(te, i);
    let continues = above != NONE
        && roles[above as usize][0] != NO_EDGE
        && edges.cell_edges[above as usize][roles[above as usize][0] as usize] == te
        && mesh.cell_layer[above as usize] == mesh.cell_layer[i as usize] + 1;
    (above, continues)
}

/// The marching's figures read back from a mesh whose edges are laid already (by recorded
/// decisions, [`crate::curve_mesh_keeping`]): every layered cell with a curved bottom edge is
/// a pipe cell; its layer counts towards the deepest curved layer; a pipe ends in a collapsed
/// cell, where the next cell is not of the pipe (`pipe_ended`; `handed_to_fill` when its top
/// took part of the bottom's deviation into a fill cell), or at a top not carried from its
/// bottom (`jacobian`: a straight top, valid); a top carried with less than the whole
/// deviation is a reduced top. `invalid` counts the pipe cells in `failing` (cells the check
/// does not prove valid), with `certified` left empty. On the mesh the marching laid, the
/// figures are the marching's own, but for the edges the repair bent after it.
pub(crate) fn read_back(
    mesh: &Mesh,
    roles: &[[u8; 2]],
    edges: &EdgeTable,
    layered_cells: usize,
    failing: &[u32],
) -> MarchOutcome {
    let mut out = MarchOutcome::default();
    for (ci, &[bottom, top]) in roles.iter().enumerate() {
        if bottom == NO_EDGE {
            continue;
        }
        let be = edges.cell_edges[ci][bottom as usize];
        if !edges.curved[be as usize] {
            continue;
        }
        let i = ci as u32;
        out.deepest_curved_layer = out.deepest_curved_layer.max(mesh.cell_layer[ci] + 1);
        if failing.binary_search(&i).is_ok() {
            out.stops.invalid += 1;
        }
        if top == NO_EDGE {
            out.stops.collapsed += 1;
            continue;
        }
        let te = edges.cell_edges[ci][top as usize];
        let carried = match edges.rules[te as usize] {
            EdgeRule::Carried(c) if c.source == be => Some(c.fraction),
            _ => None,
        };
        let (above, continues) = next_in_pipe(mesh, roles, edges, i, te);
        if !continues {
            out.stops.pipe_ended += 1;
            if carried.is_some() && above != NONE && above as usize >= layered_cells {
                out.handed_to_fill += 1;
            }
            continue;
        }
        match carried {
            Some(fraction) if fraction < 1.0 => out.reduced_tops += 1,
            Some(_) => {}
            None => out.stops.jacobian += 1,
        }
    }
    out
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
