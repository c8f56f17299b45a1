//! The local spring problem of a layered mesher, generic over the dimension `D`: which nodes
//! of the top layers move, a local numbering of the nodes the springs touch, the solve on
//! local copies, and the undo of a rejected step.
//!
//! A layered mesher (afsf2d, afsf3d, mesh movement) keeps its nodes in creation order, layer
//! after layer, each node knowing its parents (two for a node made by merging). A step
//! creates a new layer from `new_start` on and balances the springs of a window of the top
//! layers (`window_start..`): [`LocalProblem::select_layered`] picks the moving nodes (the
//! alive new nodes and their ancestors inside the window, except nodes the mesher pins);
//! the mesher then writes its springs with [`LocalProblem::local`] (which numbers the fixed
//! nodes on first use); [`LocalProblem::solve`] solves on local copies, writes the moving
//! nodes back and returns an [`Undo`] of the older nodes it moved
//! ([`LocalProblem::solve_making`]: the same, the model made beside the solve's set-up).
//!
//! Local numbering: the moving nodes first, in ascending global order, then the fixed nodes
//! in the order the springs first name them. The order is part of the result (it sets the
//! order of the floating-point sums), so it is kept as documented. A mesher may write its
//! springs in two parts at once ([`LocalProblem::number_in_two`]): the second part names
//! its fixed nodes by [`Deferred`] numbers, numbered after the first part has named its own,
//! in the order the second named them: the numbering of the springs written one after the
//! other.

use crate::error::SpringError;
use crate::model::ForceModel;
use crate::params::SolverParams;
use crate::solver::{SolveOutcome, Start};

/// A solve's set-up: the local copies of the positions, the scales, and the solver's start.
type SetUp<const D: usize> = (Vec<[f64; D]>, Vec<f64>, Result<Start<D>, SpringError>);

/// "No node": the value of an absent parent (the same as `mesh_model::NONE`).
pub const NO_NODE: u32 = u32::MAX;

/// The positions an accepted solve overwrote, to put back when the step is rejected.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Undo<const D: usize> {
    saved: Vec<(u32, [f64; D])>,
}

impl<const D: usize> Undo<D> {
    /// Puts the saved positions back.
    pub fn restore(self, positions: &mut [[f64; D]]) {
        for (node, p) in self.saved {
            positions[node as usize] = p;
        }
    }

    /// Number of nodes saved.
    pub fn len(&self) -> usize {
        self.saved.len()
    }

    /// True when nothing was saved.
    pub fn is_empty(&self) -> bool {
        self.saved.is_empty()
    }
}

/// A local spring problem and its reusable scratch space (see the module documentation).
#[derive(Debug, Clone, Default)]
pub struct LocalProblem<const D: usize> {
    /// Global → local number, [`NO_NODE`] for nodes outside the problem (all of them between
    /// problems).
    local_of: Vec<u32>,
    /// Local → global number.
    nodes: Vec<u32>,
    movable: Vec<bool>,
    /// Scratch: moving flags over the window.
    moving: Vec<bool>,
    /// The local numbers of the window's moving nodes ([`NO_NODE`] for the others), from
    /// `window_start` on: read by a [`Deferred`] numbering beside the problem's own.
    window_local: Vec<u32>,
    window_start: usize,
}

/// What names the nodes of the springs a mesher writes: whether a node moves, and its local
/// number. [`LocalProblem`] numbers a fixed node on first use; [`Deferred`] defers it.
pub trait Numbering {
    /// True when global node `g` moves in this problem.
    fn is_moving(&self, g: u32) -> bool;
    /// The local number of global node `g` (for [`Deferred`], of a fixed node, a deferred
    /// number: see [`Deferred::resolve`]).
    fn local(&mut self, g: u32) -> u32;
}

