//! A quadrilateral of the shape balance as one spring: its four corner triangles' shape
//! springs and its own jump springs ([`crate::jump::quad_jumps`]) summed.
//!
//! The parts alone give a Newton matrix 272 entries per quadrilateral (four triangles of three
//! nodes, two jumps of four), most of them repeated; summed over its four nodes they are one
//! 8 × 8 block, 64 entries. On a 30P30N move (20 000 quadrilaterals) the Jacobian's triplets,
//! the memory and the time to assemble and scatter them are what this saves; the energy, the
//! forces and the matrix are the parts' sums.
//!
//! It owns the summing. It does not choose the weights (the mover does).

use crate::jump::JumpSpring;
use crate::model::{FiniteDifference, Spring, Triplet, push_block};
use crate::params::SpringParams;
use crate::shape::{QUAD_CORNERS, ShapeLaw, ShapeSpring};

/// A quadrilateral held by its four corner triangles' shape springs and, where the mover
/// asks, its two jump springs.
///
/// It keeps only what its parts do not share: each corner triangle's rest matrix, and one
/// weight and law for all four; the parts are made from them when used (a 30P30N move's
/// 20 000 quadrilaterals kept whole, four triangles with their corners, weights and laws and
/// two jump springs with their nodes and gradients, took 12 MB of its 94 MB; now 3.6).
#[derive(Debug, Clone, PartialEq)]
pub struct QuadSpring {
    /// Its corners, counter-clockwise.
    corners: [u32; 4],
    /// `Dm⁻¹` of each corner triangle, in `QUAD_CORNERS`' order.
    inverse_rest: [[[f64; 2]; 2]; 4],
    /// Each corner triangle's energy weight.
    weight: f64,
    /// The corner triangles' energy density.
    law: ShapeLaw,
    /// The weight of its jump springs, if it has them.
    jump_weight: Option<f64>,
}

impl QuadSpring {
    /// The quadrilateral `corners` held by `shapes`, its corner triangles' shape springs (as
    /// [`crate::shape_springs`] makes them: in `QUAD_CORNERS`' order, one weight and
    /// law), and, given `jump_weight`, by its jump springs ([`crate::quad_jumps`]) with that
    /// weight. `None` when `shapes` are not so.
    pub fn new(
        corners: [u32; 4],
        shapes: [ShapeSpring; 4],
        jump_weight: Option<f64>,
    ) -> Option<QuadSpring> {
        let [first, ..] = shapes;
        let alike = shapes.iter().zip(QUAD_CORNERS).all(|(s, t)| {
            s.corners == t.map(|i| corners[i]) && s.weight == first.weight && s.law == first.law
        });
        alike.then(|| QuadSpring {
            corners,
            inverse_rest: shapes.map(|s| s.inverse_rest),
            weight: first.weight,
            law: first.law,
            jump_weight,
        })
    }

    /// Its corners, counter-clockwise.
    pub fn corners(&self) -> [u32; 4] {
        self.corners
    }

    /// Its corner triangles' shape springs.
    pub fn shapes(&self) -> [ShapeSpring; 4] {
        std::array::from_fn(|i| ShapeSpring {
            corners: QUAD_CORNERS[i].map(|k| self.corners[k]),
            inverse_rest: self.inverse_rest[i],
            weight: self.weight,
            law: self.law,
        })
    }

    /// Its jump springs, if it has them: the same as [`crate::quad_jumps`] makes from its
    /// rest corners, bit for bit (over 4 nodes instead of 6).
    pub fn jumps(&self) -> Option<[JumpSpring<4>; 2]> {
        let weight = self.jump_weight?;
        let shapes = self.shapes();
        Some([0, 1].map(|i| self.jump(i, &shapes, weight)))
    }

    /// Its jump spring `i` (0 or 1) of weight `weight`, `shapes` its corner triangles'
    /// springs. Corner triangles `i` (corners `i, i+1, i+3`) and `i + 2` (corners `i+2, i+3,
    /// i+1`) with rest gradients `g` and `h`: nodes `i, i+1, i+3, i+2`, gradients `g₀,
    /// g₁ − h₂, g₂ − h₁, −h₀` (as `JumpSpring::between` sums them).
    fn jump(&self, i: usize, shapes: &[ShapeSpring; 4], weight: f64) -> JumpSpring<4> {
        let (g, h) = (shapes[i].gradients(), shapes[i + 2].gradients());
        let q = |k: usize| self.corners[(i + k) % 4];
        let minus = |a: [f64; 2], b: [f64; 2]| [a[0] - b[0], a[1] - b[1]];
        JumpSpring {
            nodes: [q(0), q(1), q(3), q(2)],
            gradients: [
                g[0],
                minus(g[1], h[2]),
                minus(g[2], h[1]),
                [-h[0][0], -h[0][1]],
            ],
            count: 4,
            weight,
        }
    }

