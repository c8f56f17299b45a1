//! The layer loop: ideal steps, two spring balances, checks, and the cells appended to the
//! polyhedral mesh.

use geom_predicates::vector::dist;
use geom_surface::{Facet, Surface};
use mesh_model::poly::{CellFace, PolyMesh};
use mesh_model::{NONE, Role};
use springfield::{
    AngleSpring3d, ExtrusionSpring, NeighbourSpring3d, SpringField3d, SpringSet3d, TensionSpring,
    solve_model,
};

use crate::aspect::{limit_ratio, mean_edge};
use crate::check::{Failed, bad_cells, shrink_until_valid, turned_steps};
use crate::children::{Ideal, Layer};
use crate::front::{Topo, ideal_steps};
use crate::layer::{add_twisted, choose_merges, merged_layer};
use crate::repair::{CUT_LIMIT, repair_layer};
use crate::squeeze::squeezed_layer;
use crate::{GrowError, GrowStats, Grown3d, LayerParams};

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
    let mut topo = Topo::new(surface);
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
    let mut state = State::new(surface);
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
        thickness += height;
        state.layer_heights.push(height);
        let rounds = smoothing_rounds(params.smoothing, thickness, spacing);
        let front = &state.front;
        let (dir, len) = ideal_steps(
            front,
            &topo,
            height,
            rounds,
            params.stand_off,
            params.patch_normals,
        );
        let step = Step {
            x: &front.nodes,
            dir: &dir,
            len: &len,
            params,
            layer,
        };
        let balanced = balance(&step, &topo, &mut state.stats)?;
        // the first layer stays whole: its height is what the wall resolution needs
        let rows = (params.merge_rows > 0.0).then_some(params.merge_rows);
        let merges = if layer > 0 && params.coe_shrink > 0.0 {
            choose_merges(&topo, &balanced, &len, params.coe_shrink, rows)
        } else {
            Vec::new()
        };
        let ideal = Ideal {
            nodes: &front.nodes,
            dir: &dir,
            len: &len,
            balanced: &balanced,
        };
        // where the layers are as thick as half the wall's spacing, squeezed cells merge too
        let (mut next, merges) = if layer > 0 && params.squeeze > 0.0 && 2.0 * thickness >= spacing
        {
            squeezed_layer(&topo, &ideal, &front.facets, params.squeeze, merges)
        } else {
            (merged_layer(&ideal, &front.facets, merges.clone()), merges)
        };
        if layer > 0 && params.coe_shrink > 0.0 {
            // cells that fail merge their shortest edge rather than shrink, if it is short
            let bad = bad_cells(&front.nodes, &next, &front.facets);
            let mut more = merges.clone();
            add_twisted(&topo, &balanced, &len, &bad, TWISTED_RATIO, &mut more);
            if more.len() > merges.len() {
                next = merged_layer(&ideal, &front.facets, more);
            } else {
                // checked already: the shrinking starts from these
                next.failing = Some(bad);
            }
        }
        settle_layer(
            &ideal,
            &front.facets,
            &mut next,
            params.max_shrinks,
            params.patch_normals,
            &mut state.stats,
        )
        .map_err(|failed| failed.error(&state.pipes, layer))?;
        // the few cells no cut can keep under the limit: their children moved (checked); not
        // in the first layer, whose children stand on the wall's normals at its first height
        // (moved there, the wing's thin tip-cap cells made the second layer fail)
        if layer > 0 {
            state.stats.repaired +=
                repair_layer(&front.nodes, &front.facets, &dir, &mut next, CUT_LIMIT);
        }
        let merged = next.children.len() < front.nodes.len();
        state.push_layer(&topo, next, layer);
        if merged {
            topo = Topo::new(&state.front);
        }
    }
    Ok(state.finish())
}

/// How many times a layer that stays invalid drops the merges of its failing cells and is
/// checked again.
const UNMERGE_TRIES: usize = 4;

/// How many times a layer that stays invalid turns the steps of its failing bottom corners
/// ([`turned_steps`]).
const TURN_TRIES: usize = 3;

/// Shrinks `next` (the layer over the front of `ideal`, its facets `facets`) until valid
/// ([`shrink_until_valid`]). Where it stays invalid and children of its failing cells are
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
        let failed = match shrink_until_valid(ideal.nodes, facets, next, max_shrinks, stats) {
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
    /// For each wall node, its column so far, and the front node at its top.
    columns: Vec<Vec<u32>>,
    column_top: Vec<u32>,
    node_layer: Vec<u32>,
    node_parents: Vec<[u32; 2]>,
    layer_merges: Vec<usize>,
    /// Each layer's height.
    layer_heights: Vec<f64>,
    stats: GrowStats,
}

