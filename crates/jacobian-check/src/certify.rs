//! The validity of a cell: the sign of its Jacobian determinant over the whole reference
//! cell, certified from Bernstein coefficients (Johnen, Remacle & Geuzaine 2013), plus the
//! sampled check the dissertation used, and the whole-mesh check built on both.
//!
//! The determinant of a P_p triangle is a polynomial of degree 2(p − 1), of a Q_p
//! quadrilateral of degree 2p − 1 per direction, of a P_p tetrahedron 3(p − 1), of a Q_p
//! hexahedron 3p − 1 per direction, of a P_p prism 3p − 2 on the triangle and 3p − 1 along
//! its axis; the linear pyramid's, rational in the reference coordinates, is a biquadratic
//! in the coordinates of the rays from the apex (see `determinant_space`: the approach of
//! Johnen & Geuzaine for pyramids, 2015, at order 1); the 14- and 30-node pyramids' is a
//! polynomial of degree 3p − 1, 3p − 1, 3(p − 1) in the collapsed coordinates (ξ̂, η̂, ζ) of the
//! box [−1, 1]² × [0, 1] (the `pyramid` module). It is sampled at the lattice points of that degree and
//! turned into Bernstein coefficients by a per-type matrix. The coefficients bound the
//! determinant (convex hull property) and the corner coefficients equal it at the corners:
//! all coefficients > 0 proves validity, a corner coefficient ≤ 0 proves invalidity,
//! otherwise the region is subdivided and each child examined, down to a depth limit;
//! a region still undecided there makes the cell [`Certificate::Undecided`].
//!
//! Certified: every type of order 1–3 — triangles, quadrilaterals, tetrahedra, prisms,
//! hexahedra and pyramids (a straight-sided high-order one as its order-1 cell).
//! This module does not move nodes or repair cells.

use std::sync::OnceLock;

use mesh_model::{CellType, Dim, Mesh, Shape};

use crate::bernstein::{Domain, Region, Space};
use crate::error::JacobianError;
use crate::jacobian::{check_cell, ref_point};
use crate::lagrange::basis;
use crate::matrix::{det, matrix_from_gradients};
use crate::measure::measure_from_coefficients;
use crate::point::RefPoint;
use crate::types::{Feature, SLOTS, slot};

/// Parameters of the certified and sampled checks.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CertifyParams {
    /// Deepest level of regular subdivision before a cell is declared
    /// [`Certificate::Undecided`] (each level splits a triangle or quadrilateral into 4,
    /// a tetrahedron or hexahedron into 8). 0 to 20; default 8.
    pub max_depth: u32,
    /// Points per edge of the sampling lattice used where no certificate exists (3D cells
    /// without one) and for the sampled scaled Jacobian of cells that are not certified
    /// valid. At least 2; default 11.
    pub sample_points_per_edge: usize,
}

impl Default for CertifyParams {
    fn default() -> Self {
        CertifyParams {
            max_depth: 8,
            sample_points_per_edge: 11,
        }
    }
}

impl CertifyParams {
    fn check(&self) -> Result<(), JacobianError> {
        if self.max_depth > 20 {
            return Err(JacobianError::BadParameter {
                name: "max_depth",
                value: self.max_depth as f64,
                rule: "0 to 20",
            });
        }
        check_points_per_edge(self.sample_points_per_edge)
    }
}

fn check_points_per_edge(n: usize) -> Result<(), JacobianError> {
    if n < 2 {
        return Err(JacobianError::BadParameter {
            name: "sample_points_per_edge",
            value: n as f64,
            rule: "at least 2",
        });
    }
    Ok(())
}

/// The outcome of the certified check of one cell. `P` is a reference point (`[f64; 2]`
/// in 2D, `[f64; 3]` in 3D).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Certificate<P = [f64; 2]> {
    /// The determinant is positive everywhere in the cell (proved).
    Valid {
        /// The least Bernstein coefficient over the final subdivision: a lower bound of the
        /// determinant (physical area or volume per reference area or volume).
        min_coeff: f64,
        /// The greatest Bernstein coefficient over the final subdivision: an upper bound of
        /// the determinant.
        max_coeff: f64,
    },
    /// The determinant is ≤ 0 at the reference point `at` (proved: it is a corner value).
    Invalid {
        /// Where, in the reference coordinates of the cell.
        at: P,
    },
    /// Neither proved within [`CertifyParams::max_depth`] (the determinant comes within
    /// rounding of zero somewhere, or the depth limit is too low).
    Undecided,
}

