//! Newton's method on a conservative spring field, and its linearisation at the balance.
//!
//! The damped explicit solver ([`crate::solve`]) moves nodes a bounded step at a time and
//! stops at a tolerance of about 10⁻⁴ of a node's length scale; a balance that must be a
//! smooth, differentiable function of the fixed nodes (mesh movement, shape optimisation)
//! needs it to machine precision. Here the springs are the gradient of an energy
//! ([`EnergyModel`]): each step solves `(−∂F/∂X) δ = F` over the movable nodes with a sparse
//! Cholesky factorisation (`faer`, fill-reducing ordering computed once; in single precision,
//! each solve refined to double precision's accuracy: half the memory), shifting the
//! diagonal when the matrix is not positive definite, and takes the longest step of
//! 1, ½, ¼, … along `δ` whose energy is finite (no cell inverts) and not higher. Near the
//! balance the full step is taken and convergence is quadratic; there a factor also serves
//! the next steps (chord steps, a solve each) while they keep shrinking tenfold.
//!
//! [`Linearised`] is the factorised `−∂F/∂X` at the balance (in double precision) with the block coupling the
//! movable nodes to the fixed ones: by the implicit function theorem, a motion `dB` of the
//! fixed nodes moves the balanced nodes by `dX = (−J_XX)⁻¹ J_XB dB` — one solve per design
//! variable, no finite differences.
//!
//! It owns the solve. It does not build springs (the mover does) nor know what a design
//! variable is.

use dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::sparse::linalg::cholesky::{
    LltRef, SymbolicCholesky, SymbolicCholeskyRaw, SymmetricOrdering, factorize_symbolic_cholesky,
};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMat};
use faer::traits::ComplexField;
use faer::{Conj, MatMut, Par, Side};

use crate::SpringError;
use crate::model::{ForceModel, Triplet};

/// A spring field that is the gradient of an energy.
pub trait EnergyModel<const D: usize>: ForceModel<D> {
    /// The energy at `positions`; `None` where the field refuses to go (a cell flat or
    /// inverted).
    fn energy(&self, positions: &[[f64; D]]) -> Option<f64>;
    /// The Jacobian of the energy's Hessian made positive semidefinite spring by spring
    /// ([`crate::Spring::add_convex_jacobian`]), with the same entries as
    /// [`ForceModel::jacobian`]'s. The default: the Jacobian itself.
    fn convex_jacobian(&self, positions: &[[f64; D]], movable: &[bool], out: &mut Vec<Triplet>) {
        self.jacobian(positions, movable, out);
    }
    /// The entries on and below the diagonal (row ≥ column) of [`ForceModel::jacobian`]
    /// (`convex`: of [`EnergyModel::convex_jacobian`]), in the same order, handed to `sink`
    /// in chunks: all a Newton step's Cholesky factorisation reads, in about half the
    /// entries, and never all in memory at once (a 30P30N move's 1.6 million entries were
    /// 26 MB, at the peak of its memory). The default: every entry in one chunk (the
    /// assembly drops those above).
    fn lower_jacobian(
        &self,
        positions: &[[f64; D]],
        movable: &[bool],
        convex: bool,
        sink: &mut dyn FnMut(&[Triplet]),
    ) {
        let mut out = Vec::new();
        if convex {
            self.convex_jacobian(positions, movable, &mut out);
        } else {
            self.jacobian(positions, movable, &mut out);
        }
        sink(&out);
    }
}

/// Parameters of [`solve_newton`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NewtonParams {
    /// Most Newton steps.
    pub max_iterations: usize,
    /// Converged when a full step moves no node by more than this times its length scale, or
    /// by less than a thousand times this but no less than half the step before (the
    /// round-off floor of the solve).
    pub tolerance: f64,
    /// Most halvings of a step.
    pub max_halvings: usize,
}

impl Default for NewtonParams {
    fn default() -> Self {
        NewtonParams {
            max_iterations: 60,
            tolerance: 1e-10,
            max_halvings: 40,
        }
    }
}

/// What a Newton solve did.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct NewtonOutcome {
    /// Steps taken.
    pub iterations: usize,
    /// True when the last full step was within the tolerance.
    pub converged: bool,
    /// The largest move of the last step over the node's length scale.
    pub residual: f64,
    /// The energy at the end.
    pub energy: f64,
    /// Steps that took the convex Hessian ([`EnergyModel::convex_jacobian`]): the exact one
    /// was not positive definite.
    pub convex: usize,
    /// Steps that needed a diagonal shift (the matrix was not positive definite).
    pub shifted: usize,
    /// Cholesky factorisations, the failed ones of the shifts included.
    pub factorisations: usize,
    /// Energy evaluations of the line search.
    pub energy_evaluations: usize,
}

/// The numbering of the movable nodes' coordinates.
struct Dofs<const D: usize> {
    /// Node → its first unknown, or `u32::MAX` when held.
    of_node: Vec<u32>,
    count: usize,
}

impl<const D: usize> Dofs<D> {
    fn new(movable: &[bool]) -> Self {
        let mut count = 0usize;
        let of_node = movable
            .iter()
            .map(|&m| {
                if m {
                    count += D;
                    (count - D) as u32
                } else {
                    u32::MAX
                }
            })
            .collect();
        Dofs { of_node, count }
    }

    /// The unknown of global coordinate `g = D·node + a`, if movable.
    fn of(&self, g: u32) -> Option<usize> {
        let (node, a) = (g as usize / D, g as usize % D);
        let first = self.of_node[node];
        (first != u32::MAX).then(|| first as usize + a)
    }

    /// The largest move of a node by `step` over its length scale `scale`.
    fn largest_move(&self, step: &[f64], scale: &[f64]) -> f64 {
        (0..self.of_node.len())
            .filter_map(|i| self.of((D * i) as u32).map(|f| (i, f)))
            .map(|(i, f)| {
                crate::vec::norm(&std::array::from_fn::<f64, D, _>(|a| step[f + a])) / scale[i]
            })
            .fold(0.0f64, f64::max)
    }
}

/// Where a Jacobian's triplets are handed, a chunk at a time and in order.
type Sink<'a> = &'a mut dyn FnMut(&[Triplet]);

