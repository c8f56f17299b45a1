//! Two baseline movers of the nodes of a linear 2D mesh that follow a [`BoundaryMotion`]:
//! every boundary node goes exactly to its target, every other node by a displacement
//! interpolated from the boundary's.
//!
//! - **Rotation-aware inverse-distance weighting** (Witteveen & Bijl 2009; Luke, Collins &
//!   Blades 2012): each boundary node `i` (position `b_i`, displacement `d_i`, linear part
//!   `M_i` of its body's motion) predicts that a node at `x` moves rigidly with it, to
//!   `x + d_i + (M_i − I)(x − b_i)`; the node's new position is the weighted mean of these
//!   predictions with weights `w_i = A_i / |x − b_i|^p`, `A_i` half the length of the two
//!   boundary facets at `i` (so that clustered nodes do not outweigh sparse ones) and `p` the
//!   exponent ([`IdwParams::exponent`], 3 by default). A motion that is the same rigid motion
//!   for every boundary node is reproduced exactly (up to rounding). O(N · Nb), on all cores.
//! - **Radial basis functions** (de Boer, van der Schoot & Bijl 2007) with a linear
//!   polynomial: the displacement `s(x) = Σ α_j φ(|x − b_j|) + β₀ + β·x` interpolates the
//!   boundary displacements with `Σ α_j = 0`, `Σ α_j b_j = 0`; the kernel is Wendland's C2
//!   `φ(r) = (1 − r/R)⁴ (4r/R + 1)` (support radius `R`, by default the domain's bounding-box
//!   diagonal, which makes it global) or the thin-plate spline `φ(r) = r² ln r`. The dense
//!   system is solved by LU with partial pivoting (`nalgebra`). The affine part of the
//!   boundary displacement is fitted first by least squares and the system solved for the
//!   rest (a remainder below 1e-13 of the largest displacement counts as rounding noise and is
//!   dropped), so that affine motions (rigid, scaled) are reproduced to rounding whatever the
//!   system's conditioning.

use std::collections::HashMap;

use mesh_model::Mesh;
use nalgebra::{DMatrix, Matrix3, Vector3};
use rayon::prelude::*;

use crate::MoveError;
use crate::boundary::{BoundaryMotion, check_linear_2d};
use crate::motion::Mat2;
pub use crate::outcome::{MoveStats, Moved};
use crate::params::SpringMoveParams;
pub use crate::params::{IdwParams, Kernel, RbfParams};

/// A mover.
#[derive(Debug, Clone, Copy, PartialEq)]
// one `Method` per move: the spring parameters' size does not matter
#[allow(clippy::large_enum_variant)]
pub enum Method {
    /// Rotation-aware inverse-distance weighting.
    Idw(IdwParams),
    /// Radial basis functions.
    Rbf(RbfParams),
    /// The Spring-Field re-balanced on the original layers ([`crate::springs`]); needs the
    /// layering, so only [`crate::move_layered`] takes it.
    Springs(SpringMoveParams),
}

/// `mesh` with its boundary nodes at the targets of `boundary` and its other nodes moved by
/// `method`.
///
/// # Errors
/// [`MoveError::NotLinear2d`], [`MoveError::BadBoundaryMotion`] (lengths differ, a node out of
/// range or twice, a non-finite target), [`MoveError::MissingBoundaryNode`],
/// [`MoveError::BadParameter`] (exponent, support radius), [`MoveError::SingularSystem`].
pub fn move_mesh(
    mesh: &Mesh,
    boundary: &BoundaryMotion,
    method: &Method,
) -> Result<Moved, MoveError> {
    check_boundary(mesh, boundary)?;
    let sources = Sources::new(mesh, boundary);
    let in_boundary = {
        let mut flag = vec![false; mesh.nodes.len()];
        boundary.nodes.iter().for_each(|&k| flag[k as usize] = true);
        flag
    };
    let interior: Vec<u32> = (0..mesh.nodes.len() as u32)
        .filter(|&k| !in_boundary[k as usize])
        .collect();
    let (displacements, residual) = match method {
        Method::Idw(p) => {
            positive("IDW exponent", p.exponent)?;
            let d = interior
                .par_iter()
                .map(|&k| sources.idw(mesh.xy(k), p.exponent))
                .collect::<Vec<_>>();
            (d, 0.0)
        }
        Method::Rbf(p) => {
            let rbf = Rbf::fit(mesh, &sources, p)?;
            let d = interior
                .par_iter()
                .map(|&k| rbf.displacement(mesh.xy(k)))
                .collect::<Vec<_>>();
            (d, rbf.residual(&sources))
        }
        Method::Springs(_) => return Err(MoveError::NeedsLayering),
    };
    let mut moved = mesh.clone();
    let mut stats = MoveStats {
        boundary_nodes: boundary.nodes.len(),
        interior_nodes: interior.len(),
        interpolation_residual: residual,
        ..MoveStats::default()
    };
    for (&k, t) in boundary.nodes.iter().zip(&boundary.targets) {
        let p = &mut moved.nodes[k as usize];
        let d = (t[0] - p[0]).hypot(t[1] - p[1]);
        stats.largest_boundary_displacement = stats.largest_boundary_displacement.max(d);
        p[0] = t[0];
        p[1] = t[1];
    }
    stats.largest_displacement = stats.largest_boundary_displacement;
    for (&k, d) in interior.iter().zip(&displacements) {
        let p = &mut moved.nodes[k as usize];
        p[0] += d[0];
        p[1] += d[1];
        stats.largest_displacement = stats.largest_displacement.max(d[0].hypot(d[1]));
    }
    stats.inverted_cells = crate::quality::inverted_cells(&moved);
    Ok(Moved {
        mesh: moved,
        stats,
        start: None,
    })
}

