//! The shortcut for straight-sided high-order cells: when every node of a P2/P3 cell sits
//! where the order-1 map of its corners puts it (up to rounding), the cell's map *is* that
//! order-1 map, and its determinant is certified from the order-1 cell's few coefficients
//! instead of the full Bernstein expansion. Most cells of a curved viscous mesh are such
//! cells, so this is where the certification spends least.
//!
//! The same argument covers the 14- and 30-node pyramids (Gmsh types 14 and 118,
//! [`crate::pyramid`]): their (Bergot) spaces contain the linear pyramid's, so a high-order
//! pyramid whose nodes sit where the linear pyramid puts them (the 14-node one's edge nodes at
//! the edge midpoints, its base node at the mean of the base corners) *is* the linear
//! pyramid, and is certified as one; a curved one gets the full check.

use std::sync::OnceLock;

use mesh_model::{CellType, Shape};

use crate::error::JacobianError;
use crate::lagrange::{basis, reference_nodes};
use crate::types::{Feature, SLOTS, capabilities, slot};

/// Per type: the order-1 shape values at each of its reference nodes (row per node).
fn table(ty: CellType) -> Option<&'static Vec<f64>> {
    if is_pyramid14(ty) {
        return Some(pyramid14_table());
    }
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

/// Whether `ty` is the 14-node (P2) pyramid.
pub(crate) fn is_pyramid14(ty: CellType) -> bool {
    ty.shape == Shape::Pyramid && ty.order == 2
}

/// The linear pyramid's shape values at the 14-node pyramid's reference nodes: ½, ½ at an
/// edge's midpoint (the linear pyramid is linear along each edge), ¼ each at the base's
/// centre.
fn pyramid14_table() -> &'static Vec<f64> {
    static CACHE: OnceLock<Vec<f64>> = OnceLock::new();
    CACHE.get_or_init(|| {
        let mut values = vec![0.0; 14 * 5];
        for i in 0..5 {
            values[i * 5 + i] = 1.0;
        }
        for (k, e) in Shape::Pyramid.edges().iter().enumerate() {
            values[(5 + k) * 5 + e[0]] = 0.5;
            values[(5 + k) * 5 + e[1]] = 0.5;
        }
        values[13 * 5..13 * 5 + 4].fill(0.25);
        values
    })
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

    /// A linear pyramid (a sheared base, the apex off-centre) as 14 nodes: its corners, the
    /// edge midpoints, the base's centre.
    fn pyramid14(apex: [f64; 3]) -> Vec<[f64; 3]> {
        let mut k = vec![
            [0.0, 0.0, 0.0],
            [2.0, 0.1, 0.0],
            [2.1, 1.9, 0.1],
            [-0.1, 2.0, 0.0],
            apex,
        ];
        let mid = |a: [f64; 3], b: [f64; 3]| [0, 1, 2].map(|d| 0.5 * (a[d] + b[d]));
        for e in Shape::Pyramid.edges() {
            k.push(mid(k[e[0]], k[e[1]]));
        }
        k.push([0, 1, 2].map(|d| 0.25 * (k[0][d] + k[1][d] + k[2][d] + k[3][d])));
        k
    }

    #[test]
    fn a_straight_14_node_pyramid_is_its_linear_pyramid() {
        let ty = CellType::new(Shape::Pyramid, 2);
        let linear = CellType::new(Shape::Pyramid, 1);
        let params = CertifyParams::default();
        for apex in [[0.8, 1.1, 1.5], [0.8, 1.1, -0.7]] {
            let k = pyramid14(apex);
            let c = certify_cell(ty, &k, &params).unwrap();
            assert_eq!(c, certify_cell(linear, &k[..5], &params).unwrap());
            assert_eq!(c.is_valid(), apex[2] > 0.0);
            let v = crate::cell_volume(ty, &k).unwrap();
            assert_eq!(v, crate::cell_volume(linear, &k[..5]).unwrap());
        }
        // in a mesh: judged as the linear pyramid, the folded one named
        let mut mesh = mesh_model::Mesh::new(mesh_model::Dim::Three, 2);
        for apex in [[0.8, 1.1, 1.5], [0.8, 1.1, -0.7]] {
            let n0 = mesh.nodes.len() as u32;
            mesh.nodes.extend(pyramid14(apex));
            let ids: Vec<u32> = (n0..n0 + 14).collect();
            mesh.cells.push(ty, &ids);
        }
        let v = crate::check_mesh(&mesh, &params).unwrap();
        assert_eq!(v.invalid_cells, vec![1]);
        assert!(v.per_cell_scaled_jacobian[0] > 0.0);
    }

    #[test]
    fn a_curved_14_node_pyramid_gets_the_full_check() {
        let ty = CellType::new(Shape::Pyramid, 2);
        let mut k = pyramid14([0.8, 1.1, 1.5]);
        k[7][0] += 0.05; // the node on edge 0–4 off its midpoint
        assert!(is_straight(ty, &k).unwrap().is_none());
        let c = certify_cell(ty, &k, &CertifyParams::default()).unwrap();
        assert!(c.is_valid(), "{c:?}");
        let linear = crate::cell_volume(CellType::new(Shape::Pyramid, 1), &k[..5]).unwrap();
        let curved = crate::cell_volume(ty, &k).unwrap();
        assert!((curved - linear).abs() > 1e-4 && (curved - linear).abs() < 0.1);
    }
}
