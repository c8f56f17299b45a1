//! The advancing-front core: grows one layer at a time from every front at once, balances the
//! top layers with the Spring-Field, and stops the parts of the fronts that close.
//!
//! A front is a closed loop of nodes with the region still to mesh on its left; each of its
//! edges is active (it will beget a child edge and a cell above it, in the pipe of the boundary
//! facet it descends from) or frozen (it is final and bounds the region left for the hole
//! filling). One layer step is:
//! 1. plan: every node on an active edge gets one child on the bisector at the ideal length,
//!    or a fan of children at a convex corner;
//! 2. closing: a planned cell that would come nearer than its clearance to another part of the
//!    fronts (another loop, or its own loop far away along the front) freezes its edge;
//! 3. build: nodes and cells are created, new neighbour edges shorter than Coe_shrink times
//!    their extrusion edges break (their nodes merge, the quad below becomes a triangle);
//! 4. solve: the springs of the top layers are balanced (`springfield`);
//! 5. verify: every cell that moved must stay convex and positive, and no new front edge may
//!    touch another front edge; otherwise the step is undone, the offending edges are frozen
//!    and the step is redone with fewer moving layers (finally with no solve at all).
//!
//! Invariant after each step: all cells are positive and the fronts are disjoint simple
//! loops, so the cells cover exactly the region between the boundary and the fronts.
//!
//! It does not fill the region left between the fronts (`fill`), nor build the output mesh.

use mesh_model::NONE;
use springfield::{AngleSpring, ExtrusionSpring, NeighbourSpring, SpringSet2d, assemble_2d_active};

use geom_predicates::vector::{cross2, dist, dot};
use geom_predicates::{for_each_overlapping_pair, orient2d, segment_distance, segments_meet};

use crate::geom::{Aabb, P2};
use crate::input::AfsfParams;

/// How the ideal extrusion length of a front's layers is chosen.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Law {
    /// Walls: first height × growth^layer.
    Geometric { first: f64, growth: f64 },
    /// Far field: isotropic layers, factor × the local spacing.
    Isotropic { factor: f64 },
}

/// One edge of a front, from `items[i]` to `items[i + 1]`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct FEdge {
    /// Will beget a cell in the next step.
    pub active: bool,
    /// The boundary facet whose pipe this edge is the top of, or NONE (step edges).
    pub pipe: u32,
    /// The cell this edge bounds (top or side), or NONE (boundary edges).
    pub cell: u32,
}

/// One front loop.
#[derive(Debug, Clone)]
pub(crate) struct Loop {
    pub items: Vec<u32>,
    pub edges: Vec<FEdge>,
    pub law: Law,
}

/// A cell under construction (corners counter-clockwise; `len` 3 or 4, 0 when deleted).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Cell {
    pub nodes: [u32; 4],
    pub len: u8,
    pub layer: u32,
    pub pipe: u32,
    /// (loop, front edge, second front edge or NONE) that begot it, to freeze on failure.
    pub origin: [u32; 3],
}

impl Cell {
    pub(crate) fn corners(&self) -> &[u32] {
        &self.nodes[..self.len as usize]
    }
}

/// Figures of one layer step.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct LayerStats {
    /// The layer index of the nodes created (1 = first layer off the boundary).
    pub layer: u32,
    /// Cells created.
    pub cells: usize,
    /// Spring-solver iterations in the accepted attempt.
    pub iterations: usize,
    /// Whether the accepted attempt's solve converged (true when no solve was needed).
    pub converged: bool,
    /// Attempts undone before the accepted one.
    pub retries: u32,
    /// Front edges frozen in this step (closing and failed attempts).
    pub frozen_edges: usize,
    /// Neighbour edges broken (node merges) in this step.
    pub merges: usize,
}

/// Timings (seconds) of the phases of the growth.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Timings {
    /// Planning children and the closing test.
    pub plan_and_closing: f64,
    /// Building nodes, cells, merges and the new fronts.
    pub build: f64,
    /// Spring solves.
    pub solve: f64,
    /// Verification of the cells and fronts.
    pub verify: f64,
    /// Filling the region left between the fronts.
    pub fill: f64,
    /// The whole run.
    pub total: f64,
}

/// The growing mesh.
pub(crate) struct Work<'p> {
    pub params: &'p AfsfParams,
    pub pos: Vec<P2>,
    pub layer: Vec<u32>,
    pub parent: Vec<u32>,
    pub parent2: Vec<u32>,
    /// Neighbours on the node's own layer (front order), NONE at a step or a layer's end.
    pub left: Vec<u32>,
    pub right: Vec<u32>,
    /// Ideal length of the extrusion edge ending at the node.
    pub ideal: Vec<f64>,
    /// C_aniso of the parent in that extrusion spring.
    pub share: Vec<f64>,
    /// Fan offset of the node's ideal direction from its parent's bisector (radians).
    pub offset: Vec<f64>,
    pub alive: Vec<bool>,
    pub n_boundary: usize,
    pub cells: Vec<Cell>,
    /// First node and first cell of each step (index = layer of the step's nodes).
    pub node_step: Vec<usize>,
    pub cell_step: Vec<usize>,
    pub loops: Vec<Loop>,
    pub layer_stats: Vec<LayerStats>,
    pub timings: Timings,
    springs: SpringSet2d,
    local_of: Vec<u32>,
}

