//! The length spring of the shape balance, and the one spring type the balance solves.
//!
//! A shape spring ([`crate::shape`]) holds a cell to its shape, not its size in one direction:
//! when a wall stretches under it (a bump near a leading edge stretches its facets by 15 %), a
//! thin wall cell stays similar to itself and its height grows with its width, which moves
//! the first cell height a solver's wall treatment (y⁺) was set for. A [`LengthSpring`] on an
//! extrusion edge (a layer node and its parent) holds that edge's length with the energy
//! `w (l/l₀ − 1)²`, in closed form with its exact Hessian, so the balance stays a smooth,
//! differentiable function of the boundary. [`BalanceSpring`] is either kind, so one
//! [`SpringList`] (one energy, one Newton matrix) holds both.
//!
//! It owns these two springs. It does not choose the edges nor the weights (the mover does).

use crate::corner::CornerSpring;
use crate::jump::JumpSpring;
use crate::model::{FiniteDifference, Spring, SpringList, Triplet, push_block};
use crate::newton::EnergyModel;
use crate::params::SpringParams;
use crate::quad::QuadSpring;
use crate::shape::ShapeSpring;

/// An edge `ends[0] → ends[1]` held to its rest length `rest` with energy `w (l/rest − 1)²`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LengthSpring {
    /// The edge's nodes.
    pub ends: [u32; 2],
    /// Its rest length (> 0).
    pub rest: f64,
    /// The weight `w` of its energy.
    pub weight: f64,
}

impl LengthSpring {
    /// The unit vector from the first end to the second and the length; `None` when the
    /// ends coincide or are not finite.
    fn direction(&self, x: &[[f64; 2]]) -> Option<([f64; 2], f64)> {
        let (a, b) = (x[self.ends[0] as usize], x[self.ends[1] as usize]);
        let d = [b[0] - a[0], b[1] - a[1]];
        let l = (d[0] * d[0] + d[1] * d[1]).sqrt();
        (l > 0.0 && l.is_finite()).then(|| ([d[0] / l, d[1] / l], l))
    }

    /// Its energy; `None` when the edge has collapsed.
    pub fn energy(&self, x: &[[f64; 2]]) -> Option<f64> {
        let (_, l) = self.direction(x)?;
        let s = l / self.rest - 1.0;
        Some(self.weight * s * s)
    }

    /// `∂E/∂x_b` (the first end's is its opposite) and the Hessian block `∂²E/∂x_b²`
    /// (`∂²E/∂x_a∂x_b` is its opposite): `H = 2w/l₀ [u uᵀ/l₀ + (l/l₀ − 1)(I − u uᵀ)/l]`.
    fn derivatives(&self, x: &[[f64; 2]]) -> Option<([f64; 2], [[f64; 2]; 2])> {
        self.derivatives_of(x, false)
    }

    /// [`LengthSpring::derivatives`]; `convex`: without the negative transverse term of a
    /// compressed edge (the Hessian made positive semidefinite).
    fn derivatives_of(&self, x: &[[f64; 2]], convex: bool) -> Option<([f64; 2], [[f64; 2]; 2])> {
        let (u, l) = self.direction(x)?;
        let (w, r) = (self.weight, self.rest);
        let s = l / r - 1.0;
        let g = [2.0 * w * s / r * u[0], 2.0 * w * s / r * u[1]];
        let mut h = [[0.0; 2]; 2];
        for (i, row) in h.iter_mut().enumerate() {
            for (j, v) in row.iter_mut().enumerate() {
                let uu = u[i] * u[j];
                let eye = if i == j { 1.0 } else { 0.0 };
                let transverse = if convex { s.max(0.0) } else { s };
                *v = 2.0 * w / r * (uu / r + transverse * (eye - uu) / l);
            }
        }
        Some((g, h))
    }
}

impl Spring<2> for LengthSpring {
    fn reads(&self, out: &mut Vec<u32>) {
        out.extend(self.ends);
    }

