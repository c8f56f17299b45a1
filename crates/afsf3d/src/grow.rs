//! The layer loop: ideal steps, two spring balances, merges, checks (columns that still fail
//! stop, `stop`), and the cells appended to the polyhedral mesh.

use geom_predicates::vector::dist;
use geom_surface::{Facet, Surface};
use mesh_model::poly::{CellFace, PolyMesh};
use mesh_model::{NONE, Role};
use springfield::{
    AngleSpring3d, ExtrusionSpring, NeighbourSpring3d, SpringField3d, SpringSet3d, TensionSpring,
    solve_model,
};

use crate::aspect::{limit_ratio, mean_edge};
use crate::check::{Failed, INVERTED_SHRINKS, bad_cells, shrink_until_valid, turned_steps};
use crate::children::{FanTopo, Ideal, Layer};
use crate::fan::{Fanned, fan_wall};
use crate::front::{Topo, coarse_nodes, ideal_steps};
use crate::layer::{add_twisted, choose_merges, merged_layer};
use crate::proximity::facing_fronts;
use crate::repair::{CUT_LIMIT, repair_layer};
use crate::shape::{RESHAPE_SPACINGS, reshape_layer, shape_bars};
use crate::squeeze::squeezed_layer;
use crate::stop::{MIN_RISE, rises, why_failed};
use crate::{ColumnStop, GrowError, GrowStats, Grown3d, LayerParams, StopWhy};

/// A cell that fails its check merges the children of its shortest edge when that edge is
/// shorter than this fraction of the mean ideal extrusion length (the second trigger of
/// §5.2.1: "a mesh cell twisted to a negative volume").
const TWISTED_RATIO: f64 = 1.0;

/// Grows `params.layers` layers from the wall surface `surface` (see the crate's doc).
pub fn grow_layers(surface: &Surface, params: &LayerParams) -> Result<Grown3d, GrowError> {
    check_params(params)?;
    surface.check()?;
    if let Some(facet) = (0..surface.facets.len()).find(|&f| surface.role(f) != Role::Wall) {
        return Err(GrowError::NotWall { facet });
    }
    let wall = Wall::new(surface);
    let fans = (params.fan_threshold_deg, params.fan_max_angle_deg);
    if fan_wall(surface, &wall.topo, fans, &[]).fanned_nodes() == 0 {
        return grow_fanned(&wall, params, false);
    }
    // fans whose copies' children stand unbalanced at their turned directions, else balanced
    // by the springs: the first whose first layer stops no column and keeps fans; else the
    // unbalanced fans, unless the first layer without fans stops fewer columns. Next to a
    // chain's end at a tip, where the first layer is as high as the span step, an unbalanced
    // fan may fold its neighbours' cells (the built-in section's sharp form at 1e-3), and a
    // column stopped in the first layer then stops every column around as a thick stack
    // grows; where columns stop there whatever the fans (the extruded 30P30N's slat at its
    // tips), the fans stay.
    let first_layer = |p: &LayerParams, free: bool| {
        let one = LayerParams {
            layers: 1,
            ..p.clone()
        };
        grow_fanned(&wall, &one, free).map(|g| (g.stats.stopped_columns, g.stats.fanned_nodes))
    };
    let fixed = first_layer(params, false)?;
    if fixed.0 == 0 && fixed.1 > 0 {
        return grow_fanned(&wall, params, false);
    }
    if first_layer(params, true).is_ok_and(|(stops, fans)| stops == 0 && fans > 0) {
        return grow_fanned(&wall, params, true);
    }
    let plain = LayerParams {
        fan_threshold_deg: 0.0,
        ..params.clone()
    };
    match first_layer(&plain, false) {
        Ok((stops, _)) if stops < fixed.0 => grow_fanned(&wall, &plain, false),
        _ => grow_fanned(&wall, params, false),
    }
}

/// Grows the layers with the wall's fans (none when [`LayerParams::fan_threshold_deg`] is 0),
/// their copies' first children balanced by the springs when `free`: a fan column that would
/// stop in the first layer makes its node grow one column instead, and the layers are grown
/// again.
fn grow_fanned(wall: &Wall<'_>, params: &LayerParams, free: bool) -> Result<Grown3d, GrowError> {
    let surface = wall.surface;
    let fans = (params.fan_threshold_deg, params.fan_max_angle_deg);
    let mut skip = vec![false; surface.nodes.len()];
    let mut unfanned = 0;
    loop {
        let fanned = fan_wall(surface, &wall.topo, fans, &skip);
        match grow_from(wall, &fanned, params, free)? {
            Ok(mut grown) => {
                grown.stats.unfanned_nodes = unfanned;
                return Ok(grown);
            }
            Err(stopped) => {
                let fresh: Vec<u32> = stopped.into_iter().filter(|&v| !skip[v as usize]).collect();
                if fresh.is_empty() {
                    // not expected: the stopped fans are skipped already
                    return Err(GrowError::LayerFailed {
                        layer: 0,
                        facet: 0,
                        what: "a fan's column stops in the first layer",
                    });
                }
                unfanned += fresh.len();
                fresh.iter().for_each(|&v| skip[v as usize] = true);
            }
        }
    }
}

