//! The shape spring: a triangle of nodes held to the shape it had, whatever its position and
//! orientation — the conservative, smooth spring that a Newton solve can converge tightly and
//! differentiate (mesh movement's final balance and its sensitivities).
//!
//! The dissertation's springs (extrusion, neighbour, angle) are not the gradient of an energy
//! and switch on and off (the angle spring's activation, its turn at 90°), so their balance
//! is not a smooth function of where the boundary is. A shape spring stores its triangle's
//! rest shape (the inverse of its rest edge matrix `Dm`) and a weight chosen by the caller
//! (see `mesh-move`'s balance for why not simply the area); with `F = Ds·Dm⁻¹` the deformation gradient
//! of the triangle (`Ds` its current edge matrix), its energy is the symmetric Dirichlet
//! energy
//!
//! `E = w · (‖F‖² + ‖F⁻¹‖² − 4) = w · (‖F‖² (1 + 1/J²) − 4)`,  `J = det F`,
//!
//! zero for a rigid motion of the rest shape, smooth while `J > 0` and infinite as the
//! triangle flattens, so a descent never inverts a cell. The force is `−∂E/∂x` and the
//! Jacobian of the force `−∂²E/∂x²`, both in closed form (see [`ShapeSpring::add_jacobian`]):
//! symmetric, as a Cholesky factorisation wants. A quadrilateral is held by its four corner
//! triangles at half weight each, which keeps it convex.
//!
//! It owns the 2D shape spring. It does not choose which triangles to hold (the mover does)
//! nor solve ([`crate::newton`]).

use crate::active::Influence;
use crate::model::{FiniteDifference, ForceModel, Spring, SpringList, Triplet, push_block};
use crate::newton::EnergyModel;
use crate::params::SpringParams;

/// A triangle `(a, b, c)` held to its rest shape.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShapeSpring {
    /// The corners, counter-clockwise at rest.
    pub corners: [u32; 3],
    /// `Dm⁻¹`, the inverse of the rest edge matrix `[b − a, c − a]` (columns).
    pub inverse_rest: [[f64; 2]; 2],
    /// The weight of its energy (1 for a triangle cell, ½ for a quadrilateral's corner).
    pub weight: f64,
    /// Its energy density.
    pub law: ShapeLaw,
}

impl ShapeSpring {
    /// The spring of the triangle `corners` at rest at `rest` with energy weight `share`;
    /// `None` when the rest triangle is not positive.
    pub fn at_rest(
        corners: [u32; 3],
        rest: &[[f64; 2]],
        share: f64,
        law: ShapeLaw,
    ) -> Option<ShapeSpring> {
        let [a, b, c] = corners.map(|k| rest[k as usize]);
        let (e1, e2) = ([b[0] - a[0], b[1] - a[1]], [c[0] - a[0], c[1] - a[1]]);
        let det = e1[0] * e2[1] - e2[0] * e1[1];
        if det.is_nan() || det <= 0.0 || !det.is_finite() {
            return None;
        }
        // Dm = [[e1x, e2x], [e1y, e2y]]
        let inverse_rest = [[e2[1] / det, -e2[0] / det], [-e1[1] / det, e1[0] / det]];
        Some(ShapeSpring {
            corners,
            inverse_rest,
            weight: share,
            law,
        })
    }

    /// `∂F_ab/∂x_{k,a} = g_k[b]`: the rest-shape gradients of the three corners.
    pub(crate) fn gradients(&self) -> [[f64; 2]; 3] {
        let m = self.inverse_rest;
        let (g1, g2) = (m[0], m[1]);
        [[-g1[0] - g2[0], -g1[1] - g2[1]], g1, g2]
    }

    /// The deformation gradient at `positions`, row-major `[F00, F01, F10, F11]`.
    fn deformation(&self, positions: &[[f64; 2]]) -> [f64; 4] {
        let [a, b, c] = self.corners.map(|k| positions[k as usize]);
        let ds = [[b[0] - a[0], c[0] - a[0]], [b[1] - a[1], c[1] - a[1]]];
        let m = self.inverse_rest;
        let f = |r: usize, col: usize| ds[r][0] * m[0][col] + ds[r][1] * m[1][col];
        [f(0, 0), f(0, 1), f(1, 0), f(1, 1)]
    }

