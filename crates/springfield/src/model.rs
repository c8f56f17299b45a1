//! The force-model interface over the node dimension `D`: what a solver needs from a set of
//! springs, whichever solver it is.
//!
//! - [`Spring`] is one spring kind: the nodes it reads and pushes, its force and stiffness, and
//!   its part of the forces' Jacobian ∂F/∂X (by default a central difference over the nodes it
//!   reads, so the Jacobian stays sparse and its cost linear in the number of springs);
//! - [`ForceModel`] is a whole set of springs bound to its coefficients: the damped explicit
//!   solver ([`crate::solve_model`], [`crate::solve_model_active`]) uses its assembly and
//!   influence table, a Newton solver (mesh movement) also its [`ForceModel::jacobian`];
//! - [`SpringList`] makes a model of one kind of spring in any dimension (the extrusion
//!   spring is generic over `D`), [`crate::SpringField2d`] is the 2D set of the mesher.
//!
//! # Where the 3D set goes
//!
//! The 3D springs of the dissertation (§5: the neighbour spring weighted by facet area, the
//! angle spring with f(a) = 8a³ + 0.2a, and the tension spring) will be three `Spring<3>`
//! types in a `springs3d` module next to [`crate::springs`], gathered in a `SpringSet3d` with
//! its `ForceModel<3>` binding like [`crate::SpringField2d`]; the extrusion spring and everything in
//! this module are reused as they are. Nothing of it exists yet.

use crate::active::{Active, Influence};
use crate::params::SpringParams;

/// One entry of a sparse matrix in coordinate form; repeated (row, col) entries add up.
/// For the forces' Jacobian, `row = D·i + a` is component `a` of the force on node `i` and
/// `col = D·j + b` component `b` of the position of node `j`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Triplet {
    /// Row (force component).
    pub row: u32,
    /// Column (position component).
    pub col: u32,
    /// ∂F_row / ∂X_col.
    pub value: f64,
}

/// One spring kind in dimension `D`.
pub trait Spring<const D: usize> {
    /// Appends the nodes whose positions this spring's force depends on.
    fn reads(&self, out: &mut Vec<u32>);
    /// Appends the nodes this spring pushes (a subset of [`Spring::reads`]).
    fn pushes(&self, out: &mut Vec<u32>);
    /// Adds this spring's force and stiffness (see [`crate::springs`]).
    fn add_force(
        &self,
        params: &SpringParams,
        positions: &[[f64; D]],
        force: &mut [[f64; D]],
        stiffness: &mut [f64],
    );
    /// Appends this spring's entries of ∂F/∂X for the nodes flagged in `movable` (rows and
    /// columns both movable). The default is [`FiniteDifference::add`]; a spring with a
    /// closed form overrides it.
    fn add_jacobian(
        &self,
        params: &SpringParams,
        movable: &[bool],
        fd: &mut FiniteDifference<D>,
        out: &mut Vec<Triplet>,
    ) {
        fd.add(self, params, movable, out);
    }
    /// [`Spring::add_jacobian`] of the energy's Hessian made positive semidefinite (its
    /// negative curvature dropped), for Newton steps far from a balance. The default: the
    /// Jacobian itself (a spring whose energy is convex, or that has none).
    fn add_convex_jacobian(
        &self,
        params: &SpringParams,
        movable: &[bool],
        fd: &mut FiniteDifference<D>,
        out: &mut Vec<Triplet>,
    ) {
        self.add_jacobian(params, movable, fd, out);
    }
}

/// Scratch space of a central-difference Jacobian over `n` nodes, made once per Jacobian: a
/// copy of the positions perturbed one coordinate at a time, and force arrays of which only
/// the nodes of the spring being differenced are ever touched.
#[derive(Debug, Clone)]
pub struct FiniteDifference<const D: usize> {
    positions: Vec<[f64; D]>,
    force: Vec<[f64; D]>,
    stiffness: Vec<f64>,
    reads: Vec<u32>,
    pushes: Vec<u32>,
    /// Forces on the pushed nodes at +h.
    plus: Vec<[f64; D]>,
}

