//! Bernstein (Bézier) polynomial spaces on the reference simplex, box, prism (triangle ×
//! line) and square × line (the pyramid's collapsed coordinates), in which the
//! Jacobian determinant of a cell is expanded to bound its sign (Johnen, Remacle &
//! Geuzaine 2013).
//!
//! A space of degree n holds, per type and computed once: the equispaced lattice points at
//! which the determinant is sampled; the inverse of the Bernstein–Lagrange matrix
//! `T[k][m] = B_m(lattice_k)` that turns the samples into Bernstein coefficients; and, for
//! each child of the regular subdivision (4 triangles, 8 tetrahedra, 2ᵈ boxes, 4 × 2
//! prisms), the matrix
//! that turns a region's coefficients into the child's. The child matrices give exactly
//! what the de Casteljau algorithm gives (the Bernstein coefficients of the restriction of
//! the polynomial to the child); as precomputed matrices they cost one small
//! matrix–vector product per child.
//!
//! Regions are parametrised by unit coordinates t: the unit simplex, [0, 1]ᵈ for boxes, the
//! unit triangle × [0, 1] for prisms; a [`Region`] maps them affinely into Gmsh's reference
//! coordinates.

use crate::linalg::{invert, mat_mul};
use crate::point::RefPoint;

/// The shape of a Bernstein space's domain.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Domain {
    /// The unit simplex of the dimension.
    Simplex,
    /// The unit box of the dimension (tensor-product basis, same degree per direction).
    Box,
    /// The unit triangle × [0, 1] (3D only): the triangle's Bernstein basis (of the space's
    /// degree) times the line's, of degree `axis`.
    Prism {
        /// The degree along the axis.
        axis: usize,
    },
    /// The unit square × [0, 1] (3D only): the square's tensor Bernstein basis (of the
    /// space's degree per direction) times the line's, of degree `axis`. The root region
    /// spans the pyramid's collapsed coordinates (ξ̂, η̂) ∈ [−1, 1]², ζ ∈ [0, 1].
    Pyramid {
        /// The degree along ζ.
        axis: usize,
    },
}

/// An affine map from unit coordinates to reference coordinates:
/// `x = origin + Σ_k t_k · axes[k]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Region {
    pub(crate) origin: RefPoint,
    pub(crate) axes: [RefPoint; 3],
}

impl Region {
    /// The region spanning a reference cell: the unit simplex itself, [−1, 1]ᵈ, or the unit
    /// triangle × [−1, 1].
    pub(crate) fn root(domain: Domain, dim: usize) -> Region {
        let mut axes = [[0.0; 3]; 3];
        let mut origin = [0.0; 3];
        for k in 0..dim {
            let simplex_axis = match domain {
                Domain::Simplex => true,
                Domain::Box => false,
                Domain::Prism { .. } => k < 2,
                Domain::Pyramid { .. } => k == 2,
            };
            if simplex_axis {
                axes[k][k] = 1.0;
            } else {
                axes[k][k] = 2.0;
                origin[k] = -1.0;
            }
        }
        Region { origin, axes }
    }

    /// The point at unit coordinates `t`.
    pub(crate) fn apply(&self, t: RefPoint) -> RefPoint {
        let mut x = self.origin;
        for (k, a) in self.axes.iter().enumerate() {
            for i in 0..3 {
                x[i] += t[k] * a[i];
            }
        }
        x
    }

    /// The child region `child` (given in this region's unit coordinates).
    pub(crate) fn compose(&self, child: &Region) -> Region {
        let origin = self.apply(child.origin);
        let o0 = self.apply([0.0; 3]);
        let axes = child.axes.map(|a| {
            let p = self.apply(a);
            [p[0] - o0[0], p[1] - o0[1], p[2] - o0[2]]
        });
        Region { origin, axes }
    }
}