impl<const D: usize> Numbering for LocalProblem<D> {
    #[inline]
    fn is_moving(&self, g: u32) -> bool {
        LocalProblem::is_moving(self, g)
    }
    #[inline]
    fn local(&mut self, g: u32) -> u32 {
        LocalProblem::local(self, g)
    }
}

/// The numbering of the second part of springs written in two parts at once
/// ([`LocalProblem::number_in_two`]): the moving nodes by their local numbers, the fixed
/// nodes by deferred numbers ([`DEFERRED`] and the place of their first naming here), which
/// [`Deferred::resolve`] turns into local numbers once the first part is numbered.
#[derive(Debug)]
pub struct Deferred<'a> {
    window_start: usize,
    window_local: &'a [u32],
    /// The fixed nodes named, in the order first named.
    named: Vec<u32>,
    /// Global → place in `named`, for the nodes named so far.
    place: std::collections::HashMap<u32, u32>,
}

/// The mark of a deferred number ([`Deferred`]).
pub const DEFERRED: u32 = 1 << 31;

impl Numbering for Deferred<'_> {
    #[inline]
    fn is_moving(&self, g: u32) -> bool {
        (g as usize)
            .checked_sub(self.window_start)
            .and_then(|w| self.window_local.get(w))
            .is_some_and(|&l| l != NO_NODE)
    }
    #[inline]
    fn local(&mut self, g: u32) -> u32 {
        if let Some(&l) = (g as usize)
            .checked_sub(self.window_start)
            .and_then(|w| self.window_local.get(w))
            .filter(|&&l| l != NO_NODE)
        {
            return l;
        }
        let next = self.named.len() as u32;
        let at = *self.place.entry(g).or_insert(next);
        if at == next {
            self.named.push(g);
        }
        DEFERRED | at
    }
}

impl Deferred<'_> {
    /// The local number of `l`, a number given by this numbering, in `numbers` (what
    /// [`LocalProblem::number_in_two`] returns).
    #[inline]
    pub fn resolve(l: u32, numbers: &[u32]) -> u32 {
        if l & DEFERRED != 0 {
            numbers[(l & !DEFERRED) as usize]
        } else {
            l
        }
    }
}

impl<const D: usize> LocalProblem<D> {
    /// An empty problem.
    pub fn new() -> Self {
        Self::default()
    }

    /// Starts a problem over global nodes `0..n` with the nodes of `window_start..n` that
    /// move: walking down from the newest node, an alive node moves when it is new
    /// (`>= new_start`) or the parent of a moving node, unless `pinned` (indexed from
    /// `window_start`) holds it. A pinned parent is never marked; a pinned node reached as a
    /// parent stays fixed. `parents(g)` gives the node's parents, [`NO_NODE`] for none.
    pub fn select_layered(
        &mut self,
        n: usize,
        window_start: usize,
        new_start: usize,
        pinned: &[bool],
        alive: impl Fn(usize) -> bool,
        parents: impl Fn(usize) -> [u32; 2],
    ) {
        let moving = &mut self.moving;
        moving.clear();
        moving.resize(n - window_start, false);
        for g in (window_start..n).rev() {
            if !alive(g) {
                continue;
            }
            let is_new = g >= new_start;
            if is_new || moving[g - window_start] {
                if !is_new && pinned[g - window_start] {
                    moving[g - window_start] = false;
                    continue;
                }
                moving[g - window_start] = true;
                for p in parents(g) {
                    if p != NO_NODE
                        && (p as usize) >= window_start
                        && !pinned[p as usize - window_start]
                    {
                        moving[p as usize - window_start] = true;
                    }
                }
            }
        }
        if self.local_of.len() < n {
            self.local_of.resize(n, NO_NODE);
        }
        self.nodes.clear();
        self.movable.clear();
        self.window_start = window_start;
        self.window_local.clear();
        for g in window_start..n {
            let l = if self.moving[g - window_start] {
                let l = self.nodes.len() as u32;
                self.local_of[g] = l;
                self.nodes.push(g as u32);
                self.movable.push(true);
                l
            } else {
                NO_NODE
            };
            self.window_local.push(l);
        }
    }