/// The assembly of `−∂F/∂X` over the movable nodes into a sparse matrix and its Cholesky
/// factor, the pattern and the fill-reducing ordering found once. A model emits its Jacobian
/// triplets in the same order at every step while no cell inverts, so the sort that merges
/// duplicates and orders columns (most of the time of a Newton step when redone: profiled on
/// the 30P30N) is done once: each step scatters the values straight into the matrix's value
/// array as the model emits them, never holding them all (a 30P30N flap move's peak memory
/// 94 → 81 MB), and factorises into the same factor and workspace buffers (allocating them
/// at every factorisation was a sixth of a 30P30N move, in page faults). When the triplets'
/// positions change the pattern is found again. Only the lower triangle is kept: the matrix
/// is symmetric and the Cholesky factorisation reads no more.
struct Assembly<const D: usize> {
    dofs: Dofs<D>,
    /// How many triplets the pattern was found for, and a hash of their (row, column)s in
    /// order, to tell a change (keeping the keys themselves took 24 MB on a 30P30N move).
    keys: (usize, u64),
    /// The index in the matrix's values of every triplet, or `u32::MAX` when dropped (held
    /// or upper).
    slot: Vec<u32>,
    /// The index in the matrix's values of each unknown's diagonal entry.
    diagonal_slot: Vec<u32>,
    pattern: Option<Pattern>,
    /// The matrix's values (column by column, in the pattern's order).
    values: Vec<f64>,
    /// The unshifted diagonal.
    diagonal: Vec<f64>,
    /// Whether the factor is in single precision, each solve refined in double
    /// ([`Assembly::solve`]): a Newton step's, until a refinement fails; not an exact
    /// linearisation's.
    mixed: bool,
    /// The matrix's values in single precision (mixed).
    values32: Vec<f32>,
    /// The factor in single precision (mixed; valid after a successful factorisation).
    single: Factor<f32>,
    /// The factor in double precision (not mixed; valid after a successful factorisation).
    double: Factor<f64>,
    par: Par,
    /// The diagonal shift the last factorisation needed (0: none).
    last_shift: f64,
    /// Factorisations attempted, failed ones included.
    pub(crate) factorisations: usize,
}

/// The lower triangle's sparsity pattern and its symbolic Cholesky factorisation.
struct Pattern {
    matrix: SymbolicSparseColMat<u32>,
    cholesky: SymbolicCholesky<u32>,
}

impl<const D: usize> Assembly<D> {
    /// An empty assembly over the nodes `movable`; `mixed`: factorised in single precision,
    /// solves refined in double ([`Assembly::solve`]).
    fn new(movable: &[bool], mixed: bool) -> Self {
        Assembly {
            dofs: Dofs::new(movable),
            keys: (0, 0),
            slot: Vec::new(),
            diagonal_slot: Vec::new(),
            pattern: None,
            values: Vec::new(),
            diagonal: Vec::new(),
            mixed,
            values32: Vec::new(),
            single: Factor::new(),
            double: Factor::new(),
            par: faer::get_global_parallelism(),
            last_shift: 0.0,
            factorisations: 0,
        }
    }

    /// Loads `−∂F/∂X` into the matrix: `emit` hands its triplets to the sink it is given
    /// (the same entries in the same order at every call while the pattern holds). Known
    /// the pattern, they are scattered as they come and their (row, column)s hashed; if
    /// they turn out not to be the pattern's, or there is none yet, `emit` is called again
    /// and the triplets gathered, the pattern found and the triplets dropped before the
    /// factor is allocated.
    fn load(
        &mut self,
        mut emit: impl FnMut(&mut dyn FnMut(&[Triplet])),
    ) -> Result<(), SpringError> {
        if self.pattern.is_none() || self.scatter(&mut emit) != self.keys {
            let mut all = Vec::new();
            emit(&mut |chunk| all.extend_from_slice(chunk));
            self.pattern(&all)?;
            self.keys = self.scatter(&mut |sink| sink(&all));
        }
        self.keep_diagonal();
        Ok(())
    }

