//! The certificates of the prisms (6 and 18 nodes) and the linear pyramid: straight-sided
//! cells are valid with the sampled scaled Jacobian, a node pushed through the opposite face
//! makes the cell invalid, and on randomly perturbed cells the certificate never says valid
//! where a dense sample is negative (nor invalid where the determinant is positive).

use jacobian_check::{
    Certificate, CertifyParams, certify_cell, jacobian, reference_nodes, sampled_check,
    shape_functions,
};
use mesh_model::{CellType, Shape};
use proptest::prelude::*;

const PRISM1: CellType = CellType::new(Shape::Prism, 1);
const PRISM2: CellType = CellType::new(Shape::Prism, 2);
const PYRAMID1: CellType = CellType::new(Shape::Pyramid, 1);

fn deep() -> CertifyParams {
    CertifyParams {
        max_depth: 12,
        ..CertifyParams::default()
    }
}

/// The cell of type `ty` whose corners are `corners` and whose other nodes sit where the
/// corners' order-1 map puts them (a straight-sided cell).
fn straight(ty: CellType, corners: &[[f64; 3]]) -> Vec<[f64; 3]> {
    let linear = CellType::new(ty.shape, 1);
    reference_nodes(ty)
        .unwrap()
        .iter()
        .map(|r| {
            let w = shape_functions(linear, *r).unwrap();
            [0, 1, 2].map(|d| (0..corners.len()).map(|j| w[j] * corners[j][d]).sum())
        })
        .collect()
}

/// The reference corners of `shape` with corner `i` moved by `moves[i]`.
fn moved_corners(shape: Shape, moves: &[[f64; 3]]) -> Vec<[f64; 3]> {
    let mut c = reference_nodes(CellType::new(shape, 1)).unwrap();
    for (x, m) in c.iter_mut().zip(moves) {
        for d in 0..3 {
            x[d] += m[d];
        }
    }
    c
}

/// Checks a certificate against dense sampling: a valid cell has every sample positive and
/// inside the certified bounds; an invalid one has a non-positive determinant at `at`.
fn agrees_with_sampling(ty: CellType, nodes: &[[f64; 3]], c: Certificate<[f64; 3]>) {
    match c {
        Certificate::Valid {
            min_coeff,
            max_coeff,
        } => {
            let dense = sampled_check(ty, nodes, 21).unwrap();
            assert!(dense.min_det > 0.0, "{ty:?}: valid but sampled {dense:?}");
            let slack = 1e-12 * max_coeff.abs();
            assert!(
                min_coeff <= dense.min_det + slack && dense.max_det <= max_coeff + slack,
                "{ty:?}: bounds [{min_coeff}, {max_coeff}] vs {dense:?}"
            );
        }
        Certificate::Invalid { at } => {
            let d = jacobian(ty, nodes, at).unwrap().det;
            assert!(d <= 1e-12, "{ty:?}: invalid at {at:?} but det {d}");
        }
        Certificate::Undecided => {}
    }
}

#[test]
fn reference_cells_are_valid_with_scaled_jacobian_one() {
    for ty in [PRISM1, PRISM2, PYRAMID1] {
        let nodes = reference_nodes(ty).unwrap();
        let c = certify_cell(ty, &nodes, &CertifyParams::default()).unwrap();
        let sj = c.scaled_jacobian_lower_bound().unwrap();
        assert!((sj - 1.0).abs() < 1e-12, "{ty:?}: {c:?}");
    }
}

#[test]
fn a_node_pushed_through_the_opposite_face_makes_the_cell_invalid() {
    // prisms: a top corner pushed below the bottom triangle
    for ty in [PRISM1, PRISM2] {
        let corners = moved_corners(
            Shape::Prism,
            &[[0.0; 3], [0.0; 3], [0.0; 3], [0.0, 0.0, -2.5]],
        );
        let nodes = straight(ty, &corners);
        let c = certify_cell(ty, &nodes, &deep()).unwrap();
        assert!(matches!(c, Certificate::Invalid { .. }), "{ty:?}: {c:?}");
        agrees_with_sampling(ty, &nodes, c);
    }
    // the pyramid: its apex pushed below the base
    let corners = moved_corners(
        Shape::Pyramid,
        &[[0.0; 3], [0.0; 3], [0.0; 3], [0.0; 3], [0.3, 0.1, -1.2]],
    );
    let c = certify_cell(PYRAMID1, &corners, &deep()).unwrap();
    assert!(matches!(c, Certificate::Invalid { .. }), "{c:?}");
    agrees_with_sampling(PYRAMID1, &corners, c);
    // a base corner pushed across the opposite base edge folds the base: invalid too
    let corners = moved_corners(Shape::Pyramid, &[[0.0; 3], [0.0; 3], [-2.6, 0.0, 0.0]]);
    let c = certify_cell(PYRAMID1, &corners, &deep()).unwrap();
    assert!(matches!(c, Certificate::Invalid { .. }), "{c:?}");
    // a P2 prism folded by a mid-edge node alone (the top triangle's edge 3-4 node pushed
    // down through the bottom face), its corners untouched
    let mut nodes = reference_nodes(PRISM2).unwrap();
    nodes[12][2] = -2.0;
    let c = certify_cell(PRISM2, &nodes, &deep()).unwrap();
    assert!(matches!(c, Certificate::Invalid { .. }), "{c:?}");
    agrees_with_sampling(PRISM2, &nodes, c);
}

