//! Lagrange shape functions of the reference cells, in Gmsh's node order and on Gmsh's
//! reference domains: triangles and tetrahedra on the unit simplex; quadrilaterals and
//! hexahedra on [−1, 1]ⁿ; prisms on the unit triangle × [−1, 1]; pyramids on the base
//! [−1, 1]² with the apex at (0, 0, 1).
//!
//! Supported: triangles, quadrilaterals, tetrahedra, prisms and hexahedra of order 1 to 3;
//! the linear pyramid (its classical rational shape functions) and Gmsh's 14- and 30-node
//! pyramids (their rational Bergot bases, the `pyramid` module). Polynomial
//! bases are built once per type from their monomial space and reference nodes (the
//! inverse of the Vandermonde matrix) and cached.
//!
//! This module owns the reference cells only; mapping to physical space is
//! [`mod@crate::jacobian`].

use std::sync::OnceLock;

use mesh_model::{CellType, Shape};

use crate::error::JacobianError;
use crate::linalg::invert;
use crate::types::{Feature, SLOTS, slot};

pub use crate::point::RefPoint;

/// Position of a supported type in the table of types ([`crate::types`]).
fn type_index(ty: CellType) -> Result<usize, JacobianError> {
    slot(ty, Feature::ShapeFunctions)
}

/// The reference coordinates of the nodes of a cell type, in Gmsh's node order: corners,
/// then the nodes of each edge (in [`Shape::edges`] order, running from the edge's first
/// corner to its second), then face nodes, then interior nodes (the centroid of a P3
/// triangle; the centre of a P2 quadrilateral; the four nodes at ±1/3 of a P3
/// quadrilateral, counter-clockwise from (−1/3, −1/3); the quadrilateral-face centres and
/// the centre of P2 3D cells; at P3 each face's interior, a third in from its corners, and
/// the cell's: see `mesh_model::reference`).
///
/// # Errors
/// [`JacobianError::Unsupported`] for types outside the supported list (module docs).
pub fn reference_nodes(ty: CellType) -> Result<Vec<RefPoint>, JacobianError> {
    type_index(ty)?;
    Ok(mesh_model::reference::reference_nodes(ty).expect("every listed type has reference nodes"))
}

/// The monomial exponents spanning the polynomial space of a (polynomial) cell type.
fn monomials(ty: CellType) -> Vec<[u8; 3]> {
    let p = ty.order;
    let mut out = Vec::new();
    for c in 0..=p {
        for b in 0..=p {
            for a in 0..=p {
                let keep = match ty.shape {
                    Shape::Tri => c == 0 && a + b <= p,
                    Shape::Quad => c == 0,
                    Shape::Tet => a + b + c <= p,
                    Shape::Prism => a + b <= p,
                    Shape::Hex => true,
                    Shape::Line | Shape::Pyramid => false,
                };
                if keep {
                    out.push([a, b, c]);
                }
            }
        }
    }
    out
}

/// Powers 0..=3 of each coordinate of `xi`.
fn powers(xi: RefPoint) -> [[f64; 4]; 3] {
    xi.map(|x| [1.0, x, x * x, x * x * x])
}

/// A cached shape-function basis of one cell type.
#[derive(Debug)]
pub(crate) enum Basis {
    /// A polynomial Lagrange basis: `N_i = Σ_j coeffs[j·n + i] · m_j`.
    Polynomial {
        monomials: Vec<[u8; 3]>,
        coeffs: Vec<f64>,
    },
    /// The linear pyramid's rational shape functions.
    Pyramid1,
    /// The 14- or 30-node pyramid's (Bergot's space, the `pyramid` module), by order.
    Bergot(u8),
}

impl Basis {
    fn build(ty: CellType) -> Basis {
        if ty.shape == Shape::Pyramid {
            return if ty.order == 1 {
                Basis::Pyramid1
            } else {
                Basis::Bergot(ty.order)
            };
        }
        let nodes = reference_nodes(ty).expect("supported type");
        let monomials = monomials(ty);
        let n = nodes.len();
        assert_eq!(monomials.len(), n, "{ty:?}: monomial space size");
        let mut v = vec![0.0; n * n];
        for (i, x) in nodes.iter().enumerate() {
            let pw = powers(*x);
            for (j, m) in monomials.iter().enumerate() {
                v[i * n + j] = pw[0][m[0] as usize] * pw[1][m[1] as usize] * pw[2][m[2] as usize];
            }
        }
        let coeffs = invert(&v, n).expect("unisolvent reference nodes");
        Basis::Polynomial { monomials, coeffs }
    }

    /// The shape functions at `xi` into `values` (one per node).
    pub(crate) fn values(&self, xi: RefPoint, values: &mut [f64]) {
        match self {
            Basis::Polynomial { monomials, coeffs } => {
                let n = monomials.len();
                let pw = powers(xi);
                values.iter_mut().for_each(|v| *v = 0.0);
                for (j, m) in monomials.iter().enumerate() {
                    let mj = pw[0][m[0] as usize] * pw[1][m[1] as usize] * pw[2][m[2] as usize];
                    for (i, v) in values.iter_mut().enumerate() {
                        *v += coeffs[j * n + i] * mj;
                    }
                }
            }
            Basis::Pyramid1 => {
                let [u, v, w] = xi;
                let r = pyramid_ratio(u, v, w);
                for (i, c) in mesh_model::reference::corners(Shape::Pyramid)[..4]
                    .iter()
                    .enumerate()
                {
                    let (a, b) = (c[0], c[1]);
                    values[i] = 0.25 * ((1.0 - w) + a * u + b * v + a * b * r);
                }
                values[4] = w;
            }
            Basis::Bergot(order) => crate::pyramid::bergot(*order).values(xi, values),
        }
    }