pub(crate) fn check_boundary(mesh: &Mesh, b: &BoundaryMotion) -> Result<(), MoveError> {
    check_linear_2d(mesh)?;
    let bad = |what: String| Err(MoveError::BadBoundaryMotion { what });
    if b.targets.len() != b.nodes.len()
        || b.linear.len() != b.nodes.len()
        || b.turn.len() != b.nodes.len()
    {
        return bad(format!(
            "{} nodes, {} targets, {} linear parts, {} turns",
            b.nodes.len(),
            b.targets.len(),
            b.linear.len(),
            b.turn.len()
        ));
    }
    let mut seen = vec![false; mesh.nodes.len()];
    for (i, &k) in b.nodes.iter().enumerate() {
        if k as usize >= mesh.nodes.len() {
            return bad(format!(
                "node {k} out of range ({} nodes)",
                mesh.nodes.len()
            ));
        }
        if std::mem::replace(&mut seen[k as usize], true) {
            return bad(format!("node {k} given twice"));
        }
        let t = b.targets[i];
        let m = b.linear[i];
        if !(t.iter().chain(m.iter().flatten()).all(|v| v.is_finite()))
            || b.turn[i].is_nan()
            || b.turn[i].abs() > std::f64::consts::PI
        {
            return bad(format!(
                "node {k}: non-finite target or linear part, or a turn outside [-pi, pi]"
            ));
        }
    }
    if let Some(&node) = mesh
        .boundary
        .flat_nodes()
        .iter()
        .find(|&&k| !seen[k as usize])
    {
        return Err(MoveError::MissingBoundaryNode { node });
    }
    Ok(())
}

fn positive(what: &'static str, value: f64) -> Result<(), MoveError> {
    if value > 0.0 && value.is_finite() {
        Ok(())
    } else {
        Err(MoveError::BadParameter { what, value })
    }
}

/// The boundary nodes as sources of displacement.
pub(crate) struct Sources {
    /// Original positions.
    pub(crate) at: Vec<[f64; 2]>,
    /// Displacements.
    pub(crate) d: Vec<[f64; 2]>,
    /// `M − I` of each.
    pub(crate) m: Vec<Mat2>,
    /// Half the length of the boundary facets at each.
    pub(crate) area: Vec<f64>,
    /// The turn of each one's body, radians ([`BoundaryMotion::turn`]): the branch its
    /// rotation angle is read on.
    pub(crate) turn: Vec<f64>,
    /// The log of the scale of each one's body (0 for fixed loops and bumps).
    pub(crate) log_scale: Vec<f64>,
}

impl Sources {
    fn new(mesh: &Mesh, b: &BoundaryMotion) -> Sources {
        let index: HashMap<u32, usize> = b.nodes.iter().enumerate().map(|(i, &k)| (k, i)).collect();
        let mut area = vec![0.0; b.nodes.len()];
        for f in mesh.boundary.iter() {
            let k = f.corners();
            let (p, q) = (mesh.xy(k[0]), mesh.xy(k[1]));
            let half = 0.5 * (p[0] - q[0]).hypot(p[1] - q[1]);
            area[index[&k[0]]] += half;
            area[index[&k[1]]] += half;
        }
        let at: Vec<[f64; 2]> = b.nodes.iter().map(|&k| mesh.xy(k)).collect();
        let d = at
            .iter()
            .zip(&b.targets)
            .map(|(p, t)| [t[0] - p[0], t[1] - p[1]])
            .collect();
        let m = b
            .linear
            .iter()
            .map(|l| [[l[0][0] - 1.0, l[0][1]], [l[1][0], l[1][1] - 1.0]])
            .collect();
        Sources {
            at,
            d,
            m,
            area,
            turn: b.turn.clone(),
            log_scale: b.linear.iter().map(|&l| log_scale(l)).collect(),
        }
    }