/// A Bernstein space with its sampling lattice and subdivision matrices.
#[derive(Debug)]
pub(crate) struct Space {
    pub(crate) domain: Domain,
    pub(crate) dim: usize,
    pub(crate) degree: usize,
    /// Multi-indices: the exponents of t₁…t_d (simplex; λ₀ takes the rest) or the
    /// per-direction indices (box).
    index: Vec<[usize; 3]>,
    /// Lattice points in unit coordinates, one per coefficient.
    pub(crate) lattice_unit: Vec<RefPoint>,
    /// Indices of the coefficients at the corners of the domain (equal to the polynomial's
    /// value there).
    pub(crate) corners: Vec<usize>,
    /// Inverse of the Bernstein–Lagrange matrix (row-major, `len × len`).
    pub(crate) to_bernstein: Vec<f64>,
    /// The subdivision children: their region in unit coordinates and the matrix from the
    /// parent's coefficients to theirs.
    pub(crate) children: Vec<(Region, Vec<f64>)>,
}

fn binomial(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
}

fn factorial(n: usize) -> f64 {
    (1..=n).fold(1.0, |acc, i| acc * i as f64)
}

/// Whether the simplex multi-index `m` (of degree `n`) is a corner's.
fn simplex_corner(m: &[usize], n: usize) -> bool {
    m.iter().sum::<usize>() == 0 || m.contains(&n)
}

/// The simplex Bernstein polynomial of degree `n` and exponents `a` (λ₀ takes the rest) at `t`.
fn simplex_basis(a: &[usize], t: &[f64], n: usize) -> f64 {
    let rest = n - a.iter().sum::<usize>();
    let l0 = 1.0 - t.iter().sum::<f64>();
    let mut v = factorial(n) / factorial(rest) * l0.powi(rest as i32);
    for (&ak, &tk) in a.iter().zip(t) {
        v *= tk.powi(ak as i32) / factorial(ak);
    }
    v
}

/// The line Bernstein polynomial of degree `n` and index `a` at `t`.
fn line_basis(a: usize, t: f64, n: usize) -> f64 {
    binomial(n, a) * t.powi(a as i32) * (1.0 - t).powi((n - a) as i32)
}

impl Space {
    /// Builds the space (lattice, transformation and subdivision matrices).
    pub(crate) fn new(domain: Domain, dim: usize, degree: usize) -> Space {
        let n = degree;
        let mut index = Vec::new();
        let top = match domain {
            Domain::Prism { axis } | Domain::Pyramid { axis } => axis,
            _ if dim == 3 => n,
            _ => 0,
        };
        for c in 0..=top {
            for b in 0..=n {
                for a in 0..=n {
                    let keep = match domain {
                        Domain::Simplex => a + b + c <= n,
                        Domain::Box | Domain::Pyramid { .. } => true,
                        Domain::Prism { .. } => a + b <= n,
                    };
                    if keep {
                        index.push([a, b, c]);
                    }
                }
            }
        }
        let lattice_unit: Vec<RefPoint> = index
            .iter()
            .map(|m| {
                let at = |k: usize, of: usize, mid: f64| {
                    if of == 0 { mid } else { k as f64 / of as f64 }
                };
                if let Domain::Prism { axis } = domain {
                    [
                        at(m[0], n, 1.0 / 3.0),
                        at(m[1], n, 1.0 / 3.0),
                        at(m[2], axis, 0.5),
                    ]
                } else if let Domain::Pyramid { axis } = domain {
                    [at(m[0], n, 0.5), at(m[1], n, 0.5), at(m[2], axis, 0.5)]
                } else if n == 0 {
                    let mut t = [0.0; 3];
                    t[..dim].fill(if domain == Domain::Simplex {
                        1.0 / (dim as f64 + 1.0)
                    } else {
                        0.5
                    });
                    t
                } else {
                    m.map(|k| k as f64 / n as f64)
                }
            })
            .collect();
        let corners = index
            .iter()
            .enumerate()
            .filter(|(_, m)| match domain {
                Domain::Simplex => simplex_corner(&m[..dim], n),
                Domain::Box => m[..dim].iter().all(|&k| k == 0 || k == n),
                Domain::Prism { axis } => simplex_corner(&m[..2], n) && (m[2] == 0 || m[2] == axis),
                Domain::Pyramid { axis } => {
                    m[..2].iter().all(|&k| k == 0 || k == n) && (m[2] == 0 || m[2] == axis)
                }
            })
            .map(|(i, _)| i)
            .collect();
        let mut space = Space {
            domain,
            dim,
            degree,
            index,
            lattice_unit,
            corners,
            to_bernstein: Vec::new(),
            children: Vec::new(),
        };
        let len = space.len();
        let t = space.basis_matrix(&Region::root_unit());
        space.to_bernstein = invert(&t, len).expect("Bernstein–Lagrange matrix is invertible");
        space.children = space
            .child_regions()
            .into_iter()
            .map(|r| {
                let s = space.basis_matrix(&r);
                let m = mat_mul(&space.to_bernstein, &s, len);
                (r, m)
            })
            .collect();
        space
    }