#[test]
fn a_pyramid_with_a_slanted_apex_is_certified_over_the_whole_cell() {
    // The determinant is constant along the rays from the apex: an apex far off to the side
    // but above the base plane keeps the cell valid, one just below it does not.
    let above = moved_corners(
        Shape::Pyramid,
        &[[0.0; 3], [0.0; 3], [0.0; 3], [0.0; 3], [3.0, 2.0, 0.2]],
    );
    let c = certify_cell(PYRAMID1, &above, &deep()).unwrap();
    assert!(c.is_valid(), "{c:?}");
    agrees_with_sampling(PYRAMID1, &above, c);
    let below = moved_corners(
        Shape::Pyramid,
        &[[0.0; 3], [0.0; 3], [0.0; 3], [0.0; 3], [3.0, 2.0, -1.01]],
    );
    let c = certify_cell(PYRAMID1, &below, &deep()).unwrap();
    assert!(!c.is_valid(), "{c:?}");
}

proptest! {
    #[test]
    fn straight_cells_are_valid_with_the_sampled_scaled_jacobian(
        moves in prop::collection::vec(prop::array::uniform3(-0.15..0.15f64), 6),
        scale in 0.01..100.0f64,
    ) {
        for ty in [PRISM1, PRISM2, PYRAMID1] {
            let corners: Vec<[f64; 3]> = moved_corners(ty.shape, &moves)
                .iter()
                .map(|x| x.map(|v| scale * v + 7.0 * scale))
                .collect();
            let nodes = straight(ty, &corners);
            let c = certify_cell(ty, &nodes, &CertifyParams::default()).unwrap();
            prop_assert!(c.is_valid(), "{:?}: {:?}", ty, c);
            let bound = c.scaled_jacobian_lower_bound().unwrap();
            let dense = sampled_check(ty, &nodes, 21).unwrap();
            let sampled = dense.min_det / dense.max_det;
            // a lower bound, and close: the prism's determinant is at most quadratic
            prop_assert!(bound <= sampled + 1e-12, "{:?}: {} > {}", ty, bound, sampled);
            prop_assert!(bound > 0.5 * sampled, "{:?}: {} vs {}", ty, bound, sampled);
            if ty.order == 2 {
                // the straight P2 prism is its P1 prism
                let linear = certify_cell(PRISM1, &corners, &CertifyParams::default()).unwrap();
                prop_assert_eq!(c, linear);
            }
            agrees_with_sampling(ty, &nodes, c);
        }
    }

    #[test]
    fn certificates_agree_with_dense_sampling_on_perturbed_cells(
        bumps in prop::collection::vec(prop::array::uniform3(-1.0..1.0f64), 18),
        amplitude in 0.0..0.6f64,
    ) {
        let mut prism = reference_nodes(PRISM2).unwrap();
        for (i, n) in prism.iter_mut().enumerate().skip(6) {
            for d in 0..3 {
                n[d] += amplitude * bumps[i][d];
            }
        }
        agrees_with_sampling(PRISM2, &prism, certify_cell(PRISM2, &prism, &deep()).unwrap());
        let mut prism1 = reference_nodes(PRISM1).unwrap();
        let mut pyramid = reference_nodes(PYRAMID1).unwrap();
        for (i, n) in prism1.iter_mut().chain(pyramid.iter_mut()).enumerate() {
            for d in 0..3 {
                n[d] += 1.5 * amplitude * bumps[i][d];
            }
        }
        agrees_with_sampling(PRISM1, &prism1, certify_cell(PRISM1, &prism1, &deep()).unwrap());
        agrees_with_sampling(PYRAMID1, &pyramid, certify_cell(PYRAMID1, &pyramid, &deep()).unwrap());
    }
}

#[test]
fn volumes_are_exact_for_straight_and_curved_cells() {
    use jacobian_check::cell_volume;
    // reference cells
    for (ty, v) in [
        (PRISM1, 1.0),
        (PRISM2, 1.0),
        (PYRAMID1, 4.0 / 3.0),
        (CellType::new(Shape::Tet, 2), 1.0 / 6.0),
        (CellType::new(Shape::Hex, 2), 8.0),
    ] {
        let got = cell_volume(ty, &reference_nodes(ty).unwrap()).unwrap();
        assert!((got - v).abs() < 1e-13, "{ty:?}: {got}");
    }
    // a pyramid with a slanted apex at height 2 over a 2 × 2 base: 8/3
    let mut pyramid = reference_nodes(PYRAMID1).unwrap();
    pyramid[4] = [0.7, -0.4, 2.0];
    assert!((cell_volume(PYRAMID1, &pyramid).unwrap() - 8.0 / 3.0).abs() < 1e-13);
    // a P2 tet whose edge 0–1 node is pushed out of its face z = 0 by 0.1: the face moves by
    // 0.1 · 4λ₀λ₁ along −z, whose integral over the unit triangle is 0.1 · 4/24
    let tet2 = CellType::new(Shape::Tet, 2);
    let mut tet = reference_nodes(tet2).unwrap();
    tet[4][2] -= 0.1;
    let got = cell_volume(tet2, &tet).unwrap();
    assert!((got - (1.0 / 6.0 + 0.1 / 6.0)).abs() < 1e-13, "{got}");
}