    /// Calls `each` with each of its parts as a spring.
    fn for_each_part(&self, mut each: impl FnMut(&dyn Spring<2>)) {
        let shapes = self.shapes();
        for s in &shapes {
            each(s);
        }
        if let Some(w) = self.jump_weight {
            for i in 0..2 {
                each(&self.jump(i, &shapes, w));
            }
        }
    }

    /// Its energy; `None` when a corner triangle is flat or inverted.
    pub fn energy(&self, x: &[[f64; 2]]) -> Option<f64> {
        let shapes = self.shapes();
        let on_shapes: Option<f64> = shapes.iter().map(|s| s.energy(x)).sum();
        let jumps: f64 = match self.jump_weight {
            Some(w) => (0..2).map(|i| self.jump(i, &shapes, w).energy(x)).sum(),
            None => 0.0,
        };
        Some(on_shapes? + jumps)
    }
}

impl Spring<2> for QuadSpring {
    fn reads(&self, out: &mut Vec<u32>) {
        out.extend(self.corners);
    }

    fn pushes(&self, out: &mut Vec<u32>) {
        out.extend(self.corners);
    }

    fn add_force(
        &self,
        params: &SpringParams,
        positions: &[[f64; 2]],
        force: &mut [[f64; 2]],
        stiffness: &mut [f64],
    ) {
        self.for_each_part(|s| s.add_force(params, positions, force, stiffness));
    }

    /// The parts' entries summed into one 8 × 8 block over the movable corners (each corner
    /// triangle's 6 × 6 block and the jumps' entries added at their corners' places).
    fn add_jacobian(
        &self,
        _: &SpringParams,
        movable: &[bool],
        fd: &mut FiniteDifference<2>,
        out: &mut Vec<Triplet>,
    ) {
        self.push_jacobian(fd.positions(), false, movable, out);
    }