    /// The gradients of the shape functions with respect to the reference coordinates.
    pub(crate) fn gradients(&self, xi: RefPoint, grads: &mut [[f64; 3]]) {
        match self {
            Basis::Polynomial { monomials, coeffs } => {
                let n = monomials.len();
                let pw = powers(xi);
                grads.iter_mut().for_each(|g| *g = [0.0; 3]);
                for (j, m) in monomials.iter().enumerate() {
                    let e = m.map(|k| k as usize);
                    let d = |k: usize| -> f64 {
                        if e[k] == 0 {
                            return 0.0;
                        }
                        let mut t = e[k] as f64 * pw[k][e[k] - 1];
                        for l in 0..3 {
                            if l != k {
                                t *= pw[l][e[l]];
                            }
                        }
                        t
                    };
                    let dm = [d(0), d(1), d(2)];
                    for (i, g) in grads.iter_mut().enumerate() {
                        let c = coeffs[j * n + i];
                        for k in 0..3 {
                            g[k] += c * dm[k];
                        }
                    }
                }
            }
            Basis::Pyramid1 => {
                let [u, v, w] = xi;
                let s = 1.0 - w;
                let (ru, rv, rw) = if s.abs() < 1e-14 {
                    (0.0, 0.0, 0.0)
                } else {
                    (v / s, u / s, u * v / (s * s))
                };
                for (i, c) in mesh_model::reference::corners(Shape::Pyramid)[..4]
                    .iter()
                    .enumerate()
                {
                    let (a, b) = (c[0], c[1]);
                    grads[i] = [
                        0.25 * (a + a * b * ru),
                        0.25 * (b + a * b * rv),
                        0.25 * (-1.0 + a * b * rw),
                    ];
                }
                grads[4] = [0.0, 0.0, 1.0];
            }
            Basis::Bergot(order) => crate::pyramid::bergot(*order).gradients(xi, grads),
        }
    }
}

/// `u·v / (1 − w)`, taken as 0 at the apex (its limit inside the pyramid).
fn pyramid_ratio(u: f64, v: f64, w: f64) -> f64 {
    let s = 1.0 - w;
    if s.abs() < 1e-14 { 0.0 } else { u * v / s }
}

/// The cached basis of a supported type.
pub(crate) fn basis(ty: CellType) -> Result<&'static Basis, JacobianError> {
    static CACHE: [OnceLock<Basis>; SLOTS] = [const { OnceLock::new() }; SLOTS];
    let i = type_index(ty)?;
    Ok(CACHE[i].get_or_init(|| Basis::build(ty)))
}

/// The values of the shape functions of `ty` at the reference point `xi`, one per node in
/// Gmsh order. They are 1 at their own node, 0 at the others, and sum to 1.
///
/// # Errors
/// [`JacobianError::Unsupported`] for types outside the supported list (module docs).
pub fn shape_functions(ty: CellType, xi: RefPoint) -> Result<Vec<f64>, JacobianError> {
    let b = basis(ty)?;
    let mut v = vec![0.0; ty.node_count()];
    b.values(xi, &mut v);
    Ok(v)
}

/// The gradients of the shape functions of `ty` with respect to the reference coordinates
/// at `xi`, one `[∂/∂ξ, ∂/∂η, ∂/∂ζ]` per node (the unused components are 0 in 2D).
///
/// # Errors
/// [`JacobianError::Unsupported`] for types outside the supported list (module docs).
pub fn shape_gradients(ty: CellType, xi: RefPoint) -> Result<Vec<[f64; 3]>, JacobianError> {
    let b = basis(ty)?;
    let mut g = vec![[0.0; 3]; ty.node_count()];
    b.gradients(xi, &mut g);
    Ok(g)
}

/// The Lagrange basis of degree `p` (1 to 3) on [0, 1] through the equally spaced points
/// `j / p`, `j = 0..=p` (in order along the line, not Gmsh's order), at `s`: the values and
/// the derivatives d/ds, one per point (entries beyond `p` are 0). The curving, the area
/// of curved boundary lines and the drawer all evaluate edges through this one basis.
pub fn equispaced_line(p: usize, s: f64) -> ([f64; 4], [f64; 4]) {
    assert!((1..=3).contains(&p), "degree {p} outside 1..=3");
    let (mut value, mut derivative) = ([0.0; 4], [0.0; 4]);
    for j in 0..=p {
        let sj = j as f64 / p as f64;
        let (mut l, mut dl) = (1.0, 0.0);
        for m in (0..=p).filter(|&m| m != j) {
            let sm = m as f64 / p as f64;
            dl = dl * (s - sm) / (sj - sm) + l / (sj - sm);
            l *= (s - sm) / (sj - sm);
        }
        value[j] = l;
        derivative[j] = dl;
    }
    (value, derivative)
}
