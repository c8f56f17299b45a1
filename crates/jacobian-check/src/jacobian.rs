//! The Jacobian matrix of the map from a reference cell to a physical cell given by its
//! node coordinates, and its determinant, at one reference point.
//!
//! Owns the input checks shared by every per-cell function (node count, dimension,
//! finiteness). Does not decide validity: that is [`crate::certify`].

use mesh_model::CellType;

use crate::error::JacobianError;
use crate::lagrange::{RefPoint, basis};

/// The Jacobian of a cell of dimension `D` at a reference point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jacobian<const D: usize> {
    /// `matrix[i][j] = ∂x_i/∂ξ_j` (row: physical coordinate; column: reference coordinate).
    pub matrix: [[f64; D]; D],
    /// Its determinant: the ratio of physical to reference area (2D) or volume (3D) there.
    pub det: f64,
}

/// Checks that `ty` has dimension `dim` and that `nodes` are its finite node coordinates.
pub(crate) fn check_cell<const D: usize>(
    ty: CellType,
    nodes: &[[f64; D]],
) -> Result<(), JacobianError> {
    let actual = ty.shape.dim();
    if actual as usize != D {
        return Err(JacobianError::WrongDimension {
            ty,
            actual,
            needed: D as u8,
        });
    }
    if nodes.len() != ty.node_count() {
        return Err(JacobianError::NodeCount {
            ty,
            expected: ty.node_count(),
            got: nodes.len(),
        });
    }
    if let Some(node) = nodes.iter().position(|p| !p.iter().all(|c| c.is_finite())) {
        return Err(JacobianError::NonFiniteNode { node });
    }
    Ok(())
}

/// `Σ_i x_i ⊗ ∇N_i`: the Jacobian matrix from node coordinates and shape gradients.
pub(crate) fn matrix_from_gradients<const D: usize>(
    nodes: &[[f64; D]],
    grads: &[[f64; 3]],
) -> [[f64; D]; D] {
    let mut m = [[0.0; D]; D];
    for (x, g) in nodes.iter().zip(grads) {
        for i in 0..D {
            for j in 0..D {
                m[i][j] += x[i] * g[j];
            }
        }
    }
    m
}

/// Determinant of a 3 × 3 matrix.
pub(crate) fn det3(m: &[[f64; 3]; 3]) -> f64 {
    m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
}

/// Determinant of a D × D matrix (D = 2 or 3).
pub(crate) fn det<const D: usize>(m: &[[f64; D]; D]) -> f64 {
    match D {
        2 => m[0][0] * m[1][1] - m[0][1] * m[1][0],
        _ => {
            let mut a = [[0.0; 3]; 3];
            a[2][2] = 1.0;
            for i in 0..D.min(3) {
                a[i][..D.min(3)].copy_from_slice(&m[i][..D.min(3)]);
            }
            det3(&a)
        }
    }
}

/// `xi` padded with zeros to a reference point.
pub(crate) fn ref_point<const D: usize>(xi: [f64; D]) -> RefPoint {
    std::array::from_fn(|k| if k < D { xi[k] } else { 0.0 })
}

/// The Jacobian of the cell `ty` (dimension `D`) with node coordinates `nodes` (Gmsh order)
/// at the reference point `xi` (see [`crate::lagrange`] for the reference domains).
///
/// # Errors
/// Unsupported type, wrong dimension, wrong node count, non-finite node.
pub fn jacobian<const D: usize>(
    ty: CellType,
    nodes: &[[f64; D]],
    xi: [f64; D],
) -> Result<Jacobian<D>, JacobianError> {
    check_cell(ty, nodes)?;
    let mut grads = vec![[0.0; 3]; nodes.len()];
    basis(ty)?.gradients(ref_point(xi), &mut grads);
    let matrix = matrix_from_gradients(nodes, &grads);
    Ok(Jacobian {
        det: det(&matrix),
        matrix,
    })
}

/// The physical point of the cell `ty` at the reference point `xi`: `Σ_i N_i(ξ) x_i`.
///
/// # Errors
/// Unsupported type, wrong dimension, wrong node count, non-finite node.
pub fn physical_from_reference<const D: usize>(
    ty: CellType,
    nodes: &[[f64; D]],
    xi: [f64; D],
) -> Result<[f64; D], JacobianError> {
    check_cell(ty, nodes)?;
    let mut n = vec![0.0; nodes.len()];
    basis(ty)?.values(ref_point(xi), &mut n);
    let mut p = [0.0; D];
    for (x, w) in nodes.iter().zip(&n) {
        for d in 0..D {
            p[d] += w * x[d];
        }
    }
    Ok(p)
}