/// The wall surface with its edges, mean edge length and the nodes on coarsely faceted
/// curves (`front::coarse_nodes`).
struct Wall<'a> {
    surface: &'a Surface,
    topo: Topo,
    spacing: f64,
    coarse: Vec<bool>,
}

impl Wall<'_> {
    fn new(surface: &Surface) -> Wall<'_> {
        let topo = Topo::new(surface);
        let spacing = topo
            .edges
            .iter()
            .map(|e| {
                dist(
                    surface.nodes[e.nodes[0] as usize],
                    surface.nodes[e.nodes[1] as usize],
                )
            })
            .sum::<f64>()
            / topo.edges.len() as f64;
        let coarse = coarse_nodes(surface, &topo);
        Wall {
            surface,
            topo,
            spacing,
            coarse,
        }
    }
}

/// Grows the layers from the wall with its fans `fanned`; `Err` with the fanned surface
/// nodes of which a column stopped in the first layer.
fn grow_from(
    wall: &Wall<'_>,
    fanned: &Fanned,
    params: &LayerParams,
    free: bool,
) -> Result<Result<Grown3d, Vec<u32>>, GrowError> {
    let mut topo = Topo::new(&fanned.wall);
    let mut state = State::new(wall.surface, fanned, &wall.coarse);
    let mut thickness = 0.0;
    // the last layer's height over `first_height × growth^k` (`aspect`; 1 unless limited)
    let mut height_ratio = 1.0;
    for layer in 0..params.layers {
        let mut height = params.first_height * params.growth.powi(layer as i32);
        if layer > 0 && params.max_aspect > 0.0 {
            // the layer no higher than max_aspect × the front's mean edge (`aspect`)
            let spacing = mean_edge(&topo, &state.front.nodes);
            let (g, a) = (params.growth, params.max_aspect);
            height_ratio = limit_ratio(height_ratio, spacing, height, g, a);
            if height_ratio < 1.0 {
                height *= height_ratio;
                state.stats.capped_layers += 1;
                state.stats.first_capped.get_or_insert(layer);
            }
        }
        if layer > 0
            && stops_here(
                params,
                height,
                thickness,
                mean_edge(&topo, &state.front.nodes),
            )
        {
            break;
        }
        thickness += height;
        state.layer_heights.push(height);
        let rounds = smoothing_rounds(params.smoothing, thickness, wall.spacing);
        // where the layers are as thick as half the wall's spacing, squeezed cells merge too
        let squeezing = 2.0 * thickness >= wall.spacing;
        // the facets kept in shape while the layers are a boundary layer's (`shape`)
        let reshaping = params.reshape && thickness <= RESHAPE_SPACINGS * wall.spacing;
        let at = (layer, height, rounds, squeezing, reshaping);
        let first = (layer == 0).then_some((wall, fanned, free));
        let (next, stops) = match grow_layer(&mut state, &topo, params, at, first)? {
            Ok(grown) => grown,
            Err(unfan) => return Ok(Err(unfan)),
        };
        if layer == 0 {
            let mut stopped: Vec<u32> = (0..fanned.fan.origin.len())
                .filter(|&v| fanned.is_fanned(v) && next.is_kept(v as u32))
                .map(|v| fanned.fan.origin[v])
                .collect();
            if !stopped.is_empty() {
                stopped.sort_unstable();
                stopped.dedup();
                return Ok(Err(stopped));
            }
        }
        let merged = next.children.len() < state.front.nodes.len();
        state.push_layer(&topo, next, layer, &stops);
        if merged {
            topo = Topo::new(&state.front);
        }
    }
    state.stats.fanned_nodes = fanned.fanned_nodes();
    Ok(Ok(state.finish()))
}

/// Whether the growth stops before a layer of `height` over layers `thickness` thick, the
/// front's mean edge `spacing`: the layer would be over [`LayerParams::stop_aspect`] ×
/// `spacing` high, or the layers over [`LayerParams::max_thickness`] thick.
fn stops_here(params: &LayerParams, height: f64, thickness: f64, spacing: f64) -> bool {
    (params.stop_aspect > 0.0 && height > params.stop_aspect * spacing)
        || thickness + height > params.max_thickness
}

/// What a layer's stops leave for the next: each front node's rise (its layer's height there,
/// 0 where it stopped) and, for those that stopped in this layer, why.
struct LayerStops {
    rise: Vec<f64>,
    why: Vec<Option<StopWhy>>,
}