    /// Numbers the nodes of springs written in two parts at once (after
    /// [`LocalProblem::select_layered`]), on two threads when the pool has them: `first`
    /// writes with this problem's numbering, `second` with a [`Deferred`] one. Returns both
    /// results and the local numbers of the second part's deferred numbers (for
    /// [`Deferred::resolve`]): its fixed nodes numbered after every one the first part named,
    /// in the order the second part named them, so that the numbering is that of the first
    /// part's springs written before the second's.
    pub fn number_in_two<A: Send, B: Send>(
        &mut self,
        first: impl FnOnce(&mut Self) -> A + Send,
        second: impl FnOnce(&mut Deferred<'_>) -> B + Send,
    ) -> (A, B, Vec<u32>) {
        // the moving nodes' numbers are read beside the numbering, which never changes them
        let window_local = std::mem::take(&mut self.window_local);
        let mut deferred = Deferred {
            window_start: self.window_start,
            window_local: &window_local,
            named: Vec::new(),
            place: std::collections::HashMap::new(),
        };
        let (a, b) = rayon::join(|| first(self), || second(&mut deferred));
        let numbers = deferred.named.iter().map(|&g| self.local(g)).collect();
        self.window_local = window_local;
        (a, b, numbers)
    }

    /// True when global node `g` moves in this problem.
    #[inline]
    pub fn is_moving(&self, g: u32) -> bool {
        match self.local_of.get(g as usize) {
            Some(&l) if l != NO_NODE => self.movable[l as usize],
            _ => false,
        }
    }

    /// The local number of global node `g`, numbering it as a fixed node on first use.
    #[inline]
    pub fn local(&mut self, g: u32) -> u32 {
        let l = self.local_of[g as usize];
        if l != NO_NODE {
            return l;
        }
        let l = self.nodes.len() as u32;
        self.local_of[g as usize] = l;
        self.nodes.push(g);
        self.movable.push(false);
        l
    }

    /// Number of nodes in the problem (moving and fixed).
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// True when the problem has no node.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// The global numbers of the local nodes.
    pub fn nodes(&self) -> &[u32] {
        &self.nodes
    }

    /// Solves `model` (written in local numbers) with the active-set solver on copies of the
    /// positions, each moving node's scale being `scale(g)` (fixed nodes 1); writes the moving
    /// nodes back into `positions` and forgets the numbering. Returns the saved positions of
    /// the moving nodes older than `new_start` (the new ones go with the step on undo).
    pub fn solve<M: ForceModel<D> + Sync + ?Sized>(
        &mut self,
        positions: &mut [[f64; D]],
        new_start: usize,
        scale: impl Fn(u32) -> f64,
        model: &M,
        params: &SolverParams,
    ) -> Result<(Undo<D>, SolveOutcome), SpringError> {
        let set_up = self.set_up(positions, &scale, params);
        self.finish(positions, new_start, set_up, model, params)
    }

    /// [`LocalProblem::solve`] of the model `make` gives (its springs' index, say), made
    /// beside the solve's set-up (the copies of the positions, the scales, the solver's arrays
    /// and mass schedule), on another thread of the pool when there is one: the same solve.
    pub fn solve_making<M, F>(
        &mut self,
        positions: &mut [[f64; D]],
        new_start: usize,
        scale: impl Fn(u32) -> f64 + Sync,
        make: F,
        params: &SolverParams,
    ) -> Result<(Undo<D>, SolveOutcome), SpringError>
    where
        M: ForceModel<D> + Sync + Send,
        F: FnOnce() -> M + Send,
    {
        let read: &[[f64; D]] = positions;
        let (model, set_up) = rayon::join(make, || self.set_up(read, &scale, params));
        self.finish(positions, new_start, set_up, &model, params)
    }

    /// The local copies of the positions and the scales, and the solver's set-up of them.
    fn set_up(
        &self,
        positions: &[[f64; D]],
        scale: &impl Fn(u32) -> f64,
        params: &SolverParams,
    ) -> SetUp<D> {
        let x: Vec<[f64; D]> = self.nodes.iter().map(|&g| positions[g as usize]).collect();
        let scales: Vec<f64> = self
            .nodes
            .iter()
            .zip(&self.movable)
            .map(|(&g, &m)| if m { scale(g) } else { 1.0 })
            .collect();
        let start = Start::new(&x, &scales, &self.movable, None, params);
        (x, scales, start)
    }

    /// The solve from its set-up, the moving nodes written back, the numbering forgotten.
    fn finish<M: ForceModel<D> + Sync + ?Sized>(
        &mut self,
        positions: &mut [[f64; D]],
        new_start: usize,
        (mut x, scales, start): SetUp<D>,
        model: &M,
        params: &SolverParams,
    ) -> Result<(Undo<D>, SolveOutcome), SpringError> {
        let outcome = start.and_then(|start| {
            let local = (&scales[..], &self.movable[..]);
            crate::solver::solve_model_active_from(&mut x, local, start, model, params)
        });
        let mut undo = Undo::default();
        for (l, &g) in self.nodes.iter().enumerate() {
            if outcome.is_ok() && self.movable[l] {
                if (g as usize) < new_start {
                    undo.saved.push((g, positions[g as usize]));
                }
                positions[g as usize] = x[l];
            }
            self.local_of[g as usize] = NO_NODE;
        }
        Ok((undo, outcome?))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::SpringParams;
    use crate::model::SpringList;
    use crate::springs::ExtrusionSpring;

    /// A column of three nodes per wall node in 3D, the top layer new: the new layer and the
    /// one below move, the wall and pinned nodes do not, and undo puts the old nodes back.
    #[test]
    fn a_layered_problem_in_3d_moves_the_top_layers_and_undoes() {
        // wall 0, 1; layer 1: 2, 3 (3 pinned); layer 2 (new): 4, 5
        let mut pos: Vec<[f64; 3]> = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 0.0, 0.12],
            [1.0, 0.0, 0.1],
            [0.1, 0.0, 0.25],
            [1.0, 0.1, 0.2],
        ];
        let parents = [
            [NO_NODE; 2],
            [NO_NODE; 2],
            [0, NO_NODE],
            [1, NO_NODE],
            [2, NO_NODE],
            [3, NO_NODE],
        ];
        let mut problem = LocalProblem::<3>::new();
        let pinned = [false, true, false, false]; // window 2..6
        problem.select_layered(6, 2, 4, &pinned, |_| true, |g| parents[g]);
        assert_eq!(problem.nodes(), &[2, 4, 5]);
        assert!(problem.is_moving(2) && !problem.is_moving(3) && !problem.is_moving(0));
        let mut springs = Vec::new();
        for g in 2..6u32 {
            let p = parents[g as usize][0];
            if problem.is_moving(g) || problem.is_moving(p) {
                springs.push(ExtrusionSpring {
                    lower: problem.local(p),
                    upper: problem.local(g),
                    ideal_length: 0.1,
                    lower_share: 1.0,
                });
            }
        }
        assert_eq!(problem.nodes(), &[2, 4, 5, 0, 3]);
        let before = pos.clone();
        let params = SpringParams::default();
        let model = SpringList {
            springs: &springs,
            params: &params,
        };
        // the same solve with the model made beside the set-up, on two threads
        let (mut problem_2, mut pos_2) = (problem.clone(), pos.clone());
        let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build();
        let made = pool.expect("a pool").install(|| {
            problem_2.solve_making(
                &mut pos_2,
                4,
                |_| 0.1,
                || SpringList {
                    springs: &springs,
                    params: &params,
                },
                &SolverParams::default(),
            )
        });
        let (undo, outcome) = problem
            .solve(&mut pos, 4, |_| 0.1, &model, &SolverParams::default())
            .unwrap();
        assert_eq!(made.unwrap(), (undo.clone(), outcome));
        assert_eq!(pos_2, pos);
        assert_eq!(problem_2.local_of, problem.local_of);
        assert!(outcome.converged);
        assert_eq!(undo.len(), 1); // node 2: the new nodes are not saved
        assert_eq!((pos[0], pos[1], pos[3]), (before[0], before[1], before[3]));
        let len = |a: [f64; 3], b: [f64; 3]| crate::vec::norm(&crate::vec::sub(&a, &b));
        for (lo, up) in [(0, 2), (2, 4), (3, 5)] {
            assert!(
                (len(pos[lo], pos[up]) - 0.1).abs() < 1e-3,
                "{lo}-{up}: {pos:?}"
            );
        }
        undo.restore(&mut pos);
        assert_eq!(pos[2], before[2]);
        // the numbering is forgotten: a second problem starts clean
        problem.select_layered(6, 2, 4, &[false; 4], |g| g != 5, |g| parents[g]);
        assert_eq!(problem.nodes(), &[2, 4]);
    }