    /// Finds the pattern of `jacobian` and its fill-reducing ordering.
    fn pattern(&mut self, jacobian: &[Triplet]) -> Result<(), SpringError> {
        let n = self.dofs.count;
        let (col_ptr, row_idx, slot, diagonal_slot) = lower_pattern(&self.dofs, jacobian);
        self.slot = slot;
        self.diagonal_slot = diagonal_slot;
        let matrix = SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx);
        let cholesky = factorize_symbolic_cholesky(
            matrix.as_ref(),
            Side::Lower,
            SymmetricOrdering::Amd,
            Default::default(),
        )
        .map_err(|e| SpringError::Solver(format!("ordering the Newton matrix: {e:?}")))?;
        // allocated at the first factorisation, after the triplets are gone
        (self.single, self.double) = (Factor::new(), Factor::new());
        self.values = vec![0.0; matrix.compute_nnz()];
        self.pattern = Some(Pattern { matrix, cholesky });
        Ok(())
    }

    /// Scatters the triplets `emit` hands over into the matrix's values through their slots
    /// (those past the slots dropped); their count and the hash of their (row, column)s,
    /// which are the pattern's [`Assembly::keys`] when the triplets are its own.
    fn scatter(&mut self, emit: &mut dyn FnMut(Sink<'_>)) -> (usize, u64) {
        self.values.iter_mut().for_each(|v| *v = 0.0);
        let mut hash = KeyHash::new();
        let (slot, values) = (&self.slot, &mut self.values);
        emit(&mut |chunk| {
            let at = hash.count;
            hash.feed(chunk);
            for (t, &s) in chunk.iter().zip(slot.get(at..).unwrap_or_default()) {
                if s != u32::MAX {
                    values[s as usize] -= t.value;
                }
            }
        });
        (hash.count, hash.finish())
    }

    /// Frees the numeric factors and the single-precision values
    /// ([`NewtonWorkspace::release_factor`]); the next factorisation allocates them again.
    fn release_factor(&mut self) {
        (self.single, self.double) = (Factor::new(), Factor::new());
        self.values32 = Vec::new();
    }

    /// Keeps the loaded matrix's diagonal, which the shifts change.
    fn keep_diagonal(&mut self) {
        self.diagonal.clear();
        self.diagonal
            .extend(self.diagonal_slot.iter().map(|&s| self.values[s as usize]));
    }

    /// A Cholesky factorisation of the loaded `−∂F/∂X` ([`Assembly::load`]) that shifts its
    /// diagonal until it is positive definite; returns whether it had to. `shift_allowed`
    /// false: no shift, an indefinite matrix is an error. The factor is then
    /// [`Assembly::solve`]'s.
    fn factorise(&mut self, shift_allowed: bool) -> Result<bool, SpringError> {
        // consecutive steps tend to need similar shifts: start a decade below the last one
        // instead of climbing from no shift again (a factorisation each), and climb by
        // decades from 10⁻⁶ (a relative shift that small changes a step as little as 10⁻⁸
        // does, in two factorisations fewer; climbing by two decades overshot, and the
        // steps shortened by the larger shifts cost more than the factorisations saved)
        let mut shift = if self.last_shift > 1e-6 {
            self.last_shift / 10.0
        } else {
            0.0
        };
        for _ in 0..24 {
            if self.factorise_shifted(shift) {
                self.last_shift = shift;
                return Ok(shift > 0.0);
            }
            if !shift_allowed {
                return Err(SpringError::Solver(
                    "the balance is not stable (indefinite stiffness)".into(),
                ));
            }
            shift = if shift == 0.0 { 1e-6 } else { shift * 10.0 };
        }
        Err(SpringError::Solver(
            "the Newton matrix stays indefinite after shifting its diagonal".into(),
        ))
    }

    /// A Cholesky factorisation of the loaded `−∂F/∂X` as it is: whether it is positive
    /// definite (the factor is then [`Assembly::solve`]'s).
    fn factorise_exact(&mut self) -> bool {
        let factored = self.factorise_shifted(0.0);
        if factored {
            self.last_shift = 0.0;
        }
        factored
    }

    /// One attempt at factorising the scattered matrix with its diagonal `d` made
    /// `d + shift·|d|`.
    fn factorise_shifted(&mut self, shift: f64) -> bool {
        for (&s, d) in self.diagonal_slot.iter().zip(&self.diagonal) {
            self.values[s as usize] = d + shift * d.abs();
        }
        self.factorise_loaded()
    }

    /// Factorises the matrix as it is loaded, in single precision when mixed: whether it is
    /// positive definite.
    fn factorise_loaded(&mut self) -> bool {
        let Some(pattern) = self.pattern.as_ref() else {
            return false;
        };
        self.factorisations += 1;
        let (matrix, cholesky) = (pattern.matrix.as_ref(), &pattern.cholesky);
        if self.mixed {
            self.values32.clear();
            self.values32.extend(self.values.iter().map(|&v| v as f32));
            let a = SparseColMatRef::new(matrix, &self.values32[..]);
            self.single.factorise(cholesky, a, self.par)
        } else {
            let a = SparseColMatRef::new(matrix, &self.values[..]);
            self.double.factorise(cholesky, a, self.par)
        }
    }

    /// The Newton step for the forces `force` (every node's, held ones ignored) with the last
    /// factor, over the unknowns, to the relative residual `accuracy` ([`Assembly::solve`]).
    fn step(&mut self, force: &[[f64; D]], accuracy: f64) -> Vec<f64> {
        let mut step = vec![0.0; self.dofs.count];
        for (node, f) in force.iter().enumerate() {
            if let Some(first) = self.dofs.of((D * node) as u32) {
                step[first..first + D].copy_from_slice(f);
            }
        }
        self.solve(&mut step, accuracy);
        step
    }

    /// Solves `A x = rhs` in place with the last factor: in double precision directly; in
    /// mixed, by iterative refinement — `x += L⁻ᵀ L⁻¹ r` in single precision, the residual
    /// `r = rhs − A x` in double — until the residual is within `accuracy` of `rhs` or stops
    /// halving (3 to 5 solves on every motion of `tests/movement`, to 10⁻¹³–10⁻¹⁶ of `rhs`,
    /// as a double factor's). If the residual stays above [`REFINED`] of `rhs` (and
    /// `accuracy`) the matrix is factorised again in double and the assembly stays there.
    ///
    /// Why single precision: the factor is most of a move's memory (the 30P30N flap's 30 of
    /// its 73 MB), and the Newton step only needs the solve's accuracy, which refinement in
    /// double gives: the same Newton steps and the same moved meshes to 10⁻¹² of their
    /// length scales, in half the factor's memory and no more time.
    fn solve(&mut self, rhs: &mut [f64], accuracy: f64) {
        if self.mixed {
            let (x, refined) = self.refine(rhs, accuracy);
            // the single factor does not refine: this matrix, and the next ones, in double
            if !refined {
                (self.mixed, self.single) = (false, Factor::new());
            }
            if refined || !self.factorise_loaded() {
                rhs.copy_from_slice(&x);
                return;
            }
        }
        let pattern = self.pattern.as_ref().expect("factorised first");
        self.double.solve(&pattern.cholesky, rhs, self.par);
    }

    /// [`Assembly::solve`]'s refinement through the single factor: its solution, and
    /// whether its residual is within [`REFINED`] (and `accuracy`) of `rhs`.
    fn refine(&mut self, rhs: &[f64], accuracy: f64) -> (Vec<f64>, bool) {
        let pattern = self.pattern.as_ref().expect("factorised first");
        let norm = |v: &[f64]| v.iter().map(|a| a * a).sum::<f64>().sqrt();
        let n = rhs.len();
        let size = norm(rhs);
        if size == 0.0 {
            return (vec![0.0; n], true);
        }
        let (mut x, mut r, mut ax) = (vec![0.0; n], rhs.to_vec(), vec![0.0; n]);
        let mut z = vec![0.0f32; n];
        let (mut residual, mut last) = (1.0, f64::INFINITY);
        for _ in 0..MAX_REFINEMENTS {
            z.iter_mut().zip(&r).for_each(|(z, r)| *z = *r as f32);
            self.single.solve(&pattern.cholesky, &mut z, self.par);
            x.iter_mut().zip(&z).for_each(|(x, z)| *x += f64::from(*z));
            self.product(&x, &mut ax);
            r.iter_mut()
                .zip(rhs.iter().zip(&ax))
                .for_each(|(r, (b, a))| *r = b - a);
            residual = norm(&r) / size;
            if residual <= accuracy || residual > 0.5 * last {
                break;
            }
            last = residual;
        }
        (x, residual <= REFINED.max(accuracy))
    }

    /// `y = A x` with the loaded matrix (its lower triangle, symmetric).
    fn product(&self, x: &[f64], y: &mut [f64]) {
        let Some(pattern) = self.pattern.as_ref() else {
            return;
        };
        let (col_ptr, row_idx) = (pattern.matrix.col_ptr(), pattern.matrix.row_idx());
        y.iter_mut().for_each(|v| *v = 0.0);
        for (c, &xc) in x.iter().enumerate() {
            let mut yc = 0.0;
            let column = col_ptr[c] as usize..col_ptr[c + 1] as usize;
            for (&r, &v) in row_idx[column.clone()].iter().zip(&self.values[column]) {
                let r = r as usize;
                yc += v * x[r];
                if r != c {
                    y[r] += v * xc;
                }
            }
            y[c] += yc;
        }
    }

    /// [`Assembly::solve`] with a workspace of its own, for a shared factor.
    fn solve_with_own_scratch(&self, rhs: &mut [f64]) {
        let pattern = self.pattern.as_ref().expect("factorised first");
        let mut scratch =
            MemBuffer::new(pattern.cholesky.solve_in_place_scratch::<f64>(1, self.par));
        solve_in(
            &pattern.cholesky,
            &self.double.values,
            self.par,
            rhs,
            &mut scratch,
        );
    }
}

