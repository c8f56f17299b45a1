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
//! The 3D spaces of the P3 boxes, prisms and pyramids (324 to 729 coefficients) are tensor
//! products (line × line × line, triangle × line): there the dense matrices would take tens
//! of megabytes and seconds to build, and the inverse of the 729 × 729 matrix loses seven
//! digits, so such a space keeps its factors' own small maps and applies them one direction
//! at a time — the same coefficients, to rounding, from the Kronecker product of the factors'
//! inverses. The smaller spaces keep their dense matrices. At degree 8 the equispaced
//! samples' rounding is amplified up to the product of the factors' inverse norms (1.7e8 for
//! the P3 hexahedron, 2.8e7 for the P3 pyramid, 2.3e5 for the P3 prism: the observed error
//! of the coefficients is about 1e-8 of the determinant), so these spaces carry that factor
//! ([`Space::amplification`]) and the certificate asks their coefficients to clear it.
//!
//! Regions are parametrised by unit coordinates t: the unit simplex, [0, 1]ᵈ for boxes, the
//! unit triangle × [0, 1] for prisms; a [`Region`] maps them affinely into Gmsh's reference
//! coordinates.

use crate::linalg::{invert, mat_mul, mat_vec};
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

/// The maps of a space: from samples to coefficients, and from a region's coefficients to a
/// child's.
#[derive(Debug)]
enum Maps {
    /// Row-major `len × len` matrices: the inverse of the Bernstein–Lagrange matrix, and one
    /// per child.
    Dense {
        to_bernstein: Vec<f64>,
        children: Vec<Vec<f64>>,
    },
    /// The space is the tensor product of these factors, the first running fastest in the
    /// coefficient order; child `i` is the product of one child per factor, the first
    /// factor's child index running fastest.
    Tensor(Vec<Space>),
}