/// Children planned for one loop.
#[derive(Default)]
struct Plan {
    advancing: Vec<bool>,
    start: Vec<u32>,
    pos: Vec<P2>,
    ideal: Vec<f64>,
    offset: Vec<f64>,
}

impl Plan {
    fn children(&self, v: usize) -> std::ops::Range<usize> {
        self.start[v] as usize..self.start[v + 1] as usize
    }
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Mode {
    Full,
    NewLayerOnly,
    NoSolve,
}

fn left_normal(a: P2, b: P2) -> Option<P2> {
    let d = [b[0] - a[0], b[1] - a[1]];
    let l = dot(d, d).sqrt();
    (l > 0.0).then(|| [-d[1] / l, d[0] / l])
}

fn rotate(v: P2, angle: f64) -> P2 {
    let (s, c) = angle.sin_cos();
    [c * v[0] - s * v[1], s * v[0] + c * v[1]]
}

impl<'p> Work<'p> {
    /// Starts from the oriented boundary loops: `fronts[l]` lists node indices into
    /// `points` with the domain on the left; `pipes[l][i]` is the facet under front edge i.
    pub(crate) fn new(
        params: &'p AfsfParams,
        points: Vec<P2>,
        fronts: Vec<(Vec<u32>, Vec<u32>, Law)>,
    ) -> Self {
        let n = points.len();
        let mut w = Work {
            params,
            layer: vec![0; n],
            parent: vec![NONE; n],
            parent2: vec![NONE; n],
            left: vec![NONE; n],
            right: vec![NONE; n],
            ideal: vec![0.0; n],
            share: vec![1.0; n],
            offset: vec![0.0; n],
            alive: vec![true; n],
            n_boundary: n,
            pos: points,
            cells: Vec::new(),
            node_step: vec![0],
            cell_step: vec![0],
            loops: Vec::new(),
            layer_stats: Vec::new(),
            timings: Timings::default(),
            springs: SpringSet2d::default(),
            local_of: Vec::new(),
        };
        for (items, pipes, law) in fronts {
            let m = items.len();
            for i in 0..m {
                w.left[items[i] as usize] = items[(i + m - 1) % m];
                w.right[items[i] as usize] = items[(i + 1) % m];
            }
            let edges = pipes
                .iter()
                .map(|&pipe| FEdge {
                    active: true,
                    pipe,
                    cell: NONE,
                })
                .collect();
            w.loops.push(Loop { items, edges, law });
        }
        w
    }

    /// Grows layers until every front is closed or the layer budget is spent.
    pub(crate) fn grow(&mut self) -> Result<(), springfield::SpringError> {
        for step in 1..=self.params.max_layers {
            if !self.loops.iter().any(|l| l.edges.iter().any(|e| e.active)) {
                break;
            }
            self.step(step)?;
        }
        for l in &mut self.loops {
            l.edges.iter_mut().for_each(|e| e.active = false);
        }
        Ok(())
    }

    fn ideal_length(&self, law: Law, g: usize) -> f64 {
        match law {
            Law::Geometric { first, growth } => first * growth.powi(self.layer[g] as i32),
            Law::Isotropic { factor } => {
                let (l, r) = (self.left[g], self.right[g]);
                let mut sum = 0.0;
                let mut k = 0.0f64;
                for o in [l, r] {
                    if o != NONE {
                        sum += dist(self.pos[g], self.pos[o as usize]);
                        k += 1.0;
                    }
                }
                factor * sum / k.max(1.0)
            }
        }
    }

    /// Plans the children of the advancing nodes of one loop. A node advances when one of
    /// its active edges has both ends able to advance (so every child belongs to a cell).
    fn plan_loop(&self, lp: &Loop) -> Plan {
        let m = lp.items.len();
        let fan_threshold = self.params.fan_threshold_deg.to_radians();
        let cos_fan_threshold = fan_threshold.cos();
        let fan_max = self.params.fan_max_angle_deg.to_radians();
        // directions (and fan offsets) of every node on an active edge
        let mut dirs: Vec<Vec<(P2, f64)>> = vec![Vec::new(); m];
        for (v, dirs_v) in dirs.iter_mut().enumerate() {
            if !(lp.edges[(v + m - 1) % m].active || lp.edges[v].active) {
                continue;
            }
            let g = lp.items[v] as usize;
            let p = self.pos[g];
            let n1 = (self.left[g] != NONE)
                .then(|| left_normal(self.pos[self.left[g] as usize], p))
                .flatten();
            let n2 = (self.right[g] != NONE)
                .then(|| left_normal(p, self.pos[self.right[g] as usize]))
                .flatten();
            match (n1, n2) {
                (Some(a), Some(b)) => {
                    // the turn angle (atan2) is needed only for an outward turn of more
                    // than the fan threshold: cross < 0 and cos(turn) < cos(threshold)
                    let maybe_fan = cross2(a, b) < 0.0 && dot(a, b) < cos_fan_threshold + 1e-9;
                    let theta = if maybe_fan {
                        cross2(a, b).atan2(dot(a, b))
                    } else {
                        0.0
                    };
                    if maybe_fan && -theta > fan_threshold {
                        let pieces = (-theta / fan_max).ceil().max(1.0) as usize;
                        for j in 0..=pieces {
                            let phi = theta * j as f64 / pieces as f64;
                            dirs_v.push((rotate(a, phi), phi - 0.5 * theta));
                        }
                    } else {
                        let s = [a[0] + b[0], a[1] + b[1]];
                        let l = dot(s, s).sqrt();
                        if l > 1e-6 {
                            dirs_v.push(([s[0] / l, s[1] / l], 0.0));
                        } else if let Some(d) = left_normal(
                            self.pos[self.left[g] as usize],
                            self.pos[self.right[g] as usize],
                        ) {
                            dirs_v.push((d, 0.0));
                        }
                    }
                }
                (Some(a), None) | (None, Some(a)) => dirs_v.push((a, 0.0)),
                (None, None) => {}
            }
        }
        let can = |v: usize| !dirs[v].is_empty();
        let mut plan = Plan {
            advancing: vec![false; m],
            start: Vec::with_capacity(m + 1),
            ..Plan::default()
        };
        #[allow(clippy::needless_range_loop)] // v also indexes the loop's items and edges
        for v in 0..m {
            plan.start.push(plan.pos.len() as u32);
            let prev = (v + m - 1) % m;
            let next = (v + 1) % m;
            let adv = can(v)
                && ((lp.edges[prev].active && can(prev)) || (lp.edges[v].active && can(next)));
            if !adv {
                continue;
            }
            let g = lp.items[v] as usize;
            let p = self.pos[g];
            let h = self.ideal_length(lp.law, g);
            for &(d, offset) in &dirs[v] {
                plan.pos.push([p[0] + h * d[0], p[1] + h * d[1]]);
                plan.ideal.push(h);
                plan.offset.push(offset);
            }
            plan.advancing[v] = true;
        }
        plan.start.push(plan.pos.len() as u32);
        plan
    }