/// Grows one layer over `state`'s front (its edges `topo`): layer `layer` (from 0) of height
/// `height`, the directions smoothed `rounds` times, squeezed cells merged when `squeezing`
/// (the layers as thick as half the wall's spacing). The front nodes of stopped columns keep
/// themselves, those near them rise less ([`rises`]); the children are balanced, merged
/// (Coe_shrink, the squeeze, the twisted cells), settled ([`settle_layer`]) — where the layer
/// still fails, its failing cells' nodes stop and it is settled again — and repaired. The
/// first layer (`first`: the wall and its fans) grows over the fanned wall: the copies'
/// children stand at their fan directions, unbalanced, and the other steps are the wall's;
/// where a failing cell has a fan's node, `Err` with those nodes (to be grown unfanned).
fn grow_layer(
    state: &mut State,
    topo: &Topo,
    params: &LayerParams,
    (layer, height, rounds, squeezing, reshaping): (usize, f64, usize, bool, bool),
    first: Option<(&Wall<'_>, &Fanned, bool)>,
) -> Result<Result<(Layer, LayerStops), Vec<u32>>, GrowError> {
    let front = &state.front;
    let n = front.nodes.len();
    let (dir, mut len, fixed, fan) = layer_steps(state, topo, params, (height, rounds), first);
    // the stopped columns keep themselves; those facing another front too near stop now;
    // those near them rise less, or stop
    let mut stopped = state.stopped.clone();
    let mut why: Vec<Option<StopWhy>> = vec![None; n];
    if params.stop_gap > 0.0 {
        let reach = (params.stop_gap * height, params.stop_gap_spacing);
        let near = facing_fronts(topo, &front.nodes, &dir, &stopped, reach);
        for v in (0..n).filter(|&v| near[v]) {
            stopped[v] = true;
            why[v] = Some(StopWhy::FrontsNear);
        }
    }
    let mut rise = rises(topo, &front.nodes, &state.thick, &stopped, height);
    for v in 0..n {
        if !stopped[v] && rise[v] < MIN_RISE * height {
            stopped[v] = true;
            why[v] = Some(StopWhy::Transition);
            rise[v] = 0.0;
        }
        len[v] *= rise[v] / height;
    }
    let step = Step {
        x: &front.nodes,
        dir: &dir,
        len: &len,
        stopped: &stopped,
        fixed: &fixed,
        params,
        layer,
    };
    let mut balanced = balance(&step, topo, &mut state.stats)?;
    // the first layer stays whole: its height is what the wall resolution needs
    let rows = (params.merge_rows > 0.0).then_some(params.merge_rows);
    let merges = if layer > 0 && params.coe_shrink > 0.0 {
        choose_merges(topo, &balanced, &len, params.coe_shrink, rows, &stopped)
    } else {
        Vec::new()
    };
    let ideal = Ideal {
        nodes: &front.nodes,
        dir: &dir,
        len: &len,
        balanced: &balanced,
        stopped: &stopped,
        fan,
    };
    let squeeze = (layer > 0 && params.squeeze > 0.0 && squeezing).then_some(params.squeeze);
    let twisted = layer > 0 && params.coe_shrink > 0.0;
    let (mut next, mut merges) =
        merged_and_twisted(topo, (&ideal, &front.facets), squeeze, twisted, merges);
    // where the layer still fails, the nodes of its failing cells stop and it is settled again
    loop {
        let ideal = Ideal {
            nodes: &front.nodes,
            dir: &dir,
            len: &len,
            balanced: &balanced,
            stopped: &stopped,
            fan,
        };
        let failed = match settle_layer(
            &ideal,
            &front.facets,
            &mut next,
            params.max_shrinks,
            params.patch_normals,
            &mut state.stats,
        ) {
            Ok(()) => break,
            Err(failed) => failed,
        };
        if let Some((_, fanned, _)) = first {
            // a fan's column must not stop in the first layer: its node grows one instead
            let fans = fans_at(&failed.bad, front, fanned);
            if !fans.is_empty() {
                return Ok(Err(fans));
            }
        }
        let mut newly = 0;
        for &f in &failed.bad {
            for &v in front.facets[f].nodes() {
                let v = v as usize;
                if !stopped[v] {
                    stopped[v] = true;
                    why[v] = Some(why_failed(failed.what));
                    rise[v] = 0.0;
                    balanced[v] = front.nodes[v];
                    newly += 1;
                }
            }
        }
        if newly == 0 {
            return Err(failed.error(&state.pipes, layer));
        }
        merges.retain(|m| !stopped[m[0] as usize] && !stopped[m[1] as usize]);
        let ideal = Ideal {
            nodes: &front.nodes,
            dir: &dir,
            len: &len,
            balanced: &balanced,
            stopped: &stopped,
            fan,
        };
        next = merged_layer(&ideal, &front.facets, merges.clone());
    }
    // the few cells no cut can keep under the limit: their children moved (checked); not
    // in the first layer, whose children stand on the wall's normals at its first height
    // (moved there, the wing's thin tip-cap cells made the second layer fail)
    if layer > 0 {
        state.stats.repaired +=
            repair_layer(&front.nodes, &front.facets, &dir, &mut next, CUT_LIMIT);
    }
    if layer > 0 && reshaping {
        state.stats.reshaped +=
            reshape_layer(&front.nodes, &front.facets, &state.shape_bars, &mut next);
    }
    Ok(Ok((next, LayerStops { rise, why })))
}

/// A layer's ideal steps: each front node's direction and length, which children stay at
/// their steps unbalanced, and the wall's fans (the first layer's).
type Steps<'a> = (Vec<[f64; 3]>, Vec<f64>, Vec<bool>, Option<&'a FanTopo>);

