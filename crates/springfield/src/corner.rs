//! The corner spring of the shape balance: the angle a layer's extrusion edge makes with its
//! wall held.
//!
//! A shape spring ([`crate::shape`]) holds a thin wall cell to its shape, and a
//! [`crate::LengthSpring`] its height; when the wall stretches under it (a scaled body) the
//! two disagree on the cell's aspect, and the balance settles by shearing the cells where
//! the wall's columns meet a corner's fan (a 1.5× scale turned the first layer's edges at a
//! blunt trailing edge by 6.6°). A solver's wall treatment wants those edges where they were
//! relative to the wall. A [`CornerSpring`] holds the angle `θ` at a node between two edges
//! (a wall facet and an extrusion edge) with the energy `w (θ − θ₀)²`, zero under any
//! rigid motion or scaling, in closed form with its exact Hessian and its Gauss–Newton part
//! (the convex one).
//!
//! It owns this spring. It does not choose the corners nor the weights (the mover does).

use crate::model::{FiniteDifference, Spring, Triplet, push_block};
use crate::params::SpringParams;

/// The angle at `nodes[1]` from the edge to `nodes[0]` to the edge to `nodes[2]`
/// (counter-clockwise positive) held to `rest` with energy `w (θ − rest)²`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CornerSpring {
    /// The first edge's far end, the corner, the second edge's far end.
    pub nodes: [u32; 3],
    /// Its rest angle, radians.
    pub rest: f64,
    /// The weight `w` of its energy.
    pub weight: f64,
}

/// `φ(v) = atan2(v_y, v_x)`'s gradient and Hessian.
fn polar_derivatives(v: [f64; 2]) -> ([f64; 2], [[f64; 2]; 2]) {
    let r2 = v[0] * v[0] + v[1] * v[1];
    let r4 = r2 * r2;
    let g = [-v[1] / r2, v[0] / r2];
    let off = (v[1] * v[1] - v[0] * v[0]) / r4;
    let h = [
        [2.0 * v[0] * v[1] / r4, off],
        [off, -2.0 * v[0] * v[1] / r4],
    ];
    (g, h)
}

/// The angle's change `θ − rest`, wrapped to (−π, π], its gradient over the three nodes and
/// its Hessian (3 × 3 blocks of 2 × 2).
type AngleDerivatives = (f64, [[f64; 2]; 3], [[[[f64; 2]; 2]; 3]; 3]);

impl CornerSpring {
    /// The corner's two edge vectors; `None` when either has collapsed or is not finite.
    fn edges(&self, x: &[[f64; 2]]) -> Option<([f64; 2], [f64; 2])> {
        let [a, b, c] = self.nodes.map(|k| x[k as usize]);
        let u = [a[0] - b[0], a[1] - b[1]];
        let v = [c[0] - b[0], c[1] - b[1]];
        let ok = |e: [f64; 2]| {
            let l = e[0] * e[0] + e[1] * e[1];
            l > 0.0 && l.is_finite()
        };
        (ok(u) && ok(v)).then_some((u, v))
    }

    /// `θ − rest` wrapped to (−π, π]; `None` when an edge has collapsed.
    fn change(&self, x: &[[f64; 2]]) -> Option<f64> {
        let (u, v) = self.edges(x)?;
        let theta = (u[0] * v[1] - u[1] * v[0]).atan2(u[0] * v[0] + u[1] * v[1]);
        let d = theta - self.rest;
        Some(d - std::f64::consts::TAU * (d / std::f64::consts::TAU).round())
    }

    /// Its energy; `None` when an edge has collapsed.
    pub fn energy(&self, x: &[[f64; 2]]) -> Option<f64> {
        let d = self.change(x)?;
        Some(self.weight * d * d)
    }

    /// `θ = φ(c − b) − φ(a − b)`: its change, gradient and Hessian.
    fn angle_derivatives(&self, x: &[[f64; 2]]) -> Option<AngleDerivatives> {
        let (u, v) = self.edges(x)?;
        let d = self.change(x)?;
        let (gu, hu) = polar_derivatives(u);
        let (gv, hv) = polar_derivatives(v);
        let grad = [
            [-gu[0], -gu[1]],
            [gu[0] - gv[0], gu[1] - gv[1]],
            [gv[0], gv[1]],
        ];
        let mut hess = [[[[0.0; 2]; 2]; 3]; 3];
        for i in 0..2 {
            for j in 0..2 {
                hess[0][0][i][j] = -hu[i][j];
                hess[0][1][i][j] = hu[i][j];
                hess[1][0][i][j] = hu[i][j];
                hess[1][1][i][j] = hv[i][j] - hu[i][j];
                hess[1][2][i][j] = -hv[i][j];
                hess[2][1][i][j] = -hv[i][j];
                hess[2][2][i][j] = hv[i][j];
            }
        }
        Some((d, grad, hess))
    }