    /// One layer step, with undo and retry.
    fn step(&mut self, step: u32) -> Result<(), springfield::SpringError> {
        let t0 = std::time::Instant::now();
        let saved_loops = self.loops.clone();
        let mut frozen: Vec<Vec<bool>> = self
            .loops
            .iter()
            .map(|l| l.edges.iter().map(|e| !e.active).collect())
            .collect();
        let initially_frozen: usize = frozen.iter().flatten().filter(|&&f| f).count();
        // plan on ideal positions and close
        let plans: Vec<Plan> = self.loops.iter().map(|l| self.plan_loop(l)).collect();
        self.closing(&plans, &mut frozen);
        self.timings.plan_and_closing += t0.elapsed().as_secs_f64();
        let mut stats = LayerStats {
            layer: step,
            ..LayerStats::default()
        };
        let mut attempt = 0u32;
        loop {
            let mode = match attempt {
                0 => Mode::Full,
                1 => Mode::NewLayerOnly,
                _ => Mode::NoSolve,
            };
            self.loops.clone_from(&saved_loops);
            for (l, f) in self.loops.iter_mut().zip(&frozen) {
                for (e, &fz) in l.edges.iter_mut().zip(f) {
                    e.active &= !fz;
                }
            }
            min_runs(&mut self.loops);
            let t1 = std::time::Instant::now();
            let node_start = self.pos.len();
            let cell_start = self.cells.len();
            self.node_step.push(node_start);
            self.cell_step.push(cell_start);
            let plans: Vec<Plan> = self.loops.iter().map(|l| self.plan_loop(l)).collect();
            stats.merges = self.build(step, &plans);
            self.timings.build += t1.elapsed().as_secs_f64();
            let t2 = std::time::Instant::now();
            let saved = if mode == Mode::NoSolve {
                stats.iterations = 0;
                stats.converged = true;
                Vec::new()
            } else {
                let (saved, outcome) = self.solve(step, mode)?;
                stats.iterations = outcome.iterations;
                stats.converged = outcome.converged;
                saved
            };
            if step == 1 {
                self.pin_first_layer();
            }
            self.timings.solve += t2.elapsed().as_secs_f64();
            let t3 = std::time::Instant::now();
            let (bad_edges, old_cells_bad) = self.verify(step, mode);
            self.timings.verify += t3.elapsed().as_secs_f64();
            if bad_edges.is_empty() && !old_cells_bad {
                stats.cells = self.cells.len() - cell_start;
                break;
            }
            // undo
            for (node, p) in saved {
                self.pos[node as usize] = p;
            }
            self.truncate(node_start, cell_start);
            self.node_step.pop();
            self.cell_step.pop();
            for (l, e) in bad_edges {
                frozen[l as usize][e as usize] = true;
            }
            attempt += 1;
            stats.retries = attempt;
        }
        stats.frozen_edges = frozen.iter().flatten().filter(|&&f| f).count() - initially_frozen;
        self.layer_stats.push(stats);
        Ok(())
    }