    /// The block with the corner triangles' convex Hessians (the jumps' are convex).
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

impl QuadSpring {
    /// Appends its 8 × 8 block ([`Spring::add_jacobian`]); `convex`: of the corner triangles'
    /// convex Hessians.
    fn push_jacobian(
        &self,
        x: &[[f64; 2]],
        convex: bool,
        movable: &[bool],
        out: &mut Vec<Triplet>,
    ) {
        let mut block = [[0.0; 8]; 8];
        let shapes = self.shapes();
        for s in &shapes {
            let Some(part) = s.jacobian_block(x, convex) else {
                continue;
            };
            let at = s.corners.map(|k| self.corners.iter().position(|&c| c == k));
            for (k, &i) in at.iter().enumerate() {
                for (m, &j) in at.iter().enumerate() {
                    let (Some(i), Some(j)) = (i, j) else {
                        continue;
                    };
                    for a in 0..2 {
                        for b in 0..2 {
                            block[2 * i + a][2 * j + b] += part[2 * k + a][2 * m + b];
                        }
                    }
                }
            }
        }
        let jumps = self
            .jump_weight
            .map(|w| [0, 1].map(|i| self.jump(i, &shapes, w)));
        for jump in jumps.iter().flatten() {
            let at = jump
                .nodes
                .map(|k| self.corners.iter().position(|&c| c == k));
            let at = &at[..jump.count];
            for (m, &i) in at.iter().enumerate() {
                for (k, &j) in at.iter().enumerate() {
                    let (Some(i), Some(j)) = (i, j) else {
                        continue;
                    };
                    let v = jump.entry(m, k);
                    for a in 0..2 {
                        block[2 * i + a][2 * j + a] += v;
                    }
                }
            }
        }
        push_block(&self.corners, movable, out, |i, j| block[i][j]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::jump::quad_jumps;
    use crate::length::{BalanceSpring, derivative_errors};
    use crate::model::{ForceModel, SpringList};
    use crate::shape::{ShapeLaw, shape_springs};

    /// A skewed quadrilateral's spring at rest and its nodes moved off it.
    fn quad() -> (QuadSpring, Vec<[f64; 2]>, Vec<[f64; 2]>) {
        let rest = vec![[0.0, 0.0], [1.0, 0.1], [0.9, 1.0], [0.0, 1.2]];
        let corners = [0u32, 1, 2, 3];
        let law = ShapeLaw::default();
        let shapes = shape_springs([&corners[..]], &rest, law, &[1.7]).unwrap();
        let shapes = [shapes[0], shapes[1], shapes[2], shapes[3]];
        let spring = QuadSpring::new(corners, shapes, Some(30.0)).unwrap();
        let x = crate::length::nudged(&rest);
        (spring, rest, x)
    }

    /// Its parts are those the shape springs and `quad_jumps` make from its rest corners, bit
    /// for bit; shapes of another quadrilateral, weight or law are refused.
    #[test]
    fn its_parts_are_made_as_alone() {
        let (spring, rest, _) = quad();
        let corners = [0u32, 1, 2, 3];
        let law = ShapeLaw::default();
        let shapes = shape_springs([&corners[..]], &rest, law, &[1.7]).unwrap();
        assert_eq!(spring.shapes()[..], shapes[..]);
        let alone = quad_jumps(&corners, &rest, 30.0).unwrap();
        for (j, a) in spring.jumps().unwrap().iter().zip(&alone) {
            assert_eq!(
                (&j.nodes[..], &j.gradients[..], j.count, j.weight),
                (&a.nodes[..4], &a.gradients[..4], a.count, a.weight)
            );
        }
        let mut other = [shapes[0], shapes[1], shapes[2], shapes[3]];
        assert!(
            QuadSpring::new(corners, other, None)
                .unwrap()
                .jumps()
                .is_none()
        );
        other[2].weight *= 2.0;
        assert!(QuadSpring::new(corners, other, None).is_none());
        assert!(
            QuadSpring::new(
                [1, 2, 3, 0],
                [shapes[0], shapes[1], shapes[2], shapes[3]],
                None
            )
            .is_none()
        );
    }

    #[test]
    fn force_and_jacobian_are_the_energy_derivatives() {
        let (spring, _, x) = quad();
        let (force, jacobian, asymmetry) =
            derivative_errors(&[BalanceSpring::Quad(Box::new(spring))], &x);
        assert!(force < 1e-6 && jacobian < 1e-5, "{force} {jacobian}");
        assert!(asymmetry < 1e-12, "{asymmetry}");
    }

    /// Its energy, forces and matrix are its parts' sums, the matrix in 64 entries (48 with a
    /// node held).
    #[test]
    fn it_sums_its_parts() {
        let (spring, rest, x) = quad();
        let mut parts: Vec<BalanceSpring> = spring
            .shapes()
            .iter()
            .map(|&s| BalanceSpring::Shape(Box::new(s)))
            .collect();
        let alone = quad_jumps(&spring.corners(), &rest, 30.0).unwrap();
        parts.extend(alone.map(|j| BalanceSpring::Jump(Box::new(j))));
        let whole = [BalanceSpring::Quad(Box::new(spring.clone()))];
        let params = SpringParams::default();
        fn model<'a>(
            springs: &'a [BalanceSpring],
            params: &'a SpringParams,
        ) -> SpringList<'a, BalanceSpring> {
            SpringList { springs, params }
        }
        let e_parts: f64 = parts.iter().map(|s| s.energy(&x).unwrap()).sum();
        assert!((whole[0].energy(&x).unwrap() - e_parts).abs() < 1e-12 * e_parts);
        let dense = |springs: &[BalanceSpring], movable: &[bool]| {
            let mut t = Vec::new();
            model(springs, &params).jacobian(&x, movable, &mut t);
            let mut m = [[0.0; 8]; 8];
            for e in &t {
                m[e.row as usize][e.col as usize] += e.value;
            }
            (m, t.len())
        };
        let all = [true; 4];
        let ((a, n), (b, _)) = (dense(&whole, &all), dense(&parts, &all));
        assert_eq!(n, 64);
        for i in 0..8 {
            for j in 0..8 {
                assert!((a[i][j] - b[i][j]).abs() < 1e-12 * (1.0 + b[i][j].abs()));
            }
        }
        let (_, held) = dense(&whole, &[true, false, true, true]);
        assert_eq!(held, 36);
        let (mut f1, mut f2, mut k) = ([[0.0; 2]; 4], [[0.0; 2]; 4], [0.0; 4]);
        model(&whole, &params).assemble(&x, &mut f1, &mut k);
        model(&parts, &params).assemble(&x, &mut f2, &mut k);
        for (p, q) in f1.iter().zip(&f2) {
            assert!((p[0] - q[0]).abs() < 1e-12 && (p[1] - q[1]).abs() < 1e-12);
        }
    }
}
