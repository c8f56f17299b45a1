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
//!    fronts (another loop, or its own loop far away along the front, measured on the current
//!    front and on the planned one: the two sides of a concave corner are near along the
//!    planned front, where their children meet) freezes its edge;
//! 3. build: nodes and cells are created, new neighbour edges shorter than Coe_shrink times
//!    their extrusion edges break (their nodes merge, the quad below becomes a triangle);
//! 4. solve: the springs of the top layers are balanced (`springfield`);
//! 5. verify: every cell that moved must stay convex and positive, and no new front edge may
//!    touch another front edge; otherwise the step is undone, the offending edges are frozen
//!    and the step is redone with fewer moving layers (finally with no solve at all).
//!
//! With more than one thread, steps 1 and 2 of the next layer, which read only the fronts and
//! the nodes, are made beside step 5 (and dropped when it fails).
//!
//! Invariant after each step: all cells are positive and the fronts are disjoint simple
//! loops, so the cells cover exactly the region between the boundary and the fronts.
//!
//! It does not fill the region left between the fronts (`fill`), nor build the output mesh.

use mesh_model::NONE;
use springfield::{
    AngleSpring, ExtrusionSpring, LocalProblem, NeighbourSpring, SpringField2d, SpringSet2d, Undo,
    bisector, left_normal,
};

use geom_predicates::vector::{cross2, dist, dot};
use geom_predicates::{orient2d, segment_distance};

use crate::contact::front_edges_meet;
use crate::geom::{Aabb, P2, Strips, par_overlapping_strips_in};
use crate::input::AfsfParams;
use crate::nodes::{NodeStore, PARALLEL_SHARES_MIN};

/// Cells from which `verify` tests them on every thread: below, a fork-join costs more than
/// it saves (a cell's test takes some 50 ns).
const PARALLEL_MIN_CELLS: usize = 8192;

/// Cells per task of `verify`'s parallel test.
const VERIFY_CHUNK: usize = 4096;

/// Loop nodes from which the plan finds their directions on every thread.
const PARALLEL_MIN_NODES: usize = 8192;

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

/// A starting front: its nodes, the boundary facet under each of its edges, its law.
pub(crate) type StartFront = (Vec<u32>, Vec<u32>, Law);

/// A front edge: (node a, node b, loop, edge index).
pub(crate) type FrontSeg = (u32, u32, u32, u32);

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
    /// Planning children and the closing test (with more than one thread, only the first
    /// layer's: the others are made beside the verification, in its time).
    pub plan_and_closing: f64,
    /// Building nodes, cells, merges and the new fronts.
    pub build: f64,
    /// Spring solves.
    pub solve: f64,
    /// Verification of the cells and fronts (with more than one thread, and the next layer's
    /// plan and closing made beside it).
    pub verify: f64,
    /// Filling the region left between the fronts.
    pub fill: f64,
    /// The whole run.
    pub total: f64,
}

/// The growing mesh.
pub(crate) struct Work<'p> {
    pub params: &'p AfsfParams,
    pub nodes: NodeStore,
    pub n_boundary: usize,
    pub cells: Vec<Cell>,
    /// First node and first cell of each step (index = layer of the step's nodes).
    pub node_step: Vec<usize>,
    pub cell_step: Vec<usize>,
    pub loops: Vec<Loop>,
    pub layer_stats: Vec<LayerStats>,
    pub timings: Timings,
    springs: SpringSet2d,
    problem: LocalProblem<2>,
    buffers: StepBuffers,
    /// The buffers of the next step's closing made beside a verification.
    ahead_buffers: StepBuffers,
}

/// A loop's children from which its cells are made beside its nodes (on two threads when
/// there are two): below, the fork costs more than it saves.
const PARALLEL_BUILD_MIN: usize = 4096;

/// What the closing and front tests build again at every layer step, kept so that each step
/// reuses the memory of the last: fresh buffers each step touched fresh pages (at 1M cells
/// the closing's segments and strips were a third of the run's page faults).
#[derive(Default)]
struct StepBuffers {
    segs: Vec<Seg>,
    boxes: Vec<Aabb>,
    strips: Strips,
}

/// The directions planned from one front node, each with its fan offset: none (the node
/// cannot advance), one along its bisector or its one normal (offset 0: no allocation for
/// nearly every node), or a fan at an outward corner.
enum Dirs {
    None,
    One([(P2, f64); 1]),
    Fan(Vec<(P2, f64)>),
}

impl Dirs {
    /// Each direction with its fan offset.
    fn each(&self) -> &[(P2, f64)] {
        match self {
            Dirs::None => &[],
            Dirs::One(one) => one,
            Dirs::Fan(fan) => fan,
        }
    }
}

/// What a verification found: the front edges (loop, edge of the old front) to freeze, and
/// whether an old cell failed.
type Verdict = (Vec<(u32, u32)>, bool);

