//! Newton's method on a conservative spring field, and its linearisation at the balance.
//!
//! The damped explicit solver ([`crate::solve`]) moves nodes a bounded step at a time and
//! stops at a tolerance of about 10⁻⁴ of a node's length scale; a balance that must be a
//! smooth, differentiable function of the fixed nodes (mesh movement, shape optimisation)
//! needs it to machine precision. Here the springs are the gradient of an energy
//! ([`EnergyModel`]): each step solves `(−∂F/∂X) δ = F` over the movable nodes with a sparse
//! Cholesky factorisation (`faer`, fill-reducing ordering computed once), shifting the
//! diagonal when the matrix is not positive definite, and takes the longest step of
//! 1, ½, ¼, … along `δ` whose energy is finite (no cell inverts) and not higher. Near the
//! balance the full step is taken and convergence is quadratic.
//!
//! [`Linearised`] is the factorised `−∂F/∂X` at the balance with the block coupling the
//! movable nodes to the fixed ones: by the implicit function theorem, a motion `dB` of the
//! fixed nodes moves the balanced nodes by `dX = (−J_XX)⁻¹ J_XB dB` — one solve per design
//! variable, no finite differences.
//!
//! It owns the solve. It does not build springs (the mover does) nor know what a design
//! variable is.

use faer::Side;
use faer::sparse::linalg::solvers::{Llt, SymbolicLlt};
use faer::sparse::{Argsort, Pair, SparseColMat, SymbolicSparseColMat};
use faer::{Mat, MatMut};

use crate::SpringError;
use crate::model::{ForceModel, Triplet};

/// A spring field that is the gradient of an energy.
pub trait EnergyModel<const D: usize>: ForceModel<D> {
    /// The energy at `positions`; `None` where the field refuses to go (a cell flat or
    /// inverted).
    fn energy(&self, positions: &[[f64; D]]) -> Option<f64>;
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
}

/// The assembly of `−∂F/∂X` over the movable nodes into a sparse matrix, its pattern found
/// once. A model emits its Jacobian triplets in the same order at every step while no cell
/// inverts, so the sort that merges duplicates and orders columns (most of the time of a
/// Newton step when redone: profiled on the 30P30N) is done once, and each step only scatters
/// the values; when the triplets' positions change the pattern is found again. Only the lower
/// triangle is kept: the matrix is symmetric and the Cholesky factorisation reads no more.
struct Assembly<const D: usize> {
    dofs: Dofs<D>,
    /// The (row, column) of every triplet the pattern was found for, to tell a change.
    keys: Vec<(u32, u32)>,
    /// The value slot of every triplet, or `u32::MAX` when dropped (held or upper).
    slot: Vec<u32>,
    /// Kept triplets; the shifted diagonal's entries follow them.
    kept: usize,
    symbolic: Option<(SymbolicSparseColMat<u32>, Argsort<u32>, SymbolicLlt<u32>)>,
    values: Vec<f64>,
    diagonal: Vec<f64>,
    /// The diagonal shift the last factorisation needed (0: none).
    last_shift: f64,
    /// Factorisations attempted, failed ones included.
    pub(crate) factorisations: usize,
}

impl<const D: usize> Assembly<D> {
    fn new(movable: &[bool]) -> Self {
        Assembly {
            dofs: Dofs::new(movable),
            keys: Vec::new(),
            slot: Vec::new(),
            kept: 0,
            symbolic: None,
            values: Vec::new(),
            diagonal: Vec::new(),
            last_shift: 0.0,
            factorisations: 0,
        }
    }

