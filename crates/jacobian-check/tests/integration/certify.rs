//! The certified check earns its keep: cells folded only between sample points are caught
//! where a coarse sampled check passes them; curved valid cells are never rejected;
//! straight-sided cells have the constant linear determinant; affine maps and mild
//! perturbations agree with dense sampling.

use jacobian_check::{
    Certificate, CertifyParams, JacobianError, certify_cell, check_mesh,
    determinant_bernstein_coefficients, jacobian, reference_nodes, sampled_check,
};
use mesh_io::testkit::{AnnulusParams, annulus, reference_cells_3d};
use mesh_model::{CellType, Shape, polygon_area};
use proptest::prelude::*;

const TRI2: CellType = CellType::new(Shape::Tri, 2);
const TRI3: CellType = CellType::new(Shape::Tri, 3);
const QUAD2: CellType = CellType::new(Shape::Quad, 2);
const QUAD3: CellType = CellType::new(Shape::Quad, 3);

fn types_2d() -> [CellType; 6] {
    [
        CellType::new(Shape::Tri, 1),
        TRI2,
        TRI3,
        CellType::new(Shape::Quad, 1),
        QUAD2,
        QUAD3,
    ]
}

fn reference_2d(ty: CellType) -> Vec<[f64; 2]> {
    reference_nodes(ty)
        .unwrap()
        .iter()
        .map(|p| [p[0], p[1]])
        .collect()
}

/// The reference cell with `moves` (node, displacement) applied, scaled by `s`.
fn pushed(ty: CellType, moves: &[(usize, [f64; 2])], s: f64) -> Vec<[f64; 2]> {
    let mut n = reference_2d(ty);
    for (i, d) in moves {
        n[*i][0] += s * d[0];
        n[*i][1] += s * d[1];
    }
    n
}

fn deep() -> CertifyParams {
    CertifyParams {
        max_depth: 12,
        ..CertifyParams::default()
    }
}

/// The cell is folded (proved, and confirmed by dense sampling), its corners are fine,
/// the fold is away from them, and a coarse sampled check sees nothing.
fn assert_folded_between_samples(ty: CellType, nodes: &[[f64; 2]], coarse_points_per_edge: usize) {
    let cert = certify_cell(ty, nodes, &deep()).unwrap();
    let Certificate::Invalid { at } = cert else {
        panic!("{ty:?}: expected Invalid, got {cert:?}");
    };
    let det_at = jacobian(ty, nodes, at).unwrap().det;
    assert!(
        det_at <= 1e-12,
        "{ty:?}: det at the proved point {at:?} is {det_at}"
    );
    let corners = reference_2d(CellType::new(ty.shape, 1));
    for c in &corners {
        assert!(
            jacobian(ty, nodes, *c).unwrap().det > 0.0,
            "{ty:?} corner {c:?}"
        );
        let d = ((c[0] - at[0]).powi(2) + (c[1] - at[1]).powi(2)).sqrt();
        assert!(d > 0.1, "{ty:?}: fold at {at:?} is at a corner");
    }
    let coarse = sampled_check(ty, nodes, coarse_points_per_edge).unwrap();
    assert!(
        coarse.all_positive(),
        "{ty:?}: the coarse check should miss the fold: {coarse:?}"
    );
    let dense = sampled_check(ty, nodes, 301).unwrap();
    assert!(
        !dense.all_positive(),
        "{ty:?}: dense sampling confirms the fold"
    );
}

#[test]
fn p2_triangle_folded_only_between_samples_is_caught() {
    // Three edge nodes pushed together; the determinant first vanishes on edge 0–1 near
    // ξ ≈ 0.62 (at s ≈ 0.6518), between the lattice points of 5, 11 and 21 per edge.
    let moves = [(3, [0.4, 0.9]), (4, [1.0, 0.0]), (5, [-0.9, 0.4])];
    let nodes = pushed(TRI2, &moves, 0.6537);
    for coarse in [5, 11, 21] {
        assert_folded_between_samples(TRI2, &nodes, coarse);
    }
    // Slightly less pushed, the same cell is proved valid.
    assert!(
        certify_cell(TRI2, &pushed(TRI2, &moves, 0.645), &deep())
            .unwrap()
            .is_valid()
    );
}