impl<P> Certificate<P> {
    /// `min_coeff / max_coeff` for a valid cell: a lower bound, in (0, 1], of the scaled
    /// Jacobian min J / max J. `None` otherwise.
    pub fn scaled_jacobian_lower_bound(&self) -> Option<f64> {
        match self {
            Certificate::Valid {
                min_coeff,
                max_coeff,
            } => Some(min_coeff / max_coeff),
            _ => None,
        }
    }

    /// True for [`Certificate::Valid`].
    pub fn is_valid(&self) -> bool {
        matches!(self, Certificate::Valid { .. })
    }
}

/// The per-type tables of the certified check: the Bernstein space of the determinant and
/// the shape-function gradients at its lattice points.
#[derive(Debug)]
struct CertTable {
    space: Space,
    /// `grads[k · nodes + i]`: gradient of shape function i at lattice point k.
    grads: Vec<[f64; 3]>,
    nodes: usize,
}

/// The domain and degree of the determinant's polynomial space.
///
/// The prism's determinant has degree 3p − 2 on the triangle and 3p − 1 along the axis.
/// The linear pyramid's is rational in (u, v, w) but not along the rays from the apex: with
/// ξ = u / (1 − w), η = v / (1 − w) the map is `(1 − w) B(ξ, η) + w x_apex` (B the bilinear
/// base), so det J = det[∂B/∂ξ, ∂B/∂η, x_apex − B(ξ, η)], a biquadratic in (ξ, η) ∈ [−1, 1]²
/// that does not depend on w. Its expansion on the base square (w = 0) bounds the
/// determinant over the whole pyramid, the apex's directional limits included.
fn determinant_space(ty: CellType) -> (Domain, usize, usize) {
    let p = ty.order as usize;
    match ty.shape {
        Shape::Tri => (Domain::Simplex, 2, 2 * (p - 1)),
        Shape::Quad => (Domain::Box, 2, 2 * p - 1),
        Shape::Tet => (Domain::Simplex, 3, 3 * (p - 1)),
        Shape::Prism => (Domain::Prism { axis: 3 * p - 1 }, 3, 3 * p - 2),
        Shape::Pyramid if p == 1 => (Domain::Box, 2, 2),
        // the 14- and 30-node pyramids: degree 3p − 1 in (ξ̂, η̂), 3(p − 1) in ζ (`crate::pyramid`)
        Shape::Pyramid => (Domain::Pyramid { axis: 3 * (p - 1) }, 3, 3 * p - 1),
        _ => (Domain::Box, 3, 3 * p - 1),
    }
}

fn cert_table(ty: CellType) -> Result<&'static CertTable, JacobianError> {
    static CACHE: [OnceLock<CertTable>; SLOTS] = [const { OnceLock::new() }; SLOTS];
    let i = slot(ty, Feature::Certified)?;
    let b = basis(ty)?;
    Ok(CACHE[i].get_or_init(|| {
        let (domain, dim, degree) = determinant_space(ty);
        let space = Space::new(domain, dim, degree);
        let root = Region::root(domain, dim);
        let nodes = ty.node_count();
        let mut grads = vec![[0.0; 3]; space.len() * nodes];
        for (k, t) in space.lattice_unit.iter().enumerate() {
            let g = &mut grads[k * nodes..(k + 1) * nodes];
            if let Domain::Pyramid { .. } = domain {
                // the lattice is in collapsed coordinates: ζ = 1 holds the apex's limits
                crate::pyramid::bergot(ty.order).collapsed_gradients(root.apply(*t), g);
            } else {
                b.gradients(root.apply(*t), g);
            }
        }
        CertTable {
            space,
            grads,
            nodes,
        }
    }))
}

fn to_point<const D: usize>(x: RefPoint) -> [f64; D] {
    std::array::from_fn(|k| x[k])
}

/// The Bernstein coefficients of the determinant of a checked cell, and the least value a
/// region's coefficients must exceed to count as positive: 0, or for a tensor space
/// (`Space::amplification`) its amplification of the samples' rounding, 64 units of it on
/// the largest sample.
fn coefficients<const D: usize>(table: &CertTable, nodes: &[[f64; D]]) -> (Vec<f64>, f64) {
    let len = table.space.len();
    let samples: Vec<f64> = (0..len)
        .map(|k| {
            let g = &table.grads[k * table.nodes..(k + 1) * table.nodes];
            det(&matrix_from_gradients(nodes, g))
        })
        .collect();
    let mut coeffs = vec![0.0; len];
    table.space.to_bernstein(&samples, &mut coeffs);
    // A corner coefficient is the value at the corner: take it exactly, not through the
    // (rounded) inverse matrix, so that an invalid verdict rests on an evaluated value.
    for &k in &table.space.corners {
        coeffs[k] = samples[k];
    }
    let margin = if table.space.amplification > 0.0 {
        let largest = samples.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        table.space.amplification * 64.0 * f64::EPSILON * largest
    } else {
        0.0
    };
    (coeffs, margin)
}