/// The ideal steps of a layer `height` high over `state`'s front (its edges `topo`), the
/// directions smoothed `rounds` times: each front node's direction and length, which
/// children stay at their steps unbalanced, and the wall's fans. The first layer (`first`:
/// the wall and its fans) takes the wall's own steps (its fans' facets have no normal) and
/// each fan's copies their turned directions, unbalanced.
fn layer_steps<'a>(
    state: &State,
    topo: &Topo,
    params: &LayerParams,
    (height, rounds): (f64, usize),
    first: Option<(&Wall<'_>, &'a Fanned, bool)>,
) -> Steps<'a> {
    let steps = |front: &Surface, topo: &Topo, coarse: &[bool]| {
        let (s, b) = (params.stand_off, params.patch_normals);
        ideal_steps(front, topo, height, rounds, s, (b, coarse))
    };
    let Some((wall, fanned, free)) = first else {
        let (d, l) = steps(&state.front, topo, &state.coarse_front());
        return (d, l, Vec::new(), None);
    };
    let n = state.front.nodes.len();
    let (d, l) = steps(wall.surface, &wall.topo, &wall.coarse);
    let o = |v: usize| fanned.fan.origin[v] as usize;
    let dir = (0..n).map(|v| fanned.dir[v].unwrap_or(d[o(v)])).collect();
    let len = (0..n)
        .map(|v| if fanned.is_fanned(v) { height } else { l[o(v)] })
        .collect();
    let fixed = (0..n).map(|v| fanned.is_fanned(v) && !free).collect();
    let fan = (fanned.wall.facets.len() > fanned.real_facets).then_some(&fanned.fan);
    (dir, len, fixed, fan)
}

/// The fanned surface nodes (of `fanned`) of the front facets `bad` (of `front`), sorted.
fn fans_at(bad: &[usize], front: &Surface, fanned: &Fanned) -> Vec<u32> {
    let mut fans: Vec<u32> = bad
        .iter()
        .flat_map(|&f| front.facets[f].nodes())
        .filter(|&&v| fanned.is_fanned(v as usize))
        .map(|&v| fanned.fan.origin[v as usize])
        .collect();
    fans.sort_unstable();
    fans.dedup();
    fans
}

