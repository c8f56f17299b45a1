//! The jump spring of the shape balance: two triangles held to deform alike.
//!
//! A quadrilateral held by its four corner triangles' shape springs ([`crate::shape`]) can
//! keep each of them nearly similar while it keystones, and its Jacobian then varies over it.
//! A [`JumpSpring`] costs the jump of the deformation gradient between two cells, `w ‖F₁ −
//! F₂‖²` (Frobenius); [`quad_jumps`] joins a quadrilateral's opposite corner triangles, so
//! what they cost is its non-affine part. `F` is linear in the nodes (`F = Σ x_k ⊗ g_k` with
//! constant rest gradients `g_k`), so the energy is a constant quadratic form: zero for any
//! affine motion, its Hessian `2w (g_m · g_n) I`.
//!
//! It owns the jump spring and a quadrilateral's pair of them. It does not choose the cells
//! nor the weights (the mover does).

use crate::model::{FiniteDifference, Spring, Triplet};
use crate::params::SpringParams;
use crate::shape::{ShapeLaw, ShapeSpring, corner_triangles};

/// The most nodes of a pair of cells sharing an edge (two quadrilaterals).
pub const JUMP_NODES: usize = 6;

/// Two cells sharing an edge held to the same deformation gradient, over at most `N` nodes
/// (a quadrilateral's own pair: 4).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JumpSpring<const N: usize = JUMP_NODES> {
    /// The nodes of both cells (`count` of them).
    pub nodes: [u32; N],
    /// `g_k`: `F₁ − F₂ = Σ x_k ⊗ g_k` over the nodes.
    pub gradients: [[f64; 2]; N],
    /// How many of `nodes` are used.
    pub count: usize,
    /// The weight `w` of its energy.
    pub weight: f64,
}

/// The jump springs across a quadrilateral (its `nodes`, counter-clockwise, at rest at
/// `corners`): each pair of opposite corner triangles held to the same deformation gradient,
/// with weight `weight`. Zero for any affine motion of the quadrilateral; what they cost is its
/// non-affine part (a keystone, an hourglass), which makes its Jacobian vary over it. `None`
/// when a corner triangle is not positive at rest.
pub fn quad_jumps(nodes: &[u32], corners: &[[f64; 2]], weight: f64) -> Option<[JumpSpring; 2]> {
    let triangles = corner_triangles(4)?;
    if nodes.len() != 4 || corners.len() != 4 {
        return None;
    }
    let mut own = Vec::with_capacity(4);
    for t in triangles {
        let spring = ShapeSpring::at_rest(t.map(|i| i as u32), corners, 1.0, ShapeLaw::default())?;
        own.push((t.map(|i| nodes[i]), spring.gradients()));
    }
    let pair = |a: usize, b: usize| {
        JumpSpring::between((&own[a].0, &own[a].1), (&own[b].0, &own[b].1), weight)
    };
    Some([pair(0, 2)?, pair(1, 3)?])
}

impl JumpSpring {
    /// The spring between the cells `first` and `second` (their corners and the rest
    /// gradients of their deformation, `F = Σ x_k ⊗ g_k`) with weight `weight`.
    pub fn between(
        first: (&[u32], &[[f64; 2]]),
        second: (&[u32], &[[f64; 2]]),
        weight: f64,
    ) -> Option<JumpSpring> {
        let mut spring = JumpSpring {
            nodes: [u32::MAX; JUMP_NODES],
            gradients: [[0.0; 2]; JUMP_NODES],
            count: 0,
            weight,
        };
        for ((nodes, grads), sign) in [(first, 1.0), (second, -1.0)] {
            for (&k, g) in nodes.iter().zip(grads) {
                let slot = match spring.nodes[..spring.count].iter().position(|&m| m == k) {
                    Some(s) => s,
                    None if spring.count < JUMP_NODES => {
                        spring.nodes[spring.count] = k;
                        spring.count += 1;
                        spring.count - 1
                    }
                    None => return None,
                };
                let own = &mut spring.gradients[slot];
                own[0] += sign * g[0];
                own[1] += sign * g[1];
            }
        }
        Some(spring)
    }
}

