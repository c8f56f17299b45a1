//! The Jacobian matrix of the map from a reference cell to a physical cell given by its
//! node coordinates, and its determinant, at one reference point.
//!
//! Owns the input checks shared by every per-cell function (node count, dimension,
//! finiteness). Does not decide validity: that is [`crate::certify`].

use mesh_model::CellType;

use crate::error::JacobianError;
use crate::lagrange::{RefPoint, basis};

/// The Jacobian of a 2D cell at a reference point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jacobian2 {
    /// `matrix[i][j] = ∂x_i/∂ξ_j` (row: physical coordinate x or y; column: reference
    /// coordinate ξ or η).
    pub matrix: [[f64; 2]; 2],
    /// Its determinant: the ratio of physical to reference area at the point.
    pub det: f64,
}

/// The Jacobian of a 3D cell at a reference point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jacobian3 {
    /// `matrix[i][j] = ∂x_i/∂ξ_j`.
    pub matrix: [[f64; 3]; 3],
    /// Its determinant: the ratio of physical to reference volume at the point.
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

/// Determinant of a 2 × 2 matrix.
pub(crate) fn det2(m: &[[f64; 2]; 2]) -> f64 {
    m[0][0] * m[1][1] - m[0][1] * m[1][0]
}

/// Determinant of a 3 × 3 matrix.
pub(crate) fn det3(m: &[[f64; 3]; 3]) -> f64 {
    m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
}

/// The Jacobian of the 2D cell `ty` with node coordinates `nodes` (Gmsh order) at the
/// reference point `xi` (see [`crate::lagrange`] for the reference domains).
///
/// # Errors
/// Unsupported type, wrong dimension, wrong node count, non-finite node.
pub fn jacobian_2d(
    ty: CellType,
    nodes: &[[f64; 2]],
    xi: [f64; 2],
) -> Result<Jacobian2, JacobianError> {
    check_cell(ty, nodes)?;
    let mut grads = vec![[0.0; 3]; nodes.len()];
    basis(ty)?.gradients([xi[0], xi[1], 0.0], &mut grads);
    let matrix = matrix_from_gradients(nodes, &grads);
    Ok(Jacobian2 {
        det: det2(&matrix),
        matrix,
    })
}

/// The Jacobian of the 3D cell `ty` with node coordinates `nodes` (Gmsh order) at the
/// reference point `xi`.
///
/// # Errors
/// Unsupported type, wrong dimension, wrong node count, non-finite node.
pub fn jacobian_3d(
    ty: CellType,
    nodes: &[[f64; 3]],
    xi: RefPoint,
) -> Result<Jacobian3, JacobianError> {
    check_cell(ty, nodes)?;
    let mut grads = vec![[0.0; 3]; nodes.len()];
    basis(ty)?.gradients(xi, &mut grads);
    let matrix = matrix_from_gradients(nodes, &grads);
    Ok(Jacobian3 {
        det: det3(&matrix),
        matrix,
    })
}

/// The physical point of the 2D cell `ty` at the reference point `xi`: `Σ_i N_i(ξ) x_i`.
///
/// # Errors
/// Unsupported type, wrong dimension, wrong node count, non-finite node.
pub fn physical_from_reference_2d(
    ty: CellType,
    nodes: &[[f64; 2]],
    xi: [f64; 2],
) -> Result<[f64; 2], JacobianError> {
    check_cell(ty, nodes)?;
    let mut n = vec![0.0; nodes.len()];
    basis(ty)?.values([xi[0], xi[1], 0.0], &mut n);
    let mut p = [0.0; 2];
    for (x, w) in nodes.iter().zip(&n) {
        p[0] += w * x[0];
        p[1] += w * x[1];
    }
    Ok(p)
}
