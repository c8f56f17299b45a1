//! The small matrices of a Jacobian: the matrix `Σ_i x_i ⊗ ∇N_i` assembled from node
//! coordinates and shape-function gradients, and the determinants of 2 × 2 and 3 × 3
//! matrices. A leaf: the Jacobian of a cell (`jacobian`), the certified check, the area and
//! the pyramid's volume all evaluate their determinants here.

/// `Σ_i x_i ⊗ ∇N_i`: the Jacobian matrix from node coordinates and shape gradients.
pub fn matrix_from_gradients<const D: usize>(
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