/// The start of a layer step ([`Work::close`]): each loop's plan, and per loop and edge
/// whether it is frozen.
struct Closed {
    plans: Vec<Plan>,
    frozen: Vec<Vec<bool>>,
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

fn rotate(v: P2, angle: f64) -> P2 {
    let (s, c) = angle.sin_cos();
    [c * v[0] - s * v[1], s * v[0] + c * v[1]]
}

/// A segment of the closing test: a current front edge, or a planned cell side or top.
struct Seg {
    p: P2,
    q: P2,
    /// Where the segment came from (itself for current-front segments): a planned
    /// segment only collides with what it approaches.
    base: [P2; 2],
    ids: [u64; 2],
    lp: u32,
    /// Its place along its loop: on the current front, and on the planned one (where a
    /// concave corner's children meet, the planned front is shorter).
    arc: [f64; 2],
    /// (edge, second edge) to freeze, or NONE for current-front segments.
    owner: [u32; 2],
    clearance: f64,
}

/// The distance along their loop between `a` and `b` (of loop lengths `total`): the shorter
/// way round, on the current front or on the planned one, whichever is less. Measured on the
/// planned front too, the two sides of a concave corner, whose children meet on its bisector,
/// stay near each other however many layers fold round it.
fn path(a: &Seg, b: &Seg, total: [f64; 2]) -> f64 {
    (0..2)
        .map(|k| {
            let delta = (a.arc[k] - b.arc[k]).abs();
            delta.min(total[k] - delta)
        })
        .fold(f64::INFINITY, f64::min)
}

/// Whether segments `a` and `b` are farther apart than `c` on some axis by more than the
/// rounding of [`segment_distance`] (a margin of 1e-6 of `c`): their distance is then
/// surely `c` or more, and the closing test skips it.
#[inline]
fn surely_apart(a: &Seg, b: &Seg, c: f64) -> bool {
    let reach = c * (1.0 + 1e-6);
    (0..2).any(|k| {
        let (a_lo, a_hi) = (a.p[k].min(a.q[k]), a.p[k].max(a.q[k]));
        let (b_lo, b_hi) = (b.p[k].min(b.q[k]), b.p[k].max(b.q[k]));
        b_lo - a_hi > reach || a_lo - b_hi > reach
    })
}

impl<'p> Work<'p> {
    /// Starts from the oriented boundary loops: `fronts[l]` lists node indices into
    /// `points` with the domain on the left; `pipes[l][i]` is the facet under front edge i.
    pub(crate) fn new(params: &'p AfsfParams, points: Vec<P2>, fronts: Vec<StartFront>) -> Self {
        let n = points.len();
        let mut w = Work {
            params,
            nodes: NodeStore::boundary(points),
            n_boundary: n,
            cells: Vec::new(),
            node_step: vec![0],
            cell_step: vec![0],
            loops: Vec::new(),
            layer_stats: Vec::new(),
            timings: Timings::default(),
            springs: SpringSet2d::default(),
            problem: LocalProblem::new(),
            buffers: StepBuffers::default(),
            ahead_buffers: StepBuffers::default(),
        };
        for (items, pipes, law) in fronts {
            let m = items.len();
            for i in 0..m {
                w.nodes.left[items[i] as usize] = items[(i + m - 1) % m];
                w.nodes.right[items[i] as usize] = items[(i + 1) % m];
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
        // the next step's closing, made beside this step's verification
        let mut ahead: Option<Closed> = None;
        for step in 1..=self.params.max_layers {
            if !self.loops.iter().any(|l| l.edges.iter().any(|e| e.active)) {
                break;
            }
            ahead = self.step(step, ahead.take())?;
            // debug builds (and so every test) check the whole front state after each layer
            // and stop on a broken invariant, like a debug_assert; release skips the walk
            if cfg!(debug_assertions) {
                self.sanity_check().unwrap_or_else(|problem| {
                    panic!("afsf2d: the front state after layer {step} is broken: {problem}")
                });
            }
        }
        for l in &mut self.loops {
            l.edges.iter_mut().for_each(|e| e.active = false);
        }
        Ok(())
    }

    /// Lets go of the layer loop's arrays (the node store, the cells, the fronts, the spring
    /// problem and the step buffers: some 150 MB at 1M cells) on another thread when there
    /// is one: allocators hand such large blocks back to the system at once (jemalloc, the
    /// xtask binaries', as glibc's mapped blocks), 9 ms of the 1M-cell run spent alone on the
    /// thread that goes on to the output and the curving.
    pub(crate) fn let_go(self) {
        let Work {
            nodes,
            cells,
            loops,
            springs,
            problem,
            buffers,
            ahead_buffers,
            ..
        } = self;
        let arrays = (
            nodes,
            cells,
            loops,
            springs,
            problem,
            (buffers, ahead_buffers),
        );
        if rayon::current_num_threads() > 1 {
            rayon::spawn(move || drop(arrays));
        }
    }

    /// Every front edge as (first node, second node, the cell it bounds or `NONE`), loop
    /// after loop: the region left to fill is on their left.
    pub(crate) fn front_edges(&self) -> Vec<(u32, u32, u32)> {
        let mut out = Vec::new();
        for l in &self.loops {
            let m = l.items.len();
            out.extend((0..m).map(|i| (l.items[i], l.items[(i + 1) % m], l.edges[i].cell)));
        }
        out
    }

    /// Every front edge with its bounding box.
    pub(crate) fn front_segments(&self) -> (Vec<FrontSeg>, Vec<Aabb>) {
        let mut segs: Vec<FrontSeg> = Vec::new();
        let mut boxes = Vec::new();
        for (li, l) in self.loops.iter().enumerate() {
            let k = l.items.len();
            for i in 0..k {
                let (a, b) = (l.items[i], l.items[(i + 1) % k]);
                segs.push((a, b, li as u32, i as u32));
                boxes.push(Aabb::of_segment(
                    self.nodes.pos[a as usize],
                    self.nodes.pos[b as usize],
                    0.0,
                ));
            }
        }
        (segs, boxes)
    }

    fn ideal_length(&self, law: Law, g: usize) -> f64 {
        match law {
            Law::Geometric { first, growth } => first * growth.powi(self.nodes.layer[g] as i32),
            Law::Isotropic { factor } => {
                let (l, r) = (self.nodes.left[g], self.nodes.right[g]);
                let mut sum = 0.0;
                let mut k = 0.0f64;
                for o in [l, r] {
                    if o != NONE {
                        sum += dist(self.nodes.pos[g], self.nodes.pos[o as usize]);
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
        let dirs_of = |v: usize| {
            if !(lp.edges[(v + m - 1) % m].active || lp.edges[v].active) {
                return Dirs::None;
            }
            let g = lp.items[v] as usize;
            let p = self.nodes.pos[g];
            let n1 = (self.nodes.left[g] != NONE)
                .then(|| left_normal(self.nodes.pos[self.nodes.left[g] as usize], p))
                .flatten();
            let n2 = (self.nodes.right[g] != NONE)
                .then(|| left_normal(p, self.nodes.pos[self.nodes.right[g] as usize]))
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
                        let fan = (0..=pieces).map(|j| {
                            let phi = theta * j as f64 / pieces as f64;
                            (rotate(a, phi), phi - 0.5 * theta)
                        });
                        Dirs::Fan(fan.collect())
                    } else if let Some(d) = bisector(
                        self.nodes.pos[self.nodes.left[g] as usize],
                        p,
                        self.nodes.pos[self.nodes.right[g] as usize],
                    ) {
                        Dirs::One([(d, 0.0)])
                    } else {
                        Dirs::None
                    }
                }
                (Some(a), None) | (None, Some(a)) => Dirs::One([(a, 0.0)]),
                (None, None) => Dirs::None,
            }
        };
        // each node's directions on its own: on every thread for a long loop
        let dirs: Vec<Dirs> = if m >= PARALLEL_MIN_NODES && rayon::current_num_threads() > 1 {
            use rayon::prelude::*;
            (0..m).into_par_iter().map(dirs_of).collect()
        } else {
            (0..m).map(dirs_of).collect()
        };
        let can = |v: usize| !dirs[v].each().is_empty();
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
            let p = self.nodes.pos[g];
            let h = self.ideal_length(lp.law, g);
            for &(d, offset) in dirs[v].each() {
                plan.pos.push([p[0] + h * d[0], p[1] + h * d[1]]);
                plan.ideal.push(h);
                plan.offset.push(offset);
            }
            plan.advancing[v] = true;
        }
        plan.start.push(plan.pos.len() as u32);
        plan
    }

    /// The start of a layer step, which reads only the fronts and the nodes: every loop
    /// planned on ideal positions, and the edges frozen (those already inactive, and those
    /// the closing freezes).
    fn close(&self, buffers: &mut StepBuffers) -> Closed {
        let mut frozen: Vec<Vec<bool>> = self
            .loops
            .iter()
            .map(|l| l.edges.iter().map(|e| !e.active).collect())
            .collect();
        let plans: Vec<Plan> = self.loops.iter().map(|l| self.plan_loop(l)).collect();
        self.closing(&plans, &mut frozen, buffers);
        Closed { plans, frozen }
    }

    /// One layer step, with undo and retry; `ahead`: its start ([`Work::close`]) when it was
    /// made beside the last step's verification. Returns the next step's start when it is
    /// made beside this one's (with more than one thread).
    fn step(
        &mut self,
        step: u32,
        ahead: Option<Closed>,
    ) -> Result<Option<Closed>, springfield::SpringError> {
        let t0 = std::time::Instant::now();
        let mut buffers = std::mem::take(&mut self.buffers);
        let saved_loops = self.loops.clone();
        let initially_frozen: usize = (self.loops.iter())
            .map(|l| l.edges.iter().filter(|e| !e.active).count())
            .sum();
        let Closed { plans, mut frozen } = match ahead {
            Some(closed) => closed,
            None => self.close(&mut buffers),
        };
        // a loop whose active edges the closing (and the runs' rule) leave as they were is
        // planned again as it was: its plan is kept for the build (taken at most once)
        let mut first_plans: Vec<Option<Plan>> = plans.into_iter().map(Some).collect();
        self.timings.plan_and_closing += t0.elapsed().as_secs_f64();
        let mut stats = LayerStats {
            layer: step,
            ..LayerStats::default()
        };
        let mut attempt = 0u32;
        let next;
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
            let node_start = self.nodes.pos.len();
            let cell_start = self.cells.len();
            self.node_step.push(node_start);
            self.cell_step.push(cell_start);
            let plans: Vec<Plan> = (self.loops.iter().zip(&saved_loops))
                .zip(&mut first_plans)
                .map(|((l, before), first)| {
                    let same = l
                        .edges
                        .iter()
                        .zip(&before.edges)
                        .all(|(a, b)| a.active == b.active);
                    match first.take() {
                        Some(plan) if same => plan,
                        _ => self.plan_loop(l),
                    }
                })
                .collect();
            stats.merges = self.build(step, &plans);
            self.timings.build += t1.elapsed().as_secs_f64();
            let t2 = std::time::Instant::now();
            let saved = if mode == Mode::NoSolve {
                stats.iterations = 0;
                stats.converged = true;
                Undo::default()
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
            let ((bad_edges, old_cells_bad), closed) =
                self.verify_and_look_ahead(step, mode, &mut buffers.strips);
            self.timings.verify += t3.elapsed().as_secs_f64();
            if bad_edges.is_empty() && !old_cells_bad {
                stats.cells = self.cells.len() - cell_start;
                next = closed;
                break;
            }
            // undo
            saved.restore(&mut self.nodes.pos);
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
        self.buffers = buffers;
        Ok(next)
    }

    /// [`Work::verify`]; with more than one thread and a step to come, the next step's start
    /// ([`Work::close`], of the fronts and nodes as this attempt leaves them, which a passed
    /// verification keeps) is made beside it, on the spare buffers: the closing's pieces on
    /// one thread fill the verification's gaps and the other way round.
    fn verify_and_look_ahead(
        &mut self,
        step: u32,
        mode: Mode,
        strips: &mut Strips,
    ) -> (Verdict, Option<Closed>) {
        if rayon::current_num_threads() < 2 || step >= self.params.max_layers {
            return (self.verify(step, mode, strips), None);
        }
        let mut spare = std::mem::take(&mut self.ahead_buffers);
        let (verdict, closed) = rayon::join(
            || self.verify(step, mode, strips),
            || self.close(&mut spare),
        );
        self.ahead_buffers = spare;
        (verdict, Some(closed))
    }

    /// The first layer's height is prescribed: after its solve, every first-layer node keeps
    /// the direction the springs gave it and gets exactly its ideal extrusion length.
    fn pin_first_layer(&mut self) {
        let start = self.node_step[1];
        for g in start..self.nodes.pos.len() {
            let p = self.nodes.parent[g];
            if !self.nodes.alive[g] || p == NONE || self.nodes.parent2[g] != NONE {
                continue;
            }
            let (a, b) = (self.nodes.pos[p as usize], self.nodes.pos[g]);
            let l = dist(a, b);
            if l > 0.0 {
                let s = self.nodes.ideal[g] / l;
                self.nodes.pos[g] = [a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1])];
            }
        }
    }

    fn truncate(&mut self, nodes: usize, cells: usize) {
        self.nodes.truncate(nodes);
        self.cells.truncate(cells);
    }

    /// The closing test on the planned (ideal) positions: freezes every active edge whose
    /// planned cell comes nearer than its clearance to a part of the fronts that is not its
    /// neighbourhood along its own loop.
    fn closing(&self, plans: &[Plan], frozen: &mut [Vec<bool>], buffers: &mut StepBuffers) {
        let loop_len = self.closing_segments(plans, &mut buffers.segs);
        let segs = &buffers.segs;
        let boxes = &mut buffers.boxes;
        boxes.clear();
        boxes.extend(segs.iter().map(|s| Aabb::of_segment(s.p, s.q, s.clearance)));
        let path_ratio = 2.5;
        // the pairs are tested on every thread; what they freeze is a set of flags, the same
        // whatever the order (the strips: the fronts of a far-field circle share ranges of x
        // with the far side of the circle, which the sweep would meet)
        let strips = &mut buffers.strips;
        let freezes =
            par_overlapping_strips_in(strips, boxes, |x, y, out: &mut Vec<(u32, [u32; 2])>| {
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
                        || (a.lp == b.lp
                            && path(a, b, loop_len[a.lp as usize]) < path_ratio * a.clearance)
                };
                if never_frozen(sx, sy) && never_frozen(sy, sx) {
                    return;
                }
                let c = sx.clearance.max(sy.clearance);
                if surely_apart(sx, sy, c) {
                    return;
                }
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
                    if a.lp == b.lp
                        && path(a, b, loop_len[a.lp as usize]) < path_ratio * (d + a.clearance)
                    {
                        continue;
                    }
                    out.push((a.lp, a.owner));
                }
            });
        for (li, owner) in freezes {
            for e in owner {
                if e != NONE {
                    frozen[li as usize][e as usize] = true;
                }
            }
        }
    }

