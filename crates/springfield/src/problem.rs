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
//! order of the floating-point sums), so it is kept as documented.

use crate::error::SpringError;
use crate::model::ForceModel;
use crate::params::SolverParams;
use crate::solver::{SolveOutcome, Start};

/// Nodes from which a solve writes its moving nodes back on one thread while the other
/// forgets the numbering.
const PARALLEL_FINISH_MIN: usize = 4096;

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
        for g in window_start..n {
            if self.moving[g - window_start] {
                self.local_of[g] = self.nodes.len() as u32;
                self.nodes.push(g as u32);
                self.movable.push(true);
            }
        }
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
        let (nodes, movable, local_of) = (&self.nodes, &self.movable, &mut self.local_of);
        let mut write_back = || {
            let mut undo = Undo::default();
            if outcome.is_ok() {
                for ((&g, &m), &p) in nodes.iter().zip(movable).zip(&x) {
                    if m {
                        if (g as usize) < new_start {
                            undo.saved.push((g, positions[g as usize]));
                        }
                        positions[g as usize] = p;
                    }
                }
            }
            undo
        };
        let mut forget = || nodes.iter().for_each(|&g| local_of[g as usize] = NO_NODE);
        // (two walks of scattered writes: on two threads for a large problem)
        let undo = if nodes.len() >= PARALLEL_FINISH_MIN && rayon::current_num_threads() > 1 {
            rayon::join(write_back, forget).0
        } else {
            forget();
            write_back()
        };
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
}