    /// The energy at `positions`; `None` when the triangle is flat or inverted.
    pub fn energy(&self, positions: &[[f64; 2]]) -> Option<f64> {
        let f = self.deformation(positions);
        let j = f[0] * f[3] - f[1] * f[2];
        if j.is_nan() || j <= 0.0 {
            return None;
        }
        let a: f64 = f.iter().map(|v| v * v).sum();
        Some(self.weight * self.law.value(a, j))
    }

    /// `∂E/∂f` and `∂²E/∂f²` at the deformation gradient `f` (`J > 0`), from the law's
    /// partial derivatives in `a = ‖F‖²` and `J`: with `∂a/∂f = 2f`, `∂J/∂f = c` (the
    /// cofactor), `∂²a/∂f² = 2I` and `∂²J/∂f² = K` (constant),
    /// `∇W = W_a 2f + W_J c` and
    /// `∇²W = 2 W_a I + W_J K + W_aa 4 f⊗f + 2 W_aJ (f⊗c + c⊗f) + W_JJ c⊗c`.
    fn derivatives(&self, f: &[f64; 4]) -> ([f64; 4], [[f64; 4]; 4]) {
        let j = f[0] * f[3] - f[1] * f[2];
        let a: f64 = f.iter().map(|v| v * v).sum();
        let d = self.law.partials(a, j);
        let c = [f[3], -f[2], -f[1], f[0]];
        let da = f.map(|v| 2.0 * v);
        let w = self.weight;
        let grad = std::array::from_fn(|i| w * (d.a * da[i] + d.j * c[i]));
        let mut hess = [[0.0; 4]; 4];
        for (i, row) in hess.iter_mut().enumerate() {
            for (k, h) in row.iter_mut().enumerate() {
                let identity = if i == k { 2.0 * d.a } else { 0.0 };
                *h = w
                    * (identity
                        + d.aa * da[i] * da[k]
                        + d.aj * (da[i] * c[k] + c[i] * da[k])
                        + d.jj * c[i] * c[k]);
            }
        }
        // ∂²J/∂f²: J = F00·F11 − F01·F10
        let wj = w * d.j;
        hess[0][3] += wj;
        hess[3][0] += wj;
        hess[1][2] -= wj;
        hess[2][1] -= wj;
        (grad, hess)
    }
}

/// `det F > 0` (false for NaN).
fn positive(f: &[f64; 4]) -> bool {
    f[0] * f[3] - f[1] * f[2] > 0.0
}

/// The partial derivatives of an energy density `W(a, J)`.
#[derive(Debug, Clone, Copy)]
struct Partials {
    a: f64,
    j: f64,
    aa: f64,
    aj: f64,
    jj: f64,
}

/// The energy density of a shape spring as a function of `a = ‖F‖²` and `J = det F`: a
/// power of the conformal distortion `K = a / 2J` (1 for a similar copy of the rest shape,
/// growing as its angles change: the scaled Jacobian's ratio is what the mover is judged
/// by) plus a size term `J + 1/J` (2 at rest size). The exponent stresses the worst cells:
/// with 1 every cell's distortion counts alike (an even spread is the balance), with larger
/// ones the balance leans towards the smallest largest distortion. Both terms are infinite
/// as `J → 0`. The default, `p = 8` and `s = 0.05`, was measured on the moved NACA0012 and
/// 30P30N meshes (worst-cell ratio of the moved mesh): against `p = 4, s = 0.25` it gives
/// 0.770 for 0.733 at a 90° pitch and 0.856/0.867 for 0.820/0.816 on the 30P30N flap turned
/// ±10°, the same at 10° and 30° (`p = 12` or `16`: within 0.02 either way). It has no term
/// against compression alone: one lifts the edge ratios but lowers others and slows the large
/// turns (measured in `docs/movement.md`, *Measured*).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShapeLaw {
    /// The exponent `p ≥ 1` of `K`.
    pub exponent: f64,
    /// The weight of the size term.
    pub size: f64,
}

impl Default for ShapeLaw {
    fn default() -> Self {
        ShapeLaw {
            exponent: 8.0,
            size: 0.05,
        }
    }
}