/// The layer of the balanced children of `ideal` (over `facets`) with Coe_shrink's `merges`,
/// the merges of squeezed cells (with `squeeze`, [`LayerParams::squeeze`]'s floor where it
/// applies) and the second trigger's (cells that fail merge their shortest edge rather than
/// shrink, if it is short); and the merges it was built with.
fn merged_and_twisted(
    topo: &Topo,
    (ideal, facets): (&Ideal<'_>, &[Facet]),
    squeeze: Option<f64>,
    twisted: bool,
    merges: Vec<[u32; 2]>,
) -> (Layer, Vec<[u32; 2]>) {
    let (mut next, mut merges) = match squeeze {
        Some(floor) => squeezed_layer(topo, ideal, facets, floor, merges),
        None => (merged_layer(ideal, facets, merges.clone()), merges),
    };
    if twisted {
        let bad = bad_cells(ideal.nodes, &next, facets);
        let mut more = merges.clone();
        let (balanced, len) = (ideal.balanced, ideal.len);
        add_twisted(
            topo,
            balanced,
            len,
            (&bad, ideal.stopped),
            TWISTED_RATIO,
            &mut more,
        );
        if more.len() > merges.len() {
            next = merged_layer(ideal, facets, more.clone());
            merges = more;
        } else {
            // checked already: the shrinking starts from these
            next.failing = Some(bad);
        }
    }
    (next, merges)
}

/// How many times a layer that stays invalid drops the merges of its failing cells and is
/// checked again.
const UNMERGE_TRIES: usize = 4;

/// How many times a layer that stays invalid turns the steps of its failing bottom corners
/// ([`turned_steps`]).
const TURN_TRIES: usize = 3;

/// Shrinks `next` (the layer over the front of `ideal`, its facets `facets`) until valid
/// ([`shrink_until_valid`]: once where a cell is inverted, `max_shrinks` times where the front
/// crosses itself). Where it stays invalid and children of its failing cells are
/// merged, the layer is built again from the balanced children without those merges
/// ([`merged_layer`] with the others) and shrunk again, at most [`UNMERGE_TRIES`] times:
/// a merged child stands over the middle of its two parents, half an edge off each
/// parent's column, and the halving moves it towards that middle, so an unmerged cell
/// next to it that it shears stays inverted however far it is shrunk (the quad wing's
/// side near a tip, `docs/3d.md`). With `turn` (the wing's quad side, with
/// [`LayerParams::patch_normals`]), the first time it stays invalid the steps of the nodes
/// whose bottom corners fail are turned first ([`turned_steps`]) and the layer built again
/// from them.
fn settle_layer(
    ideal: &Ideal<'_>,
    facets: &[Facet],
    next: &mut Layer,
    max_shrinks: usize,
    turn: bool,
    stats: &mut GrowStats,
) -> Result<(), Failed> {
    let mut merges: Vec<[u32; 2]> = next
        .parents
        .iter()
        .filter(|p| p[1] != NONE)
        .copied()
        .collect();
    let mut tries = 0;
    // the balanced children with the steps of failing bottom corners turned, once turned
    let mut turned: Option<Vec<[f64; 3]>> = None;
    let mut turns = 0;
    loop {
        // an inverted cell shrunk further only flattens: its columns stop instead (`stop`)
        let shrinks = (max_shrinks.min(INVERTED_SHRINKS), max_shrinks);
        let failed = match shrink_until_valid(ideal.nodes, facets, next, shrinks, stats) {
            Ok(()) => return Ok(()),
            Err(failed) => failed,
        };
        if turn && turns < TURN_TRIES {
            turns += 1;
            let from = turned.as_deref().unwrap_or(ideal.balanced);
            if let Some(balanced) = turned_steps(ideal.nodes, facets, from, &failed.bad) {
                let balanced = turned.insert(balanced).as_slice();
                *next = merged_layer(&Ideal { balanced, ..*ideal }, facets, merges.clone());
                continue;
            }
            // nothing to turn: never try again
            turns = TURN_TRIES;
        }
        let mut drop: Vec<u32> = failed
            .bad
            .iter()
            .flat_map(|&f| facets[f].nodes().iter().copied())
            .collect();
        drop.sort_unstable();
        let before = merges.len();
        merges.retain(|m| drop.binary_search(&m[0]).is_err() && drop.binary_search(&m[1]).is_err());
        if tries == UNMERGE_TRIES || merges.len() == before {
            return Err(failed);
        }
        tries += 1;
        let balanced = turned.as_deref().unwrap_or(ideal.balanced);
        *next = merged_layer(&Ideal { balanced, ..*ideal }, facets, merges.clone());
    }
}

/// What the layer loop carries from one layer to the next.
struct State {
    mesh: PolyMesh,
    /// The current front: nodes, facets (each over the cell of the layer below) and patches.
    front: Surface,
    /// For each front node, its mesh node.
    front_mesh: Vec<u32>,
    /// For each front facet, its mesh face (the bottom of the next cell) and its pipe.
    front_faces: Vec<u32>,
    pipes: Vec<u32>,
    /// For each front facet, the corner scaled Jacobian its cell is held to (`shape`): what
    /// its wall facet allows.
    shape_bars: Vec<f64>,
    /// The number of surface nodes: the columns after them are the fans' copies'.
    wall_nodes: usize,
    /// For each column, whether its wall node is on a coarsely faceted curve
    /// (`front::coarse_nodes`).
    coarse: Vec<bool>,
    /// For each wall node (each copy of a fanned node apart), its column so far, and the
    /// front node at its top.
    columns: Vec<Vec<u32>>,
    column_top: Vec<u32>,
    /// For each wall node, where its column stopped.
    stops: Vec<Option<ColumnStop>>,
    /// For each front node, whether its column stopped, and its thickness (the sum of its
    /// layers' heights; a merged child's the mean of its parents').
    stopped: Vec<bool>,
    thick: Vec<f64>,
    node_layer: Vec<u32>,
    node_parents: Vec<[u32; 2]>,
    layer_merges: Vec<usize>,
    /// Each layer's height.
    layer_heights: Vec<f64>,
    stats: GrowStats,
}

impl State {
    /// The state before the first layer: the front is the wall `fanned` (the surface
    /// `surface` with its fans), each copy of a fanned node on its node's mesh node, the
    /// fans' zero-area facets without a face.
    fn new(surface: &Surface, fanned: &Fanned, coarse: &[bool]) -> State {
        let n = surface.nodes.len();
        let nf = fanned.wall.nodes.len();
        let mut mesh = PolyMesh::new();
        mesh.nodes = surface.nodes.clone();
        let front_faces = fanned
            .wall
            .facets
            .iter()
            .enumerate()
            .map(|(f, facet)| {
                if f < fanned.real_facets {
                    let k: Vec<u32> = facet
                        .nodes()
                        .iter()
                        .map(|&v| fanned.fan.origin[v as usize])
                        .collect();
                    mesh.push_face(&k)
                } else {
                    NONE
                }
            })
            .collect();
        State {
            mesh,
            front: fanned.wall.clone(),
            front_mesh: fanned.fan.origin.clone(),
            front_faces,
            pipes: fanned.pipe.clone(),
            shape_bars: shape_bars(&fanned.wall.nodes, &fanned.wall.facets, fanned.real_facets),
            wall_nodes: n,
            coarse: fanned
                .fan
                .origin
                .iter()
                .map(|&o| coarse[o as usize])
                .collect(),
            columns: fanned.fan.origin.iter().map(|&o| vec![o]).collect(),
            column_top: (0..nf as u32).collect(),
            stops: vec![None; nf],
            stopped: vec![false; nf],
            thick: vec![0.0; nf],
            node_layer: vec![0; n],
            node_parents: vec![[NONE; 2]; n],
            layer_merges: Vec::new(),
            layer_heights: Vec::new(),
            stats: GrowStats {
                converged: true,
                ..GrowStats::default()
            },
        }
    }

    /// For each front node, whether a column through it grew from a coarsely faceted curve.
    fn coarse_front(&self) -> Vec<bool> {
        let mut out = vec![false; self.front.nodes.len()];
        for (&top, &c) in self.column_top.iter().zip(&self.coarse) {
            out[top as usize] |= c;
        }
        out
    }

    /// Appends the layer `next` grown over the current front (its edges `topo`): its nodes
    /// (a kept child is its parent's node), its cells, the records (`stops`: the nodes'
    /// rises and why those that stopped in this layer did); then `next`'s top is the front.
    fn push_layer(&mut self, topo: &Topo, next: Layer, layer: usize, stops: &LayerStops) {
        let mut mesh_node = Vec::with_capacity(next.children.len());
        let mut thick = Vec::with_capacity(next.children.len());
        for (c, p) in next.parents.iter().enumerate() {
            let parents = p.iter().filter(|&&v| v != NONE).map(|&v| v as usize);
            let grown: f64 = parents
                .clone()
                .map(|v| self.thick[v] + stops.rise[v])
                .sum::<f64>();
            thick.push(grown / parents.clone().count() as f64);
            if next.kept[c] {
                mesh_node.push(self.front_mesh[p[0] as usize]);
                continue;
            }
            mesh_node.push(self.mesh.nodes.len() as u32);
            self.mesh.nodes.push(next.children[c]);
            self.node_layer.push(layer as u32 + 1);
            self.node_parents.push(p.map(|v| {
                if v == NONE {
                    NONE
                } else {
                    self.front_mesh[v as usize]
                }
            }));
        }
        let merges = next.parents.iter().filter(|p| p[1] != NONE).count();
        self.stats.merges += merges;
        self.layer_merges.push(merges);
        let top_faces = self.push_cells(topo, &next, &mesh_node, layer);
        for (w, (column, top)) in self
            .columns
            .iter_mut()
            .zip(&mut self.column_top)
            .enumerate()
        {
            let was = *top as usize;
            *top = next.child[was];
            if !next.kept[*top as usize] {
                column.push(mesh_node[*top as usize]);
            } else if let Some(why) = stops.why[was] {
                // the column stops here (a column already stopped keeps its record)
                self.stops[w] = Some(ColumnStop { layer, why });
                // (a fan's other columns are counted with their node's first)
                self.stats.stopped_columns += usize::from(w < self.wall_nodes);
            }
        }
        self.pipes = next
            .top_of
            .iter()
            .map(|&f| self.pipes[f as usize])
            .collect();
        self.shape_bars = next
            .top_of
            .iter()
            .map(|&f| self.shape_bars[f as usize])
            .collect();
        self.front.facet_patch = next
            .top_of
            .iter()
            .map(|&f| self.front.facet_patch[f as usize])
            .collect();
        self.front_faces = top_faces;
        self.front_mesh = mesh_node;
        self.stopped = next.kept;
        self.thick = thick;
        self.front.nodes = next.children;
        self.front.facets = next.top;
    }

    /// Appends the cells of one layer: the children of `layer` (child `c` is mesh node
    /// `mesh_node[c]`) over the front (its edges `topo`), one cell per front facet with its
    /// faces in the contract's order (bottom, top when it keeps three nodes, sides along the
    /// bottom's edges); each side face is stored once, as (a, b, b', a') for the edge a → b
    /// of its first facet without the repeated nodes of merged or kept children (a triangle,
    /// or no face where both a and b stopped). A facet whose nodes all stopped has no cell:
    /// its face stays the front's. Returns the mesh faces of the new front's facets.
    fn push_cells(
        &mut self,
        topo: &Topo,
        layer: &Layer,
        mesh_node: &[u32],
        layer_index: usize,
    ) -> Vec<u32> {
        let (mesh, front, level) = (&mut self.mesh, &self.front, &self.front_mesh);
        let (bottom_faces, pipes) = (&self.front_faces, &self.pipes);
        let top_faces: Vec<u32> = layer
            .top
            .iter()
            .zip(&layer.top_of)
            .map(|(f, &below)| {
                if layer.is_bare(&front.facets[below as usize]) {
                    return bottom_faces[below as usize];
                }
                let k: Vec<u32> = f.nodes().iter().map(|&c| mesh_node[c as usize]).collect();
                mesh.push_face(&k)
            })
            .collect();
        let mut top_of_facet = vec![NONE; front.facets.len()];
        for (t, &f) in layer.top_of.iter().enumerate() {
            top_of_facet[f as usize] = top_faces[t];
        }
        // a face of `Layer::side_faces` (front nodes, children after them) as mesh nodes
        let nf = layer.child.len() as u32;
        let to_mesh = |v: u32| {
            if v < nf {
                level[v as usize]
            } else {
                mesh_node[(v - nf) as usize]
            }
        };
        let up_front = |v: u32| {
            if layer.is_kept(v) {
                layer.origin(v)
            } else {
                nf + layer.child[v as usize]
            }
        };
        // each edge's side face, and the triangle where the cells either side of a fan's
        // end meet (one face for both, `pinches` by the edge's two places)
        let mut pinches: Vec<([u32; 2], u32, Vec<u32>)> = Vec::new();
        let side_faces: Vec<[(u32, bool); 2]> = topo
            .edges
            .iter()
            .map(|e| {
                let [a, b] = e.nodes;
                let [side, pinch] = layer.side_faces(a, b, up_front);
                let side = if side.len() < 3 {
                    NONE
                } else {
                    let k: Vec<u32> = side.into_iter().map(to_mesh).collect();
                    mesh.push_face(&k)
                };
                let pinch = if pinch.len() == 3 {
                    let k: Vec<u32> = pinch.into_iter().map(to_mesh).collect();
                    let key = [k[0].min(k[1]), k[0].max(k[1])];
                    match pinches.iter().find(|p| p.0 == key) {
                        Some((_, face, first)) => (*face, first[0] != k[0]),
                        None => {
                            let face = mesh.push_face(&k);
                            pinches.push((key, face, k));
                            (face, false)
                        }
                    }
                } else {
                    (NONE, false)
                };
                [(side, false), pinch]
            })
            .collect();
        let mut faces = Vec::with_capacity(6);
        for (f, facet) in front.facets.iter().enumerate() {
            if layer.is_bare(facet) {
                continue;
            }
            faces.clear();
            let fan = layer.is_fan(facet);
            let sides = facet.nodes().iter().zip(&topo.facet_edges[f]);
            let mut sides = sides.flat_map(|(&v, &e)| {
                let [(side, _), (pinch, turned)] = side_faces[e as usize];
                let along = topo.edges[e as usize].nodes[0] == v;
                let side = (side != NONE).then_some(CellFace {
                    face: side,
                    reversed: !along,
                });
                // the pinch is stored as the first cell to reach it sees it
                let pinch = (!fan && pinch != NONE).then_some(CellFace {
                    face: pinch,
                    reversed: turned,
                });
                side.into_iter().chain(pinch)
            });
            if bottom_faces[f] != NONE {
                faces.push(CellFace {
                    face: bottom_faces[f],
                    reversed: true,
                });
            } else {
                // a fan's cell has no bottom: its first side comes first (`topo-cut`'s face
                // 0, between two columns of the fan, never on the boundary)
                faces.extend(sides.next());
            }
            if top_of_facet[f] != NONE {
                faces.push(CellFace {
                    face: top_of_facet[f],
                    reversed: false,
                });
            }
            faces.extend(sides);
            mesh.push_cell(&faces, layer_index as u32, pipes[f]);
        }
        top_faces
    }

    fn finish(mut self) -> Grown3d {
        let n = self.wall_nodes;
        let fan_columns = self.columns.drain(n..).map(|c| (c[0], c)).collect();
        self.stops.truncate(n);
        Grown3d {
            mesh: self.mesh,
            columns: self.columns,
            fan_columns,
            stops: self.stops,
            front: self.front,
            front_nodes: self.front_mesh,
            node_layer: self.node_layer,
            node_parents: self.node_parents,
            layer_merges: self.layer_merges,
            layer_heights: self.layer_heights,
            stats: self.stats,
        }
    }
}

/// The rounds of direction smoothing of a layer whose top is `thickness` off the wall:
/// `smoothing × 2·thickness / spacing`, rounded up, at most `smoothing` — none near the
/// wall, where the layers are thin and must stay normal to it, all of them once the layers
/// are half as thick as the wall's mean edge `spacing`, where a concave front would fold.
fn smoothing_rounds(smoothing: usize, thickness: f64, spacing: f64) -> usize {
    let ramp = (2.0 * thickness / spacing).min(1.0);
    (smoothing as f64 * ramp).ceil() as usize
}

fn check_params(p: &LayerParams) -> Result<(), GrowError> {
    let bad = |what: &str| Err(GrowError::Params(what.to_string()));
    if !(p.first_height.is_finite() && p.first_height > 0.0) {
        return bad("first_height must be positive and finite");
    }
    if !(p.growth.is_finite() && p.growth >= 1.0) {
        return bad("growth must be at least 1");
    }
    if !(p.coe_shrink >= 0.0 && p.coe_shrink < 1.0) {
        return bad("coe_shrink must be in [0, 1)");
    }
    if !(p.stand_off >= 0.0 && p.stand_off < 1.0) {
        return bad("stand_off must be in [0, 1)");
    }
    if !(p.squeeze >= 0.0 && p.squeeze < 1.0) {
        return bad("squeeze must be in [0, 1)");
    }
    if !(p.max_aspect >= 0.0 && p.max_aspect.is_finite()) {
        return bad("max_aspect must be finite and at least 0");
    }
    if !(p.merge_rows >= 0.0 && p.merge_rows.is_finite()) {
        return bad("merge_rows must be finite and at least 0");
    }
    if !(p.stop_aspect >= 0.0 && p.stop_aspect.is_finite()) {
        return bad("stop_aspect must be finite and at least 0");
    }
    if !(p.stop_gap_spacing >= 0.0 && p.stop_gap_spacing.is_finite()) {
        return bad("stop_gap_spacing must be finite and at least 0");
    }
    if !(p.stop_gap >= 0.0 && p.stop_gap.is_finite()) {
        return bad("stop_gap must be finite and at least 0");
    }
    if !(p.fan_threshold_deg >= 0.0 && p.fan_threshold_deg < 180.0) {
        return bad("fan_threshold_deg must be in [0, 180)");
    }
    if !(p.fan_max_angle_deg > 0.0 && p.fan_max_angle_deg < 180.0) {
        return bad("fan_max_angle_deg must be in (0, 180)");
    }
    if p.max_thickness.is_nan() || p.max_thickness <= 0.0 {
        return bad("max_thickness must be positive");
    }
    if !(p.springs.tension_ratio > 0.0 && p.springs.tension_ratio <= 1.0) {
        return bad("tension_ratio must be in (0, 1]");
    }
    p.solver
        .check()
        .map_err(|e| GrowError::Params(e.to_string()))
}

/// One layer's step: the front's nodes `x`, their ideal directions and lengths, the
/// parameters and the layer.
#[derive(Clone, Copy)]
struct Step<'a> {
    x: &'a [[f64; 3]],
    dir: &'a [[f64; 3]],
    len: &'a [f64],
    /// The nodes whose columns stopped: their children stay on them.
    stopped: &'a [bool],
    /// The nodes whose children stay at their ideal steps, unbalanced (a fan's, in the first
    /// layer; empty: none).
    fixed: &'a [bool],
    params: &'a LayerParams,
    layer: usize,
}