    /// What boundary node `i` predicts for the displacement of a node at `x`.
    fn predict(&self, i: usize, x: [f64; 2]) -> [f64; 2] {
        let (b, d, m) = (self.at[i], self.d[i], self.m[i]);
        let r = [x[0] - b[0], x[1] - b[1]];
        [
            d[0] + (m[0][0] * r[0] + m[0][1] * r[1]),
            d[1] + (m[1][0] * r[0] + m[1][1] * r[1]),
        ]
    }

    /// The inverse-distance-weighted displacement at `x`.
    pub(crate) fn idw(&self, x: [f64; 2], exponent: f64) -> [f64; 2] {
        let (mut sum, mut total) = ([0.0, 0.0], 0.0);
        for i in 0..self.at.len() {
            let b = self.at[i];
            let r2 = (x[0] - b[0]).powi(2) + (x[1] - b[1]).powi(2);
            if r2 == 0.0 {
                return self.predict(i, x);
            }
            let w = self.area[i] * inverse_power(r2, exponent);
            let p = self.predict(i, x);
            sum[0] += w * p[0];
            sum[1] += w * p[1];
            total += w;
        }
        if total > 0.0 {
            [sum[0] / total, sum[1] / total]
        } else {
            [0.0, 0.0]
        }
    }
}

/// The log of the scale of a linear part `scale · rotation`.
pub(crate) fn log_scale(l: Mat2) -> f64 {
    let det = l[0][0] * l[1][1] - l[0][1] * l[1][0];
    if det > 0.0 { 0.5 * det.ln() } else { 0.0 }
}

/// `r^-p` from `r²`, without `powf` for the usual integer exponents.
fn inverse_power(r2: f64, p: f64) -> f64 {
    if p == 2.0 {
        1.0 / r2
    } else if p == 3.0 {
        1.0 / (r2 * r2.sqrt())
    } else if p == 4.0 {
        1.0 / (r2 * r2)
    } else if p == 5.0 {
        1.0 / (r2 * r2 * r2.sqrt())
    } else {
        r2.powf(-0.5 * p)
    }
}

/// Relative size (to the largest boundary displacement) under which what is left after the
/// affine fit counts as rounding noise and is not interpolated.
const AFFINE_NOISE: f64 = 1e-13;

/// A fitted RBF interpolant of the boundary displacements, in scaled coordinates
/// `(x − centre) / scale`.
pub(crate) struct Rbf {
    kernel: Kernel,
    centre: [f64; 2],
    scale: f64,
    /// Scaled boundary positions.
    at: Vec<[f64; 2]>,
    /// Affine part fitted first, per component: `c0 + c1 x̂ + c2 ŷ`.
    affine: [Vector3<f64>; 2],
    /// Kernel weights α, per component.
    alpha: [Vec<f64>; 2],
    /// Polynomial of the interpolation of the rest, per component.
    beta: [Vector3<f64>; 2],
}