impl<const N: usize> JumpSpring<N> {
    /// `F₁ − F₂` at `x`, row-major.
    fn jump(&self, x: &[[f64; 2]]) -> [[f64; 2]; 2] {
        let mut d = [[0.0; 2]; 2];
        for (&k, g) in self.nodes[..self.count].iter().zip(&self.gradients) {
            let p = x[k as usize];
            for (r, row) in d.iter_mut().enumerate() {
                row[0] += p[r] * g[0];
                row[1] += p[r] * g[1];
            }
        }
        d
    }

    /// Its energy `w ‖F₁ − F₂‖²`.
    pub fn energy(&self, x: &[[f64; 2]]) -> f64 {
        let d = self.jump(x);
        self.weight
            * (d[0][0] * d[0][0] + d[0][1] * d[0][1] + d[1][0] * d[1][0] + d[1][1] * d[1][1])
    }
}

impl<const N: usize> Spring<2> for JumpSpring<N> {
    fn reads(&self, out: &mut Vec<u32>) {
        out.extend(&self.nodes[..self.count]);
    }

    fn pushes(&self, out: &mut Vec<u32>) {
        out.extend(&self.nodes[..self.count]);
    }

    /// The force `−∂E/∂x_m = −2w (F₁ − F₂) g_m`; the stiffness is the Hessian's diagonal.
    fn add_force(
        &self,
        _: &SpringParams,
        positions: &[[f64; 2]],
        force: &mut [[f64; 2]],
        stiffness: &mut [f64],
    ) {
        let d = self.jump(positions);
        let w = self.weight;
        for (&k, g) in self.nodes[..self.count].iter().zip(&self.gradients) {
            let f = &mut force[k as usize];
            for (r, fr) in f.iter_mut().enumerate() {
                *fr -= 2.0 * w * (d[r][0] * g[0] + d[r][1] * g[1]);
            }
            stiffness[k as usize] += 2.0 * w * (g[0] * g[0] + g[1] * g[1]);
        }
    }

    fn add_jacobian(
        &self,
        _: &SpringParams,
        movable: &[bool],
        _: &mut FiniteDifference<2>,
        out: &mut Vec<Triplet>,
    ) {
        self.push_entries(movable, out);
    }
}

impl<const N: usize> JumpSpring<N> {
    /// `∂F_p/∂x_q` between its nodes `m` and `k` (the same on both axes, zero across them;
    /// constant: the energy is quadratic).
    pub(crate) fn entry(&self, m: usize, k: usize) -> f64 {
        let (gm, gk) = (self.gradients[m], self.gradients[k]);
        -2.0 * self.weight * (gm[0] * gk[0] + gm[1] * gk[1])
    }

