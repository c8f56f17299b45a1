//! The damped explicit pseudo-time solver, generic over the node dimension `D`.
//!
//! Each iteration the caller's assembly fills, for every node, the force F (in length units
//! times stiffness) and the sum S of the stiffnesses of the springs acting on it. A movable
//! node then moves by `ω·F/(S·m)`, clamped to `max_move·scale`: with m = 1 this is a Jacobi
//! step of the linearised spring system, stable for ω < 2 whatever the spring coefficients.
//! The mass schedule is the dissertation's (§2.1, §4.1): constant mass for a first number of
//! iterations, then a node that travels without getting anywhere (oscillates) gets heavier
//! and its travel is reset. Convergence is judged on relative displacement, not on force.

use crate::active::{Active, Influence};
use crate::error::SpringError;
use crate::model::{ForceModel, zero_active};
use crate::params::SolverParams;
use crate::vec::norm;

/// What a solve achieved.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SolveOutcome {
    /// True when the largest relative move fell below the tolerance within the budget.
    pub converged: bool,
    /// Iterations done.
    pub iterations: usize,
    /// Largest move of a node in the last iteration, relative to its scale.
    pub max_relative_step: f64,
    /// Number of nodes whose mass was increased at least once.
    pub heavy_nodes: usize,
}

/// Balances the springs by damped explicit pseudo-time stepping.
///
/// - `positions`: node coordinates, updated in place (fixed nodes are never written);
/// - `scale`: each node's characteristic length (e.g. its ideal extrusion length); moves and
///   the convergence test are relative to it;
/// - `movable`: which nodes may move;
/// - `assemble(positions, force, stiffness)`: adds each spring's force and stiffness into
///   the two arrays, which the solver zeroes before each call.
///
/// Every iteration updates every movable node; [`solve_active`] gives the same balance for
/// much less work when few nodes move.
///
/// Running out of iterations is an outcome (`converged: false`), not an error.
pub fn solve<const D: usize, A>(
    positions: &mut [[f64; D]],
    scale: &[f64],
    movable: &[bool],
    params: &SolverParams,
    mut assemble: A,
) -> Result<SolveOutcome, SpringError>
where
    A: FnMut(&[[f64; D]], &mut [[f64; D]], &mut [f64]),
{
    solve_core(
        positions,
        scale,
        movable,
        None,
        params,
        |p, active: Active<'_>, f: &mut [[f64; D]], s: &mut [f64]| {
            zero_active(active.nodes, f, s);
            assemble(p, f, s);
        },
        &no_axis,
    )
}

/// [`solve()`] with an active set: a node is updated only while it, or a node its force
/// depends on (`influence`), moved by at least `wake_fraction × tolerance` of its scale in
/// the previous iteration; the others are at rest and keep their place. When the active
/// nodes' largest move falls below the tolerance, one full iteration over every movable
/// node decides convergence (the same test as [`solve()`]), and wakes whatever is not yet
/// at rest.
///
/// `assemble(positions, active, force, stiffness)` must add the complete force and
/// stiffness of every active node (it may skip springs that push no active node; the
/// forces of the other nodes are not read, nor zeroed).
pub fn solve_active<const D: usize, A>(
    positions: &mut [[f64; D]],
    scale: &[f64],
    movable: &[bool],
    influence: &Influence,
    params: &SolverParams,
    mut assemble: A,
) -> Result<SolveOutcome, SpringError>
where
    A: FnMut(&[[f64; D]], Active<'_>, &mut [[f64; D]], &mut [f64]),
{
    solve_core(
        positions,
        scale,
        movable,
        Some(Table::Given(influence)),
        params,
        |p, active: Active<'_>, f: &mut [[f64; D]], s: &mut [f64]| {
            zero_active(active.nodes, f, s);
            assemble(p, active, f, s);
        },
        &no_axis,
    )
}

/// [`solve()`] with the forces of a [`ForceModel`].
pub fn solve_model<const D: usize, M: ForceModel<D> + ?Sized>(
    positions: &mut [[f64; D]],
    scale: &[f64],
    movable: &[bool],
    model: &M,
    params: &SolverParams,
) -> Result<SolveOutcome, SpringError> {
    let axis = |i: usize, p: &[[f64; D]]| model.extrusion_axis(i, p);
    solve_core(
        positions,
        scale,
        movable,
        None,
        params,
        |p, active: Active<'_>, f: &mut [[f64; D]], s: &mut [f64]| {
            zero_active(active.nodes, f, s);
            model.assemble(p, f, s);
        },
        &axis,
    )
}

/// [`solve_active()`] with the forces and influence table of a [`ForceModel`]. The first
/// iteration, a sweep over every movable node, needs no influence table: the table is built
/// on another thread of the pool while that iteration's forces are assembled on this one
/// ([`ForceModel::assemble_active_here`]; the same table, the same iterations, whatever the
/// number of threads).
pub fn solve_model_active<const D: usize, M: ForceModel<D> + Sync + ?Sized>(
    positions: &mut [[f64; D]],
    scale: &[f64],
    movable: &[bool],
    model: &M,
    params: &SolverParams,
) -> Result<SolveOutcome, SpringError> {
    let start = Start::new(positions, scale, movable, None, params)?;
    solve_model_active_from(positions, (scale, movable), start, model, params)
}