/// The Bernstein coefficients of the Jacobian determinant of a cell of dimension `D`, in the
/// order of the lattice `(i, j[, k])` with i fastest (simplex: i + j (+ k) ≤ degree). Their
/// minimum and maximum bound the determinant over the cell; a straight-sided simplex has all
/// of them equal.
///
/// # Errors
/// Unsupported type (no certificate), wrong dimension, wrong node count, non-finite node.
pub fn determinant_bernstein_coefficients<const D: usize>(
    ty: CellType,
    nodes: &[[f64; D]],
) -> Result<Vec<f64>, JacobianError> {
    check_cell(ty, nodes)?;
    Ok(coefficients(cert_table(ty)?, nodes).0)
}

fn min_max(c: &[f64]) -> (f64, f64) {
    c.iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        })
}

/// The certified check of the sign of the determinant from its root coefficients: a region
/// is positive when its least coefficient exceeds `margin` (see `coefficients`).
fn certify_coefficients(
    space: &Space,
    root: Region,
    (coeffs, margin): (Vec<f64>, f64),
    max_depth: u32,
) -> Certificate<RefPoint> {
    let mut stack = vec![(coeffs, root, 0u32)];
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    let mut undecided = false;
    while let Some((c, region, depth)) = stack.pop() {
        if let Some(&k) = space
            .corners
            .iter()
            .find(|&&k| c[k] <= 0.0 || c[k].is_nan())
        {
            return Certificate::Invalid {
                at: region.apply(space.lattice_unit[k]),
            };
        }
        let (cmin, cmax) = min_max(&c);
        if cmin > margin {
            lo = lo.min(cmin);
            hi = hi.max(cmax);
            continue;
        }
        if depth >= max_depth {
            undecided = true;
            continue;
        }
        for (i, child) in space.children.iter().enumerate() {
            let mut cc = vec![0.0; c.len()];
            space.child(i, &c, &mut cc);
            stack.push((cc, region.compose(child), depth + 1));
        }
    }
    if undecided {
        Certificate::Undecided
    } else {
        Certificate::Valid {
            min_coeff: lo,
            max_coeff: hi,
        }
    }
}

/// The certified validity of a cell of dimension `D` (every shape of order 1 to 3: triangles,
/// quadrilaterals, tetrahedra, prisms, hexahedra, pyramids) with node coordinates `nodes` in
/// Gmsh order. Valid means the Jacobian determinant is > 0 everywhere in the cell: the cell is
/// not folded and is positively oriented (counter-clockwise in 2D).
///
/// # Errors
/// Unsupported type (order above 3), wrong dimension, wrong node count, non-finite node, bad
/// parameter.
pub fn certify_cell<const D: usize>(
    ty: CellType,
    nodes: &[[f64; D]],
    params: &CertifyParams,
) -> Result<Certificate<[f64; D]>, JacobianError> {
    params.check()?;
    check_cell(ty, nodes)?;
    Ok(certify_measured(ty, nodes, params, false)?.0)
}