/// The lower triangle's pattern of `jacobian` over the unknowns `dofs`, the diagonal always
/// present (so a shift never changes it): the column starts and row indices (rows sorted in
/// each column), each triplet's slot in the values (`u32::MAX`: held or upper) and each
/// diagonal entry's. The entries are bucketed by column (a counting sort), and each column's
/// few sorted and merged alone, each triplet's slot found on the way (a global sort of the
/// entries and a binary search per triplet before: the same pattern, a 30P30N flap move's
/// balance 13 ms faster).
fn lower_pattern<const D: usize>(
    dofs: &Dofs<D>,
    jacobian: &[Triplet],
) -> (Vec<u32>, Vec<u32>, Vec<u32>, Vec<u32>) {
    let n = dofs.count;
    let kept = |t: &Triplet| match (dofs.of(t.row), dofs.of(t.col)) {
        (Some(r), Some(c)) if r >= c => Some((c, r as u32)),
        _ => None,
    };
    // every kept entry (and each diagonal, its triplet index u32::MAX) in its column's bucket
    let mut start = vec![0usize; n + 1];
    for t in jacobian {
        if let Some((c, _)) = kept(t) {
            start[c + 1] += 1;
        }
    }
    for c in 0..n {
        start[c + 1] += start[c] + 1;
    }
    let mut fill = start.clone();
    let mut bucket = vec![(0u32, 0u32); start[n]];
    for c in 0..n {
        bucket[fill[c]] = (c as u32, u32::MAX);
        fill[c] += 1;
    }
    for (i, t) in jacobian.iter().enumerate() {
        if let Some((c, r)) = kept(t) {
            bucket[fill[c]] = (r, i as u32);
            fill[c] += 1;
        }
    }
    let mut slot = vec![u32::MAX; jacobian.len()];
    let mut diagonal_slot = vec![0u32; n];
    let mut col_ptr = Vec::with_capacity(n + 1);
    let mut row_idx = Vec::new();
    col_ptr.push(0u32);
    for c in 0..n {
        let entries = &mut bucket[start[c]..start[c + 1]];
        entries.sort_unstable();
        for &(r, i) in entries.iter() {
            if row_idx.len() as u32 == col_ptr[c] || row_idx.last() != Some(&r) {
                row_idx.push(r);
            }
            let at = row_idx.len() as u32 - 1;
            match i {
                u32::MAX => diagonal_slot[c] = at,
                i => slot[i as usize] = at,
            }
        }
        col_ptr.push(row_idx.len() as u32);
    }
    (col_ptr, row_idx, slot, diagonal_slot)
}

/// A 64-bit hash of a Jacobian's (row, column)s in order (a multiply-xorshift mix), fed in
/// chunks: entry `i` goes to lane `i mod 4`, the lanes mixed at the end. One lane would be a
/// chain of dependent multiplies; four let the processor overlap them (a 30P30N move's
/// million entries hashed each Newton step took a fifth of its pattern check).
struct KeyHash {
    lanes: [u64; 4],
    /// Entries fed so far.
    count: usize,
}

impl KeyHash {
    const SEEDS: [u64; 4] = [
        0x9e37_79b9_7f4a_7c15,
        0xc2b2_ae3d_27d4_eb4f,
        0x1656_67b1_9e37_79f9,
        0x27d4_eb2f_1656_67c5,
    ];

    fn new() -> Self {
        KeyHash {
            lanes: Self::SEEDS,
            count: 0,
        }
    }

    fn mix(h: u64, k: u64) -> u64 {
        let h = (h ^ k).wrapping_mul(0xff51_afd7_ed55_8ccd);
        h ^ (h >> 29)
    }

    fn feed(&mut self, entries: &[Triplet]) {
        let key = |t: &Triplet| (u64::from(t.row) << 32) | u64::from(t.col);
        // up to the next multiple of four one by one, then four at a time
        let lead = ((4 - self.count % 4) % 4).min(entries.len());
        let (head, rest) = entries.split_at(lead);
        for t in head {
            let lane = self.count % 4;
            self.lanes[lane] = Self::mix(self.lanes[lane], key(t));
            self.count += 1;
        }
        let chunks = rest.chunks_exact(4);
        let tail = chunks.remainder();
        for c in chunks {
            for (lane, t) in self.lanes.iter_mut().zip(c) {
                *lane = Self::mix(*lane, key(t));
            }
        }
        self.count += rest.len() - tail.len();
        for t in tail {
            let lane = self.count % 4;
            self.lanes[lane] = Self::mix(self.lanes[lane], key(t));
            self.count += 1;
        }
    }

    fn finish(&self) -> u64 {
        self.lanes.into_iter().fold(self.count as u64, Self::mix)
    }
}

