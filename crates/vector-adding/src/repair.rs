//! Repair of the cells the marching leaves invalid, typically a triangle of the filled region
//! that sits on a curved boundary edge, or the last cell of a pipe that had to stop. Such a
//! cell is mended by giving one or more of its straight interior edges the deviation of its
//! most curved edge — Vector-Adding from a shared corner instead of up a pipe — as long as the
//! neighbour across each bent edge stays valid too.

use mesh_model::{Mesh, NONE};

use crate::cellcheck::{Candidate, Ctx, check};
use crate::cellmap::Interiors;
use crate::decisions::{Carry, EdgeRule, lay};
use crate::edges::EdgeTable;
use crate::error::CurvingError;
use crate::params::CurvingParams;
use crate::scratch::Scratch;

/// What the repair did.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct RepairOutcome {
    /// Cells made valid.
    pub repaired: usize,
    /// Cells still invalid after the last pass.
    pub unrepaired: usize,
}

/// Mends invalid cells, pass after pass, until a pass changes nothing.
pub(crate) fn repair(
    mesh: &Mesh,
    roles: &[[u8; 2]],
    edges: &mut EdgeTable,
    interiors: &Interiors,
    params: &CurvingParams,
    certified: &[bool],
) -> Result<RepairOutcome, CurvingError> {
    let ctx = Ctx {
        mesh,
        interiors,
        params,
        roles,
    };
    let mut s = Scratch::default();
    let mut out = RepairOutcome::default();
    // cells next to an edge the repair bent lose the marching's certificate
    let mut touched = vec![false; mesh.cells.len()];
    let mut log = Vec::new();
    for _pass in 0..4 {
        let mut changed = false;
        let mut still = 0;
        for ci in 0..mesh.cells.len() {
            let n = mesh.cells.get(ci).corners().len();
            if certified[ci] && !touched[ci] {
                continue;
            }
            if !edges.cell_edges[ci][..n]
                .iter()
                .any(|&e| edges.curved[e as usize])
            {
                continue;
            }
            if check(&ctx, edges, ci, &[], &mut s)?.is_valid() {
                continue;
            }
            log.clear();
            let mut budget = MEND_BUDGET;
            if mend(&ctx, ci, edges, &mut s, &mut log, MEND_DEPTH, &mut budget)? {
                for (e, ..) in &log {
                    for c in edges.cells[*e as usize] {
                        if c != NONE {
                            touched[c as usize] = true;
                        }
                    }
                }
                out.repaired += 1;
                changed = true;
            } else {
                still += 1;
            }
        }
        out.unrepaired = still;
        if !changed {
            break;
        }
    }
    Ok(out)
}

/// How many cells away from the invalid one a repair may reach: a bent edge may make the
/// neighbour across it invalid (a needle of the filled region), which is then mended in turn.
/// Deep enough to carry a wall edge's bulge up a stack of thin layers whose pipe was broken
/// (a merge or a stopped neighbour front) to the filled region, where cells are large enough
/// to take it: a thin first layer under coarse wall edges needs that.
const MEND_DEPTH: u32 = 24;

/// The most certified checks one repair may spend, whatever its depth: the search tries the
/// pipe-like choice first (the edge opposite the source on a quadrilateral), so a chain that
/// can be mended is usually found at once; the budget bounds the failing searches.
const MEND_BUDGET: usize = 400;

/// The edges changed by a repair, with their previous points, curved flag and rule, to undo
/// it.
type ChangeLog = Vec<(u32, Vec<[f64; 2]>, bool, EdgeRule)>;