    /// The segments of the closing test (current front edges, planned cell sides and tops,
    /// fan edges), into `segs`; returns the length of each loop, current and planned.
    fn closing_segments(&self, plans: &[Plan], segs: &mut Vec<Seg>) -> Vec<[f64; 2]> {
        let factor = self.params.closing_factor;
        // a front edge and the three sides of its planned cell, and a fan's edges
        let capacity = self
            .loops
            .iter()
            .zip(plans)
            .map(|(lp, plan)| 4 * lp.items.len() + plan.pos.len())
            .sum();
        segs.clear();
        segs.reserve(capacity);
        let mut loop_len = Vec::with_capacity(self.loops.len());
        for (li, (lp, plan)) in self.loops.iter().zip(plans).enumerate() {
            let m = lp.items.len();
            let mut arc = vec![0.0; m + 1];
            for i in 0..m {
                let (a, b) = (lp.items[i] as usize, lp.items[(i + 1) % m] as usize);
                arc[i + 1] = arc[i] + dist(self.nodes.pos[a], self.nodes.pos[b]);
            }
            let (planned, planned_len) = planned_arcs(&self.nodes.pos, lp, plan);
            loop_len.push([arc[m], planned_len]);
            let child_id = |c: usize| ((li as u64 + 1) << 40) | c as u64;
            for i in 0..m {
                let (a, b) = (lp.items[i], lp.items[(i + 1) % m]);
                let (pa, pb) = (self.nodes.pos[a as usize], self.nodes.pos[b as usize]);
                let next_start = if i + 1 < m {
                    planned[i + 1][0]
                } else {
                    planned_len
                };
                let mid = [
                    0.5 * (arc[i] + arc[i + 1]),
                    0.5 * (planned[i][1] + next_start),
                ];
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
                        let pv = self.nodes.pos[lp.items[i] as usize];
                        segs.push(Seg {
                            p: qa,
                            q: qb,
                            base: [pv, pv],
                            ids: [child_id(c), child_id(c + 1)],
                            lp: li as u32,
                            arc: [arc[i], 0.5 * (planned[i][0] + planned[i][1])],
                            owner: [((i + m - 1) % m) as u32, i as u32],
                            clearance: factor * h.max(0.5 * dist(qa, qb)),
                        });
                    }
                }
            }
        }
        loop_len
    }

    /// Creates the planned nodes and cells, breaks short neighbour edges, and replaces the
    /// fronts by the new ones. Returns the number of merges.
    fn build(&mut self, step: u32, plans: &[Plan]) -> usize {
        let mut merges = 0;
        let old_loops = std::mem::take(&mut self.loops);
        let mut new_loops = Vec::with_capacity(old_loops.len());
        for (li, (lp, plan)) in old_loops.iter().zip(plans).enumerate() {
            // the children are numbered in plan order from the store's end, so the cells over
            // them are made beside the nodes (each side grows its own arrays)
            let n0 = self.nodes.len() as u32;
            let child_ids: Vec<u32> = (n0..n0 + plan.pos.len() as u32).collect();
            let layers: Vec<u32> = lp
                .items
                .iter()
                .map(|&g| self.nodes.layer[g as usize])
                .collect();
            let (nodes, cells) = (&mut self.nodes, &mut self.cells);
            let edges = (li, lp, &layers[..]);
            let (edge_cell, fan_cells) = if plan.pos.len() >= PARALLEL_BUILD_MIN {
                rayon::join(
                    || create_children(nodes, step, lp, plan),
                    || create_cells(cells, edges, plan, &child_ids),
                )
                .1
            } else {
                create_children(nodes, step, lp, plan);
                create_cells(cells, edges, plan, &child_ids)
            };
            debug_assert_eq!(self.nodes.len(), (n0 as usize) + plan.pos.len());
            let (mut items, mut edges) =
                self.new_front(lp, plan, &child_ids, &edge_cell, &fan_cells);
            debug_assert_eq!(items.len(), edges.len());
            merges += self.break_short_edges(&mut items, &mut edges);
            self.link_layer(step, &items, &edges);
            new_loops.push(Loop {
                items,
                edges,
                law: lp.law,
            });
        }
        self.loops = new_loops;
        merges
    }

    /// The new front of one loop: the children where the loop advanced (with steps up and
    /// down at the ends of an advancing run), the old nodes elsewhere.
    fn new_front(
        &self,
        lp: &Loop,
        plan: &Plan,
        child_ids: &[u32],
        edge_cell: &[u32],
        fan_cells: &[u32],
    ) -> (Vec<u32>, Vec<FEdge>) {
        let m = lp.items.len();
        // the new front
        let mut items: Vec<u32> = Vec::with_capacity(m + plan.pos.len());
        let mut edges: Vec<FEdge> = Vec::with_capacity(m + plan.pos.len());
        for v in 0..m {
            let g = lp.items[v];
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
        (items, edges)
    }

    /// The layer neighbours of the new nodes of a new front.
    fn link_layer(&mut self, step: u32, items: &[u32], edges: &[FEdge]) {
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
                self.nodes.left[g as usize] = prev;
            }
            if next >= first_new && edges[i].active {
                self.nodes.right[g as usize] = next;
            }
        }
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
            let ext = 0.5 * (self.nodes.ideal[xu] + self.nodes.ideal[yu]);
            if dist(self.nodes.pos[xu], self.nodes.pos[yu]) >= coe * ext {
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
            self.nodes.pos[x] = [
                0.5 * (self.nodes.pos[x][0] + self.nodes.pos[y][0]),
                0.5 * (self.nodes.pos[x][1] + self.nodes.pos[y][1]),
            ];
            self.nodes.ideal[x] = 0.5 * (self.nodes.ideal[x] + self.nodes.ideal[y]);
            if self.nodes.parent[y] != self.nodes.parent[x] {
                self.nodes.parent2[x] = self.nodes.parent[y];
            }
            self.nodes.offset[x] = 0.0;
            self.nodes.alive[y] = false;
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

    /// Balances the springs of the top layers; returns the undo of the older nodes that
    /// moved and the solver outcome.
    fn solve(
        &mut self,
        step: u32,
        mode: Mode,
    ) -> Result<(Undo<2>, springfield::SolveOutcome), springfield::SpringError> {
        let new_start = self.node_step[step as usize];
        let depth = match mode {
            Mode::Full => self.params.moving_layers.min(step),
            _ => 1,
        };
        // the first layer is pinned once made (its height must stay the first height)
        let range_start = self.node_step[(step + 1 - depth).max(step.min(2)) as usize];
        let n = self.nodes.pos.len();
        // nodes on the fronts that are not new are fixed (they bound frozen parts)
        let mut fixed_front = vec![false; n - range_start];
        for l in &self.loops {
            for &g in &l.items {
                if (g as usize) >= range_start && (g as usize) < new_start {
                    fixed_front[g as usize - range_start] = true;
                }
            }
        }
        let mut problem = std::mem::take(&mut self.problem);
        // the neighbour springs' shares (scattered reads of the node store) are found on the
        // other thread while the problem's nodes are chosen, in a large window
        let nodes = &self.nodes;
        let select = |problem: &mut LocalProblem<2>| {
            problem.select_layered(
                n,
                range_start,
                new_start,
                &fixed_front,
                |g| nodes.alive[g],
                |g| nodes.parents(g),
            )
        };
        let shares = if n - range_start >= PARALLEL_SHARES_MIN && rayon::current_num_threads() > 1 {
            rayon::join(
                || select(&mut problem),
                || nodes.neighbour_shares(range_start..n),
            )
            .1
        } else {
            select(&mut problem);
            nodes.neighbour_shares(range_start..n)
        };
        let mut springs = std::mem::take(&mut self.springs);
        springs.clear();
        for g in range_start..n {
            if self.nodes.alive[g] {
                let share = shares[g - range_start];
                self.springs_of(g as u32, share, &mut problem, &mut springs);
            }
        }
        // the springs' index is made beside the solver's set-up
        let (set, n_local) = (&springs, problem.len());
        let (spring_params, ideal) = (&self.params.springs, &self.nodes.ideal);
        let result = problem.solve_making(
            &mut self.nodes.pos,
            new_start,
            |g| ideal[g as usize],
            || SpringField2d::new(set, spring_params, n_local),
            &self.params.solver,
        );
        self.springs = springs;
        self.problem = problem;
        result
    }

    /// Adds the springs of alive node `g` to the problem: its extrusion and angle springs
    /// (one per parent) when it or that parent moves, its neighbour spring (whose left share
    /// is `left_share`, see [`NodeStore::neighbour_shares`]) when it moves.
    fn springs_of(
        &self,
        gu: u32,
        left_share: f64,
        problem: &mut LocalProblem<2>,
        springs: &mut SpringSet2d,
    ) {
        let g = gu as usize;
        let me_moving = problem.is_moving(gu);
        for p in [self.nodes.parent[g], self.nodes.parent2[g]] {
            if p == NONE || !(me_moving || problem.is_moving(p)) {
                continue;
            }
            springs.extrusion.push(ExtrusionSpring {
                lower: problem.local(p),
                upper: problem.local(gu),
                ideal_length: self.nodes.ideal[g],
                lower_share: self.nodes.share[g],
            });
            let (a, b) = (self.nodes.left[p as usize], self.nodes.right[p as usize]);
            if a != NONE && b != NONE {
                springs.angle.push(AngleSpring {
                    left: problem.local(a),
                    centre: problem.local(p),
                    right: problem.local(b),
                    child: problem.local(gu),
                    offset_rad: if self.nodes.parent2[g] == NONE {
                        self.nodes.offset[g]
                    } else {
                        0.0
                    },
                    ideal_length: self.nodes.ideal[g],
                });
            }
        }
        if me_moving {
            let (a, b, p) = (
                self.nodes.left[g],
                self.nodes.right[g],
                self.nodes.parent[g],
            );
            if a != NONE && b != NONE && p != NONE {
                springs.neighbour.push(NeighbourSpring {
                    left: problem.local(a),
                    centre: problem.local(gu),
                    right: problem.local(b),
                    parent: problem.local(p),
                    left_share,
                });
            }
        }
    }

    /// Checks the cells that may have moved and the new front edges. Returns the front edges
    /// (loop, edge of the old front) to freeze, and whether an old cell failed.
    fn verify(&self, step: u32, mode: Mode, strips: &mut Strips) -> Verdict {
        let depth = match mode {
            Mode::Full => self.params.moving_layers.min(step),
            _ => 1,
        };
        let first_cell = self.cell_step[(step + 1 - depth) as usize];
        let new_cell = self.cell_step[step as usize];
        let mark = |c: &Cell, bad: &mut Vec<(u32, u32)>| {
            let [l, e1, e2] = c.origin;
            bad.push((l, e1));
            if e2 != NONE {
                bad.push((l, e2));
            }
        };
        let (mut bad, old_bad) = self.failed_cells(first_cell, new_cell, &mark);
        // new front edges must not touch other front edges
        let new_node = self.node_step[step as usize] as u32;
        let (segs, boxes) = self.front_segments();
        // tested on every thread: the edges to freeze are a set, the same in any order
        let hit_cells = par_overlapping_strips_in(strips, &boxes, |x, y, out: &mut Vec<u32>| {
            let (sx, sy) = (segs[x], segs[y]);
            let x_new = sx.0 >= new_node || sx.1 >= new_node;
            let y_new = sy.0 >= new_node || sy.1 >= new_node;
            if !(x_new || y_new) {
                return;
            }
            if !front_edges_meet(&self.nodes.pos, [sx.0, sx.1], [sy.0, sy.1]) {
                return;
            }
            for (s, is_new) in [(sx, x_new), (sy, y_new)] {
                if !is_new {
                    continue;
                }
                let cell = self.loops[s.2 as usize].edges[s.3 as usize].cell;
                if cell != NONE && (cell as usize) >= new_cell {
                    out.push(cell);
                }
            }
        });
        for cell in hit_cells {
            mark(&self.cells[cell as usize], &mut bad);
        }
        (bad, old_bad)
    }

    /// The cells from `first_cell` on that fail (not convex and positive, or, above the first
    /// layer, cut into triangles with an angle of `cell_max_angle_deg` or more): the front
    /// edges of the failing new cells (from `new_cell` on), `mark`ed in cell order, and
    /// whether an old cell failed. A large range is tested in chunks on every thread, the
    /// chunks' edges concatenated in order: the same list whatever the number of threads.
    fn failed_cells(
        &self,
        first_cell: usize,
        new_cell: usize,
        mark: &(impl Fn(&Cell, &mut Vec<(u32, u32)>) + Sync),
    ) -> (Vec<(u32, u32)>, bool) {
        let limit = crate::quality::AngleLimit::new(self.params.cell_max_angle_deg);
        // a cell above the first layer must also cut into triangles with no angle of
        // `cell_max_angle_deg` or more (else a new cell's edge freezes and the fill takes
        // over; an old one makes the step retry with fewer moving layers)
        let test = |range: std::ops::Range<usize>| {
            let (mut bad, mut old_bad) = (Vec::new(), false);
            for ci in range {
                let c = &self.cells[ci];
                if c.len == 0 {
                    continue;
                }
                let shape_ok = c.layer == 0 || self.cell_cut_below(c, limit);
                if self.cell_ok(c) && shape_ok {
                    continue;
                }
                if ci >= new_cell {
                    mark(c, &mut bad);
                } else {
                    old_bad = true;
                }
            }
            (bad, old_bad)
        };
        let end = self.cells.len();
        if rayon::current_num_threads() == 1 || end - first_cell < PARALLEL_MIN_CELLS {
            return test(first_cell..end);
        }
        use rayon::prelude::*;
        let found: Vec<(Vec<(u32, u32)>, bool)> = (first_cell..end)
            .into_par_iter()
            .step_by(VERIFY_CHUNK)
            .map(|start| test(start..(start + VERIFY_CHUNK).min(end)))
            .collect();
        let old_bad = found.iter().any(|f| f.1);
        (found.into_iter().flat_map(|f| f.0).collect(), old_bad)
    }

    /// Whether the largest angle of the triangles of a cell, a quad being cut along its
    /// shorter diagonal, is below `limit`.
    fn cell_cut_below(&self, c: &Cell, limit: crate::quality::AngleLimit) -> bool {
        let p = |i: usize| self.nodes.pos[c.nodes[i] as usize];
        let below = |a, b, c| limit.triangle_below(p(a), p(b), p(c));
        if c.len == 3 {
            return below(0, 1, 2);
        }
        if dist(p(0), p(2)) <= dist(p(1), p(3)) {
            below(0, 1, 2) && below(0, 2, 3)
        } else {
            below(0, 1, 3) && below(1, 2, 3)
        }
    }

    /// A cell is acceptable when every corner turns left by a relatively non-negligible
    /// angle (convex, positive).
    fn cell_ok(&self, c: &Cell) -> bool {
        let k = c.len as usize;
        let nodes = c.corners();
        (0..k).all(|i| {
            let a = self.nodes.pos[nodes[(i + k - 1) % k] as usize];
            let b = self.nodes.pos[nodes[i] as usize];
            let d = self.nodes.pos[nodes[(i + 1) % k] as usize];
            let o = orient2d(a, b, d);
            o > 1e-9 * dist(a, b) * dist(b, d)
        })
    }
}