/// Spaces with more coefficients than this that are tensor products are applied by factors
/// (module docs): every space of the P1 and P2 cells stays below it.
const TENSOR_ABOVE: usize = 256;

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
    /// The subdivision children's regions in unit coordinates.
    pub(crate) children: Vec<Region>,
    /// How much a tensor space's maps may amplify the rounding of the samples: the product
    /// of its factors' inverse ∞-norms; 0 for a dense space, whose callers need no margin.
    pub(crate) amplification: f64,
    maps: Maps,
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
        let mut space = Space::lattice(domain, dim, degree);
        let tensor = dim == 3 && domain != Domain::Simplex && space.len() > TENSOR_ABOVE;
        space.maps = if tensor {
            space.tensor_maps()
        } else {
            space.dense_maps()
        };
        if let Maps::Tensor(factors) = &space.maps {
            space.amplification = factors
                .iter()
                .map(|f| inverse_norm(f.dense().0, f.len()))
                .product();
        }
        space
    }

    /// The space's lattice, corners and children's regions, without maps.
    fn lattice(domain: Domain, dim: usize, degree: usize) -> Space {
        let n = degree;
        let mut index = Vec::new();
        let top = match domain {
            Domain::Prism { axis } | Domain::Pyramid { axis } => axis,
            _ if dim == 3 => n,
            _ => 0,
        };
        let middle = if dim >= 2 { n } else { 0 };
        for c in 0..=top {
            for b in 0..=middle {
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
            children: Vec::new(),
            amplification: 0.0,
            maps: Maps::Tensor(Vec::new()),
        };
        space.children = space.child_regions();
        space
    }

    /// The dense matrices of the space.
    fn dense_maps(&self) -> Maps {
        let len = self.len();
        let t = self.basis_matrix(&Region::root_unit());
        let to_bernstein = invert(&t, len).expect("Bernstein–Lagrange matrix is invertible");
        let children = self
            .children
            .iter()
            .map(|r| mat_mul(&to_bernstein, &self.basis_matrix(r), len))
            .collect();
        Maps::Dense {
            to_bernstein,
            children,
        }
    }

    /// The factors of a 3D tensor-product space: three lines (box, pyramid) or a triangle
    /// and a line (prism).
    fn tensor_maps(&self) -> Maps {
        let n = self.degree;
        let line = |degree| Space::new(Domain::Box, 1, degree);
        Maps::Tensor(match self.domain {
            Domain::Box => vec![line(n), line(n), line(n)],
            Domain::Pyramid { axis } => vec![line(n), line(n), line(axis)],
            Domain::Prism { axis } => vec![Space::new(Domain::Simplex, 2, n), line(axis)],
            Domain::Simplex => unreachable!("simplices are no tensor products"),
        })
    }

    /// The Bernstein coefficients of the polynomial sampled at the lattice (`samples`).
    pub(crate) fn to_bernstein(&self, samples: &[f64], out: &mut [f64]) {
        match &self.maps {
            Maps::Dense { to_bernstein, .. } => mat_vec(to_bernstein, samples, out),
            Maps::Tensor(factors) => {
                let maps: Vec<(&[f64], usize)> =
                    factors.iter().map(|f| (f.dense().0, f.len())).collect();
                apply_tensor(&maps, samples, out);
            }
        }
    }

    /// The coefficients on child `i` ([`Space::children`]) of the region with coefficients `c`.
    pub(crate) fn child(&self, i: usize, c: &[f64], out: &mut [f64]) {
        match &self.maps {
            Maps::Dense { children, .. } => mat_vec(&children[i], c, out),
            Maps::Tensor(factors) => {
                let mut rest = i;
                let maps: Vec<(&[f64], usize)> = factors
                    .iter()
                    .map(|f| {
                        let children = f.dense().1;
                        let k = rest % children.len();
                        rest /= children.len();
                        (children[k].as_slice(), f.len())
                    })
                    .collect();
                apply_tensor(&maps, c, out);
            }
        }
    }

    /// The dense maps of a factor.
    fn dense(&self) -> (&[f64], &[Vec<f64>]) {
        match &self.maps {
            Maps::Dense {
                to_bernstein,
                children,
            } => (to_bernstein, children),
            Maps::Tensor(_) => unreachable!("the factors of a tensor space are dense"),
        }
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

/// The ∞-norm (largest row sum of magnitudes) of the row-major `n × n` matrix `m`.
fn inverse_norm(m: &[f64], n: usize) -> f64 {
    m.chunks(n)
        .map(|row| row.iter().map(|v| v.abs()).sum::<f64>())
        .fold(0.0, f64::max)
}

/// `out = (M_k ⊗ … ⊗ M_1) x` for the factors `(M_g, size_g)` (row-major), the first
/// factor's index running fastest in `x`: one direction at a time.
fn apply_tensor(factors: &[(&[f64], usize)], x: &[f64], out: &mut [f64]) {
    let mut current = x.to_vec();
    let mut next = vec![0.0; x.len()];
    let mut inner = 1;
    for &(m, size) in factors {
        let outer = x.len() / (inner * size);
        for o in 0..outer {
            for i in 0..size {
                let row = &m[i * size..(i + 1) * size];
                for q in 0..inner {
                    let at = |j: usize| (o * size + j) * inner + q;
                    next[at(i)] = (0..size).map(|j| row[j] * current[at(j)]).sum();
                }
            }
        }
        std::mem::swap(&mut current, &mut next);
        inner *= size;
    }
    out.copy_from_slice(&current);
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

    /// A polynomial of degree ≤ n: its Bernstein coefficients reproduce it everywhere, and
    /// the child coefficients reproduce it on the child.
    fn check_reproduction(domain: Domain, dim: usize, n: usize) {
        check_space_reproduces(&Space::new(domain, dim, n));
    }

    fn check_space_reproduces(space: &Space) {
        let (domain, dim, n) = (space.domain, space.dim, space.degree);
        // of total degree n, or less where the axis' degree is less
        let top = match domain {
            Domain::Prism { axis } | Domain::Pyramid { axis } => n.min(axis),
            _ => n,
        };
        let f = |t: RefPoint| {
            let s = t[0] + 0.3 * t[1] + 0.2 * t[2];
            (0..=top)
                .map(|k| (k as f64 + 1.0) * s.powi(k as i32))
                .sum::<f64>()
                - 0.7
        };
        let samples: Vec<f64> = space.lattice_unit.iter().map(|&t| f(t)).collect();
        let mut coeffs = vec![0.0; space.len()];
        space.to_bernstein(&samples, &mut coeffs);
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
        for (i, region) in space.children.iter().enumerate() {
            let mut child = vec![0.0; space.len()];
            space.child(i, &coeffs, &mut child);
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
            (Domain::Box, 1, 4),
            // the P3 spaces, tensor products applied by factors
            (Domain::Box, 3, 8),
            (Domain::Prism { axis: 8 }, 3, 7),
            (Domain::Pyramid { axis: 6 }, 3, 8),
            (Domain::Simplex, 3, 6),
        ] {
            check_reproduction(domain, dim, n);
        }
    }

    #[test]
    fn tensor_maps_are_the_dense_maps() {
        for (domain, n) in [
            (Domain::Box, 3),
            (Domain::Prism { axis: 3 }, 2),
            (Domain::Pyramid { axis: 2 }, 3),
        ] {
            let mut dense = Space::lattice(domain, 3, n);
            dense.maps = dense.dense_maps();
            let mut tensor = Space::lattice(domain, 3, n);
            tensor.maps = tensor.tensor_maps();
            check_space_reproduces(&tensor);
            let len = dense.len();
            let x: Vec<f64> = (0..len).map(|k| ((k * 7 + 3) % 11) as f64 - 5.0).collect();
            let (mut a, mut b) = (vec![0.0; len], vec![0.0; len]);
            dense.to_bernstein(&x, &mut a);
            tensor.to_bernstein(&x, &mut b);
            let close = |a: &[f64], b: &[f64]| a.iter().zip(b).all(|(u, v)| (u - v).abs() < 1e-9);
            assert!(close(&a, &b), "{domain:?}");
            for i in 0..dense.children.len() {
                dense.child(i, &x, &mut a);
                tensor.child(i, &x, &mut b);
                assert!(close(&a, &b), "{domain:?} child {i}");
            }
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
            let total: f64 = space.children.iter().map(measure).sum();
            assert!((total - whole).abs() < 1e-14, "{domain:?} {dim}: {total}");
        }
    }
}