    fn pushes(&self, out: &mut Vec<u32>) {
        out.extend(self.ends);
    }

    /// The force `−∂E/∂x` on both ends; the stiffness is the rest Hessian's `2w/l₀²`.
    fn add_force(
        &self,
        _: &SpringParams,
        positions: &[[f64; 2]],
        force: &mut [[f64; 2]],
        stiffness: &mut [f64],
    ) {
        let Some((g, _)) = self.derivatives(positions) else {
            return;
        };
        let (a, b) = (self.ends[0] as usize, self.ends[1] as usize);
        for c in 0..2 {
            force[a][c] += g[c];
            force[b][c] -= g[c];
        }
        let k = 2.0 * self.weight / (self.rest * self.rest);
        stiffness[a] += k;
        stiffness[b] += k;
    }

    fn add_jacobian(
        &self,
        _: &SpringParams,
        movable: &[bool],
        fd: &mut FiniteDifference<2>,
        out: &mut Vec<Triplet>,
    ) {
        self.push_jacobian(fd.positions(), false, movable, out);
    }

    fn add_convex_jacobian(
        &self,
        _: &SpringParams,
        movable: &[bool],
        fd: &mut FiniteDifference<2>,
        out: &mut Vec<Triplet>,
    ) {
        self.push_jacobian(fd.positions(), true, movable, out);
    }
}

impl LengthSpring {
    /// Appends its Jacobian at `x` over the movable ends (`convex`: of the convex Hessian).
    fn push_jacobian(
        &self,
        x: &[[f64; 2]],
        convex: bool,
        movable: &[bool],
        out: &mut Vec<Triplet>,
    ) {
        let Some((_, h)) = self.derivatives_of(x, convex) else {
            return;
        };
        // ∂F_p/∂x_q = −∂²E/∂x_p∂x_q: −H on the diagonal blocks, +H off them
        push_block(&self.ends, movable, out, |i, j| {
            let sign = if i / 2 == j / 2 { -1.0 } else { 1.0 };
            sign * h[i % 2][j % 2]
        });
    }
}

/// A spring of the shape balance: a cell's shape, an edge's length or its angle to its wall.
#[derive(Debug, Clone, PartialEq)]
pub enum BalanceSpring {
    /// A triangle held to its shape (boxed, as the larger kinds are: the list is mostly
    /// length and corner springs, and each entry is as large as the largest kind inline).
    Shape(Box<ShapeSpring>),
    /// A quadrilateral held to its shape (boxed: four times a triangle's).
    Quad(Box<QuadSpring>),
    /// An edge held to its length.
    Length(LengthSpring),
    /// Two neighbouring cells held to deform alike (boxed: twice a triangle's).
    Jump(Box<JumpSpring>),
    /// An extrusion edge held to its angle with its wall.
    Corner(CornerSpring),
}

impl BalanceSpring {
    /// Its energy; `None` when its cell is flat or inverted or its edge collapsed.
    pub fn energy(&self, x: &[[f64; 2]]) -> Option<f64> {
        match self {
            BalanceSpring::Shape(s) => s.energy(x),
            BalanceSpring::Quad(s) => s.energy(x),
            BalanceSpring::Length(s) => s.energy(x),
            BalanceSpring::Jump(s) => Some(s.energy(x)),
            BalanceSpring::Corner(s) => s.energy(x),
        }
    }
}

impl Spring<2> for BalanceSpring {
    fn reads(&self, out: &mut Vec<u32>) {
        match self {
            BalanceSpring::Shape(s) => s.reads(out),
            BalanceSpring::Quad(s) => s.reads(out),
            BalanceSpring::Length(s) => s.reads(out),
            BalanceSpring::Jump(s) => s.reads(out),
            BalanceSpring::Corner(s) => s.reads(out),
        }
    }

