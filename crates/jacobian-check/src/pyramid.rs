//! The 14-node (P2) and 30-node (P3) pyramids of Gmsh (types 14 and 118): their shape
//! functions, as Gmsh defines them, and what the certified check and the volume need from them.
//!
//! Gmsh interpolates pyramids in Bergot's space (Bergot, Cohen & Duruflé, J. Sci. Comput.
//! 2010; Gmsh's `pyramidalBasis` over `BergotBasis`): in the collapsed coordinates
//! ξ̂ = ξ / (1 − ζ), η̂ = η / (1 − ζ), ζ (the pyramid is the image of the box
//! [−1, 1]² × [0, 1], its top face collapsed onto the apex), with t = 1 − ζ, the space of
//! order p is spanned by ξ̂ᵃ η̂ᵇ tᵐ ζᵏ with max(a, b) = m ≤ p and k ≤ p − m (Gmsh's
//! Legendre × Jacobi functions span the same space). At p = 2 that is 3 + 6 + 5 = 14 functions,
//! at p = 3 4 + 9 + 10 + 7 = 30, rational in (ξ, η, ζ) (ξη/(1 − ζ) among them), and they
//! contain the linear pyramid's. The Lagrange basis through Gmsh's reference nodes (corners,
//! edge nodes, face and interior nodes) is built here from that space, as Gmsh builds it.
//!
//! The Jacobian determinant is a polynomial in the collapsed coordinates (Johnen & Geuzaine,
//! "Geometrical validity of curvilinear pyramidal finite elements", J. Comput. Phys. 2015):
//! with the reduced gradient g = (∂φ/∂ξ̂ / t, ∂φ/∂η̂ / t, ∂φ/∂ζ|collapsed) — polynomial, since
//! a function with a ≥ 1 has m ≥ 1 — the gradient in (ξ, η, ζ) is (g₁, g₂, g₃ + ξ̂ g₁ + η̂ g₂),
//! a shear of g, so det J = det[Σ xᵢ ⊗ gᵢ]. Its columns have degrees (in ξ̂, η̂, ζ) at most
//! (p − 1, p, p − 1), (p, p − 1, p − 1), (p, p, p − 1), so det J has degree ≤ 3p − 1 in ξ̂
//! and η̂ and ≤ 3(p − 1) in ζ (5 and 3 at p = 2, 8 and 6 at p = 3): it is expanded in the
//! tensor Bernstein basis of those degrees on the box ([`crate::bernstein::Domain::Pyramid`]),
//! which bounds it over the whole pyramid, the limits along every ray into the apex included
//! (ζ = 1 is the apex seen from every direction). The volume ∫ det J dξ dη dζ =
//! ∫ det J · t² dξ̂ dη̂ dζ has degree ≤ 3p − 1 in each collapsed coordinate, integrated exactly
//! by (3p − 1) / 2 + 1 Gauss points per direction (3 at p = 2, 5 at p = 3).
//!
//! This module owns the high-order pyramids' bases only; certifying is [`crate::certify`]'s.

use std::sync::OnceLock;

use mesh_model::{CellType, Shape};

use crate::gauss::gauss_legendre;
use crate::linalg::invert;
use crate::matrix::{det3, matrix_from_gradients};
use crate::point::RefPoint;

/// The Bergot space of order `p`: the exponents (a, b, m, k) of ξ̂ᵃ η̂ᵇ tᵐ ζᵏ.
fn modes(p: i32) -> Vec<[i32; 4]> {
    let mut out = Vec::new();
    for m in 0..=p {
        for b in 0..=m {
            for a in 0..=m {
                if a.max(b) == m {
                    out.extend((0..=p - m).map(|k| [a, b, m, k]));
                }
            }
        }
    }
    out
}

/// `x^e`, 0 for a negative exponent (where the term's factor is 0 anyway).
fn pw(x: f64, e: i32) -> f64 {
    if e < 0 { 0.0 } else { x.powi(e) }
}

/// The collapsed coordinates (ξ̂, η̂, ζ) of a reference point; the apex is taken as
/// ξ̂ = η̂ = 0, as Gmsh takes it.
pub(crate) fn collapse(xi: RefPoint) -> RefPoint {
    let t = 1.0 - xi[2];
    if t.abs() < 1e-14 {
        [0.0, 0.0, xi[2]]
    } else {
        [xi[0] / t, xi[1] / t, xi[2]]
    }
}

/// The reference point of collapsed coordinates.
pub(crate) fn to_reference(c: RefPoint) -> RefPoint {
    let t = 1.0 - c[2];
    [c[0] * t, c[1] * t, c[2]]
}

/// Gmsh's Lagrange basis of a high-order pyramid.
#[derive(Debug)]
pub(crate) struct Bergot {
    modes: Vec<[i32; 4]>,
    /// `N_i = Σ_j coeffs[j · n + i] φ_j`, n the number of nodes.
    coeffs: Vec<f64>,
}