    /// Number of coefficients.
    pub(crate) fn len(&self) -> usize {
        self.index.len()
    }

    /// `M[k][m] = B_m(region(lattice_k))` (row-major).
    fn basis_matrix(&self, region: &Region) -> Vec<f64> {
        let len = self.len();
        let mut out = vec![0.0; len * len];
        for (k, t) in self.lattice_unit.iter().enumerate() {
            let p = region.apply(*t);
            for m in 0..len {
                out[k * len + m] = self.basis(m, p);
            }
        }
        out
    }

    /// The Bernstein basis function `m` at unit coordinates `t`.
    pub(crate) fn basis(&self, m: usize, t: RefPoint) -> f64 {
        let n = self.degree;
        let a = self.index[m];
        match self.domain {
            Domain::Simplex => simplex_basis(&a[..self.dim], &t[..self.dim], n),
            Domain::Box => (0..self.dim).map(|k| line_basis(a[k], t[k], n)).product(),
            Domain::Prism { axis } => {
                simplex_basis(&a[..2], &t[..2], n) * line_basis(a[2], t[2], axis)
            }
            Domain::Pyramid { axis } => {
                line_basis(a[0], t[0], n) * line_basis(a[1], t[1], n) * line_basis(a[2], t[2], axis)
            }
        }
    }