    /// Appends its Jacobian over the movable nodes.
    fn push_entries(&self, movable: &[bool], out: &mut Vec<Triplet>) {
        let n = self.count;
        for (m, &p) in self.nodes[..n].iter().enumerate() {
            if !movable[p as usize] {
                continue;
            }
            for (k, &q) in self.nodes[..n].iter().enumerate() {
                if !movable[q as usize] {
                    continue;
                }
                let v = self.entry(m, k);
                for a in 0..2u32 {
                    out.push(Triplet {
                        row: 2 * p + a,
                        col: 2 * q + a,
                        value: v,
                    });
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The rest gradients of a cell's mean deformation gradient: `F = Σ x_k ⊗ g_k` over its
    /// corners (a triangle's own `F`; a quadrilateral's mean over its four corner triangles).
    /// `None` when a corner triangle is not positive at rest.
    fn cell_gradients(corners: &[[f64; 2]]) -> Option<Vec<[f64; 2]>> {
        let triangles = corner_triangles(corners.len())?;
        let share = 1.0 / triangles.len() as f64;
        let mut g = vec![[0.0; 2]; corners.len()];
        for t in triangles {
            // the shape spring of the corner triangle gives its corners' rest gradients
            let spring =
                ShapeSpring::at_rest(t.map(|i| i as u32), corners, 1.0, ShapeLaw::default())?;
            for (&k, gk) in t.iter().zip(spring.gradients()) {
                g[k][0] += share * gk[0];
                g[k][1] += share * gk[1];
            }
        }
        Some(g)
    }

    /// A quadrilateral's own jump springs cost nothing for an affine motion of it, and its
    /// keystone (one side shortened, the other kept) costs.
    #[test]
    fn a_quadrilateral_s_jumps_cost_its_non_affine_part() {
        let rest = [[0.0, 0.0], [2.0, 0.1], [2.2, 1.0], [-0.1, 1.1]];
        let nodes = [0u32, 1, 2, 3];
        let springs = quad_jumps(&nodes, &rest, 1.0).unwrap();
        let energy = |x: &[[f64; 2]]| springs.iter().map(|s| s.energy(x)).sum::<f64>();
        assert!(energy(&rest) < 1e-24);
        let affine: Vec<[f64; 2]> = rest
            .iter()
            .map(|p| {
                [
                    0.3 + 1.4 * p[0] - 0.6 * p[1],
                    -1.0 + 0.2 * p[0] + 0.7 * p[1],
                ]
            })
            .collect();
        assert!(energy(&affine) < 1e-20, "{}", energy(&affine));
        let mut keystone = rest;
        keystone[2][1] -= 0.3; // the right side shortened
        assert!(energy(&keystone) > 1e-3, "{}", energy(&keystone));
        assert!(quad_jumps(&nodes[..3], &rest[..3], 1.0).is_none());
    }

    #[test]
    fn an_affine_motion_of_two_cells_costs_nothing() {
        let rest = [
            [0.0, 0.0],
            [1.0, 0.0],
            [1.0, 1.0],
            [0.0, 1.0],
            [2.0, 0.0],
            [2.0, 1.2],
        ];
        let quad = [0u32, 1, 2, 3];
        let other = [1u32, 4, 5, 2];
        let pick = |c: &[u32]| c.iter().map(|&k| rest[k as usize]).collect::<Vec<_>>();
        let (g1, g2) = (
            cell_gradients(&pick(&quad)).unwrap(),
            cell_gradients(&pick(&other)).unwrap(),
        );
        let s = JumpSpring::between((&quad, &g1), (&other, &g2), 1.0).unwrap();
        assert_eq!(s.count, 6);
        let moved: Vec<[f64; 2]> = rest
            .iter()
            .map(|p| {
                [
                    0.3 + 0.8 * p[0] - 0.6 * p[1],
                    -1.0 + 0.6 * p[0] + 0.9 * p[1],
                ]
            })
            .collect();
        assert!(s.energy(&moved) < 1e-24);
        let mut bent = moved.clone();
        bent[5][1] += 0.1;
        assert!(s.energy(&bent) > 1e-4);
    }

    #[test]
    fn force_and_jacobian_are_the_energy_derivatives() {
        use crate::length::{BalanceSpring, derivative_errors};
        let rest = [[0.0, 0.0], [1.0, 0.1], [0.9, 1.0], [0.0, 1.2], [1.1, -0.9]];
        let quad = [0u32, 1, 2, 3];
        let tri = [0u32, 4, 1];
        let pick = |c: &[u32]| c.iter().map(|&k| rest[k as usize]).collect::<Vec<_>>();
        let (g1, g2) = (
            cell_gradients(&pick(&quad)).unwrap(),
            cell_gradients(&pick(&tri)).unwrap(),
        );
        let spring = [BalanceSpring::Jump(Box::new(
            JumpSpring::between((&quad, &g1), (&tri, &g2), 2.5).unwrap(),
        ))];
        let x = crate::length::nudged(&rest);
        let (force, jacobian, asymmetry) = derivative_errors(&spring, &x);
        assert!(force < 1e-6 && jacobian < 1e-5, "{force} {jacobian}");
        assert!(asymmetry < 1e-12, "{asymmetry}");
    }
}