/// The cached basis of the pyramid of order `order` (2 or 3).
pub(crate) fn bergot(order: u8) -> &'static Bergot {
    static CACHE: [OnceLock<Bergot>; 2] = [const { OnceLock::new() }; 2];
    assert!((2..=3).contains(&order), "pyramid of order {order}");
    CACHE[order as usize - 2].get_or_init(|| {
        let modes = modes(i32::from(order));
        let n = modes.len();
        let nodes = mesh_model::reference::reference_nodes(CellType::new(Shape::Pyramid, order))
            .expect("the high-order pyramids' reference nodes");
        let mut v = vec![0.0; n * n];
        for (i, x) in nodes.iter().enumerate() {
            let c = collapse(*x);
            for (j, m) in modes.iter().enumerate() {
                v[i * n + j] = mode_value(*m, c);
            }
        }
        let coeffs = invert(&v, n).expect("unisolvent pyramid nodes");
        Bergot { modes, coeffs }
    })
}

fn mode_value([a, b, m, k]: [i32; 4], c: RefPoint) -> f64 {
    pw(c[0], a) * pw(c[1], b) * pw(1.0 - c[2], m) * pw(c[2], k)
}

/// The reduced gradient (∂/∂ξ̂ / t, ∂/∂η̂ / t, ∂/∂ζ) of a mode, polynomial in `c`.
fn mode_reduced_gradient([a, b, m, k]: [i32; 4], c: RefPoint) -> [f64; 3] {
    let (x, y, z, t) = (c[0], c[1], c[2], 1.0 - c[2]);
    let tail = pw(t, m - 1) * pw(z, k);
    let dz = pw(x, a) * pw(y, b) * (k as f64 * pw(t, m) * pw(z, k - 1) - m as f64 * tail);
    [
        a as f64 * pw(x, a - 1) * pw(y, b) * tail,
        b as f64 * pw(x, a) * pw(y, b - 1) * tail,
        dz,
    ]
}

impl Bergot {
    /// The shape functions at the reference point `xi`.
    pub(crate) fn values(&self, xi: RefPoint, values: &mut [f64]) {
        let c = collapse(xi);
        let n = self.modes.len();
        values.iter_mut().for_each(|v| *v = 0.0);
        for (j, m) in self.modes.iter().enumerate() {
            let phi = mode_value(*m, c);
            for (i, v) in values.iter_mut().enumerate() {
                *v += self.coeffs[j * n + i] * phi;
            }
        }
    }

    /// The gradients in (ξ, η, ζ) at the reference point `xi` (at the apex: the limit along
    /// the pyramid's axis).
    pub(crate) fn gradients(&self, xi: RefPoint, grads: &mut [[f64; 3]]) {
        self.collapsed_gradients(collapse(xi), grads);
    }

    /// The gradients in (ξ, η, ζ) as functions of the collapsed coordinates `c`: defined on
    /// the whole box, ζ = 1 included (the limits at the apex along the ray of (ξ̂, η̂)).
    pub(crate) fn collapsed_gradients(&self, c: RefPoint, grads: &mut [[f64; 3]]) {
        let n = self.modes.len();
        grads.iter_mut().for_each(|g| *g = [0.0; 3]);
        for (j, m) in self.modes.iter().enumerate() {
            let g = mode_reduced_gradient(*m, c);
            let d = [g[0], g[1], g[2] + c[0] * g[0] + c[1] * g[1]];
            for (i, out) in grads.iter_mut().enumerate() {
                let w = self.coeffs[j * n + i];
                for k in 0..3 {
                    out[k] += w * d[k];
                }
            }
        }
    }
}

/// The Gauss rule on the collapsed box (module docs), with the weight t² of the collapse
/// folded in, and the gradients at its points.
struct VolumeRule {
    weights: Vec<f64>,
    /// `grads[q · n + i]`, n the number of nodes.
    grads: Vec<[f64; 3]>,
}

fn volume_rule(order: u8) -> &'static VolumeRule {
    static CACHE: [OnceLock<VolumeRule>; 2] = [const { OnceLock::new() }; 2];
    CACHE[order as usize - 2].get_or_init(|| {
        let g = gauss_legendre((3 * order as usize - 1) / 2 + 1);
        let b = bergot(order);
        let n = CellType::new(Shape::Pyramid, order).node_count();
        let (mut weights, mut grads) = (Vec::new(), Vec::new());
        for &(z, wz) in &g {
            let zeta = 0.5 * (z + 1.0);
            let t = 1.0 - zeta;
            for &(y, wy) in &g {
                for &(x, wx) in &g {
                    weights.push(wx * wy * 0.5 * wz * t * t);
                    let mut q = vec![[0.0; 3]; n];
                    b.collapsed_gradients([x, y, zeta], &mut q);
                    grads.extend_from_slice(&q);
                }
            }
        }
        VolumeRule { weights, grads }
    })
}

/// The signed volume of a 14- or 30-node pyramid with node coordinates `nodes` (checked by
/// the caller), exact up to rounding (module docs).
pub(crate) fn volume(nodes: &[[f64; 3]]) -> f64 {
    let n = nodes.len();
    let order = if n == 14 { 2 } else { 3 };
    let rule = volume_rule(order);
    rule.weights
        .iter()
        .enumerate()
        .map(|(q, w)| {
            w * det3(&matrix_from_gradients(
                nodes,
                &rule.grads[q * n..(q + 1) * n],
            ))
        })
        .sum()
}