/// Tries to make cell `ci` valid by bending its straight interior edges. A choice is kept when
/// the cell is valid and each neighbour across a bent edge is valid too, or, `depth` allowing,
/// can be mended the same way. Every change is recorded in `log`; on failure nothing changes.
fn mend(
    ctx: &Ctx<'_>,
    ci: usize,
    edges: &mut EdgeTable,
    s: &mut Scratch,
    log: &mut ChangeLog,
    depth: u32,
    budget: &mut usize,
) -> Result<bool, CurvingError> {
    let mesh = ctx.mesh;
    let ty = mesh.cells.get(ci).ty;
    let p = edges.p;
    let q = p - 1;
    let k: Vec<u32> = mesh.cells.get(ci).corners().to_vec();
    let n = k.len();
    let local = ty.shape.edges();
    let ce = edges.cell_edges[ci];
    let mut dev = vec![[0.0; 2]; q];
    // the most curved edge is the source of the deviation
    let Some(src) = most_curved(mesh, edges, (&k, local, &ce), &mut dev) else {
        return Ok(false);
    };
    let (a, b) = (k[local[src][0]], k[local[src][1]]);
    edges.deviation(mesh, ce[src], a, &mut dev);
    let mut free: Vec<usize> = (0..n)
        .filter(|&j| {
            let e = ce[j] as usize;
            !edges.curved[e] && edges.cells[e][1] != NONE
        })
        .collect();
    // the edge that shares no corner with the source (a quadrilateral's top) first: that is
    // how a pipe would carry the deviation
    free.sort_by_key(|&j| {
        let (u, w) = (k[local[j][0]], k[local[j][1]]);
        u == a || w == a || u == b || w == b
    });
    let mut subsets: Vec<Vec<usize>> = free.iter().map(|&j| vec![j]).collect();
    if free.len() > 1 {
        subsets.push(free.clone());
    }
    let mut cand: Vec<(u8, Carry, Vec<[f64; 2]>)> = Vec::new();
    for subset in &subsets {
        for lambda in [1.0, 0.5] {
            cand.clear();
            for &j in subset {
                let (rule, pts) = bent(mesh, p, (&k, local, &ce), j, (src, a, b), &dev, lambda);
                cand.push((j as u8, rule, pts));
            }
            let mine: Vec<Candidate<'_>> = cand
                .iter()
                .map(|(j, rule, pts)| (*j, rule.from, pts.as_slice()))
                .collect();
            if *budget == 0 {
                return Ok(false);
            }
            *budget -= 1;
            if !check(ctx, edges, ci, &mine, s)?.is_valid() {
                continue;
            }
            // apply the choice, then look at the neighbours across the bent edges
            let mark = log.len();
            for (j, rule, pts) in &cand {
                let e = ce[*j as usize];
                let mut old = vec![[0.0; 2]; edges.p - 1];
                edges.points_from(e, edges.ends[e as usize][0], &mut old);
                log.push((e, old, edges.curved[e as usize], edges.rules[e as usize]));
                edges.carry(e, *rule, pts);
            }
            let mut neighbours_ok = true;
            for (j, _, _) in &cand {
                let e = ce[*j as usize];
                let nb = edges.other_cell(e, ci as u32);
                if nb == NONE || check(ctx, edges, nb as usize, &[], s)?.is_valid() {
                    continue;
                }
                if depth > 0 && mend(ctx, nb as usize, edges, s, log, depth - 1, budget)? {
                    continue;
                }
                neighbours_ok = false;
                break;
            }
            if neighbours_ok {
                return Ok(true);
            }
            undo(edges, log, mark);
        }
    }
    Ok(false)
}

/// The local index of the most curved of a cell's edges (corners `k`, shape edges `local`,
/// topology edges `ce`); `None` if none is curved. `dev` is scratch.
fn most_curved(
    mesh: &Mesh,
    edges: &EdgeTable,
    (k, local, ce): (&[u32], &[[usize; 2]], &[u32]),
    dev: &mut [[f64; 2]],
) -> Option<usize> {
    let mut source = None;
    let mut most = 0.0;
    for j in 0..k.len() {
        if !edges.curved[ce[j] as usize] {
            continue;
        }
        let d = edges.deviation(mesh, ce[j], k[local[j][0]], dev);
        if d > most {
            most = d;
            source = Some(j);
        }
    }
    source
}

/// The cell's local edge `j` (corners `k`, shape edges `local`, topology edges `ce`) bent
/// with `lambda` times the deviation `dev` of the source edge `src`, from its corner `a` to
/// `b`: the rule and the `p − 1` points.
fn bent(
    mesh: &Mesh,
    p: usize,
    (k, local, ce): (&[u32], &[[usize; 2]], &[u32]),
    j: usize,
    (src, a, b): (usize, u32, u32),
    dev: &[[f64; 2]],
    lambda: f64,
) -> (Carry, Vec<[f64; 2]>) {
    let (u, w) = (k[local[j][0]], k[local[j][1]]);
    // walk the bent edge from the corner it shares with the source edge, or, on a
    // quadrilateral's opposite edge, from the corner above the source's start
    let (from, to, reverse) = if u == a || w == a {
        let other = if u == a { w } else { u };
        (a, other, false)
    } else if u == b || w == b {
        let other = if u == b { w } else { u };
        (b, other, true)
    } else {
        (w, u, false)
    };
    let mut pts = vec![[0.0; 2]; p - 1];
    lay(
        p,
        mesh.xy(from),
        mesh.xy(to),
        dev,
        reverse,
        lambda,
        &mut pts,
    );
    let rule = Carry {
        source: ce[src],
        source_from: a,
        from,
        reversed: reverse,
        fraction: lambda,
    };
    (rule, pts)
}

/// Restores the edges changed since `log[mark]`, latest first.
fn undo(edges: &mut EdgeTable, log: &mut ChangeLog, mark: usize) {
    while log.len() > mark {
        let (e, old, curved, rule) = log.pop().expect("log longer than mark");
        edges.set_points_from(e, edges.ends[e as usize][0], &old, curved);
        edges.rules.set(e as usize, rule);
    }
}