/// Solves `L Lᵀ x = rhs` in place with the factor `values` of `cholesky`, in `scratch`.
fn solve_in<T: ComplexField>(
    cholesky: &SymbolicCholesky<u32>,
    values: &[T],
    par: Par,
    rhs: &mut [T],
    scratch: &mut MemBuffer,
) {
    let view = MatMut::from_column_major_slice_mut(rhs, rhs.len(), 1);
    LltRef::new(cholesky, values).solve_in_place_with_conj(
        Conj::No,
        view,
        par,
        MemStack::new(scratch),
    );
}

/// The relative residual of a Newton step's solve while its last step was large (above
/// 10⁻¹ of the length scales; below, the square of that step): a single-precision solve's
/// is 10⁻³–10⁻⁴.
const INEXACT: f64 = 1e-2;

/// The relative residual of a chord step's solve: a hundredth of the slowest rate a chord
/// step is taken at (a step shrinking tenfold, [`CHORD_BELOW`]), so that the solve's error
/// never sets the rate; a single-precision solve's is 10⁻⁵–10⁻⁷, so one solve.
const CHORD_ACCURACY: f64 = 1e-3;

/// Most single-precision solves of a refinement ([`Assembly::solve`]).
const MAX_REFINEMENTS: usize = 20;

/// The largest residual, over the right-hand side's, of a refined solve: above it the matrix
/// is factorised in double precision.
const REFINED: f64 = 1e-10;

/// A Cholesky factor's values and the workspace of its factorisation and solves, in the
/// precision `T`.
struct Factor<T> {
    values: Vec<T>,
    scratch: MemBuffer,
}

impl<T: ComplexField + Default + Copy> Factor<T> {
    fn new() -> Self {
        Factor {
            values: Vec::new(),
            scratch: MemBuffer::new(StackReq::EMPTY),
        }
    }

    /// Factorises `a` (whose pattern `cholesky` is), allocating at the first call: whether
    /// it is positive definite.
    fn factorise(
        &mut self,
        cholesky: &SymbolicCholesky<u32>,
        a: SparseColMatRef<'_, u32, T>,
        par: Par,
    ) -> bool {
        if self.values.len() != cholesky.len_val() {
            self.values = vec![T::default(); cholesky.len_val()];
            self.scratch = MemBuffer::new(StackReq::any_of(&[
                cholesky.factorize_numeric_llt_scratch::<T>(par, Default::default()),
                cholesky.solve_in_place_scratch::<T>(1, par),
            ]));
        }
        // a failed attempt leaves a partial factor: the supernodal factorisation starts
        // from zeros itself, the simplicial one is given them
        if matches!(cholesky.raw(), SymbolicCholeskyRaw::Simplicial(_)) {
            self.values.iter_mut().for_each(|v| *v = T::default());
        }
        cholesky
            .factorize_numeric_llt(
                &mut self.values,
                a,
                Side::Lower,
                Default::default(),
                par,
                MemStack::new(&mut self.scratch),
                Default::default(),
            )
            .is_ok()
    }

    /// Solves `L Lᵀ x = rhs` in place.
    fn solve(&mut self, cholesky: &SymbolicCholesky<u32>, rhs: &mut [T], par: Par) {
        solve_in(cholesky, &self.values, par, rhs, &mut self.scratch);
    }
}

/// Newton steps after which a step whose matrix is not positive definite takes each
/// spring's convex Hessian ([`EnergyModel::convex_jacobian`]) instead of a diagonal shift.
///
/// Why: a shift damps every direction alike, and where the matrix stays indefinite step after
/// step the shifted steps can creep: the NACA0012 scaled 1.5× had not converged after 60
/// steps. The convex Hessian keeps the curvature of every direction but the springs'
/// negative ones: that motion converges in 46 steps. From the first step it was slower on
/// the large turns (an exact attempt, then a second Jacobian, on every step: the 30P30N
/// turned 90° in 50 chords 6.0 s against 4.4 s) and gave no fewer steps; after 20 steps it
/// changes only the motions that have not converged by then (measured over the fourteen
/// motions of `tests/movement`).
const CONVEX_AFTER: usize = 20;

/// The largest step (over a node's length scale) below which the next Newton step reuses
/// the factor (a chord step): on a 30P30N flap move the steps from 2·10⁻³ on converge
/// through the same factor, a solve each instead of a factorisation (ten times dearer).
const CHORD_BELOW: f64 = 0.01;

/// What a Newton solve keeps for the next solve of the same model with the same movable
/// nodes (the steps of a motion sequence): the matrix's pattern, its ordering and symbolic
/// factorisation, the buffers and the last diagonal shift.
///
/// Not the last factor: started with chord steps through it, the steps of the 30P30N flap's
/// sequence shrank 20-fold twice, then stalled at half a step (its trailing edge's fan, whose
/// stiffness moves fastest) and asked for a factorisation anyway: 6 steps and one
/// factorisation each, in 8 steps as in 24. Factorised at its start, each solve takes 3 or 4
/// (the flap, the slat and both in 8 steps: a step's balance 0.14 → 0.11 s; the NACA0012
/// pitched 60° in 6 steps 8 → 4 Newton steps); only steps so large that the fresh factor's
/// step is not yet near the balance need a second factorisation (the slat and flap in 4
/// steps: 0.13 → 0.15 s).
pub struct NewtonWorkspace<const D: usize> {
    movable: Vec<bool>,
    assembly: Assembly<D>,
}

impl<const D: usize> NewtonWorkspace<D> {
    /// An empty workspace for the nodes `movable`.
    pub fn new(movable: &[bool]) -> Self {
        NewtonWorkspace {
            movable: movable.to_vec(),
            assembly: Assembly::new(movable, true),
        }
    }

    /// The movable nodes it is for.
    pub fn movable(&self) -> &[bool] {
        &self.movable
    }

    /// Frees its numeric factor and the factorisation's buffers, keeping the pattern, the
    /// ordering and the symbolic factorisation: the next solve factorises afresh anyway (its
    /// first step always does), so between two solves the factor is dead weight for a
    /// caller whose own work in between would otherwise peak on top of it.
    pub fn release_factor(&mut self) {
        self.assembly.release_factor();
    }
}