    /// Finds the pattern of `jacobian` and its fill-reducing ordering, unless known.
    fn pattern(&mut self, jacobian: &[Triplet]) -> Result<(), SpringError> {
        let same = self.symbolic.is_some()
            && self.keys.len() == jacobian.len()
            && self
                .keys
                .iter()
                .zip(jacobian)
                .all(|(k, t)| *k == (t.row, t.col));
        if same {
            return Ok(());
        }
        self.keys = jacobian.iter().map(|t| (t.row, t.col)).collect();
        let mut pairs = Vec::with_capacity(jacobian.len() + self.dofs.count);
        self.slot = jacobian
            .iter()
            .map(|t| match (self.dofs.of(t.row), self.dofs.of(t.col)) {
                (Some(r), Some(c)) if r >= c => {
                    pairs.push(Pair::new(r as u32, c as u32));
                    (pairs.len() - 1) as u32
                }
                _ => u32::MAX,
            })
            .collect();
        self.kept = pairs.len();
        // the diagonal is always present, so a shift never changes the pattern
        pairs.extend((0..self.dofs.count as u32).map(|i| Pair::new(i, i)));
        let n = self.dofs.count;
        let (symbolic, argsort) = SymbolicSparseColMat::try_new_from_indices(n, n, &pairs)
            .map_err(|e| SpringError::Solver(format!("assembling the Newton matrix: {e:?}")))?;
        let llt = SymbolicLlt::try_new(symbolic.as_ref(), Side::Lower)
            .map_err(|e| SpringError::Solver(format!("ordering the Newton matrix: {e:?}")))?;
        self.symbolic = Some((symbolic, argsort, llt));
        Ok(())
    }

    /// Scatters the values of `jacobian` (whose pattern [`Assembly::pattern`] found).
    fn scatter(&mut self, jacobian: &[Triplet]) {
        self.values.clear();
        self.values.resize(self.kept + self.dofs.count, 0.0);
        self.diagonal.clear();
        self.diagonal.resize(self.dofs.count, 0.0);
        for (t, &s) in jacobian.iter().zip(&self.slot) {
            if s != u32::MAX {
                self.values[s as usize] = -t.value;
                let (r, c) = (self.dofs.of(t.row), self.dofs.of(t.col));
                if r == c {
                    self.diagonal[r.expect("kept")] -= t.value;
                }
            }
        }
    }

    /// The matrix with `shift` × |its diagonal| added to the diagonal.
    fn matrix(&mut self, shift: f64) -> Result<SparseColMat<u32, f64>, SpringError> {
        let (symbolic, argsort, _) = self.symbolic.as_ref().expect("pattern found first");
        for (i, d) in self.diagonal.iter().enumerate() {
            self.values[self.kept + i] = shift * d.abs();
        }
        SparseColMat::new_from_argsort(symbolic.clone(), argsort, &self.values)
            .map_err(|e| SpringError::Solver(format!("assembling the Newton matrix: {e:?}")))
    }

    /// A Cholesky factorisation of `−∂F/∂X` that shifts its diagonal until it is positive
    /// definite; returns it and whether it had to. `shift_allowed` false: no shift, an
    /// indefinite matrix is an error.
    fn factorise(
        &mut self,
        jacobian: &[Triplet],
        shift_allowed: bool,
    ) -> Result<(Llt<u32, f64>, bool), SpringError> {
        self.pattern(jacobian)?;
        self.scatter(jacobian);
        // consecutive steps tend to need similar shifts: start a decade below the last one
        // instead of climbing from 10⁻⁸ again (a factorisation each)
        let mut shift = if self.last_shift > 1e-8 {
            self.last_shift / 10.0
        } else {
            0.0
        };
        for _ in 0..24 {
            let a = self.matrix(shift)?;
            let llt = self.symbolic.as_ref().expect("found").2.clone();
            self.factorisations += 1;
            if let Ok(llt) = Llt::try_new_with_symbolic(llt, a.as_ref(), Side::Lower) {
                self.last_shift = shift;
                return Ok((llt, shift > 0.0));
            }
            if !shift_allowed {
                return Err(SpringError::Solver(
                    "the balance is not stable (indefinite stiffness)".into(),
                ));
            }
            shift = if shift == 0.0 { 1e-8 } else { shift * 10.0 };
        }
        Err(SpringError::Solver(
            "the Newton matrix stays indefinite after shifting its diagonal".into(),
        ))
    }
}