/// `k^e`, by multiplications when `e` is a small integer (the default law's 4, 3, 2: `powf`
/// was the largest single cost of a Newton step's assembly).
fn power(k: f64, e: f64) -> f64 {
    if e == e.trunc() && e.abs() <= 16.0 {
        k.powi(e as i32)
    } else {
        k.powf(e)
    }
}

impl ShapeLaw {
    /// `W(a, J) = K^p + s (J + 1/J) − (1 + 2s)`, zero for a rigid motion of the rest shape.
    fn value(&self, a: f64, j: f64) -> f64 {
        let k = a / (2.0 * j);
        power(k, self.exponent) + self.size * (j + 1.0 / j) - (1.0 + 2.0 * self.size)
    }

    fn partials(&self, a: f64, j: f64) -> Partials {
        let (p, s) = (self.exponent, self.size);
        let k = a / (2.0 * j);
        // K's own partials
        let (ka, kj) = (1.0 / (2.0 * j), -k / j);
        let (kaj, kjj) = (-1.0 / (2.0 * j * j), 2.0 * k / (j * j));
        let (w1, w2) = (p * power(k, p - 1.0), p * (p - 1.0) * power(k, p - 2.0));
        Partials {
            a: w1 * ka,
            j: w1 * kj + s * (1.0 - 1.0 / (j * j)),
            aa: w2 * ka * ka,
            aj: w2 * ka * kj + w1 * kaj,
            jj: w2 * kj * kj + w1 * kjj + 2.0 * s / (j * j * j),
        }
    }
}

impl Spring<2> for ShapeSpring {
    fn reads(&self, out: &mut Vec<u32>) {
        out.extend(self.corners);
    }

    fn pushes(&self, out: &mut Vec<u32>) {
        out.extend(self.corners);
    }

    /// The force `−∂E/∂x` on each corner; a flat or inverted triangle pushes nothing (its
    /// energy is infinite: a solver must not go there). The stiffness is the diagonal of the
    /// rest Hessian.
    fn add_force(
        &self,
        _: &SpringParams,
        positions: &[[f64; 2]],
        force: &mut [[f64; 2]],
        stiffness: &mut [f64],
    ) {
        let f = self.deformation(positions);
        if !positive(&f) {
            return;
        }
        let (grad, _) = self.derivatives(&f);
        for (k, gk) in self.gradients().iter().enumerate() {
            let node = self.corners[k] as usize;
            for (a, fa) in force[node].iter_mut().enumerate() {
                *fa -= grad[2 * a] * gk[0] + grad[2 * a + 1] * gk[1];
            }
            stiffness[node] += 8.0 * self.weight * (gk[0] * gk[0] + gk[1] * gk[1]);
        }
    }

    /// `∂F/∂x = −Bᵀ (∂²E/∂f²) B` with `B = ∂f/∂x` (constant: `f` is linear in the corners),
    /// in closed form.
    fn add_jacobian(
        &self,
        _: &SpringParams,
        movable: &[bool],
        fd: &mut FiniteDifference<2>,
        out: &mut Vec<Triplet>,
    ) {
        self.push_jacobian(fd.positions(), false, movable, out);
    }

    /// The Jacobian of the energy's Hessian with its negative curvature dropped
    /// (`ShapeSpring::convex_hessian`).
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

impl ShapeSpring {
    /// Appends its Jacobian at `x` over the movable corners (`convex`: of the convex Hessian);
    /// nothing when the triangle is flat or inverted.
    fn push_jacobian(
        &self,
        x: &[[f64; 2]],
        convex: bool,
        movable: &[bool],
        out: &mut Vec<Triplet>,
    ) {
        if let Some(block) = self.jacobian_block(x, convex) {
            push_block(&self.corners, movable, out, |i, j| block[i][j]);
        }
    }