    /// Appends its Jacobian `−∂²E/∂x²` at `x` over the movable nodes: `2w (∇θ ∇θᵀ + (θ −
    /// θ₀) ∇²θ)`, without the second term when `convex` (its Gauss–Newton part, positive
    /// semidefinite).
    fn push_jacobian(
        &self,
        x: &[[f64; 2]],
        convex: bool,
        movable: &[bool],
        out: &mut Vec<Triplet>,
    ) {
        let Some((d, g, h)) = self.angle_derivatives(x) else {
            return;
        };
        let curvature = if convex { 0.0 } else { d };
        let w2 = 2.0 * self.weight;
        push_block(&self.nodes, movable, out, |i, j| {
            let ((p, a), (q, b)) = ((i / 2, i % 2), (j / 2, j % 2));
            -w2 * (g[p][a] * g[q][b] + curvature * h[p][q][a][b])
        });
    }
}

impl Spring<2> for CornerSpring {
    fn reads(&self, out: &mut Vec<u32>) {
        out.extend(self.nodes);
    }

    fn pushes(&self, out: &mut Vec<u32>) {
        out.extend(self.nodes);
    }

    /// The force `−2w (θ − θ₀) ∇θ` on the three nodes; the stiffness is the Gauss–Newton
    /// diagonal `2w |∇θ|²` of each.
    fn add_force(
        &self,
        _: &SpringParams,
        positions: &[[f64; 2]],
        force: &mut [[f64; 2]],
        stiffness: &mut [f64],
    ) {
        let Some((d, g, _)) = self.angle_derivatives(positions) else {
            return;
        };
        let w2 = 2.0 * self.weight;
        for (k, &n) in self.nodes.iter().enumerate() {
            force[n as usize][0] -= w2 * d * g[k][0];
            force[n as usize][1] -= w2 * d * g[k][1];
            stiffness[n as usize] += w2 * (g[k][0] * g[k][0] + g[k][1] * g[k][1]);
        }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::BalanceSpring;
    use crate::length::derivative_errors;
    use proptest::prelude::*;

    proptest! {
        /// The force is minus the energy's gradient and the Jacobian the force's derivative
        /// (central differences), symmetric.
        #[test]
        fn force_and_jacobian_are_the_energy_derivatives(
            a in prop::array::uniform2(-1.0f64..1.0),
            b in prop::array::uniform2(-1.0f64..1.0),
            c in prop::array::uniform2(-1.0f64..1.0),
            rest in -3.0f64..3.0,
            weight in 0.1f64..10.0,
        ) {
            let len = |p: [f64; 2], q: [f64; 2]| (p[0] - q[0]).hypot(p[1] - q[1]);
            prop_assume!(len(a, b) > 0.2 && len(c, b) > 0.2);
            let spring = CornerSpring { nodes: [0, 1, 2], rest, weight };
            // away from the wrap at θ − θ₀ = ±π, where the energy jumps
            prop_assume!(spring.change(&[a, b, c]).unwrap().abs() < 3.0);
            let (force, jacobian, asymmetry) =
                derivative_errors(&[BalanceSpring::Corner(spring)], &[a, b, c]);
            prop_assert!(force < 1e-5 && jacobian < 1e-4, "{force} {jacobian}");
            prop_assert!(asymmetry < 1e-12, "{asymmetry}");
        }

        /// Any rotation, scaling and translation of the rest corner costs nothing.
        #[test]
        fn a_similar_corner_costs_nothing(
            turn in -3.1f64..3.1,
            scale in 0.1f64..10.0,
            shift in prop::array::uniform2(-5.0f64..5.0),
        ) {
            let rest = [[1.0, 0.2], [0.0, 0.0], [-0.3, 1.0]];
            let spring = CornerSpring {
                nodes: [0, 1, 2],
                rest: (1.0f64).atan2(-0.3) - (0.2f64).atan2(1.0),
                weight: 3.0,
            };
            let (s, c) = turn.sin_cos();
            let moved: Vec<[f64; 2]> = rest
                .iter()
                .map(|p| [scale * (c * p[0] - s * p[1]) + shift[0], scale * (s * p[0] + c * p[1]) + shift[1]])
                .collect();
            prop_assert!(spring.energy(&moved).unwrap() < 1e-24);
        }
    }

    #[test]
    fn a_collapsed_edge_has_no_energy() {
        let s = CornerSpring {
            nodes: [0, 1, 2],
            rest: 1.0,
            weight: 1.0,
        };
        assert_eq!(s.energy(&[[0.0, 0.0], [0.0, 0.0], [1.0, 1.0]]), None);
    }
}