    /// A problem over random layered nodes (a window of `n - window` nodes, some dead, some
    /// pinned), and the nodes its springs name in turn: movable ones, fixed ones in the
    /// window and below it, each named again now and then.
    fn layered_problem(seed: u64, n: usize) -> (LocalProblem<2>, Vec<u32>) {
        let mut x = seed | 1;
        let mut next = move |m: usize| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x % m as u64) as usize
        };
        let window = n / 3;
        let parents: Vec<[u32; 2]> = (0..n)
            .map(|g| match g {
                0..4 => [NO_NODE; 2],
                _ => [
                    next(g) as u32,
                    if next(4) == 0 {
                        next(g) as u32
                    } else {
                        NO_NODE
                    },
                ],
            })
            .collect();
        let dead: Vec<bool> = (0..n).map(|_| next(9) == 0).collect();
        let pinned: Vec<bool> = (window..n).map(|_| next(7) == 0).collect();
        let mut problem = LocalProblem::<2>::new();
        problem.select_layered(n, window, n - n / 6, &pinned, |g| !dead[g], |g| parents[g]);
        let named = (0..4 * n).map(|_| next(n) as u32).collect();
        (problem, named)
    }

    proptest::proptest! {
        /// Springs written in two parts at once, on one to three threads, number the nodes
        /// as springs written one after the other: the same local numbers, the same order of
        /// the problem's nodes.
        #[test]
        fn two_parts_number_the_nodes_as_one_after_the_other(
            seed in proptest::prelude::any::<u64>(),
            n in 8usize..300,
            cut in 0.0f64..=1.0,
            threads in 1usize..=3,
        ) {
            let (mut problem, named) = layered_problem(seed, n);
            let mut one = problem.clone();
            let want: Vec<(bool, u32)> =
                named.iter().map(|&g| (one.is_moving(g), one.local(g))).collect();
            let mid = (cut * named.len() as f64) as usize;
            let write = |part: &[u32], numbering: &mut dyn Numbering| -> Vec<(bool, u32)> {
                part.iter().map(|&g| (numbering.is_moving(g), numbering.local(g))).collect()
            };
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build();
            let (first, second, numbers) = pool.expect("a pool").install(|| {
                problem.number_in_two(|p| write(&named[..mid], p), |d| write(&named[mid..], d))
            });
            let got: Vec<(bool, u32)> = first
                .into_iter()
                .chain(second.into_iter().map(|(m, l)| (m, Deferred::resolve(l, &numbers))))
                .collect();
            proptest::prop_assert_eq!(got, want);
            proptest::prop_assert_eq!(problem.nodes(), one.nodes());
        }
    }
}