/// [`solve_model_active()`] from its set-up `start` (of the same positions, scales and
/// movable flags).
pub(crate) fn solve_model_active_from<const D: usize, M: ForceModel<D> + Sync + ?Sized>(
    positions: &mut [[f64; D]],
    (scale, movable): (&[f64], &[bool]),
    start: Start<D>,
    model: &M,
    params: &SolverParams,
) -> Result<SolveOutcome, SpringError> {
    let n = positions.len();
    let influence = std::cell::OnceCell::new();
    let axis = |i: usize, p: &[[f64; D]]| model.extrusion_axis(i, p);
    run(
        positions,
        (scale, movable),
        Some(Table::Lazy(&influence)),
        params,
        start,
        |p, active, f, s| {
            if influence.get().is_some() {
                model.assemble_active_fresh(p, active, f, s);
                return;
            }
            zero_active(active.nodes, f, s);
            // the assembly on this thread, which has just written the springs (they are in its
            // cache), whole: the other thread is busy with the table until about when it ends
            let ((), table) = rayon::join(
                || model.assemble_active_here(p, active, f, s),
                || model.influence(n),
            );
            // (set once: this is the first call)
            let _ = influence.set(table);
        },
        &axis,
    )
}

/// The influence table of an active-set solve: given, or built during the first call of the
/// assembly (which comes before any iteration that reads it).
#[derive(Clone, Copy)]
enum Table<'a> {
    Given(&'a Influence),
    Lazy(&'a std::cell::OnceCell<Influence>),
}

impl Table<'_> {
    fn get(&self) -> Option<&Influence> {
        match *self {
            Table::Given(t) => Some(t),
            Table::Lazy(cell) => cell.get(),
        }
    }
}

/// A node's extrusion axis at the positions ([`ForceModel::extrusion_axis`]).
type Axis<'a, const D: usize> = dyn Fn(usize, &[[f64; D]]) -> Option<[f64; D]> + 'a;

/// No extrusion axes: the solves given only a force closure.
fn no_axis<const D: usize>(_: usize, _: &[[f64; D]]) -> Option<[f64; D]> {
    None
}