/// Balances `model` by Newton's method: the movable nodes of `positions` move, the others
/// are held. `scale[i]` is node `i`'s length scale (convergence is relative to it). The
/// positions must be admissible (finite energy) at the start.
///
/// # Errors
/// [`SpringError::Solver`] when the start is not admissible or the linear algebra fails.
pub fn solve_newton<const D: usize, M: EnergyModel<D>>(
    model: &M,
    positions: &mut [[f64; D]],
    scale: &[f64],
    movable: &[bool],
    params: &NewtonParams,
) -> Result<NewtonOutcome, SpringError> {
    let mut workspace = NewtonWorkspace::new(movable);
    solve_newton_in(model, positions, scale, &mut workspace, params)
}

/// [`solve_newton`] in `workspace`, whose movable nodes are the solve's: a workspace kept
/// from the last solve of the same model reuses its pattern, ordering and buffers.
///
/// # Errors
/// Those of [`solve_newton`].
pub fn solve_newton_in<const D: usize, M: EnergyModel<D>>(
    model: &M,
    positions: &mut [[f64; D]],
    scale: &[f64],
    workspace: &mut NewtonWorkspace<D>,
    params: &NewtonParams,
) -> Result<NewtonOutcome, SpringError> {
    let n = positions.len();
    if workspace.movable.len() != n {
        return Err(SpringError::Solver(format!(
            "a Newton workspace of {} nodes for {n}",
            workspace.movable.len()
        )));
    }
    let NewtonWorkspace { movable, assembly } = workspace;
    let movable: &[bool] = movable;
    let factorisations_before = assembly.factorisations;
    let mut energy = model
        .energy(positions)
        .ok_or_else(|| SpringError::Solver("the start of the Newton solve is inverted".into()))?;
    let mut outcome = NewtonOutcome {
        energy,
        ..NewtonOutcome::default()
    };
    if assembly.dofs.count == 0 {
        outcome.converged = true;
        return Ok(outcome);
    }
    let (mut force, mut stiffness) = (vec![[0.0; D]; n], vec![0.0; n]);
    let mut trial = positions.to_vec();
    let mut previous = f64::INFINITY;
    // whether the next step may reuse the last factor (a chord step): not the first
    let mut chord = false;
    for _ in 0..params.max_iterations {
        force.iter_mut().for_each(|f| *f = [0.0; D]);
        model.assemble(positions, &mut force, &mut stiffness);
        let reused = chord;
        if !reused {
            factorise_step(model, (positions, movable), assembly, &mut outcome)?;
            outcome.factorisations = assembly.factorisations - factorisations_before;
        }
        // an inexact step far from the balance (Newton's convergence stays quadratic with
        // a residual within the square of the last step): one single-precision solve there;
        // a chord step converges only linearly, at the rate its factor is off by (at most
        // a tenth, or it is not taken), so its solve needs no more than [`CHORD_ACCURACY`]
        let accuracy = if reused {
            CHORD_ACCURACY
        } else {
            (previous * previous).min(INEXACT)
        };
        let step = assembly.step(&force, accuracy);
        let largest = assembly.dofs.largest_move(&step, scale);
        // converged: the step is within the tolerance, or it no longer halves while already
        // small (Newton's quadratic convergence stopped at the round-off of the solve)
        let done = largest <= params.tolerance
            || (!reused && largest < 1e3 * params.tolerance && largest > 0.5 * previous);
        // near the balance a factor serves several steps: a chord step converges linearly,
        // at the rate the stiffness changed by since the factor, which there is small; a
        // step that did not shrink tenfold asks for a fresh factor
        chord = largest < CHORD_BELOW && !(reused && largest > 0.1 * previous);
        previous = largest;
        let search = (positions as &[[f64; D]], &step[..], &assembly.dofs);
        let taken = line_search(
            model,
            search,
            (energy, done),
            params,
            &mut trial,
            &mut outcome,
        );
        outcome.iterations += 1;
        let Some((length, e)) = taken else {
            if reused {
                // the old factor's step went nowhere: factorise afresh from the same place
                chord = false;
                continue;
            }
            break;
        };
        energy = e;
        chord &= length == 1.0;
        positions.copy_from_slice(&trial);
        outcome.residual = largest * length;
        outcome.energy = energy;
        if length == 1.0 && done {
            outcome.converged = true;
            break;
        }
    }
    Ok(outcome)
}

/// Factorises `model`'s `−∂F/∂X` at `positions` for a Newton step: the exact Hessian
/// where it is positive definite (Newton's quadratic convergence); where it is not, a
/// diagonal shift, and after [`CONVEX_AFTER`] steps each spring's convex part instead.
/// Counts the shifted and convex steps in `outcome`.
fn factorise_step<const D: usize, M: EnergyModel<D>>(
    model: &M,
    (positions, movable): (&[[f64; D]], &[bool]),
    assembly: &mut Assembly<D>,
    outcome: &mut NewtonOutcome,
) -> Result<(), SpringError> {
    let lower = |convex| {
        move |sink: &mut dyn FnMut(&[Triplet])| {
            model.lower_jacobian(positions, movable, convex, sink);
        }
    };
    assembly.load(lower(false))?;
    let shifted = if outcome.iterations < CONVEX_AFTER {
        assembly.factorise(true)?
    } else if assembly.factorise_exact() {
        false
    } else {
        assembly.load(lower(true))?;
        outcome.convex += 1;
        assembly.factorise(true)?
    };
    outcome.shifted += usize::from(shifted);
    Ok(())
}

/// The backtracking along a Newton step `step` from `positions` (numbered by `dofs`): the
/// longest of 1, ½, ¼, … whose energy is finite and not above `energy` (`done`: the full step
/// is within the tolerance and taken as it is), placed in `trial`; its length and energy, or
/// `None` when no halving gave one.
fn line_search<const D: usize, M: EnergyModel<D>>(
    model: &M,
    (positions, step, dofs): (&[[f64; D]], &[f64], &Dofs<D>),
    (energy, done): (f64, bool),
    params: &NewtonParams,
    trial: &mut [[f64; D]],
    outcome: &mut NewtonOutcome,
) -> Option<(f64, f64)> {
    let mut length = 1.0;
    for _ in 0..=params.max_halvings {
        for (i, t) in trial.iter_mut().enumerate() {
            *t = positions[i];
            if let Some(f) = dofs.of((D * i) as u32) {
                for a in 0..D {
                    t[a] += length * step[f + a];
                }
            }
        }
        // at the balance the energy no longer tells steps apart (its round-off is about ε
        // times the number of terms times itself): a full step within the tolerance is taken
        // as it is, and a step within the round-off is taken
        outcome.energy_evaluations += 1;
        let lower = model
            .energy(trial)
            .filter(|&e| (length == 1.0 && done) || e <= energy * (1.0 + 1e-12));
        if let Some(e) = lower {
            return Some((length, e));
        }
        length *= 0.5;
    }
    None
}