    /// Its Jacobian at `x` as a 6 × 6 block over its corners (row `2k + a`: corner `k`'s
    /// axis `a`), `−Bᵀ h B` with `h` the energy's Hessian in `f` (`convex`: its convex
    /// part); `None` when the triangle is flat or inverted.
    pub(crate) fn jacobian_block(&self, x: &[[f64; 2]], convex: bool) -> Option<[[f64; 6]; 6]> {
        let f = self.deformation(x);
        if !positive(&f) {
            return None;
        }
        let (_, h) = self.derivatives(&f);
        let h = if convex {
            self.convex_hessian(&f, h)
        } else {
            h
        };
        let g = self.gradients();
        let mut block = [[0.0; 6]; 6];
        for k in 0..3 {
            for m in 0..3 {
                for a in 0..2 {
                    for b in 0..2 {
                        // Σ_{c,d} H[(a,c),(b,d)] g_k[c] g_m[d]
                        let mut v = 0.0;
                        for c in 0..2 {
                            for d in 0..2 {
                                v += h[2 * a + c][2 * b + d] * g[k][c] * g[m][d];
                            }
                        }
                        block[2 * k + a][2 * m + b] = -v;
                    }
                }
            }
        }
        Some(block)
    }

    /// `h`, the energy's Hessian in `f` at `f` (`J > 0`), with its negative eigenvalues
    /// dropped: positive semidefinite, so that far from the balance a Newton step is a
    /// descent direction without shifting the whole matrix's diagonal.
    ///
    /// The energy depends on `F` through `a = ‖F‖²` and `J` only, so with `F = U Σ Vᵀ` (`U`,
    /// `V` rotations) its Hessian's eigenvectors are known (Smith, de Goes & Kim 2019,
    /// *Analytic eigensystems for isotropic distortion energies*, in 2D): the twist
    /// `U [[0, −1], [1, 0]] Vᵀ/√2` with eigenvalue `2W_a + W_J`, the flip `U [[0, 1], [1, 0]]
    /// Vᵀ/√2` with `2W_a − W_J` (along either, `a` grows by `2ε²` and `J` by `±ε²`, the first
    /// derivatives vanish), and in the plane of `U diag(c, s) Vᵀ` the 2 × 2 Hessian of
    /// `Ψ(σ₁, σ₂) = W(σ₁² + σ₂², σ₁σ₂)`.
    pub(crate) fn convex_hessian(&self, f: &[f64; 4], mut h: [[f64; 4]; 4]) -> [[f64; 4]; 4] {
        // the eigenvalues first, from a and J alone: most triangles of a step have none
        // negative, and the eigenvectors' decomposition (trigonometric) is then not needed
        let a: f64 = f.iter().map(|v| v * v).sum();
        let j = f[0] * f[3] - f[1] * f[2];
        let s1 = (0.5 * (a + (a * a - 4.0 * j * j).max(0.0).sqrt())).sqrt();
        let d = self.law.partials(a, j);
        let (_, least) = scaling_block(&d, [s1, j / s1]);
        if 2.0 * d.a - d.j.abs() >= 0.0 && least >= 0.0 {
            return h;
        }
        for (lambda, v) in self.eigensystem(f) {
            if lambda < 0.0 {
                for (i, row) in h.iter_mut().enumerate() {
                    for (k, e) in row.iter_mut().enumerate() {
                        *e -= lambda * v[i] * v[k];
                    }
                }
            }
        }
        h
    }