fn solve_core<const D: usize, A>(
    positions: &mut [[f64; D]],
    scale: &[f64],
    movable: &[bool],
    influence: Option<Table<'_>>,
    params: &SolverParams,
    assemble: A,
    axis: &Axis<'_, D>,
) -> Result<SolveOutcome, SpringError>
where
    A: FnMut(&[[f64; D]], Active<'_>, &mut [[f64; D]], &mut [f64]),
{
    let given = influence.as_ref().and_then(|t| match t {
        Table::Given(t) => Some(*t),
        Table::Lazy(_) => None,
    });
    let start = Start::new(positions, scale, movable, given, params)?;
    run(
        positions,
        (scale, movable),
        influence,
        params,
        start,
        assemble,
        axis,
    )
}

/// What a solve sets up before its first iteration from the positions, the scales and the
/// movable flags alone (no force is read): the inputs checked, the force and stiffness
/// arrays, the mass schedule, and the first active set (every movable node).
pub(crate) struct Start<const D: usize> {
    force: Vec<[f64; D]>,
    stiffness: Vec<f64>,
    masses: MassSchedule<D>,
    all_movable: Vec<u32>,
    active: Vec<bool>,
    active_nodes: Vec<u32>,
}

impl<const D: usize> Start<D> {
    /// The set-up of a solve of `positions` (`influence`: a given table, whose length is
    /// checked). The force arrays are written (not only allocated zeroed), so that their
    /// pages are touched here, on the thread that makes the set-up.
    pub(crate) fn new(
        positions: &[[f64; D]],
        scale: &[f64],
        movable: &[bool],
        influence: Option<&Influence>,
        params: &SolverParams,
    ) -> Result<Self, SpringError> {
        params.check()?;
        let n = positions.len();
        check_lengths(n, scale, movable, influence)?;
        let all_movable: Vec<u32> = (0..n as u32).filter(|&i| movable[i as usize]).collect();
        let mut force = Vec::with_capacity(n);
        force.resize(n, [0.0; D]);
        let mut stiffness = Vec::with_capacity(n);
        stiffness.resize(n, 0.0);
        Ok(Start {
            force,
            stiffness,
            masses: MassSchedule::new(positions),
            active: movable.to_vec(),
            active_nodes: all_movable.clone(),
            all_movable,
        })
    }
}

/// The iterations of a solve from its set-up `start`.
fn run<const D: usize, A>(
    positions: &mut [[f64; D]],
    (scale, movable): (&[f64], &[bool]),
    influence: Option<Table<'_>>,
    params: &SolverParams,
    start: Start<D>,
    mut assemble: A,
    axis: &Axis<'_, D>,
) -> Result<SolveOutcome, SpringError>
where
    A: FnMut(&[[f64; D]], Active<'_>, &mut [[f64; D]], &mut [f64]),
{
    let Start {
        mut force,
        mut stiffness,
        mut masses,
        all_movable,
        mut active,
        mut active_nodes,
    } = start;
    // nodes that moved by at least the wake threshold in the last iteration
    let mut moved: Vec<u32> = Vec::new();
    let mut selection = Selection::default();
    let mut full_sweep = true;
    let mut outcome = SolveOutcome::default();
    for iteration in 0..params.max_iterations {
        // a full sweep's active list is every movable node, in increasing order
        let in_order = full_sweep;
        // (a lazy table is not built before the first iteration, whose active set, every
        // movable node, is already selected)
        if let Some(influence) = influence.as_ref().and_then(|t| t.get()) {
            let woken = if full_sweep { None } else { Some(&moved[..]) };
            select_active(
                (influence, movable),
                &all_movable,
                woken,
                (&mut active, &mut active_nodes),
                (&mut selection, PARALLEL_SELECT_MIN),
            );
        }
        moved.clear();
        assemble(
            positions,
            Active {
                flags: &active,
                nodes: &active_nodes,
            },
            &mut force,
            &mut stiffness,
        );
        let (max_step, heavy) = step_active(
            positions,
            (&force, &stiffness),
            scale,
            (&active_nodes, in_order),
            (params, axis, iteration),
            &mut masses,
            &mut moved,
        )?;
        outcome.heavy_nodes += heavy;
        outcome.iterations = iteration + 1;
        outcome.max_relative_step = max_step;
        if max_step < params.tolerance {
            if full_sweep || influence.is_none() {
                outcome.converged = true;
                break;
            }
            full_sweep = true;
        } else {
            full_sweep = false;
        }
    }
    Ok(outcome)
}

/// Refuses inputs whose lengths disagree with the positions' (`n`), or a movable node
/// without a finite positive scale.
fn check_lengths(
    n: usize,
    scale: &[f64],
    movable: &[bool],
    influence: Option<&Influence>,
) -> Result<(), SpringError> {
    if let Some(influence) = influence.filter(|i| i.len() != n) {
        return Err(SpringError::LengthMismatch {
            positions: n,
            scales: scale.len(),
            movable: influence.len(),
        });
    }
    if scale.len() != n || movable.len() != n {
        return Err(SpringError::LengthMismatch {
            positions: n,
            scales: scale.len(),
            movable: movable.len(),
        });
    }
    for i in 0..n {
        if movable[i] && !(scale[i].is_finite() && scale[i] > 0.0) {
            return Err(SpringError::BadScale {
                node: i,
                scale: scale[i],
            });
        }
    }
    Ok(())
}

/// Active nodes from which an iteration's moves are made on two threads (each over one range
/// of node numbers): below, the fork costs more than the half it saves.
const PARALLEL_STEP_MIN: usize = 4096;

/// One iteration's moves: each active node steps by its force over its stiffness and mass
/// (clamped), in the order of `active_nodes`; returns the largest step relative to its
/// node's scale and how many nodes became heavy, and lists in `moved` the nodes that stepped
/// past the wake threshold, in the order of `active_nodes`. A node's step reads only its own
/// force, stiffness, mass and position — except through an extrusion axis, which reads the
/// position of the node below — so without a lateral limit (no axes) the moves of a large
/// active set are made on two threads, over two ranges of node numbers: the same moves, the
/// same list.
fn step_active<const D: usize>(
    positions: &mut [[f64; D]],
    (force, stiffness): (&[[f64; D]], &[f64]),
    scale: &[f64],
    (active_nodes, in_order): (&[u32], bool),
    (params, axis, iteration): (&SolverParams, &Axis<'_, D>, usize),
    masses: &mut MassSchedule<D>,
    moved: &mut Vec<u32>,
) -> Result<(f64, usize), SpringError> {
    let wake = params.wake_fraction * params.tolerance;
    let split = params.lateral_max_move.is_none()
        && active_nodes.len() >= PARALLEL_STEP_MIN
        && rayon::current_num_threads() > 1;
    if split {
        let forces = (force, stiffness, scale);
        return step_in_two_ranges(
            positions,
            forces,
            (active_nodes, in_order),
            (params, iteration),
            masses,
            moved,
        );
    }
    let (mut max_step, mut heavy) = (0.0f64, 0);
    for &iu in active_nodes {
        let i = iu as usize;
        let axis = match params.lateral_max_move {
            Some(_) => axis(i, positions),
            None => None,
        };
        let at = NodeStep {
            force: (force[i], stiffness[i]),
            scale: scale[i],
            axis,
        };
        let Some(relative) = at
            .take(&mut positions[i], &mut masses.nodes[i], params, iteration)
            .map_err(|()| SpringError::NonFiniteForce { node: i, iteration })?
        else {
            continue;
        };
        max_step = max_step.max(relative.0);
        if relative.0 >= wake {
            moved.push(iu);
        }
        heavy += usize::from(relative.1);
    }
    Ok((max_step, heavy))
}

/// [`step_active`] on two threads: the nodes below and from the middle node number, each
/// part walking the whole active list for its own nodes; the moved nodes of both parts are
/// then merged in the list's order, and a non-finite force reported at the first such node
/// of the list.
fn step_in_two_ranges<const D: usize>(
    positions: &mut [[f64; D]],
    (force, stiffness, scale): (&[[f64; D]], &[f64], &[f64]),
    (active_nodes, in_order): (&[u32], bool),
    (params, iteration): (&SolverParams, usize),
    masses: &mut MassSchedule<D>,
    moved: &mut Vec<u32>,
) -> Result<(f64, usize), SpringError> {
    let wake = params.wake_fraction * params.tolerance;
    let (n, mid) = (positions.len(), middle_node(active_nodes));
    let (pos_low, pos_high) = positions.split_at_mut(mid);
    let (mass_low, mass_high) = masses.nodes.split_at_mut(mid);
    // a list in increasing order is cut where the high range starts: each part then walks
    // its own nodes only (else each walks the whole list for them)
    let (low_list, high_list) = if in_order {
        let cut = active_nodes.partition_point(|&i| (i as usize) < mid);
        ((0, &active_nodes[..cut]), (cut, &active_nodes[cut..]))
    } else {
        ((0, active_nodes), (0, active_nodes))
    };
    let part = |range: std::ops::Range<usize>,
                (from, list): (usize, &[u32]),
                pos: &mut [[f64; D]],
                mass: &mut [NodeMass<D>]|
     -> RangeSteps {
        let mut out = RangeSteps {
            moved: Vec::with_capacity(list.len() / 2),
            ..RangeSteps::default()
        };
        for (k, &iu) in (from..).zip(list) {
            let i = iu as usize;
            if !range.contains(&i) {
                continue;
            }
            let at = NodeStep {
                force: (force[i], stiffness[i]),
                scale: scale[i],
                axis: None,
            };
            let l = i - range.start;
            match at.take(&mut pos[l], &mut mass[l], params, iteration) {
                Err(()) => {
                    out.failed = Some(k);
                    break;
                }
                Ok(None) => {}
                Ok(Some((relative, heavy))) => {
                    out.max_step = out.max_step.max(relative);
                    if relative >= wake {
                        out.moved.push((k as u32, iu));
                    }
                    out.heavy += usize::from(heavy);
                }
            }
        }
        out
    };
    let (low, high) = rayon::join(
        || part(0..mid, low_list, pos_low, mass_low),
        || part(mid..n, high_list, pos_high, mass_high),
    );
    let failed = match (low.failed, high.failed) {
        (Some(a), Some(b)) => Some(a.min(b)),
        (a, b) => a.or(b),
    };
    if let Some(k) = failed {
        let node = active_nodes[k] as usize;
        return Err(SpringError::NonFiniteForce { node, iteration });
    }
    // both lists are in the active list's order: merge them (one after the other when the
    // active list is in increasing order)
    moved.reserve(low.moved.len() + high.moved.len());
    if in_order {
        moved.extend(low.moved.iter().chain(&high.moved).map(|&(_, node)| node));
        return Ok((low.max_step.max(high.max_step), low.heavy + high.heavy));
    }
    let (mut a, mut b) = (low.moved.iter().peekable(), high.moved.iter().peekable());
    loop {
        let next = match (a.peek(), b.peek()) {
            (Some(x), Some(y)) => {
                if x.0 < y.0 {
                    a.next()
                } else {
                    b.next()
                }
            }
            (Some(_), None) => a.next(),
            (None, Some(_)) => b.next(),
            (None, None) => break,
        };
        moved.extend(next.map(|&(_, node)| node));
    }
    Ok((low.max_step.max(high.max_step), low.heavy + high.heavy))
}

/// A node number that about half the active nodes are below: the median of 33 of them spread
/// through the list (the exact median when the list is sorted and long, as a full sweep's
/// is). Only the balance of the two ranges depends on it, not the moves (nor, in the 2D
/// springs' assembly in halves, the sums).
pub(crate) fn middle_node(active_nodes: &[u32]) -> usize {
    let len = active_nodes.len();
    if len == 0 {
        return 0;
    }
    let mut sample: Vec<u32> = (0..33).map(|k| active_nodes[k * (len - 1) / 32]).collect();
    let (_, &mut median, _) = sample.select_nth_unstable(16);
    median as usize
}

/// What one range of [`step_in_two_ranges`] did: its largest relative step, how many of its
/// nodes became heavy, its moved nodes with their places in the active list, and the place
/// of its first node with a non-finite force (where it stopped).
#[derive(Default)]
struct RangeSteps {
    max_step: f64,
    heavy: usize,
    moved: Vec<(u32, u32)>,
    failed: Option<usize>,
}

/// A node's force and stiffness, scale and extrusion axis, for its move.
struct NodeStep<const D: usize> {
    force: ([f64; D], f64),
    scale: f64,
    axis: Option<[f64; D]>,
}

impl<const D: usize> NodeStep<D> {
    /// Moves the node at `position` (its mass record `mass`): `Err` when the force or the
    /// stiffness is not finite, `None` when it has no stiffness (it stays), else its step
    /// relative to its scale and whether it became heavy for the first time.
    #[inline]
    fn take(
        &self,
        position: &mut [f64; D],
        mass: &mut NodeMass<D>,
        params: &SolverParams,
        iteration: usize,
    ) -> Result<Option<(f64, bool)>, ()> {
        let (f, s) = self.force;
        if !(s.is_finite() && f.iter().all(|c| c.is_finite())) {
            return Err(());
        }
        if s <= 0.0 {
            return Ok(None);
        }
        let (step, len) = clamped_step(&f, s, mass.mass, self.scale, params, self.axis);
        for k in 0..D {
            position[k] += step[k];
        }
        let heavy = mass.record(len, *position, self.scale, iteration, params);
        Ok(Some((len / self.scale, heavy)))
    }
}

/// Moved nodes from which the active set is selected on two threads (see [`select_active`]):
/// below, the fork costs more than the half it saves.
const PARALLEL_SELECT_MIN: usize = 4096;

/// The second thread's flags and list of a selection in two halves, kept through a solve (the
/// flags all false between selections).
#[derive(Default)]
struct Selection {
    seen: Vec<bool>,
    later: Vec<u32>,
}

/// Updates the active set: after a full sweep's failure or at the start every movable node,
/// else (`woken` = the nodes that moved) the nodes that moved and their dependents, in the
/// order first met. With at least `parallel_min` moved nodes and two threads, the second half
/// of them is walked on the other thread with flags of its own; its list, less the nodes the
/// first half met, then follows the first half's: the order first met over the whole list.
fn select_active(
    (influence, movable): (&Influence, &[bool]),
    all_movable: &[u32],
    woken: Option<&[u32]>,
    (active, active_nodes): (&mut [bool], &mut Vec<u32>),
    (selection, parallel_min): (&mut Selection, usize),
) {
    for &i in active_nodes.iter() {
        active[i as usize] = false;
    }
    active_nodes.clear();
    let Some(moved) = woken else {
        active_nodes.extend_from_slice(all_movable);
        for &i in active_nodes.iter() {
            active[i as usize] = true;
        }
        return;
    };
    if moved.len() < parallel_min || rayon::current_num_threads() < 2 {
        wake((influence, movable), moved, active, active_nodes);
        return;
    }
    let (first, second) = moved.split_at(moved.len() / 2);
    let Selection { seen, later } = selection;
    seen.resize(active.len(), false);
    later.clear();
    rayon::join(
        || wake((influence, movable), first, active, active_nodes),
        || wake((influence, movable), second, seen, later),
    );
    for &i in later.iter() {
        seen[i as usize] = false;
        if !active[i as usize] {
            active[i as usize] = true;
            active_nodes.push(i);
        }
    }
}

/// Marks in `marked` and lists, in the order first met, the movable nodes among `moved` and
/// their dependents that are not marked yet.
fn wake(
    (influence, movable): (&Influence, &[bool]),
    moved: &[u32],
    marked: &mut [bool],
    list: &mut Vec<u32>,
) {
    for &j in moved {
        for &i in std::iter::once(&j).chain(influence.dependents(j as usize)) {
            if movable[i as usize] && !marked[i as usize] {
                marked[i as usize] = true;
                list.push(i);
            }
        }
    }
}

/// The damped Jacobi move ω·F/(S·m) of one node, clamped to `max_move × scale`, and its
/// length; with a lateral limit and the node's extrusion `axis`, the parts along and across
/// the axis are clamped separately (`max_move` and `lateral_max_move`).
#[inline]
fn clamped_step<const D: usize>(
    f: &[f64; D],
    s: f64,
    mass: f64,
    scale: f64,
    params: &SolverParams,
    axis: Option<[f64; D]>,
) -> ([f64; D], f64) {
    let mut step: [f64; D] = std::array::from_fn(|k| params.relaxation * f[k] / (s * mass));
    if let (Some(lateral), Some(u)) = (params.lateral_max_move, axis) {
        let along: f64 = (0..D).map(|k| step[k] * u[k]).sum();
        let mut across: [f64; D] = std::array::from_fn(|k| step[k] - along * u[k]);
        let along = along.clamp(-params.max_move * scale, params.max_move * scale);
        let (len, limit) = (norm(&across), lateral * scale);
        if len > limit {
            across.iter_mut().for_each(|x| *x *= limit / len);
        }
        let step: [f64; D] = std::array::from_fn(|k| along * u[k] + across[k]);
        return (step, norm(&step));
    }
    let len = norm(&step);
    let limit = params.max_move * scale;
    if len > limit {
        let c = limit / len;
        step.iter_mut().for_each(|x| *x *= c);
    }
    (step, len.min(limit))
}

/// The mass schedule: each node's mass, the distance it travelled since its anchor, and the
/// anchor (where it was when its travel was last judged).
struct MassSchedule<const D: usize> {
    nodes: Vec<NodeMass<D>>,
}

/// One node's record in the [`MassSchedule`].
#[derive(Clone, Copy)]
struct NodeMass<const D: usize> {
    mass: f64,
    travel: f64,
    anchor: [f64; D],
}

impl<const D: usize> MassSchedule<D> {
    fn new(positions: &[[f64; D]]) -> Self {
        MassSchedule {
            nodes: positions
                .iter()
                .map(|&anchor| NodeMass {
                    mass: 1.0,
                    travel: 0.0,
                    anchor,
                })
                .collect(),
        }
    }
}

impl<const D: usize> NodeMass<D> {
    /// Records a move of length `len` to `position`; once its travel exceeds
    /// `judge_travel × scale`, a node that got less than half as far as it travelled (past
    /// the constant-mass iterations) gets heavier. Returns true when the node became heavy
    /// for the first time.
    #[inline]
    fn record(
        &mut self,
        len: f64,
        position: [f64; D],
        scale: f64,
        iteration: usize,
        params: &SolverParams,
    ) -> bool {
        let mut first_heavy = false;
        self.travel += len;
        if self.travel > params.judge_travel * scale {
            let net = norm(&crate::vec::sub(&position, &self.anchor));
            if iteration >= params.constant_mass_iterations && net < 0.5 * self.travel {
                first_heavy = self.mass == 1.0;
                self.mass *= params.mass_factor;
            }
            self.travel = 0.0;
            self.anchor = position;
        }
        first_heavy
    }
}

#[cfg(test)]
mod tests {

    /// The positions' bits after the steps, each iteration's moved list, and each iteration's
    /// largest relative step (its bits) and new heavy nodes.
    type Stepped = (Vec<u64>, Vec<Vec<u32>>, Vec<(u64, usize)>);

    /// Steps a scrambled active list of 6000 of 9000 nodes for a few iterations, on one thread
    /// and then in two ranges; returns the positions' bits, the moved lists and the figures,
    /// or the error, of each.
    fn steps_both_ways(nan_at: &[usize]) -> [Result<Stepped, super::SpringError>; 2] {
        steps_both_ways_of(nan_at, false)
    }

    /// [`steps_both_ways`], the active list in increasing order (and said to be) when
    /// `in_order`.
    fn steps_both_ways_of(
        nan_at: &[usize],
        in_order: bool,
    ) -> [Result<Stepped, super::SpringError>; 2] {
        let n = 9000;
        let params = SolverParams {
            judge_travel: 0.5,
            constant_mass_iterations: 1,
            ..SolverParams::default()
        };
        let mut active: Vec<u32> = (0..6000u32).map(|k| (k * 7919) % n as u32).collect();
        if in_order {
            active.sort_unstable();
        }
        let scale: Vec<f64> = (0..n).map(|i| 0.5 + (i % 7) as f64 * 0.1).collect();
        let stiffness: Vec<f64> = (0..n)
            .map(|i| {
                if i % 11 == 0 {
                    0.0
                } else {
                    1.0 + (i % 5) as f64
                }
            })
            .collect();
        let [first, second] = [false, true].map(|two| {
            let mut positions: Vec<[f64; 2]> =
                (0..n).map(|i| [i as f64 * 0.01, (i % 13) as f64]).collect();
            let mut masses = super::MassSchedule::new(&positions);
            let (mut moved_lists, mut figures) = (Vec::new(), Vec::new());
            for iteration in 0..4 {
                let mut force: Vec<[f64; 2]> = (0..n)
                    .map(|i| {
                        let w = ((i * 31 + iteration * 17) % 23) as f64 - 11.0;
                        [w * 0.05, -w * 0.03 * (iteration as f64 + 1.0)]
                    })
                    .collect();
                for &i in nan_at {
                    force[i][1] = f64::NAN;
                }
                let mut moved = Vec::new();
                let forces = (&force[..], &stiffness[..]);
                let (max, heavy) = if two {
                    super::step_in_two_ranges(
                        &mut positions,
                        (&force, &stiffness, &scale),
                        (&active, in_order),
                        (&params, iteration),
                        &mut masses,
                        &mut moved,
                    )?
                } else {
                    let axis = |_: usize, _: &[[f64; 2]]| None;
                    super::step_active(
                        &mut positions,
                        forces,
                        &scale,
                        (&active, false),
                        (&params, &axis, iteration),
                        &mut masses,
                        &mut moved,
                    )?
                };
                moved_lists.push(moved);
                figures.push((max.to_bits(), heavy));
            }
            let bits = positions.iter().flatten().map(|v| v.to_bits()).collect();
            Ok((bits, moved_lists, figures))
        });
        [first, second]
    }

    #[test]
    fn the_moves_in_two_ranges_are_the_moves_of_one_thread() {
        for in_order in [false, true] {
            let [one, two] = steps_both_ways_of(&[], in_order);
            let (one, two) = (one.unwrap(), two.unwrap());
            assert!(one.1.iter().all(|m| m.len() > 1000), "most nodes move");
            assert!(one.2.iter().any(|f| f.1 > 0), "some nodes become heavy");
            assert!(one == two, "in order: {in_order}");
        }
    }

    /// In an active list in increasing order, a non-finite force is told at its lowest node
    /// whichever range it is in.
    #[test]
    fn a_non_finite_force_in_an_ordered_list_is_told_at_its_first_node() {
        for nan_at in [&[10, 8000][..], &[8000][..], &[4500, 20][..]] {
            let [one, two] = steps_both_ways_of(nan_at, true);
            let node = |r: Result<Stepped, super::SpringError>| match r {
                Err(super::SpringError::NonFiniteForce { node, .. }) => node,
                other => panic!("{:?}", other.map(|_| ())),
            };
            let want = *nan_at.iter().min().unwrap();
            assert_eq!(node(one), want);
            assert_eq!(node(two), want);
        }
    }

    #[test]
    fn a_non_finite_force_is_told_at_the_first_such_node_of_the_active_list() {
        // node 8000 comes before node 10 in the active list (k * 7919 mod 9000)
        let first_of = |nan_at: &[usize]| {
            let [one, two] = steps_both_ways(nan_at);
            let node = |r: Result<_, super::SpringError>| match r {
                Err(super::SpringError::NonFiniteForce { node, .. }) => node,
                other => panic!("a non-finite force, not {:?}", other.map(|_| ())),
            };
            (node(one), node(two))
        };
        let at = |i: u32| (0..6000u32).position(|k| (k * 7919) % 9000 == i);
        let (a, b) = (at(8000), at(10));
        assert!(a.is_some() && b.is_some());
        let first = if a < b { 8000 } else { 10 };
        assert_eq!(first_of(&[10, 8000]), (first, first));
        assert_eq!(first_of(&[8000, 10]), (first, first));
    }

    #[test]
    fn separate_limits_clamp_the_move_along_and_across_the_extrusion_axis() {
        let separate = SolverParams {
            relaxation: 1.0,
            max_move: 0.25,
            lateral_max_move: Some(0.05),
            ..SolverParams::default()
        };
        let (step, len) =
            super::clamped_step(&[1.0, 10.0], 1.0, 1.0, 2.0, &separate, Some([0.0, 1.0]));
        assert_eq!(step, [0.1, 0.5]);
        assert!((len - 0.1f64.hypot(0.5)).abs() < 1e-15);
        // a node without an axis, or no lateral limit: the whole move clamped to max_move
        let one = SolverParams {
            lateral_max_move: None,
            ..separate
        };
        for (params, axis) in [(&separate, None), (&one, Some([0.0, 1.0]))] {
            let (step, len) = super::clamped_step(&[0.0, 10.0], 1.0, 1.0, 2.0, params, axis);
            assert_eq!((step, len), ([0.0, 0.5], 0.5));
        }
    }
    use super::*;
    use proptest::prelude::*;

    /// A chain of linear springs between fixed ends converges to even spacing.
    fn chain(n: usize, params: &SolverParams, start: &[f64]) -> (Vec<[f64; 1]>, SolveOutcome) {
        let mut x: Vec<[f64; 1]> = start.iter().map(|&v| [v]).collect();
        let movable: Vec<bool> = (0..n).map(|i| i != 0 && i != n - 1).collect();
        let scale = vec![1.0 / (n - 1) as f64; n];
        let out = solve(&mut x, &scale, &movable, params, |p, f, s| {
            for i in 0..n - 1 {
                let d = p[i + 1][0] - p[i][0];
                f[i][0] += d;
                f[i + 1][0] -= d;
                s[i] += 1.0;
                s[i + 1] += 1.0;
            }
        })
        .unwrap();
        (x, out)
    }

    proptest! {
        #[test]
        fn a_spring_chain_reaches_even_spacing(jitter in proptest::collection::vec(-0.4f64..0.4, 9)) {
            let n = 11;
            let h = 1.0 / 10.0;
            let start: Vec<f64> = (0..n)
                .map(|i| if i == 0 || i == n - 1 { i as f64 * h } else { (i as f64 + jitter[i - 1]) * h })
                .collect();
            let params = SolverParams { max_iterations: 5000, tolerance: 1e-9, ..SolverParams::default() };
            let (x, out) = chain(n, &params, &start);
            prop_assert!(out.converged, "{out:?}");
            for (i, xi) in x.iter().enumerate() {
                prop_assert!((xi[0] - i as f64 * h).abs() < 1e-6, "node {i} at {}", xi[0]);
            }
            prop_assert_eq!(x[0][0], 0.0);
            prop_assert_eq!(x[n - 1][0], 1.0);
        }
    }

    /// The chain of `chain`, solved with the active set.
    fn chain_active(
        n: usize,
        params: &SolverParams,
        start: &[f64],
    ) -> (Vec<[f64; 1]>, SolveOutcome) {
        let mut x: Vec<[f64; 1]> = start.iter().map(|&v| [v]).collect();
        let movable: Vec<bool> = (0..n).map(|i| i != 0 && i != n - 1).collect();
        let scale = vec![1.0 / (n - 1) as f64; n];
        let influence =
            Influence::from_pairs(n, (0..n as u32 - 1).flat_map(|i| [(i, i + 1), (i + 1, i)]));
        let out = solve_active(
            &mut x,
            &scale,
            &movable,
            &influence,
            params,
            |p, a, f, s| {
                for i in 0..n - 1 {
                    if !(a.flags[i] || a.flags[i + 1]) {
                        continue;
                    }
                    let d = p[i + 1][0] - p[i][0];
                    f[i][0] += d;
                    f[i + 1][0] -= d;
                    s[i] += 1.0;
                    s[i + 1] += 1.0;
                }
            },
        )
        .unwrap();
        (x, out)
    }

    proptest! {
        #[test]
        fn the_active_set_reaches_the_same_balance(
            jitter in proptest::collection::vec(-0.4f64..0.4, 39),
            still in 0usize..39,
        ) {
            // a chain at rest except for a disturbed stretch: the active set must settle it
            // to the same spacing as the full solve, and converge by the same test
            let n = 41;
            let h = 1.0 / 40.0;
            let start: Vec<f64> = (0..n)
                .map(|i| {
                    let j = if i == 0 || i == n - 1 || (i > still && i < still + 8) { 0.0 } else { jitter[i - 1] };
                    (i as f64 + j) * h
                })
                .collect();
            let params = SolverParams { max_iterations: 20000, tolerance: 1e-7, ..SolverParams::default() };
            let (x_full, out_full) = chain(n, &params, &start);
            let (x_act, out_act) = chain_active(n, &params, &start);
            prop_assert!(out_full.converged && out_act.converged, "{out_full:?} {out_act:?}");
            for i in 0..n {
                prop_assert!((x_act[i][0] - i as f64 * h).abs() < 1e-4, "node {i} at {}", x_act[i][0]);
                prop_assert!((x_act[i][0] - x_full[i][0]).abs() < 1e-4);
            }
        }
    }

    #[test]
    fn a_long_chain_disturbed_at_one_node_settles_with_the_active_set() {
        // a long chain at rest with one displaced node: the disturbance spreads from a
        // single awake node, and the active solve still settles it
        let n = 201;
        let h = 1.0 / 200.0;
        let mut start: Vec<f64> = (0..n).map(|i| i as f64 * h).collect();
        start[100] += 0.3 * h;
        let params = SolverParams::default();
        let (x, out) = chain_active(n, &params, &start);
        assert!(out.converged, "{out:?}");
        assert!((x[100][0] - 100.0 * h).abs() < 0.05 * h, "{:?}", x[100]);
        assert!((x[0][0], x[n - 1][0]) == (0.0, 1.0));
    }

    proptest! {
        /// The selection in two halves (forked from two moved nodes on) lists the nodes of the
        /// selection on one thread, in the same order, and leaves the same flags, whatever the
        /// moved nodes (repeated or not) and the dependencies.
        #[test]
        fn the_selection_in_two_halves_is_the_selection_on_one_thread(
            pairs in proptest::collection::vec((0u32..300, 0u32..300), 0..1500),
            moved in proptest::collection::vec(0u32..300, 0..400),
            fixed in proptest::collection::vec(0usize..300, 0..40),
            before in proptest::collection::vec(0u32..300, 0..50),
        ) {
            let n = 300;
            let influence = Influence::from_pairs(n, pairs);
            let mut movable = vec![true; n];
            for i in fixed {
                movable[i] = false;
            }
            let all: Vec<u32> = (0..n as u32).filter(|&i| movable[i as usize]).collect();
            let select = |threads: usize, parallel_min: usize| {
                let (mut active, mut nodes) = (vec![false; n], Vec::new());
                for &i in &before {
                    if !active[i as usize] {
                        active[i as usize] = true;
                        nodes.push(i);
                    }
                }
                let mut selection = Selection::default();
                let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
                pool.install(|| {
                    select_active(
                        (&influence, &movable),
                        &all,
                        Some(&moved),
                        (&mut active, &mut nodes),
                        (&mut selection, parallel_min),
                    )
                });
                prop_assert!(selection.seen.iter().all(|&b| !b), "the second flags left clear");
                Ok((active, nodes))
            };
            let one = select(1, usize::MAX)?;
            prop_assert_eq!(&select(2, 2)?, &one);
            prop_assert_eq!(&select(3, 2)?, &one);
        }
    }

    #[test]
    fn influence_table_lists_each_dependency_once() {
        let t = Influence::from_pairs(4, [(0, 1), (0, 1), (0, 0), (2, 3), (2, 1), (9, 1)]);
        assert_eq!(t.len(), 4);
        assert_eq!(t.dependents(1), &[0, 2]);
        assert_eq!(t.dependents(3), &[2]);
        assert_eq!(t.dependents(0), &[] as &[u32]);
        assert_eq!(t.dependents(2), &[] as &[u32]);
        let mut x = vec![[0.0f64]; 3];
        let e = solve_active(
            &mut x,
            &[1.0; 3],
            &[true; 3],
            &t,
            &SolverParams::default(),
            |_, _, _, _| {},
        )
        .unwrap_err();
        assert!(matches!(e, SpringError::LengthMismatch { .. }), "{e}");
    }

    #[test]
    fn running_out_of_iterations_is_an_outcome_with_figures() {
        let start: Vec<f64> = vec![0.0, 0.9, 0.1, 1.0];
        let params = SolverParams {
            max_iterations: 2,
            tolerance: 1e-12,
            ..SolverParams::default()
        };
        let (_, out) = chain(4, &params, &start);
        assert!(!out.converged);
        assert_eq!(out.iterations, 2);
        assert!(out.max_relative_step > 1e-12);
    }

    #[test]
    fn an_undamped_oscillator_is_calmed_by_the_mass_schedule() {
        // relaxation 1.99 on a single spring overshoots nearly fully every step: without the
        // mass schedule it would take thousands of iterations to settle.
        let mut x = vec![[0.0f64], [0.5]];
        let params = SolverParams {
            relaxation: 1.99,
            max_move: 10.0,
            constant_mass_iterations: 5,
            max_iterations: 400,
            ..SolverParams::default()
        };
        let out = solve(&mut x, &[1.0, 1.0], &[false, true], &params, |p, f, s| {
            f[1][0] += 1.0 - p[1][0];
            s[1] += 1.0;
        })
        .unwrap();
        assert!(out.converged, "{out:?}");
        assert!(out.heavy_nodes == 1, "{out:?}");
        assert!((x[1][0] - 1.0).abs() < 0.01, "{x:?}");
        assert!(out.iterations < 200, "{out:?}");
    }

    #[test]
    fn bad_input_is_an_error_not_a_panic() {
        let mut x = vec![[0.0f64, 0.0]; 3];
        let e = solve(
            &mut x,
            &[1.0; 2],
            &[true; 3],
            &SolverParams::default(),
            |_, _, _| {},
        )
        .unwrap_err();
        assert!(matches!(e, SpringError::LengthMismatch { .. }), "{e}");
        let e = solve(
            &mut x,
            &[1.0, 0.0, 1.0],
            &[true; 3],
            &SolverParams::default(),
            |_, _, _| {},
        )
        .unwrap_err();
        assert_eq!(
            e,
            SpringError::BadScale {
                node: 1,
                scale: 0.0
            }
        );
        let e = solve(
            &mut x,
            &[1.0; 3],
            &[true; 3],
            &SolverParams::default(),
            |_, f, s| {
                f[2][0] = f64::NAN;
                s[2] = 1.0;
            },
        )
        .unwrap_err();
        assert!(
            matches!(e, SpringError::NonFiniteForce { node: 2, .. }),
            "{e}"
        );
    }
}