    /// The first layer's height is prescribed: after its solve, every first-layer node keeps
    /// the direction the springs gave it and gets exactly its ideal extrusion length.
    fn pin_first_layer(&mut self) {
        let start = self.node_step[1];
        for g in start..self.pos.len() {
            let p = self.parent[g];
            if !self.alive[g] || p == NONE || self.parent2[g] != NONE {
                continue;
            }
            let (a, b) = (self.pos[p as usize], self.pos[g]);
            let l = dist(a, b);
            if l > 0.0 {
                let s = self.ideal[g] / l;
                self.pos[g] = [a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1])];
            }
        }
    }

    fn truncate(&mut self, nodes: usize, cells: usize) {
        self.pos.truncate(nodes);
        self.layer.truncate(nodes);
        self.parent.truncate(nodes);
        self.parent2.truncate(nodes);
        self.left.truncate(nodes);
        self.right.truncate(nodes);
        self.ideal.truncate(nodes);
        self.share.truncate(nodes);
        self.offset.truncate(nodes);
        self.alive.truncate(nodes);
        self.cells.truncate(cells);
    }

    /// The closing test on the planned (ideal) positions: freezes every active edge whose
    /// planned cell comes nearer than its clearance to a part of the fronts that is not its
    /// neighbourhood along its own loop.
    fn closing(&self, plans: &[Plan], frozen: &mut [Vec<bool>]) {
        // segments: current front edges and planned cell sides and tops
        struct Seg {
            p: P2,
            q: P2,
            /// Where the segment came from (itself for current-front segments): a planned
            /// segment only collides with what it approaches.
            base: [P2; 2],
            ids: [u64; 2],
            lp: u32,
            arc: f64,
            /// (edge, second edge) to freeze, or NONE for current-front segments.
            owner: [u32; 2],
            clearance: f64,
        }
        let factor = self.params.closing_factor;
        let mut segs: Vec<Seg> = Vec::new();
        let mut loop_len = Vec::with_capacity(self.loops.len());
        for (li, (lp, plan)) in self.loops.iter().zip(plans).enumerate() {
            let m = lp.items.len();
            let mut arc = vec![0.0; m + 1];
            for i in 0..m {
                let (a, b) = (lp.items[i] as usize, lp.items[(i + 1) % m] as usize);
                arc[i + 1] = arc[i] + dist(self.pos[a], self.pos[b]);
            }
            loop_len.push(arc[m]);
            let child_id = |c: usize| ((li as u64 + 1) << 40) | c as u64;
            for i in 0..m {
                let (a, b) = (lp.items[i], lp.items[(i + 1) % m]);
                let (pa, pb) = (self.pos[a as usize], self.pos[b as usize]);
                let mid = 0.5 * (arc[i] + arc[i + 1]);
                segs.push(Seg {
                    p: pa,
                    q: pb,
                    base: [pa, pb],
                    ids: [a as u64, b as u64],
                    lp: li as u32,
                    arc: mid,
                    owner: [NONE, NONE],
                    clearance: 0.0,
                });
                let j = (i + 1) % m;
                if lp.edges[i].active && plan.advancing[i] && plan.advancing[j] {
                    let ca = plan.children(i).end - 1;
                    let cb = plan.children(j).start;
                    let (qa, qb) = (plan.pos[ca], plan.pos[cb]);
                    let h = 0.5 * (plan.ideal[ca] + plan.ideal[cb]);
                    let c = factor * h.max(0.5 * dist(qa, qb));
                    let owner = [i as u32, NONE];
                    for (p, q, base, ids) in [
                        (pa, qa, [pa, pa], [a as u64, child_id(ca)]),
                        (pb, qb, [pb, pb], [b as u64, child_id(cb)]),
                        (qa, qb, [pa, pb], [child_id(ca), child_id(cb)]),
                    ] {
                        segs.push(Seg {
                            p,
                            q,
                            base,
                            ids,
                            lp: li as u32,
                            arc: mid,
                            owner,
                            clearance: c,
                        });
                    }
                }
                // fan edges of node i
                let r = plan.children(i);
                if r.len() > 1 {
                    for c in r.start..r.end - 1 {
                        let (qa, qb) = (plan.pos[c], plan.pos[c + 1]);
                        let h = plan.ideal[c];
                        let pv = self.pos[lp.items[i] as usize];
                        segs.push(Seg {
                            p: qa,
                            q: qb,
                            base: [pv, pv],
                            ids: [child_id(c), child_id(c + 1)],
                            lp: li as u32,
                            arc: arc[i],
                            owner: [((i + m - 1) % m) as u32, i as u32],
                            clearance: factor * h.max(0.5 * dist(qa, qb)),
                        });
                    }
                }
            }
        }
        let boxes: Vec<Aabb> = segs
            .iter()
            .map(|s| Aabb::of_segment(s.p, s.q, s.clearance))
            .collect();
        let path_ratio = 2.5;
        let mut freeze = |li: u32, owner: [u32; 2]| {
            for e in owner {
                if e != NONE {
                    frozen[li as usize][e as usize] = true;
                }
            }
        };
        for_each_overlapping_pair(&boxes, |x, y| {
            let (sx, sy) = (&segs[x], &segs[y]);
            if sx.owner[0] == NONE && sy.owner[0] == NONE {
                return;
            }
            if sx.ids.iter().any(|i| sy.ids.contains(i)) {
                return;
            }
            // a segment whose owner is near the other along their loop (path shorter than
            // path_ratio × its clearance) is never frozen by it, whatever their distance:
            // when that holds both ways, skip the distance (most candidate pairs)
            let never_frozen = |a: &Seg, b: &Seg| {
                a.owner[0] == NONE
                    || (a.lp == b.lp && {
                        let total = loop_len[a.lp as usize];
                        let delta = (a.arc - b.arc).abs();
                        delta.min(total - delta) < path_ratio * a.clearance
                    })
            };
            if never_frozen(sx, sy) && never_frozen(sy, sx) {
                return;
            }
            let c = sx.clearance.max(sy.clearance);
            let d = segment_distance(sx.p, sx.q, sy.p, sy.q);
            if d >= c {
                return;
            }
            // only what comes nearer than it was counts (fronts diverging at a convex corner
            // are close but do not close)
            let d_base = segment_distance(sx.base[0], sx.base[1], sy.base[0], sy.base[1]);
            if d >= d_base {
                return;
            }
            for (a, b) in [(sx, sy), (sy, sx)] {
                if a.owner[0] == NONE || d >= a.clearance {
                    continue;
                }
                if a.lp == b.lp {
                    let total = loop_len[a.lp as usize];
                    let delta = (a.arc - b.arc).abs();
                    let path = delta.min(total - delta);
                    if path < path_ratio * (d + a.clearance) {
                        continue;
                    }
                }
                freeze(a.lp, a.owner);
            }
        });
    }

    /// Creates the planned nodes and cells, breaks short neighbour edges, and replaces the
    /// fronts by the new ones. Returns the number of merges.
    fn build(&mut self, step: u32, plans: &[Plan]) -> usize {
        let mut merges = 0;
        let old_loops = std::mem::take(&mut self.loops);
        let mut new_loops = Vec::with_capacity(old_loops.len());
        for (li, (lp, plan)) in old_loops.iter().zip(plans).enumerate() {
            let m = lp.items.len();
            // global ids of the children
            let mut child_ids = vec![NONE; plan.pos.len()];
            for v in 0..m {
                let g = lp.items[v];
                for c in plan.children(v) {
                    child_ids[c] = self.pos.len() as u32;
                    self.pos.push(plan.pos[c]);
                    self.layer.push(step);
                    self.parent.push(g);
                    self.parent2.push(NONE);
                    self.left.push(NONE);
                    self.right.push(NONE);
                    self.ideal.push(plan.ideal[c]);
                    self.share.push(match lp.law {
                        Law::Geometric { growth, .. } => 1.0 / growth,
                        Law::Isotropic { .. } => 1.0,
                    });
                    self.offset.push(plan.offset[c]);
                    self.alive.push(true);
                }
            }
            // cells: quads over active edges, fan triangles
            let mut edge_cell = vec![NONE; m];
            for i in 0..m {
                let j = (i + 1) % m;
                if !(lp.edges[i].active && plan.advancing[i] && plan.advancing[j]) {
                    continue;
                }
                let (a, b) = (lp.items[i], lp.items[j]);
                let ca = child_ids[plan.children(i).end - 1];
                let cb = child_ids[plan.children(j).start];
                edge_cell[i] = self.cells.len() as u32;
                self.cells.push(Cell {
                    nodes: [a, b, cb, ca],
                    len: 4,
                    layer: self.layer[a as usize],
                    pipe: lp.edges[i].pipe,
                    origin: [li as u32, i as u32, NONE],
                });
            }
            let mut fan_cells: Vec<u32> = vec![NONE; plan.pos.len()];
            for v in 0..m {
                let r = plan.children(v);
                if r.len() < 2 {
                    continue;
                }
                let ein = lp.edges[(v + m - 1) % m];
                let eout = lp.edges[v];
                let pieces = r.len() - 1;
                for (k, c) in (r.start..r.end - 1).enumerate() {
                    let mut pipe = if 2 * k < pieces { ein.pipe } else { eout.pipe };
                    if pipe == NONE {
                        pipe = if ein.pipe != NONE {
                            ein.pipe
                        } else {
                            eout.pipe
                        };
                    }
                    fan_cells[c] = self.cells.len() as u32;
                    let g = lp.items[v];
                    self.cells.push(Cell {
                        nodes: [g, child_ids[c + 1], child_ids[c], NONE],
                        len: 3,
                        layer: self.layer[g as usize],
                        pipe,
                        origin: [li as u32, ((v + m - 1) % m) as u32, v as u32],
                    });
                }
            }
            // the new front
            let mut items: Vec<u32> = Vec::with_capacity(m + plan.pos.len());
            let mut edges: Vec<FEdge> = Vec::with_capacity(m + plan.pos.len());
            for v in 0..m {
                let g = lp.items[v];
                let ein = lp.edges[(v + m - 1) % m];
                let eout = lp.edges[v];
                if !plan.advancing[v] {
                    items.push(g);
                    edges.push(FEdge {
                        active: false,
                        ..eout
                    });
                    continue;
                }
                let r = plan.children(v);
                let in_cell = edge_cell[(v + m - 1) % m];
                let out_cell = edge_cell[v];
                if in_cell == NONE {
                    // step up from the old node to its first child
                    items.push(g);
                    edges.push(FEdge {
                        active: false,
                        pipe: NONE,
                        cell: if out_cell != NONE {
                            out_cell
                        } else {
                            fan_cells[r.start]
                        },
                    });
                }
                let _ = ein;
                for c in r.start..r.end {
                    items.push(child_ids[c]);
                    if c + 1 < r.end {
                        let cell = fan_cells[c];
                        edges.push(FEdge {
                            active: true,
                            pipe: self.cells[cell as usize].pipe,
                            cell,
                        });
                    }
                }
                if out_cell == NONE {
                    // step down from the last child back to the old node
                    edges.push(FEdge {
                        active: false,
                        pipe: NONE,
                        cell: if in_cell != NONE {
                            in_cell
                        } else {
                            fan_cells[r.end - 2]
                        },
                    });
                    items.push(g);
                    edges.push(FEdge {
                        active: false,
                        ..eout
                    });
                } else {
                    edges.push(FEdge {
                        active: true,
                        pipe: eout.pipe,
                        cell: out_cell,
                    });
                }
            }
            debug_assert_eq!(items.len(), edges.len());
            merges += self.break_short_edges(&mut items, &mut edges);
            // layer neighbours of the new nodes
            let k = items.len();
            let first_new = self.node_step[step as usize] as u32;
            for i in 0..k {
                let g = items[i];
                if g < first_new {
                    continue;
                }
                let (prev, next) = (items[(i + k - 1) % k], items[(i + 1) % k]);
                if prev >= first_new && edges[(i + k - 1) % k].active {
                    self.left[g as usize] = prev;
                }
                if next >= first_new && edges[i].active {
                    self.right[g as usize] = next;
                }
            }
            new_loops.push(Loop {
                items,
                edges,
                law: lp.law,
            });
        }
        self.loops = new_loops;
        merges
    }

    /// Coe_shrink: merges the two nodes of new active edges that are too short for their
    /// extrusion edges, never two neighbouring edges in one step.
    fn break_short_edges(&mut self, items: &mut Vec<u32>, edges: &mut Vec<FEdge>) -> usize {
        let k = items.len();
        let first_new = *self.node_step.last().expect("a step is open") as u32;
        if self.node_step.len() <= 2 {
            // the first layer stays whole: its height is the one thing the wall resolution
            // needs exactly
            return 0;
        }
        let coe = self.params.coe_shrink;
        let mut chosen: Vec<usize> = Vec::new();
        let mut taken = vec![false; k];
        for i in 0..k {
            let (x, y) = (items[i], items[(i + 1) % k]);
            if !edges[i].active || x < first_new || y < first_new || x == y {
                continue;
            }
            let (xu, yu) = (x as usize, y as usize);
            let ext = 0.5 * (self.ideal[xu] + self.ideal[yu]);
            if dist(self.pos[xu], self.pos[yu]) >= coe * ext {
                continue;
            }
            let prev = (i + k - 1) % k;
            let next = (i + 1) % k;
            if taken[prev] || taken[next] || k < 4 {
                continue;
            }
            taken[i] = true;
            chosen.push(i);
        }
        let cell_start = *self.cell_step.last().expect("a step is open");
        let mut remove_item = vec![false; k];
        let mut remove_edge = vec![false; k];
        for &i in &chosen {
            let j = (i + 1) % k;
            let (x, y) = (items[i] as usize, items[j] as usize);
            self.pos[x] = [
                0.5 * (self.pos[x][0] + self.pos[y][0]),
                0.5 * (self.pos[x][1] + self.pos[y][1]),
            ];
            self.ideal[x] = 0.5 * (self.ideal[x] + self.ideal[y]);
            if self.parent[y] != self.parent[x] {
                self.parent2[x] = self.parent[y];
            }
            self.offset[x] = 0.0;
            self.alive[y] = false;
            // the cells touching y are those of the two edges at y
            for c in [edges[i].cell, edges[j].cell] {
                if c == NONE || (c as usize) < cell_start {
                    continue;
                }
                let cell = &mut self.cells[c as usize];
                for n in cell.nodes.iter_mut().take(cell.len as usize) {
                    if *n == y as u32 {
                        *n = x as u32;
                    }
                }
                compress(cell);
            }
            remove_item[j] = true;
            remove_edge[i] = true;
        }
        let wraps = remove_item[0];
        let mut it = remove_item.iter();
        items.retain(|_| !*it.next().expect("one flag per item"));
        let mut it = remove_edge.iter();
        edges.retain(|_| !*it.next().expect("one flag per edge"));
        if wraps {
            // the first item went: edge 0 (y → a) now starts at x, at the end of the loop
            edges.rotate_left(1);
        }
        chosen.len()
    }

    /// Balances the springs of the top layers; returns the saved positions of the older
    /// nodes that moved (for undo) and the solver outcome.
    fn solve(
        &mut self,
        step: u32,
        mode: Mode,
    ) -> Result<(Vec<(u32, P2)>, springfield::SolveOutcome), springfield::SpringError> {
        let new_start = self.node_step[step as usize];
        let depth = match mode {
            Mode::Full => self.params.moving_layers.min(step),
            _ => 1,
        };
        // the first layer is pinned once made (its height must stay the first height)
        let range_start = self.node_step[(step + 1 - depth).max(step.min(2)) as usize];
        let n = self.pos.len();
        // nodes on the fronts that are not new are fixed (they bound frozen parts)
        let mut fixed_front = vec![false; n - range_start];
        for l in &self.loops {
            for &g in &l.items {
                if (g as usize) >= range_start && (g as usize) < new_start {
                    fixed_front[g as usize - range_start] = true;
                }
            }
        }
        // moving: alive nodes of the top `depth` layers that are ancestors of new nodes
        let mut moving = vec![false; n - range_start];
        for g in (range_start..n).rev() {
            if !self.alive[g] {
                continue;
            }
            let is_new = g >= new_start;
            if is_new || moving[g - range_start] {
                if !is_new && fixed_front[g - range_start] {
                    moving[g - range_start] = false;
                    continue;
                }
                moving[g - range_start] = true;
                for p in [self.parent[g], self.parent2[g]] {
                    if p != NONE
                        && (p as usize) >= range_start
                        && !fixed_front[p as usize - range_start]
                    {
                        moving[p as usize - range_start] = true;
                    }
                }
            }
        }
        let is_moving = |g: u32| (g as usize) >= range_start && moving[g as usize - range_start];
        // local numbering
        if self.local_of.len() < n {
            self.local_of.resize(n, NONE);
        }
        let mut local_nodes: Vec<u32> = Vec::new();
        let mut movable: Vec<bool> = Vec::new();
        for g in range_start..n {
            if moving[g - range_start] {
                self.local_of[g] = local_nodes.len() as u32;
                local_nodes.push(g as u32);
                movable.push(true);
            }
        }
        let mut springs = std::mem::take(&mut self.springs);
        springs.clear();
        {
            let local_of = &mut self.local_of;
            let mut loc = |g: u32| -> u32 {
                let l = local_of[g as usize];
                if l != NONE {
                    return l;
                }
                let l = local_nodes.len() as u32;
                local_of[g as usize] = l;
                local_nodes.push(g);
                movable.push(false);
                l
            };
            for g in range_start..n {
                if !self.alive[g] {
                    continue;
                }
                let gu = g as u32;
                let me_moving = is_moving(gu);
                for p in [self.parent[g], self.parent2[g]] {
                    if p == NONE || !(me_moving || is_moving(p)) {
                        continue;
                    }
                    springs.extrusion.push(ExtrusionSpring {
                        lower: loc(p),
                        upper: loc(gu),
                        ideal_length: self.ideal[g],
                        lower_share: self.share[g],
                    });
                    let (a, b) = (self.left[p as usize], self.right[p as usize]);
                    if a != NONE && b != NONE {
                        springs.angle.push(AngleSpring {
                            left: loc(a),
                            centre: loc(p),
                            right: loc(b),
                            child: loc(gu),
                            offset_rad: if self.parent2[g] == NONE {
                                self.offset[g]
                            } else {
                                0.0
                            },
                            ideal_length: self.ideal[g],
                        });
                    }
                }
                if me_moving {
                    let (a, b, p) = (self.left[g], self.right[g], self.parent[g]);
                    if a != NONE && b != NONE && p != NONE {
                        let left_share = parent_share(&self.pos, &self.parent, a, p, b);
                        springs.neighbour.push(NeighbourSpring {
                            left: loc(a),
                            centre: loc(gu),
                            right: loc(b),
                            parent: loc(p),
                            left_share,
                        });
                    }
                }
            }
        }
        let mut x: Vec<P2> = local_nodes.iter().map(|&g| self.pos[g as usize]).collect();
        let scale: Vec<f64> = local_nodes
            .iter()
            .zip(&movable)
            .map(|(&g, &m)| if m { self.ideal[g as usize] } else { 1.0 })
            .collect();
        let params = self.params.springs;
        let influence = springs.influence(x.len());
        let index = springs.index(x.len());
        let outcome = springfield::solve_active(
            &mut x,
            &scale,
            &movable,
            &influence,
            &self.params.solver,
            |p, active, f, s| assemble_2d_active(&springs, &index, &params, p, active, f, s),
        )?;
        let mut saved = Vec::new();
        for (l, &g) in local_nodes.iter().enumerate() {
            if movable[l] {
                if (g as usize) < new_start {
                    saved.push((g, self.pos[g as usize]));
                }
                self.pos[g as usize] = x[l];
            }
            self.local_of[g as usize] = NONE;
        }
        self.springs = springs;
        Ok((saved, outcome))
    }

    /// Checks the cells that may have moved and the new front edges. Returns the front edges
    /// (loop, edge of the old front) to freeze, and whether an old cell failed.
    fn verify(&self, step: u32, mode: Mode) -> (Vec<(u32, u32)>, bool) {
        let depth = match mode {
            Mode::Full => self.params.moving_layers.min(step),
            _ => 1,
        };
        let first_cell = self.cell_step[(step + 1 - depth) as usize];
        let new_cell = self.cell_step[step as usize];
        let mut bad: Vec<(u32, u32)> = Vec::new();
        let mut old_bad = false;
        let mark = |c: &Cell, bad: &mut Vec<(u32, u32)>| {
            let [l, e1, e2] = c.origin;
            bad.push((l, e1));
            if e2 != NONE {
                bad.push((l, e2));
            }
        };
        for ci in first_cell..self.cells.len() {
            let c = &self.cells[ci];
            if c.len == 0 {
                continue;
            }
            // a cell above the first layer must also cut into triangles with no angle of
            // `cell_max_angle_deg` or more (else a new cell's edge freezes and the fill
            // takes over; an old one makes the step retry with fewer moving layers)
            let shape_ok =
                c.layer == 0 || self.cell_cut_angle_deg(c) < self.params.cell_max_angle_deg;
            if self.cell_ok(c) && shape_ok {
                continue;
            }
            if ci >= new_cell {
                mark(c, &mut bad);
            } else {
                old_bad = true;
            }
        }
        // new front edges must not touch other front edges
        let new_node = self.node_step[step as usize] as u32;
        let mut segs: Vec<(u32, u32, u32, u32)> = Vec::new(); // (a, b, loop, edge)
        let mut boxes = Vec::new();
        for (li, l) in self.loops.iter().enumerate() {
            let k = l.items.len();
            for i in 0..k {
                let (a, b) = (l.items[i], l.items[(i + 1) % k]);
                segs.push((a, b, li as u32, i as u32));
                boxes.push(Aabb::of_segment(
                    self.pos[a as usize],
                    self.pos[b as usize],
                    0.0,
                ));
            }
        }
        for_each_overlapping_pair(&boxes, |x, y| {
            let (sx, sy) = (segs[x], segs[y]);
            let x_new = sx.0 >= new_node || sx.1 >= new_node;
            let y_new = sy.0 >= new_node || sy.1 >= new_node;
            if !(x_new || y_new) {
                return;
            }
            let shared = [sx.0, sx.1]
                .iter()
                .filter(|n| **n == sy.0 || **n == sy.1)
                .count();
            let (pa, pb, pc, pd) = (
                self.pos[sx.0 as usize],
                self.pos[sx.1 as usize],
                self.pos[sy.0 as usize],
                self.pos[sy.1 as usize],
            );
            let hit = match shared {
                0 => segments_meet(pa, pb, pc, pd),
                1 => {
                    // consecutive edges: they may only meet at the shared node
                    let (s, ox, oy) = if sx.0 == sy.0 {
                        (pa, pb, pd)
                    } else if sx.0 == sy.1 {
                        (pa, pb, pc)
                    } else if sx.1 == sy.0 {
                        (pb, pa, pd)
                    } else {
                        (pb, pa, pc)
                    };
                    orient2d(s, ox, oy) == 0.0
                        && dot([ox[0] - s[0], ox[1] - s[1]], [oy[0] - s[0], oy[1] - s[1]]) > 0.0
                }
                _ => true,
            };
            if !hit {
                return;
            }
            for (s, is_new) in [(sx, x_new), (sy, y_new)] {
                if !is_new {
                    continue;
                }
                let cell = self.loops[s.2 as usize].edges[s.3 as usize].cell;
                if cell != NONE && (cell as usize) >= new_cell {
                    mark(&self.cells[cell as usize], &mut bad);
                }
            }
        });
        (bad, old_bad)
    }

    /// The largest angle of the triangles of a cell, a quad being cut along its shorter
    /// diagonal.
    fn cell_cut_angle_deg(&self, c: &Cell) -> f64 {
        let p = |i: usize| self.pos[c.nodes[i] as usize];
        let tri = crate::quality::max_triangle_angle_deg;
        if c.len == 3 {
            return tri(p(0), p(1), p(2));
        }
        if dist(p(0), p(2)) <= dist(p(1), p(3)) {
            tri(p(0), p(1), p(2)).max(tri(p(0), p(2), p(3)))
        } else {
            tri(p(0), p(1), p(3)).max(tri(p(1), p(2), p(3)))
        }
    }

    /// A cell is acceptable when every corner turns left by a relatively non-negligible
    /// angle (convex, positive).
    fn cell_ok(&self, c: &Cell) -> bool {
        let k = c.len as usize;
        let nodes = c.corners();
        (0..k).all(|i| {
            let a = self.pos[nodes[(i + k - 1) % k] as usize];
            let b = self.pos[nodes[i] as usize];
            let d = self.pos[nodes[(i + 1) % k] as usize];
            let o = orient2d(a, b, d);
            o > 1e-9 * dist(a, b) * dist(b, d)
        })
    }
}