/// Relative step of the central difference: about the cube root of the machine epsilon,
/// times the spring's extent.
const FD_STEP: f64 = 1e-6;

impl<const D: usize> FiniteDifference<D> {
    /// Scratch for the Jacobian at `positions`.
    pub fn new(positions: &[[f64; D]]) -> Self {
        let n = positions.len();
        FiniteDifference {
            positions: positions.to_vec(),
            force: vec![[0.0; D]; n],
            stiffness: vec![0.0; n],
            reads: Vec::new(),
            pushes: Vec::new(),
            plus: Vec::new(),
        }
    }

    /// The positions the Jacobian is taken at.
    pub fn positions(&self) -> &[[f64; D]] {
        &self.positions
    }

    /// Appends the central-difference ∂F/∂X of one spring: each coordinate of each movable
    /// node it reads is moved by ±h (h = 10⁻⁶ × the spring's extent) and the force on each
    /// movable node it pushes is differenced. Springs are piecewise smooth (the angle spring
    /// switches on at its activation length and turns at 90°): next to a switch the
    /// difference straddles it.
    pub fn add<S: Spring<D> + ?Sized>(
        &mut self,
        spring: &S,
        params: &SpringParams,
        movable: &[bool],
        out: &mut Vec<Triplet>,
    ) {
        let (mut reads, mut pushes) = (
            std::mem::take(&mut self.reads),
            std::mem::take(&mut self.pushes),
        );
        reads.clear();
        pushes.clear();
        spring.reads(&mut reads);
        spring.pushes(&mut pushes);
        let origin = self.positions[reads[0] as usize];
        let extent = reads
            .iter()
            .map(|&r| crate::vec::norm(&crate::vec::sub(&self.positions[r as usize], &origin)))
            .fold(0.0f64, f64::max);
        let h = FD_STEP * if extent > 0.0 { extent } else { 1.0 };
        for &j in reads.iter().filter(|&&j| movable[j as usize]) {
            for b in 0..D {
                let keep = self.positions[j as usize][b];
                for sign in [1.0, -1.0] {
                    self.positions[j as usize][b] = keep + sign * h;
                    for &p in &pushes {
                        self.force[p as usize] = [0.0; D];
                    }
                    spring.add_force(
                        params,
                        &self.positions,
                        &mut self.force,
                        &mut self.stiffness,
                    );
                    if sign > 0.0 {
                        self.plus.clear();
                        self.plus
                            .extend(pushes.iter().map(|&p| self.force[p as usize]));
                    }
                }
                self.positions[j as usize][b] = keep;
                for (k, &p) in pushes.iter().enumerate() {
                    if !movable[p as usize] {
                        continue;
                    }
                    for a in 0..D {
                        out.push(Triplet {
                            row: (D * p as usize + a) as u32,
                            col: (D * j as usize + b) as u32,
                            value: (self.plus[k][a] - self.force[p as usize][a]) / (2.0 * h),
                        });
                    }
                }
            }
        }
        self.reads = reads;
        self.pushes = pushes;
    }
}