    /// The children of the regular subdivision, in unit coordinates.
    fn child_regions(&self) -> Vec<Region> {
        let simplex = |v: &[RefPoint]| {
            let mut axes = [[0.0; 3]; 3];
            for k in 1..v.len() {
                axes[k - 1] = [0, 1, 2].map(|i| v[k][i] - v[0][i]);
            }
            Region { origin: v[0], axes }
        };
        let h = 0.5;
        let (a, b, c) = ([0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
        let (ab, bc, ca) = ([h, 0.0, 0.0], [h, h, 0.0], [0.0, h, 0.0]);
        let triangles = [
            simplex(&[a, ab, ca]),
            simplex(&[ab, b, bc]),
            simplex(&[ca, bc, c]),
            simplex(&[bc, ca, ab]),
        ];
        match (self.domain, self.dim) {
            (Domain::Simplex, 2) => triangles.to_vec(),
            (Domain::Prism { .. }, _) => [0.0, h]
                .iter()
                .flat_map(|&z| {
                    triangles.iter().map(move |t| {
                        let mut r = *t;
                        r.origin[2] = z;
                        r.axes[2] = [0.0, 0.0, h];
                        r
                    })
                })
                .collect(),
            (Domain::Simplex, _) => {
                let v = [
                    [0.0, 0.0, 0.0],
                    [1.0, 0.0, 0.0],
                    [0.0, 1.0, 0.0],
                    [0.0, 0.0, 1.0],
                ];
                let mid = |i: usize, j: usize| [0, 1, 2].map(|k| 0.5 * (v[i][k] + v[j][k]));
                let (m01, m02, m03, m12, m13, m23) = (
                    mid(0, 1),
                    mid(0, 2),
                    mid(0, 3),
                    mid(1, 2),
                    mid(1, 3),
                    mid(2, 3),
                );
                vec![
                    simplex(&[v[0], m01, m02, m03]),
                    simplex(&[m01, v[1], m12, m13]),
                    simplex(&[m02, m12, v[2], m23]),
                    simplex(&[m03, m13, m23, v[3]]),
                    // The inner octahedron, cut along its diagonal m02–m13.
                    simplex(&[m02, m13, m01, m03]),
                    simplex(&[m02, m13, m03, m23]),
                    simplex(&[m02, m13, m23, m12]),
                    simplex(&[m02, m13, m12, m01]),
                ]
            }
            (Domain::Box | Domain::Pyramid { .. }, dim) => (0..1usize << dim)
                .map(|bits| {
                    let mut r = Region {
                        origin: [0.0; 3],
                        axes: [[0.0; 3]; 3],
                    };
                    for k in 0..dim {
                        r.origin[k] = if bits >> k & 1 == 1 { h } else { 0.0 };
                        r.axes[k][k] = h;
                    }
                    r
                })
                .collect(),
        }
    }
}

impl Region {
    /// The identity region in unit coordinates.
    fn root_unit() -> Region {
        Region {
            origin: [0.0; 3],
            axes: [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linalg::mat_vec;

    /// A polynomial of degree ≤ n: its Bernstein coefficients reproduce it everywhere, and
    /// the child coefficients reproduce it on the child.
    fn check_reproduction(domain: Domain, dim: usize, n: usize) {
        let space = Space::new(domain, dim, n);
        let f = |t: RefPoint| {
            let s = t[0] + 0.3 * t[1] + 0.2 * t[2];
            (0..=n)
                .map(|k| (k as f64 + 1.0) * s.powi(k as i32))
                .sum::<f64>()
                - 0.7
        };
        let samples: Vec<f64> = space.lattice_unit.iter().map(|&t| f(t)).collect();
        let mut coeffs = vec![0.0; space.len()];
        mat_vec(&space.to_bernstein, &samples, &mut coeffs);
        let eval = |c: &[f64], t: RefPoint| -> f64 {
            (0..space.len()).map(|m| c[m] * space.basis(m, t)).sum()
        };
        let mut probe = [0.21, 0.13, 0.31];
        probe[dim..].fill(0.0);
        assert!(
            (eval(&coeffs, probe) - f(probe)).abs() < 1e-10,
            "{domain:?} {dim} {n}"
        );
        for &c in &space.corners {
            assert!((coeffs[c] - f(space.lattice_unit[c])).abs() < 1e-10);
        }
        for (region, m) in &space.children {
            let mut child = vec![0.0; space.len()];
            mat_vec(m, &coeffs, &mut child);
            let inside = region.apply(probe);
            assert!(
                (eval(&child, probe) - f(inside)).abs() < 1e-9,
                "{domain:?} {dim} {n}: child {region:?}"
            );
        }
    }

    #[test]
    fn bernstein_expansions_and_subdivision_reproduce_polynomials() {
        for (domain, dim, n) in [
            (Domain::Simplex, 2, 0),
            (Domain::Simplex, 2, 2),
            (Domain::Simplex, 2, 4),
            (Domain::Box, 2, 1),
            (Domain::Box, 2, 3),
            (Domain::Box, 2, 5),
            (Domain::Simplex, 3, 3),
            (Domain::Box, 3, 2),
            (Domain::Prism { axis: 2 }, 3, 2),
            (Domain::Prism { axis: 5 }, 3, 4),
            (Domain::Prism { axis: 2 }, 3, 1),
            (Domain::Pyramid { axis: 5 }, 3, 3),
            (Domain::Pyramid { axis: 2 }, 3, 2),
        ] {
            check_reproduction(domain, dim, n);
        }
    }

    #[test]
    fn children_tile_the_domain() {
        for (domain, dim, whole) in [
            (Domain::Simplex, 2, 0.5),
            (Domain::Simplex, 3, 1.0 / 6.0),
            (Domain::Box, 2, 1.0),
            (Domain::Box, 3, 1.0),
            (Domain::Prism { axis: 1 }, 3, 0.5),
            (Domain::Pyramid { axis: 1 }, 3, 1.0),
        ] {
            let space = Space::new(domain, dim, 1);
            let measure = |r: &Region| {
                let a = r.axes;
                let d = if dim == 2 {
                    a[0][0] * a[1][1] - a[0][1] * a[1][0]
                } else {
                    crate::matrix::det3(&a)
                };
                let unit = match domain {
                    Domain::Box | Domain::Pyramid { .. } => 1.0,
                    _ => whole,
                };
                d.abs() * unit
            };
            let total: f64 = space.children.iter().map(|(r, _)| measure(r)).sum();
            assert!((total - whole).abs() < 1e-14, "{domain:?} {dim}: {total}");
        }
    }
}