#[test]
fn p3_triangle_with_an_edge_node_slid_along_its_edge_is_caught() {
    // Node 3 (ξ = 1/3 on edge 0–1) slid towards node 4: along the edge x'(ξ) = 1 + s·N₃'(ξ)
    // with min N₃' = −3.5 at ξ = 5/9, so the fold starts at s = 2/7 (node at 0.61905) and
    // sits near ξ = 5/9 — between the lattice points of 6 and 11 per edge.
    let mut nodes = reference_2d(TRI3);
    nodes[3] = [0.6219, 0.0];
    assert_folded_between_samples(TRI3, &nodes, 6);
    assert_folded_between_samples(TRI3, &nodes, 11);
    nodes[3] = [0.6160, 0.0];
    assert!(certify_cell(TRI3, &nodes, &deep()).unwrap().is_valid());
}

#[test]
fn p3_quad_with_an_edge_node_slid_along_its_edge_is_caught() {
    // The same slide on the tensor cell: node 4 (ξ = −1/3 on edge 0–1); the fold starts at
    // ξ₄ = −1/3 + 4/7 = 0.2381.
    let mut nodes = reference_2d(QUAD3);
    nodes[4] = [0.2438, -1.0];
    assert_folded_between_samples(QUAD3, &nodes, 6);
    assert_folded_between_samples(QUAD3, &nodes, 11);
    nodes[4] = [0.232, -1.0];
    assert!(certify_cell(QUAD3, &nodes, &deep()).unwrap().is_valid());
}

#[test]
fn p2_quad_folded_inside_is_caught() {
    // All five high-order nodes pushed; the fold starts inside the cell near (0.88, −0.12)
    // at s ≈ 0.7731.
    let moves = [
        (4, [0.89, 0.85]),
        (5, [0.23, -0.18]),
        (6, [-0.31, 0.72]),
        (7, [0.22, 0.09]),
        (8, [0.84, 0.98]),
    ];
    let nodes = pushed(QUAD2, &moves, 0.7754);
    assert_folded_between_samples(QUAD2, &nodes, 6);
    assert_folded_between_samples(QUAD2, &nodes, 11);
    assert!(
        certify_cell(QUAD2, &pushed(QUAD2, &moves, 0.76), &deep())
            .unwrap()
            .is_valid()
    );
}

#[test]
fn curved_annulus_cells_are_all_valid() {
    for order in [2, 3] {
        // Moderately to strongly curved: 6 cells around, thin and thick rings.
        for (angular_cells, outer_radius) in [(6, 1.3), (8, 2.0), (24, 1.05)] {
            let mesh = annulus(&AnnulusParams {
                order,
                radial_cells: 2,
                angular_cells,
                inner_radius: 1.0,
                outer_radius,
                triangle_mask: vec![true, false],
            });
            let v = check_mesh(&mesh, &CertifyParams::default()).unwrap();
            assert!(v.invalid_cells.is_empty(), "P{order}: {v:?}");
            assert!(v.undecided.is_empty(), "P{order}: {v:?}");
            assert!(v.min_scaled_jacobian > 0.0 && v.min_scaled_jacobian <= 1.0);
            assert_eq!(v.per_cell_scaled_jacobian.len(), mesh.cells.len());
        }
    }
}

/// A P3 annulus with an edge node of cell 5 slid far along its edge, past its neighbour.
fn annulus_folded_at_cell_5() -> mesh_model::Mesh {
    let mut mesh = annulus(&AnnulusParams {
        order: 3,
        ..AnnulusParams::default()
    });
    let cell = mesh.cells.get(5);
    let (a, b, n) = (cell.nodes[0], cell.nodes[1], cell.nodes[3]);
    let (pa, pb) = (mesh.nodes[a as usize], mesh.nodes[b as usize]);
    mesh.nodes[n as usize] = [0.1 * pa[0] + 0.9 * pb[0], 0.1 * pa[1] + 0.9 * pb[1], 0.0];
    mesh
}

#[test]
fn a_fold_in_a_mesh_is_reported_with_its_cell() {
    let mesh = annulus_folded_at_cell_5();
    let v = check_mesh(&mesh, &CertifyParams::default()).unwrap();
    assert!(v.invalid_cells.contains(&5), "{v:?}");
    assert!(v.per_cell_scaled_jacobian[5] <= 0.0);
    assert!(v.min_scaled_jacobian <= 0.0);
}

#[test]
fn the_per_cell_min_det_is_the_certificates_and_nan_where_not_valid() {
    let mesh = annulus_folded_at_cell_5();
    let params = CertifyParams::default();
    let v = check_mesh(&mesh, &params).unwrap();
    assert_eq!(v.per_cell_min_det.len(), mesh.cells.len());
    for (i, c) in mesh.cells.iter().enumerate() {
        let nodes: Vec<[f64; 2]> = c.nodes.iter().map(|&k| mesh.xy(k)).collect();
        match certify_cell(c.ty, &nodes, &params).unwrap() {
            Certificate::Valid { min_coeff, .. } => {
                assert_eq!(
                    v.per_cell_min_det[i].to_bits(),
                    min_coeff.to_bits(),
                    "cell {i}"
                );
            }
            other => assert!(v.per_cell_min_det[i].is_nan(), "cell {i}: {other:?}"),
        }
    }
    assert!(v.per_cell_min_det[5].is_nan());
}