    /// The eigenvalues and unit eigenvectors of the energy's Hessian in `f` at `f`
    /// ([`ShapeSpring::convex_hessian`]).
    fn eigensystem(&self, f: &[f64; 4]) -> [(f64, [f64; 4]); 4] {
        let (u, s, vt) = svd2(f);
        let d = self.law.partials(s[0] * s[0] + s[1] * s[1], s[0] * s[1]);
        let w = self.weight;
        // the mode U·m·Vᵀ (m row-major) as a vector in f
        let mode = |m: [f64; 4]| -> [f64; 4] {
            let um = [
                u[0] * m[0] + u[1] * m[2],
                u[0] * m[1] + u[1] * m[3],
                u[2] * m[0] + u[3] * m[2],
                u[2] * m[1] + u[3] * m[3],
            ];
            [
                um[0] * vt[0] + um[1] * vt[2],
                um[0] * vt[1] + um[1] * vt[3],
                um[2] * vt[0] + um[3] * vt[2],
                um[2] * vt[1] + um[3] * vt[3],
            ]
        };
        let half = std::f64::consts::FRAC_1_SQRT_2;
        let (twist, flip) = (
            (w * (2.0 * d.a + d.j), mode([0.0, -half, half, 0.0])),
            (w * (2.0 * d.a - d.j), mode([0.0, half, half, 0.0])),
        );
        let ((largest, least), angle) = (scaling_block(&d, s), scaling_angle(&d, s));
        let (sn, cs) = angle.sin_cos();
        [
            twist,
            flip,
            (w * largest, mode([cs, 0.0, 0.0, sn])),
            (w * least, mode([-sn, 0.0, 0.0, cs])),
        ]
    }
}

/// The Hessian of `Ψ(σ₁, σ₂) = W(σ₁² + σ₂², σ₁σ₂)` in the singular values `s`, from `W`'s
/// partials `d`, as `[p11, p22, p12]`.
fn scaling_hessian(d: &Partials, s: [f64; 2]) -> [f64; 3] {
    let (s1, s2) = (s[0], s[1]);
    let p11 = 2.0 * d.a + 4.0 * s1 * s1 * d.aa + 4.0 * s1 * s2 * d.aj + s2 * s2 * d.jj;
    let p22 = 2.0 * d.a + 4.0 * s2 * s2 * d.aa + 4.0 * s1 * s2 * d.aj + s1 * s1 * d.jj;
    let p12 = 4.0 * s1 * s2 * d.aa + 2.0 * (s1 * s1 + s2 * s2) * d.aj + s1 * s2 * d.jj + d.j;
    [p11, p22, p12]
}

/// The two eigenvalues of [`scaling_hessian`], largest first.
fn scaling_block(d: &Partials, s: [f64; 2]) -> (f64, f64) {
    let [p11, p22, p12] = scaling_hessian(d, s);
    let (mean, radius) = (0.5 * (p11 + p22), (0.5 * (p11 - p22)).hypot(p12));
    (mean + radius, mean - radius)
}

/// The angle of the largest eigenvalue's eigenvector `(cos, sin)` of [`scaling_hessian`].
fn scaling_angle(d: &Partials, s: [f64; 2]) -> f64 {
    let [p11, p22, p12] = scaling_hessian(d, s);
    0.5 * p12.atan2(0.5 * (p11 - p22))
}

/// The singular value decomposition `F = U diag(σ₁, σ₂) Vᵀ` of a 2 × 2 matrix with
/// `det F > 0` (row-major), `U` and `Vᵀ` rotations, as `(U, [σ₁, σ₂], Vᵀ)`.
fn svd2(f: &[f64; 4]) -> ([f64; 4], [f64; 2], [f64; 4]) {
    let (e, fq) = (0.5 * (f[0] + f[3]), 0.5 * (f[0] - f[3]));
    let (g, h) = (0.5 * (f[2] + f[1]), 0.5 * (f[2] - f[1]));
    let (q, r) = (e.hypot(h), fq.hypot(g));
    let (a1, a2) = (g.atan2(fq), h.atan2(e));
    let (theta, phi) = (0.5 * (a2 - a1), 0.5 * (a2 + a1));
    let rot = |t: f64| {
        let (s, c) = t.sin_cos();
        [c, -s, s, c]
    };
    (rot(phi), [q + r, q - r], rot(theta))
}

impl EnergyModel<2> for SpringList<'_, ShapeSpring> {
    fn energy(&self, positions: &[[f64; 2]]) -> Option<f64> {
        self.springs.iter().map(|s| s.energy(positions)).sum()
    }
}

/// The shape springs holding every cell of a 2D linear mesh given by its cells' corners
/// (counter-clockwise triangles and quadrilaterals) to its shape at `rest`, cell `c` with
/// energy weight `weight[c]`: a triangle by itself, a quadrilateral by its four corner
/// triangles at half weight. `None` when a cell is not positive at rest (or has another
/// corner count).
pub fn shape_springs<'c>(
    cells: impl IntoIterator<Item = &'c [u32]>,
    rest: &[[f64; 2]],
    law: ShapeLaw,
    weight: &[f64],
) -> Option<Vec<ShapeSpring>> {
    let mut out = Vec::new();
    for (c, &w) in cells.into_iter().zip(weight) {
        let triangles = corner_triangles(c.len())?;
        // a triangle at its weight, a quadrilateral's four corners at half
        let share = if c.len() == 3 { w } else { 0.5 * w };
        for t in triangles {
            let corners = t.map(|i| c[i]);
            out.push(ShapeSpring::at_rest(corners, rest, share, law)?);
        }
    }
    Some(out)
}