/// The share of |AK| + |KB| that |AK| should take for the neighbour spring of K (parent
/// P): the share of the parents' spacing |A'P| / (|A'P| + |PB'|), so that a wall's
/// graded spacing carries up the layers; ½ where a neighbour shares K's parent (fan
/// children) or has none. Clamped to [0.2, 0.8].
fn parent_share(pos: &[P2], parent: &[u32], a: u32, p: u32, b: u32) -> f64 {
    let (pa, pb) = (parent[a as usize], parent[b as usize]);
    if pa == NONE || pb == NONE || pa == p || pb == p {
        return 0.5;
    }
    let pp = pos[p as usize];
    let (la, lb) = (dist(pos[pa as usize], pp), dist(pp, pos[pb as usize]));
    if la + lb <= 0.0 {
        return 0.5;
    }
    (la / (la + lb)).clamp(0.2, 0.8)
}

/// Removes repeated corners of a cell after a merge; a cell left with fewer than three
/// corners is deleted (`len` = 0).
fn compress(cell: &mut Cell) {
    let k = cell.len as usize;
    let mut out = [NONE; 4];
    let mut n = 0;
    for i in 0..k {
        let v = cell.nodes[i];
        if n > 0 && out[n - 1] == v {
            continue;
        }
        out[n] = v;
        n += 1;
    }
    while n > 1 && out[n - 1] == out[0] {
        n -= 1;
    }
    cell.nodes = out;
    cell.len = if n >= 3 { n as u8 } else { 0 };
}

/// Freezes isolated active edges (runs of one between frozen edges): a lone pipe would grow
/// a column into the region being closed.
fn min_runs(loops: &mut [Loop]) {
    for l in loops {
        let k = l.edges.len();
        if l.edges.iter().all(|e| e.active) {
            continue;
        }
        let lone: Vec<usize> = (0..k)
            .filter(|&i| {
                l.edges[i].active
                    && !l.edges[(i + k - 1) % k].active
                    && !l.edges[(i + 1) % k].active
            })
            .collect();
        for i in lone {
            l.edges[i].active = false;
        }
    }
}