/// Each node's place along the planned front of loop `lp` (its first and last child, or
/// the node itself where it does not advance), and the planned front's length.
fn planned_arcs(pos: &[P2], lp: &Loop, plan: &Plan) -> (Vec<[f64; 2]>, f64) {
    let m = lp.items.len();
    let mut out = Vec::with_capacity(m);
    let (mut s, mut last): (f64, Option<P2>) = (0.0, None);
    for i in 0..m {
        let r = plan.children(i);
        let own = [pos[lp.items[i] as usize]];
        let points = if r.is_empty() { &own[..] } else { &plan.pos[r] };
        let mut first = 0.0;
        for (k, &q) in points.iter().enumerate() {
            if let Some(l) = last {
                s += dist(l, q);
            }
            if k == 0 {
                first = s;
            }
            last = Some(q);
        }
        out.push([first, s]);
    }
    // the closing edge, from the last node back to the first
    let first_point = match plan.children(0) {
        r if r.is_empty() => pos[lp.items[0] as usize],
        r => plan.pos[r.start],
    };
    if let Some(l) = last {
        s += dist(l, first_point);
    }
    (out, s)
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

/// Adds the planned children of one loop to `nodes`, in plan order.
fn create_children(nodes: &mut NodeStore, step: u32, lp: &Loop, plan: &Plan) {
    let share = match lp.law {
        Law::Geometric { growth, .. } => 1.0 / growth,
        Law::Isotropic { .. } => 1.0,
    };
    let parents = (lp.items.iter().enumerate())
        .flat_map(|(v, &g)| std::iter::repeat_n(g, plan.children(v).len()));
    nodes.push_layer(step, share, (&plan.pos, &plan.ideal, &plan.offset), parents);
}

/// Adds to `cells` the quads over loop `li`'s advancing active edges and the fan
/// triangles (`layers`: those of the loop's nodes; `child_ids`: the children's node ids);
/// returns the cell of each edge and of each fan child (NONE where there is none).
fn create_cells(
    cells: &mut Vec<Cell>,
    (li, lp, layers): (usize, &Loop, &[u32]),
    plan: &Plan,
    child_ids: &[u32],
) -> (Vec<u32>, Vec<u32>) {
    let m = lp.items.len();
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
        edge_cell[i] = cells.len() as u32;
        cells.push(Cell {
            nodes: [a, b, cb, ca],
            len: 4,
            layer: layers[i],
            pipe: lp.edges[i].pipe,
            origin: [li as u32, i as u32, NONE],
        });
    }
    let mut fan_cells: Vec<u32> = vec![NONE; plan.pos.len()];
    for (v, &layer) in layers.iter().enumerate() {
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
            fan_cells[c] = cells.len() as u32;
            let g = lp.items[v];
            cells.push(Cell {
                nodes: [g, child_ids[c + 1], child_ids[c], NONE],
                len: 3,
                layer,
                pipe,
                origin: [li as u32, ((v + m - 1) % m) as u32, v as u32],
            });
        }
    }
    (edge_cell, fan_cells)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Whenever the closing test's axis check skips a pair, the distance it skips is `c` or
    /// more (so skipping it changes nothing), for segments far from the origin and near the
    /// limit; and it skips most pairs clearly apart.
    #[test]
    fn a_pair_surely_apart_is_never_nearer_than_its_clearance() {
        let mut rng = testkit::layered::Rng(21);
        let mut next = || rng.unit();
        let seg = |p: P2, q: P2| Seg {
            p,
            q,
            base: [p, q],
            ids: [0, 0],
            lp: 0,
            arc: [0.0; 2],
            owner: [NONE, NONE],
            clearance: 0.0,
        };
        let (mut skipped, mut apart) = (0, 0);
        for k in 0..200_000 {
            let c = 1e-4 * (1.0 + 100.0 * next());
            let origin = [20.0 * next() - 10.0, 20.0 * next() - 10.0];
            let at = |u: f64, v: f64| [origin[0] + 3.0 * c * u, origin[1] + 3.0 * c * v];
            let a = seg(at(next(), next()), at(next(), next()));
            // a gap near c on one axis half the time
            let shift = if k % 2 == 0 { 1.0 } else { 3.0 * next() };
            let b = seg(
                at(next() + shift + 1.0, next()),
                at(next() + shift + 1.0, next()),
            );
            let d = segment_distance(a.p, a.q, b.p, b.q);
            for (x, y) in [(&a, &b), (&b, &a)] {
                if surely_apart(x, y, c) {
                    skipped += 1;
                    assert!(d >= c, "skipped at {d} < {c}");
                }
            }
            apart += usize::from(d >= 1.01 * c);
        }
        assert!(skipped > apart / 2, "{skipped} skipped of {apart}");
    }
}