impl State {
    fn new(surface: &Surface) -> State {
        let n = surface.nodes.len();
        let mut mesh = PolyMesh::new();
        mesh.nodes = surface.nodes.clone();
        let front_faces = surface
            .facets
            .iter()
            .map(|f| mesh.push_face(f.nodes()))
            .collect();
        State {
            mesh,
            front: surface.clone(),
            front_mesh: (0..n as u32).collect(),
            front_faces,
            pipes: (0..surface.facets.len() as u32).collect(),
            columns: (0..n as u32).map(|i| vec![i]).collect(),
            column_top: (0..n as u32).collect(),
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

    /// Appends the layer `next` grown over the current front (its edges `topo`): its nodes,
    /// its cells, the records; then `next`'s top is the front.
    fn push_layer(&mut self, topo: &Topo, next: Layer, layer: usize) {
        let base = self.mesh.nodes.len() as u32;
        self.mesh.nodes.extend_from_slice(&next.children);
        let merges = next.parents.iter().filter(|p| p[1] != NONE).count();
        self.stats.merges += merges;
        self.layer_merges.push(merges);
        for p in &next.parents {
            self.node_layer.push(layer as u32 + 1);
            self.node_parents.push(p.map(|v| {
                if v == NONE {
                    NONE
                } else {
                    self.front_mesh[v as usize]
                }
            }));
        }
        let top_faces = self.push_cells(topo, &next, base, layer);
        for (column, top) in self.columns.iter_mut().zip(&mut self.column_top) {
            *top = next.child[*top as usize];
            column.push(base + *top);
        }
        self.pipes = next
            .top_of
            .iter()
            .map(|&f| self.pipes[f as usize])
            .collect();
        self.front.facet_patch = next
            .top_of
            .iter()
            .map(|&f| self.front.facet_patch[f as usize])
            .collect();
        self.front_faces = top_faces;
        self.front_mesh = (base..base + next.children.len() as u32).collect();
        self.front.nodes = next.children;
        self.front.facets = next.top;
    }

    /// Appends the cells of one layer: the children of `layer` (mesh nodes `base + c`) over the
    /// front (its edges `topo`), one cell per front facet with its faces in the contract's order (bottom, top
    /// when it keeps three nodes, sides along the bottom's edges); each side face is stored
    /// once, as (a, b, b', a') for the edge a → b of its first facet, a triangle (a, b, b')
    /// where the two children merged. Returns the mesh faces of the new front's facets.
    fn push_cells(
        &mut self,
        topo: &Topo,
        layer: &Layer,
        base: u32,
        layer_index: usize,
    ) -> Vec<u32> {
        let (mesh, front, level) = (&mut self.mesh, &self.front, &self.front_mesh);
        let (bottom_faces, pipes) = (&self.front_faces, &self.pipes);
        let up = |v: u32| base + layer.child[v as usize];
        let top_faces: Vec<u32> = layer
            .top
            .iter()
            .map(|f| {
                let k: Vec<u32> = f.nodes().iter().map(|&c| base + c).collect();
                mesh.push_face(&k)
            })
            .collect();
        let mut top_of_facet = vec![NONE; front.facets.len()];
        for (t, &f) in layer.top_of.iter().enumerate() {
            top_of_facet[f as usize] = top_faces[t];
        }
        let side_faces: Vec<u32> = topo
            .edges
            .iter()
            .map(|e| {
                let [a, b] = e.nodes;
                let (la, lb) = (level[a as usize], level[b as usize]);
                if up(a) == up(b) {
                    mesh.push_face(&[la, lb, up(b)])
                } else {
                    mesh.push_face(&[la, lb, up(b), up(a)])
                }
            })
            .collect();
        let mut faces = Vec::with_capacity(6);
        for (f, facet) in front.facets.iter().enumerate() {
            faces.clear();
            faces.push(CellFace {
                face: bottom_faces[f],
                reversed: true,
            });
            if top_of_facet[f] != NONE {
                faces.push(CellFace {
                    face: top_of_facet[f],
                    reversed: false,
                });
            }
            for (&v, &e) in facet.nodes().iter().zip(&topo.facet_edges[f]) {
                faces.push(CellFace {
                    face: side_faces[e as usize],
                    reversed: topo.edges[e as usize].nodes[0] != v,
                });
            }
            mesh.push_cell(&faces, layer_index as u32, pipes[f]);
        }
        top_faces
    }

    fn finish(self) -> Grown3d {
        Grown3d {
            mesh: self.mesh,
            columns: self.columns,
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
    params: &'a LayerParams,
    layer: usize,
}

/// The children of the front nodes, balanced: placed at their ideal steps, balanced by the
/// extrusion, neighbour and angle springs (the neighbour springs on the front's edges
/// `topo`), then again with the tension springs (ideal length `tension_ratio` × the length
/// after the first balance). Only the children move.
fn balance(
    step: &Step<'_>,
    topo: &Topo,
    stats: &mut GrowStats,
) -> Result<Vec<[f64; 3]>, GrowError> {
    let Step {
        x,
        dir,
        len,
        params,
        layer,
    } = *step;
    let n = x.len();
    let mut p: Vec<[f64; 3]> = x.to_vec();
    p.extend((0..n).map(|i| std::array::from_fn(|d| x[i][d] + len[i] * dir[i][d])));
    let movable: Vec<bool> = (0..2 * n).map(|i| i >= n).collect();
    let scale: Vec<f64> = (0..2 * n).map(|i| len[i % n]).collect();
    let up = n as u32;
    let mut set = SpringSet3d::default();
    for i in 0..n {
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
    for e in &topo.edges {
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
    for e in &topo.edges {
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