/// A set of springs bound to its coefficients: what a solver needs.
pub trait ForceModel<const D: usize> {
    /// Adds every spring's force and stiffness.
    fn assemble(&self, positions: &[[f64; D]], force: &mut [[f64; D]], stiffness: &mut [f64]);
    /// Adds the complete force and stiffness of every node flagged in `active` (other nodes
    /// may get partial sums), for [`crate::solve_active()`]. The default assembles all.
    fn assemble_active(
        &self,
        positions: &[[f64; D]],
        active: Active<'_>,
        force: &mut [[f64; D]],
        stiffness: &mut [f64],
    ) {
        let _ = active;
        self.assemble(positions, force, stiffness);
    }
    /// Sets the force and stiffness of every node flagged in `active` to their complete sums,
    /// whatever the two arrays held there: [`ForceModel::assemble_active`] into the active
    /// entries zeroed. The default zeroes them, then adds; a model whose assembly is split
    /// between threads zeroes each part on the thread that sums it.
    fn assemble_active_fresh(
        &self,
        positions: &[[f64; D]],
        active: Active<'_>,
        force: &mut [[f64; D]],
        stiffness: &mut [f64],
    ) {
        zero_active(active.nodes, force, stiffness);
        self.assemble_active(positions, active, force, stiffness);
    }
    /// [`ForceModel::assemble_active`] on the calling thread alone, to the same bits: what a
    /// solve calls while another thread of the pool is busy with other work (the default is
    /// `assemble_active`, for models that do not split their assembly).
    fn assemble_active_here(
        &self,
        positions: &[[f64; D]],
        active: Active<'_>,
        force: &mut [[f64; D]],
        stiffness: &mut [f64],
    ) {
        self.assemble_active(positions, active, force, stiffness);
    }
    /// Which nodes' forces depend on which, over `n` nodes.
    fn influence(&self, n: usize) -> Influence;
    /// The unit direction of `node`'s extrusion edge (from its parent) at `positions`, for
    /// [`crate::SolverParams::lateral_max_move`]; `None` (the default) when the model has no
    /// such edge for it: its whole move is then limited by `max_move`.
    fn extrusion_axis(&self, node: usize, positions: &[[f64; D]]) -> Option<[f64; D]> {
        let _ = (node, positions);
        None
    }
    /// Appends ∂F/∂X at `positions` for the nodes flagged in `movable` (see [`Triplet`]).
    /// Its pattern lies within [`ForceModel::influence`] plus the diagonal blocks.
    fn jacobian(&self, positions: &[[f64; D]], movable: &[bool], out: &mut Vec<Triplet>);
}

/// Zeroes the force and stiffness of the `nodes`.
pub(crate) fn zero_active<const D: usize>(
    nodes: &[u32],
    force: &mut [[f64; D]],
    stiffness: &mut [f64],
) {
    for &i in nodes {
        force[i as usize] = [0.0; D];
        stiffness[i as usize] = 0.0;
    }
}

/// Appends (pushed node, node read) pairs of `springs`, for [`Influence::from_pairs`].
pub fn influence_pairs<const D: usize, S: Spring<D>>(springs: &[S], pairs: &mut Vec<(u32, u32)>) {
    let (mut reads, mut pushes) = (Vec::new(), Vec::new());
    for s in springs {
        reads.clear();
        pushes.clear();
        s.reads(&mut reads);
        s.pushes(&mut pushes);
        for &p in &pushes {
            pairs.extend(reads.iter().map(|&r| (p, r)));
        }
    }
}

/// Appends the Jacobian entries of `springs` (see [`ForceModel::jacobian`]).
pub fn jacobian_of<const D: usize, S: Spring<D>>(
    springs: &[S],
    params: &SpringParams,
    movable: &[bool],
    fd: &mut FiniteDifference<D>,
    out: &mut Vec<Triplet>,
) {
    for s in springs {
        s.add_jacobian(params, movable, fd, out);
    }
}

/// One kind of spring, in any dimension, bound to its coefficients: e.g. extrusion springs
/// alone, the part of the model that 2D and 3D share.
#[derive(Debug, Clone, Copy)]
pub struct SpringList<'a, S> {
    /// The springs.
    pub springs: &'a [S],
    /// Their coefficients.
    pub params: &'a SpringParams,
}

impl<const D: usize, S: Spring<D>> ForceModel<D> for SpringList<'_, S> {
    fn assemble(&self, positions: &[[f64; D]], force: &mut [[f64; D]], stiffness: &mut [f64]) {
        for s in self.springs {
            s.add_force(self.params, positions, force, stiffness);
        }
    }

    fn assemble_active(
        &self,
        positions: &[[f64; D]],
        active: Active<'_>,
        force: &mut [[f64; D]],
        stiffness: &mut [f64],
    ) {
        let mut pushes = Vec::new();
        for s in self.springs {
            pushes.clear();
            s.pushes(&mut pushes);
            if pushes.iter().any(|&p| active.flags[p as usize]) {
                s.add_force(self.params, positions, force, stiffness);
            }
        }
    }

    fn influence(&self, n: usize) -> Influence {
        let mut pairs = Vec::new();
        influence_pairs(self.springs, &mut pairs);
        Influence::from_pairs(n, pairs)
    }

    fn jacobian(&self, positions: &[[f64; D]], movable: &[bool], out: &mut Vec<Triplet>) {
        self.jacobian_in(positions, movable, (false, false), out);
    }
}