#[test]
fn straight_sided_cells_have_the_constant_linear_determinant() {
    let a = [[1.3, 0.4], [-0.2, 0.9]];
    let b = [5.0, -2.0];
    let det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
    for ty in types_2d() {
        let nodes: Vec<[f64; 2]> = reference_2d(ty)
            .iter()
            .map(|x| {
                [
                    a[0][0] * x[0] + a[0][1] * x[1] + b[0],
                    a[1][0] * x[0] + a[1][1] * x[1] + b[1],
                ]
            })
            .collect();
        let coeffs = determinant_bernstein_coefficients(ty, &nodes).unwrap();
        for c in &coeffs {
            assert!((c - det).abs() < 1e-12, "{ty:?}: {c} vs {det}");
        }
        // The determinant is the physical area over the reference area (1/2 or 4).
        let corners: Vec<[f64; 2]> = nodes[..ty.shape.corners()].to_vec();
        let ref_area = if ty.shape == Shape::Tri { 0.5 } else { 4.0 };
        assert!((polygon_area(corners) / ref_area - det).abs() < 1e-12);
        let Certificate::Valid {
            min_coeff,
            max_coeff,
        } = certify_cell(ty, &nodes, &CertifyParams::default()).unwrap()
        else {
            panic!("{ty:?} straight cell not valid");
        };
        assert!((min_coeff - det).abs() < 1e-12 && (max_coeff - det).abs() < 1e-12);
    }
}

#[test]
fn bad_input_is_an_error() {
    let p = CertifyParams::default();
    assert!(matches!(
        certify_cell(TRI2, &reference_2d(TRI3), &p),
        Err(JacobianError::NodeCount {
            expected: 6,
            got: 10,
            ..
        })
    ));
    let mut nodes = reference_2d(TRI2);
    nodes[4][1] = f64::NAN;
    assert_eq!(
        certify_cell(TRI2, &nodes, &p),
        Err(JacobianError::NonFiniteNode { node: 4 })
    );
    assert!(matches!(
        certify_cell(
            CellType::new(Shape::Tet, 1),
            &reference_2d(CellType::new(Shape::Quad, 1)),
            &p
        ),
        Err(JacobianError::WrongDimension { .. })
    ));
    let bad = CertifyParams { max_depth: 99, ..p };
    assert!(matches!(
        certify_cell(TRI2, &reference_2d(TRI2), &bad),
        Err(JacobianError::BadParameter {
            name: "max_depth",
            ..
        })
    ));
    assert!(matches!(
        sampled_check(TRI2, &reference_2d(TRI2), 1),
        Err(JacobianError::BadParameter { .. })
    ));
    let mut mesh = annulus(&AnnulusParams::default());
    mesh.cells.nodes_mut(2)[1] = 10_000;
    assert!(matches!(
        check_mesh(&mesh, &p),
        Err(JacobianError::NodeOutOfRange {
            cell: 2,
            node: 10_000
        })
    ));
}

#[test]
fn a_cell_touching_zero_is_undecided_not_a_panic() {
    // The P3 slide of the test above at its exact threshold: the determinant's minimum is
    // 0, attained at ξ = 5/9 on edge 0–1 only, so no finite subdivision proves validity;
    // rounding may make it a proved (tiny) fold instead.
    let mut nodes = reference_2d(TRI3);
    nodes[3] = [1.0 / 3.0 + 2.0 / 7.0, 0.0];
    let c = certify_cell(
        TRI3,
        &nodes,
        &CertifyParams {
            max_depth: 6,
            ..CertifyParams::default()
        },
    )
    .unwrap();
    assert!(
        matches!(c, Certificate::Undecided | Certificate::Invalid { .. }),
        "{c:?}"
    );
}