impl Rbf {
    pub(crate) fn fit(mesh: &Mesh, s: &Sources, p: &RbfParams) -> Result<Rbf, MoveError> {
        let n = s.at.len();
        let diameter = bounding_box_diagonal(mesh);
        let scale = match (p.kernel, p.support_radius) {
            (Kernel::WendlandC2, Some(r)) => {
                positive("RBF support radius", r)?;
                r
            }
            _ => diameter.max(f64::MIN_POSITIVE),
        };
        let centre = s.at.iter().fold([0.0, 0.0], |c, b| {
            [c[0] + b[0] / n as f64, c[1] + b[1] / n as f64]
        });
        let at: Vec<[f64; 2]> =
            s.at.iter()
                .map(|b| [(b[0] - centre[0]) / scale, (b[1] - centre[1]) / scale])
                .collect();
        let poly = |q: [f64; 2]| Vector3::new(1.0, q[0], q[1]);
        // affine least squares: (Pᵀ P) c = Pᵀ d
        let mut normal = Matrix3::zeros();
        let mut rhs = [Vector3::zeros(), Vector3::zeros()];
        for (q, d) in at.iter().zip(&s.d) {
            let v = poly(*q);
            normal += v * v.transpose();
            rhs[0] += v * d[0];
            rhs[1] += v * d[1];
        }
        let lu = normal.lu();
        let affine = [lu.solve(&rhs[0]), lu.solve(&rhs[1])];
        let [Some(a0), Some(a1)] = affine else {
            return Err(MoveError::SingularSystem { size: n });
        };
        let affine = [a0, a1];
        // interpolate the rest with the kernel and a linear polynomial
        let size = n + 3;
        let phi = |r: f64| kernel(p.kernel, r);
        let mut a = DMatrix::<f64>::zeros(size, size);
        let mut b = DMatrix::<f64>::zeros(size, 2);
        // what is left of an affine motion after the fit is rounding noise; the global
        // kernel's ill-conditioned system would amplify it into visible distortion
        let largest = s.d.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
        let noise = AFFINE_NOISE * largest;
        for i in 0..n {
            for j in 0..n {
                a[(i, j)] = phi(distance(at[i], at[j]));
            }
            let v = poly(at[i]);
            for k in 0..3 {
                a[(i, n + k)] = v[k];
                a[(n + k, i)] = v[k];
            }
            for c in 0..2 {
                let rest = s.d[i][c] - affine[c].dot(&v);
                b[(i, c)] = if rest.abs() <= noise { 0.0 } else { rest };
            }
        }
        let x = a
            .lu()
            .solve(&b)
            .filter(|x| x.iter().all(|v| v.is_finite()))
            .ok_or(MoveError::SingularSystem { size: n })?;
        let alpha = [
            (0..n).map(|i| x[(i, 0)]).collect(),
            (0..n).map(|i| x[(i, 1)]).collect(),
        ];
        let beta = [
            Vector3::new(x[(n, 0)], x[(n + 1, 0)], x[(n + 2, 0)]),
            Vector3::new(x[(n, 1)], x[(n + 1, 1)], x[(n + 2, 1)]),
        ];
        Ok(Rbf {
            kernel: p.kernel,
            centre,
            scale,
            at,
            affine,
            alpha,
            beta,
        })
    }

    /// The interpolated displacement at `x` (unscaled).
    pub(crate) fn displacement(&self, x: [f64; 2]) -> [f64; 2] {
        let q = [
            (x[0] - self.centre[0]) / self.scale,
            (x[1] - self.centre[1]) / self.scale,
        ];
        let v = Vector3::new(1.0, q[0], q[1]);
        let mut d = [
            self.affine[0].dot(&v) + self.beta[0].dot(&v),
            self.affine[1].dot(&v) + self.beta[1].dot(&v),
        ];
        for (j, b) in self.at.iter().enumerate() {
            let f = kernel(self.kernel, distance(q, *b));
            if f != 0.0 {
                d[0] += self.alpha[0][j] * f;
                d[1] += self.alpha[1][j] * f;
            }
        }
        d
    }

    /// Largest mismatch between the interpolant and the boundary displacements.
    fn residual(&self, s: &Sources) -> f64 {
        (0..s.at.len())
            .into_par_iter()
            .map(|i| {
                let d = self.displacement(s.at[i]);
                (d[0] - s.d[i][0]).hypot(d[1] - s.d[i][1])
            })
            .reduce(|| 0.0, f64::max)
    }
}

/// The kernel at scaled distance `r` (support radius 1 for Wendland).
fn kernel(k: Kernel, r: f64) -> f64 {
    match k {
        Kernel::WendlandC2 => {
            if r >= 1.0 {
                0.0
            } else {
                (1.0 - r).powi(4) * (4.0 * r + 1.0)
            }
        }
        Kernel::ThinPlateSpline => {
            if r == 0.0 {
                0.0
            } else {
                r * r * r.ln()
            }
        }
    }
}

fn distance(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// The diagonal of the bounding box of the mesh's nodes.
pub fn bounding_box_diagonal(mesh: &Mesh) -> f64 {
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for p in &mesh.nodes {
        for c in 0..2 {
            lo[c] = lo[c].min(p[c]);
            hi[c] = hi[c].max(p[c]);
        }
    }
    if lo[0] > hi[0] {
        return 0.0;
    }
    (hi[0] - lo[0]).hypot(hi[1] - lo[1])
}