impl<S> SpringList<'_, S> {
    /// Appends every spring's Jacobian entries at `positions` (`convex`: of its convex
    /// Hessian, [`Spring::add_convex_jacobian`]; `lower`: only those on and below the
    /// diagonal, row ≥ column), `out` reserved first.
    pub(crate) fn jacobian_in<const D: usize>(
        &self,
        positions: &[[f64; D]],
        movable: &[bool],
        kind: (bool, bool),
        out: &mut Vec<Triplet>,
    ) where
        S: Spring<D>,
    {
        reserve_jacobian(self.springs, kind.1, out);
        self.jacobian_blocks(positions, movable, kind, out, &mut |_| false);
    }

    /// [`SpringList::jacobian_in`]'s entries in order, handed to `sink` a few thousand at a
    /// time instead of gathered: a Newton step scatters them straight into its matrix (the
    /// gathered million entries of a 30P30N move were 14 MB, at the peak of its memory).
    pub(crate) fn jacobian_chunks<const D: usize>(
        &self,
        positions: &[[f64; D]],
        movable: &[bool],
        kind: (bool, bool),
        sink: &mut dyn FnMut(&[Triplet]),
    ) where
        S: Spring<D>,
    {
        const CHUNK: usize = 4096;
        let mut buffer = Vec::with_capacity(2 * CHUNK);
        self.jacobian_blocks(positions, movable, kind, &mut buffer, &mut |b| {
            if b.len() < CHUNK {
                return false;
            }
            sink(b);
            true
        });
        sink(&buffer);
    }

    /// Appends every spring's entries to `out`, cleared after each spring whose entries
    /// `flush` took (returned true).
    fn jacobian_blocks<const D: usize>(
        &self,
        positions: &[[f64; D]],
        movable: &[bool],
        (convex, lower): (bool, bool),
        out: &mut Vec<Triplet>,
        flush: &mut dyn FnMut(&[Triplet]) -> bool,
    ) where
        S: Spring<D>,
    {
        let mut fd = FiniteDifference::new(positions);
        for s in self.springs {
            let start = out.len();
            if convex {
                s.add_convex_jacobian(self.params, movable, &mut fd, out);
            } else {
                s.add_jacobian(self.params, movable, &mut fd, out);
            }
            if lower {
                keep_lower(out, start);
            }
            if flush(out) {
                out.clear();
            }
        }
    }
}

/// Appends a 2D spring's Jacobian block over its `nodes`, the movable ones only:
/// `value(2k + a, 2m + b)` is `∂F/∂x` between node `k`'s axis `a` and node `m`'s axis `b`
/// (the order the springs of the shape balance push theirs in: node by node, then axes).
pub(crate) fn push_block(
    nodes: &[u32],
    movable: &[bool],
    out: &mut Vec<Triplet>,
    value: impl Fn(usize, usize) -> f64,
) {
    for (k, &p) in nodes.iter().enumerate() {
        if !movable[p as usize] {
            continue;
        }
        for (m, &q) in nodes.iter().enumerate() {
            if !movable[q as usize] {
                continue;
            }
            for a in 0..2 {
                for b in 0..2 {
                    out.push(Triplet {
                        row: 2 * p + a as u32,
                        col: 2 * q + b as u32,
                        value: value(2 * k + a, 2 * m + b),
                    });
                }
            }
        }
    }
}

/// Drops the entries above the diagonal (row < column) from `out[start..]`, in place and in
/// order.
fn keep_lower(out: &mut Vec<Triplet>, start: usize) {
    let mut kept = start;
    for i in start..out.len() {
        if out[i].row >= out[i].col {
            out[kept] = out[i];
            kept += 1;
        }
    }
    out.truncate(kept);
}

