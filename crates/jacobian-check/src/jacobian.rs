//! The Jacobian matrix of the map from a reference cell to a physical cell given by its
//! node coordinates, and its determinant, at one reference point.
//!
//! Owns the input checks shared by every per-cell function (node count, dimension,
//! finiteness). Does not decide validity: that is [`crate::certify`].

use mesh_model::CellType;

use crate::error::JacobianError;
use crate::lagrange::basis;
use crate::matrix::{det, matrix_from_gradients};
use crate::point::RefPoint;

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
