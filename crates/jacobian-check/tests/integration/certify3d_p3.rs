//! The P3 solids — Gmsh's 20-node tetrahedron, 40-node prism, 64-node hexahedron and 30-node
//! pyramid: Lagrange bases through their reference nodes (the pyramid's equal to Gmsh's own
//! values), straight-sided cells valid with the certificate of their order-1 cell, affine
//! images with a constant determinant, a node pushed through the cell proved invalid, the
//! certified lower bound never above a dense sample on randomly perturbed cells, and volumes
//! equal to the integrated determinant.

use jacobian_check::{
    Certificate, CertifyParams, cell_volume, certify_cell, determinant_bernstein_coefficients,
    jacobian, reference_nodes, sampled_check, shape_functions, shape_gradients,
};
use mesh_model::{CellType, Shape};
use proptest::prelude::*;

const TET3: CellType = CellType::new(Shape::Tet, 3);
const PRISM3: CellType = CellType::new(Shape::Prism, 3);
const HEX3: CellType = CellType::new(Shape::Hex, 3);
const PYRAMID3: CellType = CellType::new(Shape::Pyramid, 3);
const P3: [CellType; 4] = [TET3, PRISM3, HEX3, PYRAMID3];

fn deep() -> CertifyParams {
    CertifyParams {
        max_depth: 10,
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

/// The reference nodes of `ty` mapped by the matrix `a` (row-major) plus `shift`.
fn affine(ty: CellType, a: &[f64; 9], shift: [f64; 3]) -> Vec<[f64; 3]> {
    reference_nodes(ty)
        .unwrap()
        .iter()
        .map(|r| [0, 1, 2].map(|i| shift[i] + (0..3).map(|j| a[3 * i + j] * r[j]).sum::<f64>()))
        .collect()
}

const SHEAR: [f64; 9] = [1.2, 0.3, -0.1, 0.1, 0.9, 0.2, -0.2, 0.1, 1.1];

fn det3(a: &[f64; 9]) -> f64 {
    a[0] * (a[4] * a[8] - a[5] * a[7]) - a[1] * (a[3] * a[8] - a[5] * a[6])
        + a[2] * (a[3] * a[7] - a[4] * a[6])
}

/// A certificate checked against dense sampling: a valid cell has every sample positive and
/// inside the certified bounds; an invalid one a non-positive determinant at `at`.
fn agrees_with_sampling(ty: CellType, nodes: &[[f64; 3]], c: Certificate<[f64; 3]>) {
    match c {
        Certificate::Valid {
            min_coeff,
            max_coeff,
        } => {
            let dense = sampled_check(ty, nodes, 13).unwrap();
            assert!(dense.min_det > 0.0, "{ty:?}: valid but sampled {dense:?}");
            let slack = 1e-11 * max_coeff.abs();
            assert!(
                min_coeff <= dense.min_det + slack && dense.max_det <= max_coeff + slack,
                "{ty:?}: bounds [{min_coeff}, {max_coeff}] vs {dense:?}"
            );
        }
        Certificate::Invalid { at } => {
            // at a pyramid's apex the proof is a limit along a ray into it: the least of
            // those along the four side edges, taken just below the apex
            let d = if ty.shape == Shape::Pyramid && at[2] > 1.0 - 1e-12 {
                let e = 1e-7;
                [[e, e], [-e, e], [e, -e], [-e, -e]]
                    .iter()
                    .map(|[u, v]| jacobian(ty, nodes, [*u, *v, 1.0 - e]).unwrap().det)
                    .fold(f64::INFINITY, f64::min)
            } else {
                jacobian(ty, nodes, at).unwrap().det
            };
            assert!(d <= 1e-6, "{ty:?}: invalid at {at:?} but det {d}");
        }
        Certificate::Undecided => {}
    }
}

#[test]
fn the_bases_interpolate_their_nodes_and_reproduce_affine_maps() {
    for ty in P3 {
        let nodes = reference_nodes(ty).unwrap();
        assert_eq!(nodes.len(), ty.node_count(), "{ty:?}");
        let mapped = affine(ty, &SHEAR, [0.3, -0.2, 0.5]);
        for (i, x) in nodes.iter().enumerate() {
            let n = shape_functions(ty, *x).unwrap();
            for (j, v) in n.iter().enumerate() {
                let want = if i == j { 1.0 } else { 0.0 };
                assert!((v - want).abs() < 1e-10, "{ty:?}: N{j}(x{i}) = {v}");
            }
        }
        // inside, away from the nodes: Σ N = 1, Σ ∇N = 0, the affine map reproduced
        let xi = match ty.shape {
            Shape::Hex => [0.17, -0.41, 0.29],
            Shape::Prism => [0.21, 0.33, -0.37],
            Shape::Pyramid => [0.11, -0.23, 0.31],
            _ => [0.21, 0.13, 0.31],
        };
        let n = shape_functions(ty, xi).unwrap();
        let g = shape_gradients(ty, xi).unwrap();
        assert!((n.iter().sum::<f64>() - 1.0).abs() < 1e-12, "{ty:?}");
        for d in 0..3 {
            assert!(g.iter().map(|v| v[d]).sum::<f64>().abs() < 1e-10, "{ty:?}");
        }
        let j = jacobian(ty, &mapped, xi).unwrap();
        assert!((j.det - det3(&SHEAR)).abs() < 1e-10, "{ty:?}: {}", j.det);
    }
}

#[test]
fn the_30_node_pyramid_basis_is_gmshs() {
    let text = include_str!("../data/gmsh_pyramid30_basis.txt");
    let mut rows = 0;
    for line in text.lines().filter(|l| !l.starts_with('#')) {
        let v: Vec<f64> = line.split(' ').map(|s| s.parse().unwrap()).collect();
        assert_eq!(v.len(), 3 + 30 + 90);
        let xi = [v[0], v[1], v[2]];
        let n = shape_functions(PYRAMID3, xi).unwrap();
        let g = shape_gradients(PYRAMID3, xi).unwrap();
        for i in 0..30 {
            assert!((n[i] - v[3 + i]).abs() < 1e-10, "N{i}{xi:?}");
            for d in 0..3 {
                let gmsh = v[33 + 3 * i + d];
                assert!(
                    (g[i][d] - gmsh).abs() < 1e-8 * (1.0 + gmsh.abs()),
                    "dN{i}/dx{d}{xi:?}: {} vs {gmsh}",
                    g[i][d]
                );
            }
        }
        rows += 1;
    }
    assert_eq!(rows, 43);
}

#[test]
fn affine_cells_have_a_constant_determinant() {
    for ty in P3 {
        let nodes = affine(ty, &SHEAR, [1.0, 2.0, 3.0]);
        // (the degree-8 expansions amplify the samples' rounding: about 1e-8 on the
        // hexahedron, the worst)
        let c = determinant_bernstein_coefficients(ty, &nodes).unwrap();
        for v in &c {
            assert!((v - det3(&SHEAR)).abs() < 1e-7, "{ty:?}: {v}");
        }
        let got = certify_cell(ty, &nodes, &CertifyParams::default()).unwrap();
        let sj = got.scaled_jacobian_lower_bound().unwrap();
        assert!((sj - 1.0).abs() < 1e-12, "{ty:?}: {got:?}");
    }
}

#[test]
fn a_node_pushed_through_the_cell_makes_it_invalid() {
    // the first edge node of edge 0 (corner 0 → 1) pushed far through the opposite side
    for ty in P3 {
        let mut nodes = reference_nodes(ty).unwrap();
        let k = ty.shape.corners();
        let inward = match ty.shape {
            Shape::Hex => [0.0, 4.0, 4.0],
            Shape::Prism => [0.0, 3.0, 4.0],
            _ => [0.0, 3.0, 3.0],
        };
        for d in 0..3 {
            nodes[k][d] += inward[d];
        }
        let c = certify_cell(ty, &nodes, &deep()).unwrap();
        assert!(matches!(c, Certificate::Invalid { .. }), "{ty:?}: {c:?}");
        agrees_with_sampling(ty, &nodes, c);
    }
}

/// Gauss–Legendre nodes and weights, 5 points on [−1, 1].
fn gauss5() -> [(f64, f64); 5] {
    let a = (5.0 - 2.0 * (10.0f64 / 7.0).sqrt()).sqrt() / 3.0;
    let b = (5.0 + 2.0 * (10.0f64 / 7.0).sqrt()).sqrt() / 3.0;
    let wa = (322.0 + 13.0 * 70.0f64.sqrt()) / 900.0;
    let wb = (322.0 - 13.0 * 70.0f64.sqrt()) / 900.0;
    [(0.0, 128.0 / 225.0), (a, wa), (-a, wa), (b, wb), (-b, wb)]
}

/// ∫ det J over the reference cell by a collapsed 5-point Gauss rule per direction (exact to
/// degree 9 per direction: enough for every P3 determinant), through the public Jacobian.
fn integrated(ty: CellType, nodes: &[[f64; 3]]) -> f64 {
    let g = gauss5();
    let mut total = 0.0;
    for &(a, wa) in &g {
        for &(b, wb) in &g {
            for &(c, wc) in &g {
                let (s, t, u) = (0.5 * (a + 1.0), 0.5 * (b + 1.0), 0.5 * (c + 1.0));
                let (xi, w) = match ty.shape {
                    Shape::Hex => ([a, b, c], 1.0),
                    Shape::Prism => ([s, (1.0 - s) * t, c], 0.25 * (1.0 - s)),
                    Shape::Tet => (
                        [s, (1.0 - s) * t, (1.0 - s) * (1.0 - t) * u],
                        0.125 * (1.0 - s) * (1.0 - s) * (1.0 - t),
                    ),
                    // the pyramid's collapsed box, ζ = u on [0, 1]
                    _ => (
                        [a * (1.0 - u), b * (1.0 - u), u],
                        0.5 * (1.0 - u) * (1.0 - u),
                    ),
                };
                total += wa * wb * wc * w * jacobian(ty, nodes, xi).unwrap().det;
            }
        }
    }
    total
}

#[test]
fn volumes_are_the_integrated_determinant() {
    for (ty, v) in [
        (TET3, 1.0 / 6.0),
        (PRISM3, 1.0),
        (HEX3, 8.0),
        (PYRAMID3, 4.0 / 3.0),
    ] {
        let got = cell_volume(ty, &reference_nodes(ty).unwrap()).unwrap();
        assert!((got - v).abs() < 1e-12, "{ty:?}: {got}");
        // every node off its place by a smooth field: a curved cell
        let mut nodes = affine(ty, &SHEAR, [0.0; 3]);
        for (i, x) in nodes.iter_mut().enumerate() {
            let s = (i as f64 * 0.7).sin();
            *x = [
                x[0] + 0.03 * s,
                x[1] - 0.02 * s * s,
                x[2] + 0.025 * (i as f64).cos(),
            ];
        }
        let want = integrated(ty, &nodes);
        let got = cell_volume(ty, &nodes).unwrap();
        assert!((got - want).abs() < 1e-11, "{ty:?}: {got} vs {want}");
        assert!((got - v * det3(&SHEAR)).abs() > 1e-4, "{ty:?}: not curved");
    }
}

/// The reference corners of `shape`, corner `i` moved by `moves[i]`, scaled and shifted.
fn corners(shape: Shape, moves: &[[f64; 3]], scale: f64) -> Vec<[f64; 3]> {
    let mut c = reference_nodes(CellType::new(shape, 1)).unwrap();
    for (x, m) in c.iter_mut().zip(moves) {
        *x = [0, 1, 2].map(|d| scale * (x[d] + m[d]) + 5.0 * scale);
    }
    c
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn straight_cells_are_certified_as_their_order_1_cell(
        moves in prop::collection::vec(prop::array::uniform3(-0.15..0.15f64), 8),
        scale in 0.01..100.0f64,
    ) {
        for ty in P3 {
            let k = corners(ty.shape, &moves, scale);
            let nodes = straight(ty, &k);
            let c = certify_cell(ty, &nodes, &CertifyParams::default()).unwrap();
            prop_assert!(c.is_valid(), "{:?}: {:?}", ty, c);
            let linear = CellType::new(ty.shape, 1);
            prop_assert_eq!(c, certify_cell(linear, &k, &CertifyParams::default()).unwrap());
            agrees_with_sampling(ty, &nodes, c);
            let v = cell_volume(ty, &nodes).unwrap();
            let v1 = cell_volume(linear, &k).unwrap();
            prop_assert!((v - v1).abs() <= 1e-10 * v1.abs(), "{:?}: {} vs {}", ty, v, v1);
        }
    }

    #[test]
    fn the_certified_bound_never_exceeds_a_dense_sample(
        bumps in prop::collection::vec(prop::array::uniform3(-1.0..1.0f64), 64),
        amplitude in 0.0..0.5f64,
    ) {
        for ty in P3 {
            let mut nodes = reference_nodes(ty).unwrap();
            for (n, b) in nodes.iter_mut().zip(&bumps).skip(ty.shape.corners()) {
                for d in 0..3 {
                    n[d] += amplitude * b[d];
                }
            }
            agrees_with_sampling(ty, &nodes, certify_cell(ty, &nodes, &deep()).unwrap());
        }
    }
}