/// [`certify_cell`] of a checked cell, with the cell's signed measure (area in 2D, volume in
/// 3D: the integral of det J) from the coefficients the certificate rests on — whatever the
/// verdict. The mean of the undivided cell's coefficients times the reference measure
/// (`measure_from_coefficients`), or, for a straight-sided cell the shortcut certifies,
/// that of its order-1 cell, whose map it is; a curved high-order pyramid by its own rule.
/// NaN unless `measured` (the certificate alone: the pyramid's rule is not free).
///
/// # Errors
/// Unsupported type (order above 3).
fn certify_measured<const D: usize>(
    ty: CellType,
    nodes: &[[f64; D]],
    params: &CertifyParams,
    measured: bool,
) -> Result<(Certificate<[f64; D]>, f64), JacobianError> {
    if let Some(tolerance) = crate::straight::is_straight(ty, nodes)? {
        // The cell is its corners' order-1 map up to `tolerance` per node; that moves the
        // determinant by far less than the margin asked for here (the nodes' shape
        // gradients are O(10) and the cell's extent bounds the other factor).
        let linear = CellType::new(ty.shape, 1);
        let (c, measure) =
            certify_measured(linear, &nodes[..ty.shape.corners()], params, measured)?;
        let extent = nodes
            .iter()
            .map(|x| {
                (0..D)
                    .map(|d| (x[d] - nodes[0][d]).abs())
                    .fold(0.0, f64::max)
            })
            .fold(0.0, f64::max);
        let margin = 1024.0 * tolerance * extent.powi(D as i32 - 1);
        match c {
            Certificate::Valid { min_coeff, .. } if min_coeff > margin => return Ok((c, measure)),
            Certificate::Invalid { .. } => return Ok((c, measure)),
            _ => {}
        }
    }
    let table = cert_table(ty)?;
    let coeffs = coefficients(table, nodes);
    let measure = match table.space.domain {
        _ if !measured => f64::NAN,
        Domain::Pyramid { .. } => {
            let x: Vec<[f64; 3]> = nodes
                .iter()
                .map(|p| std::array::from_fn(|k| p[k]))
                .collect();
            crate::pyramid::volume(&x)
        }
        _ => measure_from_coefficients(ty.shape, &coeffs.0),
    };
    let root = Region::root(table.space.domain, table.space.dim);
    let certificate = match certify_coefficients(&table.space, root, coeffs, params.max_depth) {
        Certificate::Valid {
            min_coeff,
            max_coeff,
        } => Certificate::Valid {
            min_coeff,
            max_coeff,
        },
        Certificate::Invalid { at } => Certificate::Invalid {
            at: to_point(match table.space.domain {
                Domain::Pyramid { .. } => crate::pyramid::to_reference(at),
                _ => at,
            }),
        },
        Certificate::Undecided => Certificate::Undecided,
    };
    Ok((certificate, measure))
}

/// The result of evaluating the determinant on a lattice of points in a cell.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SampledCheck<P = [f64; 2]> {
    /// The least determinant found.
    pub min_det: f64,
    /// The greatest determinant found.
    pub max_det: f64,
    /// Where the least was found, in reference coordinates.
    pub at_min: P,
    /// How many points were evaluated.
    pub samples: usize,
}

impl<P> SampledCheck<P> {
    /// True when every sampled determinant is > 0 (which proves nothing between samples).
    pub fn all_positive(&self) -> bool {
        self.min_det > 0.0
    }

    /// The sampled scaled Jacobian `min J / max |J|`, in [−1, 1].
    pub fn scaled_jacobian(&self) -> f64 {
        let scale = self.max_det.abs().max(self.min_det.abs());
        if scale > 0.0 {
            self.min_det / scale
        } else {
            0.0
        }
    }
}

/// The sampling lattice of a shape with `m` divisions per edge, in reference coordinates.
pub(crate) fn sample_points(shape: Shape, m: usize) -> Vec<RefPoint> {
    let f = m as f64;
    let s = |i: usize| -1.0 + 2.0 * i as f64 / f;
    let u = |i: usize| i as f64 / f;
    let mut out = Vec::new();
    match shape {
        Shape::Line => out.extend((0..=m).map(|i| [s(i), 0.0, 0.0])),
        Shape::Tri => {
            for j in 0..=m {
                for i in 0..=m - j {
                    out.push([u(i), u(j), 0.0]);
                }
            }
        }
        Shape::Quad => {
            for j in 0..=m {
                for i in 0..=m {
                    out.push([s(i), s(j), 0.0]);
                }
            }
        }
        Shape::Tet => {
            for k in 0..=m {
                for j in 0..=m - k {
                    for i in 0..=m - j - k {
                        out.push([u(i), u(j), u(k)]);
                    }
                }
            }
        }
        Shape::Prism => {
            for k in 0..=m {
                for j in 0..=m {
                    for i in 0..=m - j {
                        out.push([u(i), u(j), s(k)]);
                    }
                }
            }
        }
        Shape::Hex => {
            for k in 0..=m {
                for j in 0..=m {
                    for i in 0..=m {
                        out.push([s(i), s(j), s(k)]);
                    }
                }
            }
        }
        Shape::Pyramid => {
            for k in 0..=m {
                let w = u(k);
                let n = m - k;
                for j in 0..=n {
                    for i in 0..=n {
                        let a = |i: usize| {
                            if n == 0 {
                                0.0
                            } else {
                                (1.0 - w) * (-1.0 + 2.0 * i as f64 / n as f64)
                            }
                        };
                        out.push([a(i), a(j), w]);
                    }
                }
            }
        }
    }
    out
}