/// The children of the front nodes, balanced: placed at their ideal steps, balanced by the
/// extrusion, neighbour and angle springs (the neighbour springs on the front's edges
/// `topo`), then again with the tension springs (ideal length `tension_ratio` × the length
/// after the first balance). Only the children move, and not those of stopped nodes (they
/// stay on their parents, held by no extrusion or angle spring).
fn balance(
    step: &Step<'_>,
    topo: &Topo,
    stats: &mut GrowStats,
) -> Result<Vec<[f64; 3]>, GrowError> {
    let Step {
        x,
        dir,
        len,
        stopped,
        fixed,
        params,
        layer,
    } = *step;
    let n = x.len();
    let mut p: Vec<[f64; 3]> = x.to_vec();
    p.extend((0..n).map(|i| std::array::from_fn(|d| x[i][d] + len[i] * dir[i][d])));
    let is_fixed = |i: usize| fixed.get(i).copied().unwrap_or(false);
    let movable: Vec<bool> = (0..2 * n)
        .map(|i| i >= n && !stopped[i - n] && !is_fixed(i - n))
        .collect();
    // (a stopped node's scale is the largest step's: any positive length)
    let longest = len.iter().copied().fold(0.0, f64::max);
    let scale: Vec<f64> = (0..2 * n)
        .map(|i| if stopped[i % n] { longest } else { len[i % n] })
        .collect();
    let up = n as u32;
    let mut set = SpringSet3d::default();
    let both_stopped = |e: [u32; 2]| stopped[e[0] as usize] && stopped[e[1] as usize];
    for i in (0..n).filter(|&i| !stopped[i]) {
        let k = i as u32;
        set.extrusion.push(ExtrusionSpring {
            lower: k,
            upper: k + up,
            ideal_length: len[i],
            lower_share: 0.0,
        });
        set.angle.push(AngleSpring3d {
            parent: k,
            child: k + up,
            direction: dir[i],
        });
    }
    let edge_length = |e: [u32; 2]| (len[e[0] as usize] + len[e[1] as usize]) / 2.0;
    for e in topo.edges.iter().filter(|e| !both_stopped(e.nodes)) {
        set.neighbour.push(NeighbourSpring3d {
            edge: e.nodes.map(|v| v + up),
            far1: e.far[0].map(|v| v + up),
            far2: e.far[1].map(|v| v + up),
            extrusion_length: edge_length(e.nodes),
        });
    }
    let solve = |p: &mut Vec<[f64; 3]>, set: &SpringSet3d, stats: &mut GrowStats| {
        let model = SpringField3d::new(set, &params.springs);
        let out = solve_model(p, &scale, &movable, &model, &params.solver)
            .map_err(|source| GrowError::Spring { layer, source })?;
        stats.converged &= out.converged;
        Ok::<(), GrowError>(())
    };
    solve(&mut p, &set, stats)?;
    let longest = topo.longest_edge(&p[n..]);
    for e in topo.edges.iter().filter(|e| !both_stopped(e.nodes)) {
        let [a, b] = e.nodes.map(|v| v as usize);
        let length = dist(p[n + a], p[n + b]);
        let l_charac = longest[a].max(longest[b]);
        set.tension.push(TensionSpring::new(
            e.nodes.map(|v| v + up),
            length,
            edge_length(e.nodes),
            l_charac,
            &params.springs,
        ));
    }
    solve(&mut p, &set, stats)?;
    Ok(p.split_off(n))
}