/// Reserves room in an empty `out` for every entry `springs` can write (each spring's pushed
/// nodes' coordinates squared; `lower`: those on and below the diagonal), so a Jacobian of a
/// million entries does not grow by doubling.
fn reserve_jacobian<const D: usize, S: Spring<D>>(
    springs: &[S],
    lower: bool,
    out: &mut Vec<Triplet>,
) {
    if out.capacity() > 0 {
        return;
    }
    let mut pushes = Vec::new();
    let entries: usize = springs
        .iter()
        .map(|s| {
            pushes.clear();
            s.pushes(&mut pushes);
            let n = D * pushes.len();
            if lower { n * (n + 1) / 2 } else { n * n }
        })
        .sum();
    out.reserve_exact(entries);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::springs::tests::two_layers;
    use crate::springs::{ExtrusionSpring, SpringField2d};
    use proptest::prelude::*;

    /// The triplets summed into a dense matrix of `n·D` rows and columns.
    fn dense<const D: usize>(n: usize, t: &[Triplet]) -> Vec<Vec<f64>> {
        let mut m = vec![vec![0.0; n * D]; n * D];
        for e in t {
            m[e.row as usize][e.col as usize] += e.value;
        }
        m
    }

    /// ∂F/∂X of a whole model by central differences of its full assembly (dense, O(n²)).
    fn dense_fd<const D: usize>(
        model: &impl ForceModel<D>,
        x: &[[f64; D]],
        movable: &[bool],
        h: f64,
    ) -> Vec<Vec<f64>> {
        let n = x.len();
        let mut m = vec![vec![0.0; n * D]; n * D];
        let eval = |p: &[[f64; D]]| {
            let mut f = vec![[0.0; D]; n];
            let mut s = vec![0.0; n];
            model.assemble(p, &mut f, &mut s);
            f
        };
        for j in (0..n).filter(|&j| movable[j]) {
            for b in 0..D {
                let mut p = x.to_vec();
                p[j][b] += h;
                let fp = eval(&p);
                p[j][b] -= 2.0 * h;
                let fm = eval(&p);
                for i in (0..n).filter(|&i| movable[i]) {
                    for a in 0..D {
                        m[D * i + a][D * j + b] = (fp[i][a] - fm[i][a]) / (2.0 * h);
                    }
                }
            }
        }
        m
    }

    proptest! {
        /// The extrusion spring's closed-form Jacobian (3D) equals its central difference.
        #[test]
        fn the_extrusion_jacobian_in_3d_matches_finite_differences(
            c in proptest::collection::vec(-1.0f64..1.0, 6),
            ideal in 0.2f64..2.0,
            share in 0.5f64..1.0,
            lower_moves: bool,
        ) {
            let x = [[c[0], c[1], c[2]], [c[3] + 1.5, c[4], c[5]]];
            let springs = [ExtrusionSpring { lower: 0, upper: 1, ideal_length: ideal, lower_share: share }];
            let params = SpringParams { k_extrusion: 1.7, ..SpringParams::default() };
            let movable = [lower_moves, true];
            let mut analytic = Vec::new();
            let mut fd = FiniteDifference::new(&x);
            jacobian_of(&springs, &params, &movable, &mut fd, &mut analytic);
            let mut numeric = Vec::new();
            fd.add(&springs[0], &params, &movable, &mut numeric);
            let (a, b) = (dense::<3>(2, &analytic), dense::<3>(2, &numeric));
            for r in 0..6 {
                for col in 0..6 {
                    prop_assert!((a[r][col] - b[r][col]).abs() < 1e-6, "({r},{col}): {} vs {}", a[r][col], b[r][col]);
                }
            }
            let model = SpringList { springs: &springs, params: &params };
            let mut t = Vec::new();
            model.jacobian(&x, &movable, &mut t);
            prop_assert_eq!(t, analytic);
        }
    }

    proptest! {
        /// The per-spring Jacobian of the 2D set equals the central difference of its whole
        /// assembly, and its pattern lies within the influence table (plus the diagonal).
        #[test]
        fn the_2d_jacobian_matches_the_whole_model_and_its_influence(
            jitter in proptest::collection::vec(-0.1f64..0.1, 16),
        ) {
            let (x, set) = two_layers(&jitter, 0.4, 0.25);
            let params = SpringParams::default();
            let model = SpringField2d::new(&set, &params, x.len());
            let movable: Vec<bool> = (0..12).map(|i| i >= 4).collect();
            let mut t = Vec::new();
            model.jacobian(&x, &movable, &mut t);
            let sparse = dense::<2>(12, &t);
            let whole = dense_fd(&model, &x, &movable, 1e-7);
            // the springs are piecewise smooth (the angle spring switches on at its
            // activation length): a configuration with a switch within 1e-5 of it has no
            // Jacobian to compare, and two step sizes of the whole model's difference tell
            let wide = dense_fd(&model, &x, &movable, 1e-5);
            let smooth = (0..24).all(|r| {
                (0..24).all(|c| (wide[r][c] - whole[r][c]).abs() < 1e-5 * (1.0 + whole[r][c].abs()))
            });
            prop_assume!(smooth);
            for r in 0..24 {
                for c in 0..24 {
                    let scale = 1.0 + whole[r][c].abs();
                    prop_assert!((sparse[r][c] - whole[r][c]).abs() < 1e-4 * scale, "({r},{c}): {} vs {}", sparse[r][c], whole[r][c]);
                }
            }
            let influence = model.influence(12);
            for e in &t {
                let (i, j) = (e.row / 2, e.col / 2);
                prop_assert!(movable[i as usize] && movable[j as usize]);
                prop_assert!(i == j || influence.dependents(j as usize).contains(&i), "({i},{j}) outside the influence table");
            }
        }
    }

    #[test]
    fn every_influence_pair_of_moving_nodes_has_jacobian_entries() {
        // generic positions: every spring is on, so the pattern is the influence table
        let jitter: Vec<f64> = (0..16).map(|k| 0.03 * ((k * 7 % 5) as f64 - 2.0)).collect();
        let (x, set) = two_layers(&jitter, 0.4, 0.25);
        let params = SpringParams::default();
        let model = SpringField2d::new(&set, &params, x.len());
        let movable = vec![true; 12];
        let mut t = Vec::new();
        model.jacobian(&x, &movable, &mut t);
        let m = dense::<2>(12, &t);
        let influence = model.influence(12);
        for j in 0..12 {
            for &i in influence.dependents(j) {
                let block = (0..4)
                    .map(|k| m[2 * i as usize + k / 2][2 * j + k % 2].abs())
                    .sum::<f64>();
                assert!(block > 0.0, "no entry for ({i},{j})");
            }
        }
    }

    #[test]
    fn solving_through_the_model_is_solving_through_the_closure() {
        let jitter: Vec<f64> = (0..16).map(|k| 0.05 * ((k * 3 % 7) as f64 - 3.0)).collect();
        let (x0, set) = two_layers(&jitter, 0.4, 0.25);
        let params = SpringParams::default();
        let movable: Vec<bool> = (0..12).map(|i| i >= 4).collect();
        let scale = vec![0.3; 12];
        let solver = crate::SolverParams::default();
        let model = SpringField2d::new(&set, &params, 12);
        let mut a = x0.clone();
        let out_a = crate::solve_model_active(&mut a, &scale, &movable, &model, &solver).unwrap();
        let mut b = x0.clone();
        let index = set.index(12);
        let out_b = crate::solve_active(
            &mut b,
            &scale,
            &movable,
            &set.influence(12),
            &solver,
            |p, act, f, s| crate::assemble_2d_active(&set, &index, &params, p, act, f, s),
        )
        .unwrap();
        assert_eq!((a, out_a), (b, out_b));
        let mut c = x0;
        crate::solve_model(&mut c, &scale, &movable, &model, &solver).unwrap();
    }
}