/// Solves `llt · x = rhs` in place on a vector.
fn solve_vector(llt: &Llt<u32, f64>, rhs: &mut [f64]) {
    use faer::linalg::solvers::SolveCore;
    let mut m = Mat::<f64>::from_fn(rhs.len(), 1, |i, _| rhs[i]);
    let view: MatMut<'_, f64> = m.as_mut();
    llt.solve_in_place_with_conj(faer::Conj::No, view);
    for (i, r) in rhs.iter_mut().enumerate() {
        *r = m[(i, 0)];
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
    let n = positions.len();
    let mut assembly = Assembly::<D>::new(movable);
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
    let mut jacobian = Vec::new();
    let (mut force, mut stiffness) = (vec![[0.0; D]; n], vec![0.0; n]);
    let mut trial = positions.to_vec();
    let mut previous = f64::INFINITY;
    for _ in 0..params.max_iterations {
        force.iter_mut().for_each(|f| *f = [0.0; D]);
        model.assemble(positions, &mut force, &mut stiffness);
        jacobian.clear();
        model.jacobian(positions, movable, &mut jacobian);
        let (llt, shifted) = assembly.factorise(&jacobian, true)?;
        let dofs = &assembly.dofs;
        outcome.shifted += usize::from(shifted);
        outcome.factorisations = assembly.factorisations;
        let mut step = vec![0.0; dofs.count];
        for (node, f) in force.iter().enumerate() {
            if let Some(first) = dofs.of((D * node) as u32) {
                step[first..first + D].copy_from_slice(f);
            }
        }
        solve_vector(&llt, &mut step);
        let largest = (0..n)
            .filter_map(|i| dofs.of((D * i) as u32).map(|f| (i, f)))
            .map(|(i, f)| {
                crate::vec::norm(&std::array::from_fn::<f64, D, _>(|a| step[f + a])) / scale[i]
            })
            .fold(0.0f64, f64::max);
        // converged: the step is within the tolerance, or it no longer halves while already
        // small (Newton's quadratic convergence stopped at the round-off of the solve)
        let done = largest <= params.tolerance
            || (largest < 1e3 * params.tolerance && largest > 0.5 * previous);
        previous = largest;
        let mut length = 1.0;
        let mut accepted = false;
        for _ in 0..=params.max_halvings {
            for (i, t) in trial.iter_mut().enumerate() {
                *t = positions[i];
                if let Some(f) = dofs.of((D * i) as u32) {
                    for a in 0..D {
                        t[a] += length * step[f + a];
                    }
                }
            }
            // at the balance the energy no longer tells steps apart (its round-off is about
            // ε times the number of terms times itself): a full step within the tolerance is
            // taken as it is, and a step within the round-off is taken
            outcome.energy_evaluations += 1;
            let lower = model
                .energy(&trial)
                .filter(|&e| (length == 1.0 && done) || e <= energy * (1.0 + 1e-12));
            if let Some(e) = lower {
                energy = e;
                accepted = true;
                break;
            }
            length *= 0.5;
        }
        outcome.iterations += 1;
        if !accepted {
            break;
        }
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

/// The linearised balance at a converged `positions`: `−∂F/∂X` over the movable nodes,
/// factorised once, and its coupling to the held nodes.
pub struct Linearised<const D: usize> {
    dofs: Dofs<D>,
    llt: Llt<u32, f64>,
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
        let mut assembly = Assembly::<D>::new(movable);
        let mut all = Vec::new();
        model.jacobian(positions, &vec![true; positions.len()], &mut all);
        let (llt, _) = assembly.factorise(&all, false)?;
        let dofs = assembly.dofs;
        let coupling = all
            .into_iter()
            .filter(|t| dofs.of(t.row).is_some() && dofs.of(t.col).is_none())
            .collect();
        Ok(Linearised {
            dofs,
            llt,
            coupling,
        })
    }

    /// The motion of every node when the held nodes move by `held` (entries of movable
    /// nodes are ignored): held nodes as given, movable ones by `(−J_XX)⁻¹ J_XB dB`.
    pub fn respond(&self, held: &[[f64; D]]) -> Vec<[f64; D]> {
        let mut rhs = vec![0.0; self.dofs.count];
        for t in &self.coupling {
            let r = self.dofs.of(t.row).expect("movable row");
            let (node, b) = (t.col as usize / D, t.col as usize % D);
            rhs[r] += t.value * held[node][b];
        }
        solve_vector(&self.llt, &mut rhs);
        held.iter()
            .enumerate()
            .map(|(i, h)| match self.dofs.of((D * i) as u32) {
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
    use crate::shape::{ShapeLaw, shape_springs};

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

    #[test]
    fn newton_returns_a_disturbed_grid_to_its_rest_shape_quadratically() {
        let (rest, tris, fixed) = grid(6);
        let springs = shape_springs(
            tris.iter().map(|t| &t[..]),
            &rest,
            ShapeLaw::default(),
            &vec![1.0; tris.len()],
        )
        .unwrap();
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
}
