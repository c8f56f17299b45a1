//! Curving a moved mesh (same topology, nodes moved) the way a previous run curved it, and
//! the derivative of that curving. [`replay`] lays every edge by its recorded rule and cuts
//! every quadrilateral by its recorded cut; [`curve_mesh_keeping`] replays, certifies every
//! cell, and decides afresh (as [`crate::curve_mesh`] would) only for the pipes of the cells
//! that fail, widening to the whole mesh if that is not enough; [`tangent`] replays on the
//! derivative fields, since with the decisions fixed the curving is a linear homogeneous map
//! of the linear nodes and the boundary's high-order nodes.

use mesh_model::{LayeredMesh, Layering, Mesh, NONE};

use crate::assemble::assemble;
use crate::boundary::{facet_points, place_given, place_on_curves};
use crate::cellcheck::{Ctx, check_as_cut};
use crate::cellmap::Interiors;
use crate::decisions::{DecisionChange, Decisions, Diagonal, EdgeRule, EdgeRules};
use crate::edges::EdgeTable;
use crate::error::CurvingError;
use crate::params::CurvingParams;
use crate::scratch::Scratch;
use crate::split::OutCell;
use crate::stats::CurvingStats;
use crate::{Curved, LoopCurve, check_input, curve_mesh, march, roles, split};

/// Where the boundary facets' high-order nodes come from.
#[derive(Clone, Copy)]
enum Boundary<'a> {
    /// On the loops' curves, as `curve_mesh` places them.
    Curves(&'a [LoopCurve<'a>]),
    /// Given, as [`boundary_points`] lays them out.
    Points(&'a [[f64; 2]]),
}

/// A mesh laid out by fixed decisions, before assembly.
struct Laid {
    edges: EdgeTable,
    roles: Vec<[u8; 2]>,
    cells: Vec<OutCell>,
    interiors: Interiors,
    sorted_edges: usize,
    curved_boundary_edges: usize,
    curved_diagonals: usize,
}