    fn pushes(&self, out: &mut Vec<u32>) {
        match self {
            BalanceSpring::Shape(s) => s.pushes(out),
            BalanceSpring::Quad(s) => s.pushes(out),
            BalanceSpring::Length(s) => s.pushes(out),
            BalanceSpring::Jump(s) => s.pushes(out),
            BalanceSpring::Corner(s) => s.pushes(out),
        }
    }

    fn add_force(
        &self,
        params: &SpringParams,
        positions: &[[f64; 2]],
        force: &mut [[f64; 2]],
        stiffness: &mut [f64],
    ) {
        match self {
            BalanceSpring::Shape(s) => s.add_force(params, positions, force, stiffness),
            BalanceSpring::Quad(s) => s.add_force(params, positions, force, stiffness),
            BalanceSpring::Length(s) => s.add_force(params, positions, force, stiffness),
            BalanceSpring::Jump(s) => s.add_force(params, positions, force, stiffness),
            BalanceSpring::Corner(s) => s.add_force(params, positions, force, stiffness),
        }
    }

    fn add_jacobian(
        &self,
        params: &SpringParams,
        movable: &[bool],
        fd: &mut FiniteDifference<2>,
        out: &mut Vec<Triplet>,
    ) {
        match self {
            BalanceSpring::Shape(s) => s.add_jacobian(params, movable, fd, out),
            BalanceSpring::Quad(s) => s.add_jacobian(params, movable, fd, out),
            BalanceSpring::Length(s) => s.add_jacobian(params, movable, fd, out),
            BalanceSpring::Jump(s) => s.add_jacobian(params, movable, fd, out),
            BalanceSpring::Corner(s) => s.add_jacobian(params, movable, fd, out),
        }
    }

    fn add_convex_jacobian(
        &self,
        params: &SpringParams,
        movable: &[bool],
        fd: &mut FiniteDifference<2>,
        out: &mut Vec<Triplet>,
    ) {
        match self {
            BalanceSpring::Shape(s) => s.add_convex_jacobian(params, movable, fd, out),
            BalanceSpring::Quad(s) => s.add_convex_jacobian(params, movable, fd, out),
            BalanceSpring::Length(s) => s.add_convex_jacobian(params, movable, fd, out),
            BalanceSpring::Jump(s) => s.add_convex_jacobian(params, movable, fd, out),
            BalanceSpring::Corner(s) => s.add_convex_jacobian(params, movable, fd, out),
        }
    }
}

impl EnergyModel<2> for SpringList<'_, BalanceSpring> {
    fn energy(&self, positions: &[[f64; 2]]) -> Option<f64> {
        self.springs.iter().map(|s| s.energy(positions)).sum()
    }

    fn convex_jacobian(&self, positions: &[[f64; 2]], movable: &[bool], out: &mut Vec<Triplet>) {
        self.jacobian_in(positions, movable, (true, false), out);
    }

    fn lower_jacobian(
        &self,
        positions: &[[f64; 2]],
        movable: &[bool],
        convex: bool,
        sink: &mut dyn FnMut(&[Triplet]),
    ) {
        self.jacobian_chunks(positions, movable, (convex, true), sink);
    }
}

/// `rest` with each node nudged off it (a fixed, uneven motion), for derivative tests.
#[cfg(test)]
pub(crate) fn nudged(rest: &[[f64; 2]]) -> Vec<[f64; 2]> {
    rest.iter()
        .enumerate()
        .map(|(k, p)| {
            [
                p[0] + 0.1 * (k as f64).sin(),
                p[1] + 0.07 * (k as f64).cos(),
            ]
        })
        .collect()
}