/// The linearised balance at a converged `positions`: `−∂F/∂X` over the movable nodes,
/// factorised once, and its coupling to the held nodes.
pub struct Linearised<const D: usize> {
    /// The factorised `−J_XX` (and its numbering of the movable nodes' coordinates).
    assembly: Assembly<D>,
    /// `∂F/∂X` entries with a movable row and a held column.
    coupling: Vec<Triplet>,
}

impl<const D: usize> Linearised<D> {
    /// Linearises `model` at `positions`.
    ///
    /// # Errors
    /// [`SpringError::Solver`] when the stiffness is not positive definite there (not a
    /// stable balance) or the linear algebra fails.
    pub fn at<M: ForceModel<D>>(
        model: &M,
        positions: &[[f64; D]],
        movable: &[bool],
    ) -> Result<Self, SpringError> {
        let mut assembly = Assembly::<D>::new(movable, false);
        let mut all = Vec::new();
        model.jacobian(positions, &vec![true; positions.len()], &mut all);
        assembly.load(|sink| sink(&all))?;
        assembly.factorise(false)?;
        let dofs = &assembly.dofs;
        let coupling = all
            .into_iter()
            .filter(|t| dofs.of(t.row).is_some() && dofs.of(t.col).is_none())
            .collect();
        Ok(Linearised { assembly, coupling })
    }