/// The inner points of every boundary facet on its curve, `order − 1` per facet in the
/// mesh's facet order, each listed from the facet's first node to its second: the layout of
/// the boundary points [`replay`] and [`tangent`] take.
///
/// # Errors
/// As [`crate::curve_mesh`] for the boundary.
pub fn boundary_points(
    input: &LayeredMesh,
    loops: &[LoopCurve<'_>],
    order: u8,
) -> Result<Vec<[f64; 2]>, CurvingError> {
    let params = CurvingParams {
        order,
        ..CurvingParams::default()
    };
    params.check()?;
    check_input(input)?;
    let mut edges = EdgeTable::new(&input.mesh, order as usize);
    place_on_curves(&input.mesh, loops, &mut edges)?;
    Ok(facet_points(&input.mesh, &edges))
}

/// The curved mesh `decisions` make of `input` with the boundary facets' high-order nodes
/// `boundary` (laid out as [`boundary_points`] makes them). Replaying a run's own decisions
/// on its own mesh and boundary gives its mesh to the last bit; no cell is certified.
///
/// # Errors
/// An input `curve_mesh` refuses, decisions of another topology, a wrong number of boundary
/// points.
pub fn replay(
    input: &LayeredMesh,
    decisions: &Decisions,
    boundary: &[[f64; 2]],
) -> Result<Mesh, CurvingError> {
    check_input(input)?;
    replay_on(&input.mesh, &input.layering, decisions, boundary)
}

/// The derivative of every node of the curved mesh [`replay`] makes (numbered as it numbers
/// them: the linear nodes, then the inner nodes of the edges, then the cells' interior
/// nodes) when the linear nodes move by `d_nodes` (one per node of `input`) and the boundary
/// facets' high-order nodes by `d_boundary` (laid out as [`boundary_points`] makes them), all
/// decisions fixed.
///
/// # Errors
/// As [`replay`], or `d_nodes` of the wrong length.
pub fn tangent(
    input: &LayeredMesh,
    decisions: &Decisions,
    d_nodes: &[[f64; 2]],
    d_boundary: &[[f64; 2]],
) -> Result<Vec<[f64; 2]>, CurvingError> {
    check_input(input)?;
    if d_nodes.len() != input.mesh.nodes.len() {
        return Err(CurvingError::NotTheSameMesh(format!(
            "{} node derivatives for {} nodes",
            d_nodes.len(),
            input.mesh.nodes.len()
        )));
    }
    let mut derivative = input.mesh.clone();
    derivative.nodes = d_nodes.iter().map(|d| [d[0], d[1], 0.0]).collect();
    let mesh = replay_on(&derivative, &input.layering, decisions, d_boundary)?;
    Ok(mesh.nodes.iter().map(|v| [v[0], v[1]]).collect())
}

/// [`replay`] on `mesh` with the layers `layering`, unchecked.
fn replay_on(
    mesh: &Mesh,
    layering: &Layering,
    decisions: &Decisions,
    boundary: &[[f64; 2]],
) -> Result<Mesh, CurvingError> {
    let params = CurvingParams {
        order: decisions.order,
        triangles: decisions.triangles,
        strategy: decisions.strategy,
        ..CurvingParams::default()
    };
    params.check()?;
    fits(mesh, decisions, &params)?;
    let (rules, cuts) = (&decisions.rules, &decisions.diagonals);
    let laid = lay_out(
        mesh,
        layering,
        Boundary::Points(boundary),
        rules,
        cuts,
        &params,
    )?
    .map_err(|_| CurvingError::NotTheSameMesh("its carried edges form a loop".into()))?;
    Ok(assemble_laid(mesh, laid))
}

fn assemble_laid(mesh: &Mesh, mut laid: Laid) -> Mesh {
    let nodes = std::mem::take(&mut laid.edges.nodes);
    assemble(
        mesh,
        &laid.edges,
        nodes,
        laid.sorted_edges,
        (laid.cells.len(), |i| laid.cells[i]),
        &laid.interiors,
    )
}

/// Whether `decisions` were taken on a mesh of `mesh`'s topology with `params`' order, cut
/// and strategy, and every rule names edges of its own and its source's.
fn fits(mesh: &Mesh, decisions: &Decisions, params: &CurvingParams) -> Result<(), CurvingError> {
    let bad = |what: String| Err(CurvingError::NotTheSameMesh(what));
    if (decisions.order, decisions.triangles) != (params.order, params.triangles)
        || (decisions.triangles && decisions.strategy != params.strategy)
    {
        return bad("they were taken with another order, cut or strategy".into());
    }
    let topo = mesh_model::topology::Edges::build(mesh.cells.shapes_and_corners(), []);
    let same_edges = decisions.edges.len() == topo.len()
        && (0..topo.len() as u32).all(|e| topo.key(e) == decisions.edges[e as usize]);
    if !same_edges || decisions.rules.len() != topo.len() {
        return bad(format!(
            "{} edges, the mesh has {}",
            decisions.edges.len(),
            topo.len()
        ));
    }
    if decisions.diagonals.len() != mesh.cells.len() {
        let n = decisions.diagonals.len();
        return bad(format!("{n} cells, the mesh has {}", mesh.cells.len()));
    }
    for (e, rule) in decisions.rules.not_straight() {
        let EdgeRule::Carried(c) = rule else { continue };
        let source = decisions.edges.get(c.source as usize);
        if !decisions.edges[e].contains(&c.from)
            || !source.is_some_and(|s| s.contains(&c.source_from))
        {
            return bad(format!("edge {e} is carried from a node not its own"));
        }
    }
    Ok(())
}

/// Lays out `mesh` by `rules` and `cuts`, the boundary from `boundary`: Ok(Err(edges)) when
/// carried edges form a loop (which a mix of two runs' rules can).
fn lay_out(
    mesh: &Mesh,
    layering: &Layering,
    boundary: Boundary<'_>,
    rules: &EdgeRules,
    cuts: &[Option<Diagonal>],
    params: &CurvingParams,
) -> Result<Result<Laid, Vec<u32>>, CurvingError> {
    let p = params.order as usize;
    let mut edges = EdgeTable::new(mesh, p);
    let sorted_edges = edges.len();
    match boundary {
        Boundary::Curves(loops) => place_on_curves(mesh, loops, &mut edges)?,
        Boundary::Points(pts) => place_given(mesh, pts, &mut edges)?,
    }
    let curved_boundary_edges = edges.curved.iter().filter(|&&c| c).count();
    if let Err(cycle) = lay_rules(mesh, rules, &mut edges) {
        return Ok(Err(cycle));
    }
    let roles = roles::classify(mesh, &layering.node_layer, layering.layered_cells);
    let interiors = Interiors::new(p);
    let (cells, cut) = if params.triangles {
        split::cut(mesh, &roles, &mut edges, &interiors, params, Some(cuts))?
    } else {
        let cells = split::keep(&edges.cell_edges, &edges.ends).collect();
        (cells, split::CutOutcome::default())
    };
    Ok(Ok(Laid {
        edges,
        roles,
        cells,
        interiors,
        sorted_edges,
        curved_boundary_edges,
        curved_diagonals: cut.curved_diagonals,
    }))
}

/// Lays every carried edge by its rule, each after its source; Err: the edges of a loop of
/// sources.
fn lay_rules(mesh: &Mesh, rules: &EdgeRules, edges: &mut EdgeTable) -> Result<(), Vec<u32>> {
    const TODO: u8 = 0;
    const ON_CHAIN: u8 = 1;
    const DONE: u8 = 2;
    let mut state = vec![TODO; rules.len()];
    let mut chain: Vec<usize> = Vec::new();
    let mut dev = vec![[0.0; 2]; edges.p - 1];
    // a chain starts at a carried edge (the others are laid already)
    for (e, _) in rules.not_straight() {
        chain.clear();
        let mut at = e;
        while let EdgeRule::Carried(c) = rules[at] {
            match state[at] {
                TODO => {
                    state[at] = ON_CHAIN;
                    chain.push(at);
                    at = c.source as usize;
                }
                ON_CHAIN => return Err(chain.iter().map(|&e| e as u32).collect()),
                _ => break,
            }
        }
        for &c in chain.iter().rev() {
            let EdgeRule::Carried(rule) = rules[c] else {
                unreachable!("only carried edges are chained")
            };
            edges.apply(mesh, c as u32, rule, &mut dev);
            state[c] = DONE;
        }
    }
    Ok(())
}

/// Curves `input`, a moved copy of the mesh `previous` was taken on (same topology), the
/// same way: every edge by its previous rule and every quadrilateral by its previous cut,
/// then every cell certified with the check of [`crate::curve_mesh`]. For the cells that
/// fail, the decisions of their pipes (and of their own edges) are taken afresh as
/// `curve_mesh` takes them on `input`, widening to the whole mesh if that is not enough.
/// Returns the curved mesh and every decision that changed. Its stats count edges, curved
/// boundary edges and diagonals, as `unrepaired_cells` the cells still invalid, and the
/// pipes as the mesh has them (deepest curved layer, stops, reduced tops, read back from the
/// laid edges: a run's own decisions on its own mesh give its figures, but for edges its
/// repair bent); `repaired_cells` and `invalid_after_cut` stay 0 and the timings empty
/// (nothing is repaired, and nothing judged but the cells' validity).
///
/// # Errors
/// As [`crate::curve_mesh`], and [`CurvingError::NotTheSameMesh`] when `previous` does not
/// fit `input` and `params`.
pub fn curve_mesh_keeping(
    input: &LayeredMesh,
    loops: &[LoopCurve<'_>],
    params: &CurvingParams,
    previous: &Decisions,
) -> Result<(Curved, Vec<DecisionChange>), CurvingError> {
    params.check()?;
    check_input(input)?;
    let mesh = &input.mesh;
    fits(mesh, previous, params)?;
    let mut fresh: Option<Decisions> = None;
    // which edges and cells take the fresh decisions
    let mut own = Fresh {
        edges: vec![false; previous.rules.len()],
        cells: vec![false; mesh.cells.len()],
        all: false,
    };
    loop {
        let merged = own.merge(previous, fresh.as_ref());
        let (rules, cuts) = (&merged.rules, &merged.diagonals);
        let layers = &input.layering;
        let laid = match lay_out(mesh, layers, Boundary::Curves(loops), rules, cuts, params)? {
            Ok(laid) => laid,
            Err(cycle) if fresh.is_some() => {
                for e in cycle {
                    own.edges[e as usize] = true;
                }
                continue;
            }
            Err(_) => {
                return Err(CurvingError::NotTheSameMesh(
                    "its carried edges form a loop".into(),
                ));
            }
        };
        let failing = failing_cells(mesh, &laid, &merged, params)?;
        if failing.is_empty() || own.all {
            let changes = changes(previous, &merged);
            let layered_cells = input.layering.layered_cells;
            return Ok((finish(mesh, laid, merged, layered_cells, &failing), changes));
        }
        if fresh.is_none() {
            fresh = Some(curve_mesh(input, loops, params)?.decisions);
        }
        if !own.widen(mesh, &input.layering, &laid.edges, &failing) {
            own.all = true;
        }
    }
}

/// The edges and cells whose decisions are taken afresh.
struct Fresh {
    edges: Vec<bool>,
    cells: Vec<bool>,
    all: bool,
}

impl Fresh {
    /// The previous decisions, with the fresh ones where marked.
    fn merge(&self, previous: &Decisions, fresh: Option<&Decisions>) -> Decisions {
        let mut out = previous.clone();
        let Some(fresh) = fresh else { return out };
        for e in 0..out.rules.len() {
            if self.all || self.edges[e] {
                out.rules.set(e, fresh.rules[e]);
            }
        }
        for (c, cut) in out.diagonals.iter_mut().enumerate() {
            if self.all || self.cells[c] {
                *cut = fresh.diagonals[c];
            }
        }
        out
    }

    /// Marks the failing cells, the cells of their pipes, and all their edges; false when
    /// nothing new was marked.
    fn widen(
        &mut self,
        mesh: &Mesh,
        layering: &Layering,
        edges: &EdgeTable,
        failing: &[u32],
    ) -> bool {
        let mut grew = false;
        let mut mark = |c: usize, grew: &mut bool| {
            *grew |= !self.cells[c];
            self.cells[c] = true;
            let n = mesh.cells.get(c).corners().len();
            for &e in &edges.cell_edges[c][..n] {
                *grew |= !self.edges[e as usize];
                self.edges[e as usize] = true;
            }
        };
        for &c in failing {
            mark(c as usize, &mut grew);
            let pipe = mesh.cell_pipe.get(c as usize).copied().unwrap_or(NONE) as usize;
            if let Some(w) = layering.pipe_start.get(pipe..pipe + 2) {
                for &d in &layering.pipe_cells[w[0] as usize..w[1] as usize] {
                    mark(d as usize, &mut grew);
                }
            }
        }
        grew
    }
}

/// The cells of `laid` the certified check does not prove valid, as they will be written.
fn failing_cells(
    mesh: &Mesh,
    laid: &Laid,
    decisions: &Decisions,
    params: &CurvingParams,
) -> Result<Vec<u32>, CurvingError> {
    let ctx = Ctx {
        mesh,
        interiors: &laid.interiors,
        params,
        roles: &laid.roles,
    };
    let mut s = Scratch::default();
    let mut out = Vec::new();
    for ci in 0..mesh.cells.len() {
        let cut = decisions.diagonals[ci].filter(|_| params.triangles);
        if !check_as_cut(&ctx, &laid.edges, ci, cut, &mut s)?.is_valid() {
            out.push(ci as u32);
        }
    }
    Ok(out)
}

/// Every decision of `now` that differs from `before`.
fn changes(before: &Decisions, now: &Decisions) -> Vec<DecisionChange> {
    let mut out = Vec::new();
    for (e, (old, new)) in before.rules.iter().zip(now.rules.iter()).enumerate() {
        if old != new {
            let corners = now.edges[e];
            out.push(DecisionChange::Edge { corners, old, new });
        }
    }
    for (c, (old, new)) in before.diagonals.iter().zip(&now.diagonals).enumerate() {
        let cell = c as u32;
        match (*old, *new) {
            (Some(old), Some(new)) if old != new => {
                out.push(DecisionChange::Diagonal { cell, old, new });
            }
            _ => {}
        }
    }
    out
}

/// The curved mesh of `laid` with the figures a replay knows: the pipes' figures read back
/// from its edges (`march::read_back`), `failing` (increasing) its cells the check does not
/// prove valid.
fn finish(
    mesh: &Mesh,
    laid: Laid,
    decisions: Decisions,
    layered_cells: usize,
    failing: &[u32],
) -> Curved {
    let edges = laid.edges.len();
    let curved_edges = laid.edges.curved.iter().filter(|&&c| c).count();
    let pipes = march::read_back(mesh, &laid.roles, &laid.edges, layered_cells, failing);
    let stats = CurvingStats {
        edges,
        curved_edges,
        curved_edge_fraction: curved_edges as f64 / edges.max(1) as f64,
        curved_boundary_edges: laid.curved_boundary_edges,
        stops: pipes.stops,
        reduced_tops: pipes.reduced_tops,
        handed_to_fill: pipes.handed_to_fill,
        deepest_curved_layer: pipes.deepest_curved_layer,
        curved_diagonals: laid.curved_diagonals,
        unrepaired_cells: failing.len(),
        ..CurvingStats::default()
    };
    Curved {
        mesh: assemble_laid(mesh, laid),
        stats,
        decisions,
    }
}