/// How far the forces and the Jacobian of `springs` at `x` are from the central differences
/// of their energy and forces (largest relative errors), and the Jacobian from symmetric.
#[cfg(test)]
pub(crate) fn derivative_errors(springs: &[BalanceSpring], x: &[[f64; 2]]) -> (f64, f64, f64) {
    use crate::ForceModel;
    let n = x.len();
    let params = SpringParams::default();
    let model = SpringList {
        springs,
        params: &params,
    };
    let (mut f, mut k) = (vec![[0.0; 2]; n], vec![0.0; n]);
    model.assemble(x, &mut f, &mut k);
    let mut jac = Vec::new();
    model.jacobian(x, &vec![true; n], &mut jac);
    let mut dense = vec![vec![0.0; 2 * n]; 2 * n];
    for t in &jac {
        dense[t.row as usize][t.col as usize] += t.value;
    }
    let h = 1e-6;
    let (mut force, mut jacobian, mut asymmetry) = (0.0f64, 0.0f64, 0.0f64);
    for node in 0..n {
        for c in 0..2 {
            let (mut xp, mut xm) = (x.to_vec(), x.to_vec());
            xp[node][c] += h;
            xm[node][c] -= h;
            let de = (model.energy(&xp).unwrap() - model.energy(&xm).unwrap()) / (2.0 * h);
            force = force.max((f[node][c] + de).abs() / (1.0 + de.abs()));
            let (mut fp, mut fm) = (vec![[0.0; 2]; n], vec![[0.0; 2]; n]);
            model.assemble(&xp, &mut fp, &mut k);
            model.assemble(&xm, &mut fm, &mut k);
            for m in 0..n {
                for d in 0..2 {
                    let df = (fp[m][d] - fm[m][d]) / (2.0 * h);
                    let v = dense[2 * m + d][2 * node + c];
                    jacobian = jacobian.max((v - df).abs() / (1.0 + df.abs()));
                    let sym = dense[2 * node + c][2 * m + d];
                    asymmetry = asymmetry.max((v - sym).abs() / (1.0 + v.abs()));
                }
            }
        }
    }
    (force, jacobian, asymmetry)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// The force is minus the energy's gradient and the Jacobian the force's derivative
        /// (central differences), symmetric.
        #[test]
        fn force_and_jacobian_are_the_energy_derivatives(
            a in prop::array::uniform2(-1.0f64..1.0),
            b in prop::array::uniform2(-1.0f64..1.0),
            rest in 0.1f64..2.0,
            weight in 0.1f64..10.0,
        ) {
            let x = vec![a, b];
            prop_assume!(((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt() > 0.05);
            let spring = [BalanceSpring::Length(LengthSpring { ends: [0, 1], rest, weight })];
            let (force, jacobian, asymmetry) = derivative_errors(&spring, &x);
            prop_assert!(force < 1e-5 && jacobian < 1e-4, "{force} {jacobian}");
            prop_assert!(asymmetry < 1e-12, "{asymmetry}");
        }
    }

    /// The dense matrix of `springs`' Jacobian at `x` (exact or convex), its entries' count
    /// and its largest eigenvalue.
    fn largest_eigenvalue(
        springs: &[BalanceSpring],
        x: &[[f64; 2]],
        convex: bool,
    ) -> (Vec<(u32, u32)>, f64) {
        let params = SpringParams::default();
        let model = SpringList {
            springs,
            params: &params,
        };
        let mut t = Vec::new();
        let movable = vec![true; x.len()];
        if convex {
            model.convex_jacobian(x, &movable, &mut t);
        } else {
            crate::ForceModel::jacobian(&model, x, &movable, &mut t);
        }
        let n = 2 * x.len();
        let mut m = nalgebra::DMatrix::<f64>::zeros(n, n);
        t.iter()
            .for_each(|e| m[(e.row as usize, e.col as usize)] += e.value);
        let scale = m.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        let top = m
            .symmetric_eigenvalues()
            .iter()
            .fold(f64::MIN, |a, &v| a.max(v));
        (t.iter().map(|e| (e.row, e.col)).collect(), top / scale)
    }

    /// A unit square held by its corner triangles and its jumps, and a triangle beside it
    /// (nodes 1, 4, 2), at rest on five nodes.
    fn quad_and_triangle() -> [BalanceSpring; 2] {
        let rest = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [2.0, 0.5]];
        let law = crate::ShapeLaw::default();
        let quad = [0u32, 1, 2, 3];
        let shapes = crate::shape_springs([&quad[..]], &rest, law, &[1.0]).unwrap();
        let triangle = crate::ShapeSpring::at_rest([1, 4, 2], &rest, 2.0, law).unwrap();
        [
            BalanceSpring::Quad(Box::new(
                crate::QuadSpring::new(
                    quad,
                    [shapes[0], shapes[1], shapes[2], shapes[3]],
                    Some(5.0),
                )
                .unwrap(),
            )),
            BalanceSpring::Shape(Box::new(triangle)),
        ]
    }

    /// Where the exact Jacobian of a quadrilateral, a triangle and a compressed edge is not
    /// negative semidefinite (the energy's Hessian indefinite), the convex one is, with the
    /// same entries.
    #[test]
    fn the_convex_jacobian_is_negative_semidefinite_with_the_same_entries() {
        let [quad, triangle] = quad_and_triangle();
        let springs = [
            quad,
            triangle,
            BalanceSpring::Length(LengthSpring {
                ends: [0, 4],
                rest: 2.06,
                weight: 3.0,
            }),
        ];
        // the quadrilateral sheared and squeezed, the edge compressed
        let x = [[0.0, 0.0], [1.0, 0.0], [1.6, 0.5], [0.7, 0.6], [1.5, 0.3]];
        let (exact_entries, exact) = largest_eigenvalue(&springs, &x, false);
        let (convex_entries, convex) = largest_eigenvalue(&springs, &x, true);
        assert!(
            exact > 1e-3,
            "the exact Jacobian is already semidefinite: {exact}"
        );
        assert!(convex < 1e-12, "{convex}");
        assert_eq!(exact_entries, convex_entries);
    }

    /// The lower Jacobian is the full one's entries on and below the diagonal, in order, for
    /// the exact and the convex Hessian, with some nodes held.
    #[test]
    fn the_lower_jacobian_is_the_lower_triangle_of_the_full_one() {
        let [quad, triangle] = quad_and_triangle();
        let springs = [
            quad,
            triangle,
            BalanceSpring::Corner(crate::CornerSpring {
                nodes: [0, 1, 4],
                rest: 0.3,
                weight: 2.0,
            }),
        ];
        let params = SpringParams::default();
        let model = SpringList {
            springs: &springs,
            params: &params,
        };
        let x = [[0.0, 0.0], [1.0, 0.0], [1.6, 0.5], [0.7, 0.6], [1.5, 0.3]];
        let movable = [true, false, true, true, true];
        for convex in [false, true] {
            let mut full = Vec::new();
            if convex {
                model.convex_jacobian(&x, &movable, &mut full);
            } else {
                crate::ForceModel::jacobian(&model, &x, &movable, &mut full);
            }
            full.retain(|t| t.row >= t.col);
            let mut lower = Vec::new();
            model.lower_jacobian(&x, &movable, convex, &mut |c| lower.extend_from_slice(c));
            assert!(!lower.is_empty());
            assert_eq!(lower, full, "convex {convex}");
        }
    }

    #[test]
    fn a_rest_length_edge_costs_nothing_and_pushes_nothing() {
        let s = LengthSpring {
            ends: [0, 1],
            rest: 2.0,
            weight: 3.0,
        };
        let x = [[1.0, 1.0], [1.0 + 2.0f64.sqrt(), 1.0 + 2.0f64.sqrt()]];
        assert!(s.energy(&x).unwrap() < 1e-24);
        assert_eq!(s.energy(&[[0.0, 0.0], [0.0, 0.0]]), None);
    }
}