/// A quadrilateral's corner triangles: corner `i` with its two neighbours.
pub(crate) const QUAD_CORNERS: [[usize; 3]; 4] = [[0, 1, 3], [1, 2, 0], [2, 3, 1], [3, 0, 2]];

/// The triangles a cell of `n` corners is held by, as corner positions: a triangle itself,
/// a quadrilateral its four corner triangles (each corner with its two neighbours,
/// counter-clockwise); `None` for other cells.
pub(crate) fn corner_triangles(n: usize) -> Option<&'static [[usize; 3]]> {
    match n {
        3 => Some(&[[0, 1, 2]]),
        4 => Some(&QUAD_CORNERS),
        _ => None,
    }
}

/// The influence table of shape springs over `n` nodes (every corner on every other).
pub fn shape_influence(springs: &[ShapeSpring], n: usize) -> Influence {
    SpringList {
        springs,
        params: &SpringParams::default(),
    }
    .influence(n)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn rest_area(r: &[[f64; 2]; 3]) -> f64 {
        0.5 * ((r[1][0] - r[0][0]) * (r[2][1] - r[0][1])
            - (r[2][0] - r[0][0]) * (r[1][1] - r[0][1]))
            .abs()
    }

    fn energy_at(s: &ShapeSpring, x: &[[f64; 2]]) -> f64 {
        s.energy(x).unwrap()
    }

    proptest! {
        /// The force is minus the energy's gradient, and the closed-form Jacobian is the
        /// central difference of the force.
        #[test]
        fn force_and_jacobian_are_the_energy_derivatives(
            rest in prop::array::uniform3(prop::array::uniform2(-1.0..1.0f64)),
            moved in prop::array::uniform3(prop::array::uniform2(-0.2..0.2f64)),
            exponent in 1.0..5.0f64,
            size in 0.0..1.0f64,
        ) {
            let law = ShapeLaw { exponent, size };
            let s = ShapeSpring::at_rest([0, 1, 2], &rest, 1.0, law);
            let s = match s { Some(s) => s, None => ShapeSpring::at_rest([0, 2, 1], &rest, 1.0, law).unwrap() };
            prop_assume!(rest_area(&rest) > 1e-3);
            let x: Vec<[f64; 2]> = (0..3).map(|k| [rest[k][0] + moved[k][0], rest[k][1] + moved[k][1]]).collect();
            prop_assume!(s.energy(&x).is_some_and(|e| e < 50.0));
            let _ = energy_at;
            let p = SpringParams::default();
            let (mut f, mut st) = (vec![[0.0; 2]; 3], vec![0.0; 3]);
            s.add_force(&p, &x, &mut f, &mut st);
            let h = 1e-6;
            for k in 0..3 {
                for a in 0..2 {
                    let (mut xp, mut xm) = (x.clone(), x.clone());
                    xp[k][a] += h;
                    xm[k][a] -= h;
                    let de = (energy_at(&s, &xp) - energy_at(&s, &xm)) / (2.0 * h);
                    prop_assert!((f[k][a] + de).abs() <= 1e-5 * (1.0 + de.abs()), "force {k},{a}: {} vs {}", f[k][a], -de);
                }
            }
            let mut fd = FiniteDifference::new(&x);
            let mut exact = Vec::new();
            s.add_jacobian(&p, &[true; 3], &mut fd, &mut exact);
            let mut numeric = Vec::new();
            fd.add(&s, &p, &[true; 3], &mut numeric);
            let dense = |t: &[Triplet]| {
                let mut m = [[0.0; 6]; 6];
                t.iter().for_each(|e| m[e.row as usize][e.col as usize] += e.value);
                m
            };
            let (e, n) = (dense(&exact), dense(&numeric));
            let scale = e.iter().flatten().fold(1.0f64, |m, v| m.max(v.abs()));
            for r in 0..6 {
                for c in 0..6 {
                    prop_assert!((e[r][c] - n[r][c]).abs() <= 1e-5 * scale, "J[{r}][{c}] {} vs {}", e[r][c], n[r][c]);
                    prop_assert!((e[r][c] - e[c][r]).abs() <= 1e-12 * scale, "not symmetric");
                }
            }
        }
    }

    proptest! {
        /// The analytic eigensystem is the Hessian's (`h v = λ v`, unit, orthogonal), and the
        /// convex Hessian is the Hessian with the negative eigenvalues set to zero.
        #[test]
        fn the_eigensystem_is_the_hessians_and_the_convex_part_drops_the_negative(
            f in prop::array::uniform4(-2.0..2.0f64),
            exponent in 1.0..9.0f64,
            size in 0.0..1.0f64,
        ) {
            prop_assume!(f[0] * f[3] - f[1] * f[2] > 0.05);
            let law = ShapeLaw { exponent, size };
            let s = ShapeSpring::at_rest([0, 1, 2], &[[0.0, 0.0], [1.0, 0.0], [0.3, 0.8]], 0.7, law).unwrap();
            let (_, h) = s.derivatives(&f);
            let norm = h.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
            let modes = s.eigensystem(&f);
            let apply = |m: &[[f64; 4]; 4], v: &[f64; 4]| -> [f64; 4] {
                std::array::from_fn(|i| (0..4).map(|k| m[i][k] * v[k]).sum())
            };
            for (i, (lambda, v)) in modes.iter().enumerate() {
                let hv = apply(&h, v);
                for k in 0..4 {
                    prop_assert!((hv[k] - lambda * v[k]).abs() <= 1e-9 * norm, "mode {i}: {hv:?} vs {lambda} {v:?}");
                }
                for (j, (_, w)) in modes.iter().enumerate() {
                    let dot: f64 = (0..4).map(|k| v[k] * w[k]).sum();
                    let expected = if i == j { 1.0 } else { 0.0 };
                    prop_assert!((dot - expected).abs() < 1e-12, "modes {i}, {j}: {dot}");
                }
            }
            let convex = s.convex_hessian(&f, h);
            for (lambda, v) in &modes {
                let cv = apply(&convex, v);
                for k in 0..4 {
                    prop_assert!((cv[k] - lambda.max(0.0) * v[k]).abs() <= 1e-9 * norm);
                }
            }
        }
    }

    #[test]
    fn the_svd_reconstructs_its_matrix() {
        for f in [
            [1.0, 0.2, -0.3, 0.9],
            [0.1, -2.0, 1.5, 0.05],
            [2.0, 0.0, 0.0, 2.0],
        ] {
            let (u, s, vt) = svd2(&f);
            let us = [u[0] * s[0], u[1] * s[1], u[2] * s[0], u[3] * s[1]];
            let back = [
                us[0] * vt[0] + us[1] * vt[2],
                us[0] * vt[1] + us[1] * vt[3],
                us[2] * vt[0] + us[3] * vt[2],
                us[2] * vt[1] + us[3] * vt[3],
            ];
            for k in 0..4 {
                assert!((back[k] - f[k]).abs() < 1e-12, "{f:?}: {back:?}");
            }
            assert!(s[0] >= s[1] && s[1] > 0.0);
        }
    }

    #[test]
    fn a_rigid_motion_costs_nothing_and_flattening_is_refused() {
        let rest = [[0.0, 0.0], [2.0, 0.0], [0.5, 0.1]];
        let law = ShapeLaw::default();
        let s = ShapeSpring::at_rest([0, 1, 2], &rest, 1.0, law).unwrap();
        let (c, sn) = (0.3f64.cos(), 0.3f64.sin());
        let moved: Vec<[f64; 2]> = rest
            .iter()
            .map(|p| [c * p[0] - sn * p[1] + 5.0, sn * p[0] + c * p[1] - 1.0])
            .collect();
        assert!(s.energy(&moved).unwrap().abs() < 1e-12);
        let flat = [[0.0, 0.0], [2.0, 0.0], [1.0, 0.0]];
        assert_eq!(s.energy(&flat), None);
        assert!(ShapeSpring::at_rest([0, 2, 1], &rest, 1.0, law).is_none());
    }
}