/// The determinant of a cell of dimension `D` sampled on a lattice of `points_per_edge` points
/// per edge (a triangle gets n(n+1)/2 points, a quadrilateral n²; every type with shape
/// functions, prisms and the linear pyramid included). The dissertation sampled 900 points
/// per triangle (41 points per edge give 861). Sampling cannot see a fold between its
/// points; [`certify_cell`] can.
///
/// # Errors
/// Unsupported type, wrong dimension, wrong node count, non-finite node, fewer than 2
/// points per edge.
pub fn sampled_check<const D: usize>(
    ty: CellType,
    nodes: &[[f64; D]],
    points_per_edge: usize,
) -> Result<SampledCheck<[f64; D]>, JacobianError> {
    check_points_per_edge(points_per_edge)?;
    check_cell(ty, nodes)?;
    let b = basis(ty)?;
    let points = sample_points(ty.shape, points_per_edge - 1);
    let mut grads = vec![[0.0; 3]; nodes.len()];
    let mut result = SampledCheck {
        min_det: f64::INFINITY,
        max_det: f64::NEG_INFINITY,
        at_min: [0.0; D],
        samples: points.len(),
    };
    for xi in points {
        b.gradients(xi, &mut grads);
        let d = det(&matrix_from_gradients(nodes, &grads));
        if d < result.min_det || d.is_nan() {
            result.min_det = d;
            result.at_min = to_point(xi);
        }
        result.max_det = result.max_det.max(d);
    }
    Ok(result)
}

/// The validity of every cell of a mesh.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshValidity {
    /// Cells proved invalid (a non-positive determinant somewhere), or, for 3D cells
    /// without a certificate, found non-positive at a sample point.
    pub invalid_cells: Vec<usize>,
    /// Cells neither proved valid nor invalid within the depth limit.
    pub undecided: Vec<usize>,
    /// 3D cells without a certificate whose samples were all positive: probably valid, not
    /// proved. Empty since every 3D type with shape functions has a certificate; kept for
    /// types that would come with shape functions first.
    pub uncertified: Vec<usize>,
    /// The least of `per_cell_scaled_jacobian` (1 for a mesh without cells).
    pub min_scaled_jacobian: f64,
    /// Per cell, min J / max J: for cells certified valid the certified lower bound
    /// `min_coeff / max_coeff`; for the others the sampled `min J / max |J|`, lowered to
    /// the determinant at the proved invalid point when there is one (≤ 0).
    pub per_cell_scaled_jacobian: Vec<f64>,
    /// Per cell, for the cells certified valid the certified lower bound of det J (the
    /// least Bernstein coefficient, `Certificate::Valid::min_coeff`); NaN for the others.
    /// What a caller needs for other measures built on it (Gmsh's minSJ) without
    /// certifying the cells a second time.
    pub per_cell_min_det: Vec<f64>,
    /// The signed measure of the mesh: the sum of its cells' areas (2D) or volumes (3D),
    /// each the integral of its det J, added in cell order (the same bits whatever the
    /// threads). Each cell's from the Bernstein coefficients its certificate starts from,
    /// whatever the verdict (`crate::cell_volume`'s rule; the undivided cell's coefficients,
    /// or its order-1 cell's when the cell is straight-sided): equal to
    /// [`crate::integrate_area`] or [`crate::integrate_volume`] up to rounding. NaN when a
    /// cell has no certificate (`uncertified`).
    pub measure: f64,
}