#[test]
fn reference_3d_cells_are_certified_or_sampled() {
    let mesh = reference_cells_3d(1);
    let v = check_mesh(&mesh, &CertifyParams::default()).unwrap();
    assert!(
        v.invalid_cells.is_empty() && v.undecided.is_empty(),
        "{v:?}"
    );
    // every linear 3D type has a certificate: none is left to sampling
    assert!(v.uncertified.is_empty(), "{v:?}");
    let mesh2 = reference_cells_3d(2);
    for cell in mesh2.cells.iter() {
        let xyz: Vec<[f64; 3]> = cell
            .nodes
            .iter()
            .map(|&n| mesh2.nodes[n as usize])
            .collect();
        // every P2 3D type, the 14-node pyramid included
        assert!(
            certify_cell(cell.ty, &xyz, &CertifyParams::default())
                .unwrap()
                .is_valid()
        );
        assert!(sampled_check(cell.ty, &xyz, 5).unwrap().all_positive());
    }
}

fn affine_2d(ty: CellType, a: [[f64; 2]; 2], b: [f64; 2]) -> Vec<[f64; 2]> {
    reference_2d(ty)
        .iter()
        .map(|x| {
            [
                a[0][0] * x[0] + a[0][1] * x[1] + b[0],
                a[1][0] * x[0] + a[1][1] * x[1] + b[1],
            ]
        })
        .collect()
}

proptest! {
    #[test]
    fn affine_cells_are_valid_exactly_when_positively_oriented(
        m in prop::array::uniform4(-2.0..2.0f64),
        shift in prop::array::uniform2(-10.0..10.0f64),
    ) {
        let a = [[m[0], m[1]], [m[2], m[3]]];
        let det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
        prop_assume!(det.abs() > 1e-3);
        for ty in types_2d() {
            let c = certify_cell(ty, &affine_2d(ty, a, shift), &CertifyParams::default()).unwrap();
            if det > 0.0 {
                prop_assert!(c.is_valid(), "{:?} det {} {:?}", ty, det, c);
            } else {
                prop_assert!(matches!(c, Certificate::Invalid { .. }), "{:?} det {} {:?}", ty, det, c);
            }
        }
    }

    #[test]
    fn affine_3d_cells_are_valid_exactly_when_positively_oriented(
        m in prop::array::uniform9(-2.0..2.0f64),
    ) {
        let a = [[m[0], m[1], m[2]], [m[3], m[4], m[5]], [m[6], m[7], m[8]]];
        let det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1])
            - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0])
            + a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
        prop_assume!(det.abs() > 1e-2);
        for (shape, order) in [
            (Shape::Tet, 1), (Shape::Tet, 2), (Shape::Hex, 1), (Shape::Hex, 2),
            (Shape::Prism, 1), (Shape::Prism, 2), (Shape::Pyramid, 1), (Shape::Pyramid, 2),
        ] {
            let ty = CellType::new(shape, order);
            let nodes: Vec<[f64; 3]> = reference_nodes(ty).unwrap().iter()
                .map(|x| [0, 1, 2].map(|i| (0..3).map(|j| a[i][j] * x[j]).sum()))
                .collect();
            let c = certify_cell(ty, &nodes, &CertifyParams::default()).unwrap();
            prop_assert_eq!(c.is_valid(), det > 0.0, "{:?} det {} {:?}", ty, det, c);
            if let Certificate::Invalid { at } = c {
                prop_assert!(jacobian(ty, &nodes, at).unwrap().det <= 0.0);
            }
        }
    }

    #[test]
    fn certificates_agree_with_dense_sampling_on_perturbed_cells(
        bumps in prop::collection::vec(prop::array::uniform2(-1.0..1.0f64), 16),
        amplitude in 0.0..0.35f64,
    ) {
        for ty in [TRI2, TRI3, QUAD2, QUAD3] {
            let size = if ty.shape == Shape::Tri { 1.0 } else { 2.0 };
            let mut nodes = reference_2d(ty);
            for (i, n) in nodes.iter_mut().enumerate().skip(ty.shape.corners()) {
                n[0] += amplitude * size * bumps[i][0];
                n[1] += amplitude * size * bumps[i][1];
            }
            let c = certify_cell(ty, &nodes, &deep()).unwrap();
            match c {
                Certificate::Valid { min_coeff, max_coeff } => {
                    let dense = sampled_check(ty, &nodes, 41).unwrap();
                    prop_assert!(dense.min_det > 0.0, "{:?}: valid but sampled {:?}", ty, dense);
                    prop_assert!(min_coeff <= dense.min_det + 1e-12 && dense.max_det <= max_coeff + 1e-12);
                }
                Certificate::Invalid { at } => {
                    let d = jacobian(ty, &nodes, at).unwrap().det;
                    prop_assert!(d <= 1e-12, "{:?}: invalid at {:?} but det {}", ty, at, d);
                }
                Certificate::Undecided => {}
            }
        }
    }
}