    /// The motion of every node when the held nodes move by `held` (entries of movable
    /// nodes are ignored): held nodes as given, movable ones by `(−J_XX)⁻¹ J_XB dB`.
    pub fn respond(&self, held: &[[f64; D]]) -> Vec<[f64; D]> {
        let dofs = &self.assembly.dofs;
        let mut rhs = vec![0.0; dofs.count];
        for t in &self.coupling {
            let r = dofs.of(t.row).expect("movable row");
            let (node, b) = (t.col as usize / D, t.col as usize % D);
            rhs[r] += t.value * held[node][b];
        }
        self.assembly.solve_with_own_scratch(&mut rhs);
        held.iter()
            .enumerate()
            .map(|(i, h)| match dofs.of((D * i) as u32) {
                Some(f) => std::array::from_fn(|a| rhs[f + a]),
                None => *h,
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::SpringList;
    use crate::params::SpringParams;
    use crate::shape::{ShapeLaw, ShapeSpring, shape_springs};

    /// An n×n grid of unit squares, each cut into two triangles, and its boundary flags.
    fn grid(n: usize) -> (Vec<[f64; 2]>, Vec<[u32; 3]>, Vec<bool>) {
        let id = |i: usize, j: usize| (j * (n + 1) + i) as u32;
        let mut x = Vec::new();
        let mut fixed = Vec::new();
        for j in 0..=n {
            for i in 0..=n {
                x.push([i as f64, j as f64]);
                fixed.push(i == 0 || j == 0 || i == n || j == n);
            }
        }
        let mut tris = Vec::new();
        for j in 0..n {
            for i in 0..n {
                tris.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                tris.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
        (x, tris, fixed)
    }

    /// [`grid`]'s nodes, the shape springs of its triangles (weight 1) and its boundary flags.
    fn grid_springs(n: usize) -> (Vec<[f64; 2]>, Vec<ShapeSpring>, Vec<bool>) {
        let (rest, tris, fixed) = grid(n);
        let springs = shape_springs(
            tris.iter().map(|t| &t[..]),
            &rest,
            ShapeLaw::default(),
            &vec![1.0; tris.len()],
        )
        .unwrap();
        (rest, springs, fixed)
    }

    #[test]
    fn newton_returns_a_disturbed_grid_to_its_rest_shape_quadratically() {
        let (rest, springs, fixed) = grid_springs(6);
        let params = SpringParams::default();
        let model = SpringList {
            springs: &springs,
            params: &params,
        };
        let mut x = rest.clone();
        for (k, p) in x.iter_mut().enumerate() {
            if !fixed[k] {
                p[0] += 0.2 * ((k * 7) as f64).sin();
                p[1] += 0.2 * ((k * 3) as f64).cos();
            }
        }
        let movable: Vec<bool> = fixed.iter().map(|f| !f).collect();
        let scale = vec![1.0; x.len()];
        let out = solve_newton(&model, &mut x, &scale, &movable, &NewtonParams::default()).unwrap();
        assert!(out.converged && out.iterations < 15, "{out:?}");
        for (a, b) in x.iter().zip(&rest) {
            assert!(
                (a[0] - b[0]).abs() < 1e-12 && (a[1] - b[1]).abs() < 1e-12,
                "{a:?} {b:?}"
            );
        }
    }

    #[test]
    fn a_kept_workspace_reaches_the_same_balance_and_a_released_factor_changes_nothing() {
        let (rest, springs, fixed) = grid_springs(6);
        let params = SpringParams::default();
        let model = SpringList {
            springs: &springs,
            params: &params,
        };
        let movable: Vec<bool> = fixed.iter().map(|f| !f).collect();
        let scale = vec![1.0; rest.len()];
        // a sequence: the boundary's top row pushed right by 0.1, then by 0.2
        let pushed = |by: f64| -> Vec<[f64; 2]> {
            rest.iter()
                .map(|p| [p[0] + by * p[1] / 6.0, p[1]])
                .collect()
        };
        // two workspaces through the same first solve, the second's factor then released
        let (mut workspace, mut released) = (
            NewtonWorkspace::new(&movable),
            NewtonWorkspace::new(&movable),
        );
        let mut x = pushed(0.1);
        let first = solve_newton_in(
            &model,
            &mut x,
            &scale,
            &mut workspace,
            &NewtonParams::default(),
        );
        assert!(first.unwrap().converged);
        let mut y = pushed(0.1);
        solve_newton_in(
            &model,
            &mut y,
            &scale,
            &mut released,
            &NewtonParams::default(),
        )
        .unwrap();
        released.release_factor();
        let mut start = pushed(0.2);
        for (k, p) in start.iter_mut().enumerate() {
            if movable[k] {
                *p = [x[k][0] + 0.1 * rest[k][1] / 6.0, x[k][1]];
            }
        }
        let (mut kept, mut fresh, mut after) = (start.clone(), start.clone(), start);
        let again = solve_newton_in(
            &model,
            &mut kept,
            &scale,
            &mut workspace,
            &NewtonParams::default(),
        )
        .unwrap();
        // a released factor changes nothing: the next solve factorises afresh anyway
        let after_release = solve_newton_in(
            &model,
            &mut after,
            &scale,
            &mut released,
            &NewtonParams::default(),
        )
        .unwrap();
        assert_eq!(again, after_release);
        assert_eq!(kept, after);
        let anew = solve_newton(
            &model,
            &mut fresh,
            &scale,
            &movable,
            &NewtonParams::default(),
        )
        .unwrap();
        assert!(again.converged && anew.converged);
        // the same steps: the kept pattern and ordering are those a new workspace finds
        assert_eq!(again.iterations, anew.iterations, "{again:?} {anew:?}");
        for (a, b) in kept.iter().zip(&fresh) {
            assert!(
                (a[0] - b[0]).abs() < 1e-12 && (a[1] - b[1]).abs() < 1e-12,
                "{a:?} {b:?}"
            );
        }
    }

    /// The lower Jacobian of [`grid_springs`] at its rest nodes nudged by `by`, gathered.
    fn grid_jacobian(by: f64) -> (Vec<bool>, Vec<Triplet>) {
        let (rest, springs, fixed) = grid_springs(3);
        let params = SpringParams::default();
        let model = SpringList {
            springs: &springs,
            params: &params,
        };
        let movable: Vec<bool> = fixed.iter().map(|f| !f).collect();
        let x: Vec<[f64; 2]> = crate::length::nudged(&rest)
            .iter()
            .zip(&rest)
            .map(|(n, r)| [r[0] + by * (n[0] - r[0]), r[1] + by * (n[1] - r[1])])
            .collect();
        let mut all = Vec::new();
        model.lower_jacobian(&x, &movable, false, &mut |c| all.extend_from_slice(c));
        (movable, all)
    }

    /// The hash of a Jacobian's (row, column)s is the same however it is chunked, and
    /// changes with their order.
    #[test]
    fn the_key_hash_does_not_depend_on_the_chunks() {
        let (_, all) = grid_jacobian(1.0);
        let whole = {
            let mut h = KeyHash::new();
            h.feed(&all);
            (h.count, h.finish())
        };
        for size in [1, 3, 4, 5, 7, 64] {
            let mut h = KeyHash::new();
            all.chunks(size).for_each(|c| h.feed(c));
            assert_eq!((h.count, h.finish()), whole, "chunks of {size}");
        }
        let mut swapped = all.clone();
        let last = swapped.len() - 1;
        swapped.swap(1, last);
        let mut h = KeyHash::new();
        h.feed(&swapped);
        assert_ne!(h.finish(), whole.1);
    }

    /// Streamed in chunks, a Jacobian with the known pattern is scattered as a gathered one
    /// is; one whose entries differ is found a pattern again, as a new assembly finds it.
    #[test]
    fn a_streamed_load_is_the_gathered_one() {
        let (movable, first) = grid_jacobian(1.0);
        let (_, second) = grid_jacobian(0.5);
        fn streamed(all: &[Triplet]) -> impl FnMut(Sink<'_>) + '_ {
            move |sink| all.chunks(5).for_each(sink)
        }
        let gathered = |all: &[Triplet]| {
            let mut a = Assembly::<2>::new(&movable, true);
            a.load(|sink| sink(all)).unwrap();
            a.values
        };
        let keys = |all: &[Triplet]| {
            let mut h = KeyHash::new();
            h.feed(all);
            h.finish()
        };
        // the same pattern: the second load scatters as the entries come
        assert_eq!(keys(&first), keys(&second));
        let mut kept = Assembly::<2>::new(&movable, true);
        kept.load(streamed(&first)).unwrap();
        assert_eq!(kept.values, gathered(&first));
        kept.load(streamed(&second)).unwrap();
        assert_eq!(kept.values, gathered(&second));
        assert!(kept.values != gathered(&first));
        // fewer entries: another pattern
        let fewer = &second[..second.len() - 7];
        kept.load(streamed(fewer)).unwrap();
        assert_eq!(kept.values, gathered(fewer));
        assert_eq!(kept.keys.0, fewer.len());
        assert!(kept.factorise(true).is_ok());
    }

    /// A mixed-precision solve (single factor, refined in double) is the double one's to
    /// round-off.
    #[test]
    fn a_mixed_solve_is_a_double_one() {
        let (movable, all) = grid_jacobian(1.0);
        let solve = |mixed: bool| {
            let mut a = Assembly::<2>::new(&movable, mixed);
            a.load(|sink| sink(&all)).unwrap();
            assert!(!a.factorise(true).unwrap(), "positive definite unshifted");
            let mut x: Vec<f64> = (0..a.dofs.count).map(|i| (i as f64).sin()).collect();
            a.solve(&mut x, 0.0);
            assert_eq!(a.mixed, mixed);
            x
        };
        let (single, double) = (solve(true), solve(false));
        let top = double.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for (s, d) in single.iter().zip(&double) {
            assert!((s - d).abs() < 1e-12 * top, "{s} {d}");
        }
    }

    /// Where the single factor cannot refine (a stiffness beyond single precision's range),
    /// the matrix is factorised in double and the solve is exact.
    #[test]
    fn a_solve_that_does_not_refine_is_done_in_double() {
        let movable = [true, true];
        let diagonal = [1e40, 1.0, 2.0, 3.0];
        let triplets: Vec<Triplet> = (0..4)
            .map(|i| Triplet {
                row: i,
                col: i,
                value: -diagonal[i as usize],
            })
            .collect();
        let mut a = Assembly::<2>::new(&movable, true);
        a.load(|sink| sink(&triplets)).unwrap();
        assert!(!a.factorise(false).unwrap());
        let mut x = diagonal.to_vec();
        a.solve(&mut x, 0.0);
        assert!(!a.mixed);
        for v in x {
            assert!((v - 1.0).abs() < 1e-15, "{v}");
        }
    }
}
