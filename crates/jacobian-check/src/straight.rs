//! The shortcut for straight-sided high-order cells: when every node of a P2/P3 cell sits
//! where the order-1 map of its corners puts it (up to rounding), the cell's map *is* that
//! order-1 map, and its determinant is certified from the order-1 cell's few coefficients
//! instead of the full Bernstein expansion. Most cells of a curved viscous mesh are such
//! cells, so this is where the certification spends least.

use std::sync::OnceLock;

use mesh_model::CellType;

use crate::error::JacobianError;
use crate::lagrange::{basis, reference_nodes};
use crate::types::{Feature, SLOTS, capabilities, slot};

/// Per type: the order-1 shape values at each of its reference nodes (row per node).
fn table(ty: CellType) -> Option<&'static Vec<f64>> {
    static CACHE: [OnceLock<Vec<f64>>; SLOTS] = [const { OnceLock::new() }; SLOTS];
    if !capabilities(ty)?.straight_shortcut {
        return None;
    }
    let i = slot(ty, Feature::ShapeFunctions).ok()?;
    Some(CACHE[i].get_or_init(|| {
        let linear = CellType::new(ty.shape, 1);
        let b = basis(linear).expect("order-1 bases exist for every certified shape");
        let corners = ty.shape.corners();
        let refs = reference_nodes(ty).expect("reference nodes of a certified type");
        let mut values = vec![0.0; refs.len() * corners];
        for (i, r) in refs.iter().enumerate() {
            b.values(*r, &mut values[i * corners..(i + 1) * corners]);
        }
        values
    }))
}

/// Whether the high-order cell `nodes` of type `ty` is its corners' order-1 map: every node
/// within a few units of rounding (relative to the coordinates' size) of its place.
/// `Ok(None)` for types without a shortcut.
pub(crate) fn is_straight<const D: usize>(
    ty: CellType,
    nodes: &[[f64; D]],
) -> Result<Option<f64>, JacobianError> {
    if ty.order < 2 {
        return Ok(None);
    }
    let Some(values) = table(ty) else {
        return Ok(None);
    };
    let n = ty.shape.corners();
    let scale = nodes
        .iter()
        .flat_map(|x| x.iter())
        .fold(0.0f64, |m, c| m.max(c.abs()));
    let tolerance = 16.0 * f64::EPSILON * scale.max(f64::MIN_POSITIVE);
    for (i, x) in nodes.iter().enumerate().skip(n) {
        let w = &values[i * n..(i + 1) * n];
        for d in 0..D {
            let at: f64 = (0..n).map(|j| w[j] * nodes[j][d]).sum();
            if (x[d] - at).abs() > tolerance {
                return Ok(None);
            }
        }
    }
    Ok(Some(tolerance))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::certify::{CertifyParams, certify_cell};
    use mesh_model::Shape;

    fn bilinear_quad(p: u8, bend: f64) -> Vec<[f64; 2]> {
        let c = [[0.0, 0.0], [2.0, 0.1], [2.2, 1.0], [-0.1, 0.9]];
        let ty = CellType::new(Shape::Quad, p);
        let mut out: Vec<[f64; 2]> = reference_nodes(ty)
            .unwrap()
            .iter()
            .map(|r| {
                let (u, v) = (0.5 * (r[0] + 1.0), 0.5 * (r[1] + 1.0));
                let w = [(1.0 - u) * (1.0 - v), u * (1.0 - v), u * v, (1.0 - u) * v];
                [0, 1].map(|d| (0..4).map(|j| w[j] * c[j][d]).sum())
            })
            .collect();
        out[4][1] += bend;
        out
    }

    #[test]
    fn a_straight_cell_takes_the_shortcut_with_the_same_verdict() {
        for p in [2, 3] {
            let ty = CellType::new(Shape::Quad, p);
            let straight = bilinear_quad(p, 0.0);
            assert!(is_straight(ty, &straight).unwrap().is_some());
            let fast = certify_cell(ty, &straight, &CertifyParams::default()).unwrap();
            let linear = certify_cell(
                CellType::new(Shape::Quad, 1),
                &straight[..4],
                &CertifyParams::default(),
            )
            .unwrap();
            assert_eq!(fast, linear);
        }
    }

    #[test]
    fn a_slightly_bent_cell_gets_the_full_check() {
        for p in [2, 3] {
            let ty = CellType::new(Shape::Quad, p);
            assert!(is_straight(ty, &bilinear_quad(p, 1e-9)).unwrap().is_none());
            // bent far enough to fold: the full check finds it
            let folded = bilinear_quad(p, 3.0);
            let c = certify_cell(ty, &folded, &CertifyParams::default()).unwrap();
            assert!(!c.is_valid(), "P{p}: {c:?}");
        }
    }
}