/// Checks every cell of a 2D or 3D mesh: certified where a certificate exists, sampled
/// elsewhere (see [`MeshValidity`]).
///
/// # Errors
/// A cell naming a missing node, a non-finite node, an unsupported cell type, a bad
/// parameter.
pub fn check_mesh(mesh: &Mesh, params: &CertifyParams) -> Result<MeshValidity, JacobianError> {
    use rayon::prelude::*;
    params.check()?;
    // cells are judged in parallel, in chunks large enough to amortise the scheduling
    let verdicts: Vec<Judged> = (0..mesh.cells.len())
        .into_par_iter()
        .with_min_len(256)
        .map(|i| {
            let cell = mesh.cells.get(i);
            if let Some(&node) = cell.nodes.iter().find(|&&n| n as usize >= mesh.nodes.len()) {
                return Err(JacobianError::NodeOutOfRange { cell: i, node });
            }
            match mesh.dim {
                Dim::Two if cell.nodes.len() <= MAX_2D_NODES => {
                    // on the stack: no allocation per cell (a Q3 quadrilateral has 16 nodes)
                    let mut xy = [[0.0; 2]; MAX_2D_NODES];
                    for (x, &n) in xy.iter_mut().zip(cell.nodes) {
                        *x = mesh.xy(n);
                    }
                    judge(cell.ty, &xy[..cell.nodes.len()], params)
                }
                Dim::Two => {
                    let xy: Vec<[f64; 2]> = cell.nodes.iter().map(|&n| mesh.xy(n)).collect();
                    judge(cell.ty, &xy, params)
                }
                Dim::Three => {
                    let xyz: Vec<[f64; 3]> =
                        cell.nodes.iter().map(|&n| mesh.nodes[n as usize]).collect();
                    judge(cell.ty, &xyz, params)
                }
            }
        })
        .collect::<Result<_, _>>()?;
    let mut out = MeshValidity {
        invalid_cells: Vec::new(),
        undecided: Vec::new(),
        uncertified: Vec::new(),
        min_scaled_jacobian: 1.0,
        per_cell_scaled_jacobian: Vec::with_capacity(mesh.cells.len()),
        per_cell_min_det: Vec::with_capacity(mesh.cells.len()),
        measure: 0.0,
    };
    for (i, j) in verdicts.into_iter().enumerate() {
        let (scaled, min_det) = (j.scaled, j.min_det);
        out.measure += j.measure;
        match j.verdict {
            Verdict::Valid => {}
            Verdict::Invalid => out.invalid_cells.push(i),
            Verdict::Undecided => out.undecided.push(i),
            Verdict::Uncertified => out.uncertified.push(i),
        }
        out.per_cell_scaled_jacobian.push(scaled);
        out.per_cell_min_det.push(min_det);
        out.min_scaled_jacobian = out.min_scaled_jacobian.min(scaled);
    }
    Ok(out)
}

/// The most nodes of a 2D cell [`check_mesh`] gathers on the stack.
const MAX_2D_NODES: usize = 16;

/// How one cell was judged: its scaled Jacobian, its certified lower bound of det J (NaN
/// unless certified valid), its signed measure (NaN without a certificate) and verdict.
#[derive(Debug, Clone, Copy)]
struct Judged {
    scaled: f64,
    min_det: f64,
    measure: f64,
    verdict: Verdict,
}

/// The verdict on one cell.
#[derive(Debug, Clone, Copy)]
enum Verdict {
    Valid,
    Invalid,
    Undecided,
    Uncertified,
}

/// Certifies (or samples) one cell of a mesh whose parameters are checked.
fn judge<const D: usize>(
    ty: CellType,
    nodes: &[[f64; D]],
    params: &CertifyParams,
) -> Result<Judged, JacobianError> {
    check_cell(ty, nodes)?;
    let (certificate, measure) = match certify_measured(ty, nodes, params, true) {
        Ok((c, measure)) => (Some(c), measure),
        Err(JacobianError::Unsupported { .. }) if D == 3 => (None, f64::NAN),
        Err(e) => return Err(e),
    };
    if let Some(Certificate::Valid {
        min_coeff,
        max_coeff,
    }) = certificate
    {
        return Ok(Judged {
            scaled: min_coeff / max_coeff,
            min_det: min_coeff,
            measure,
            verdict: Verdict::Valid,
        });
    }
    let sampled = sampled_check(ty, nodes, params.sample_points_per_edge)?;
    let mut scaled = sampled.scaled_jacobian();
    let verdict = match certificate {
        Some(Certificate::Invalid { at }) => {
            let mut grads = vec![[0.0; 3]; nodes.len()];
            basis(ty)?.gradients(ref_point(at), &mut grads);
            let d = det(&matrix_from_gradients(nodes, &grads));
            let scale = sampled.max_det.abs().max(sampled.min_det.abs());
            if scale > 0.0 {
                scaled = scaled.min(d / scale);
            } else {
                scaled = scaled.min(0.0);
            }
            Verdict::Invalid
        }
        Some(Certificate::Undecided) => Verdict::Undecided,
        None if sampled.all_positive() => Verdict::Uncertified,
        _ => Verdict::Invalid,
    };
    Ok(Judged {
        scaled,
        min_det: f64::NAN,
        measure,
        verdict,
    })
}
