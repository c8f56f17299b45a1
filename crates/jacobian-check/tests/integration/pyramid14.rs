//! The curved 14-node pyramid (Gmsh type 14): its shape functions are Gmsh's (compared with
//! Gmsh's own values), its certificate agrees with its linear pyramid when straight-sided,
//! gives an affine image a constant determinant, refuses a node pushed through the cell,
//! bounds the determinant sampled anywhere, and its volume is the integral of the determinant
//! and the volume its curved faces enclose.

use jacobian_check::{
    Certificate, CertifyParams, cell_volume, certify_cell, determinant_bernstein_coefficients,
    enclosed_volume, jacobian, reference_nodes, shape_functions, shape_gradients,
};
use mesh_model::{CellType, Dim, Mesh, Shape};
use proptest::prelude::*;

const PYRAMID1: CellType = CellType::new(Shape::Pyramid, 1);
const PYRAMID2: CellType = CellType::new(Shape::Pyramid, 2);

#[test]
fn the_shape_functions_and_gradients_are_gmshs() {
    let text = include_str!("../data/gmsh_pyramid14_basis.txt");
    let mut rows = 0;
    for line in text.lines().filter(|l| !l.starts_with('#')) {
        let v: Vec<f64> = line.split(' ').map(|s| s.parse().unwrap()).collect();
        assert_eq!(v.len(), 3 + 14 + 42);
        let xi = [v[0], v[1], v[2]];
        let n = shape_functions(PYRAMID2, xi).unwrap();
        let g = shape_gradients(PYRAMID2, xi).unwrap();
        for i in 0..14 {
            assert!(
                (n[i] - v[3 + i]).abs() < 1e-12,
                "N{i}{xi:?}: {} vs {}",
                n[i],
                v[3 + i]
            );
            for d in 0..3 {
                let gmsh = v[17 + 3 * i + d];
                assert!(
                    (g[i][d] - gmsh).abs() < 1e-9 * (1.0 + gmsh.abs()),
                    "dN{i}/dx{d}{xi:?}: {} vs {gmsh}",
                    g[i][d]
                );
            }
        }
        rows += 1;
    }
    assert_eq!(rows, 43);
}

/// A reference point inside the pyramid from three numbers in [0, 1] (the apex included).
fn inside(a: f64, b: f64, c: f64) -> [f64; 3] {
    [(1.0 - c) * (2.0 * a - 1.0), (1.0 - c) * (2.0 * b - 1.0), c]
}

/// The reference 14-node pyramid mapped by `a` (row-major 3 × 3), its non-corner nodes moved
/// by `moves`.
fn pyramid(a: &[f64; 9], moves: &[[f64; 3]]) -> Vec<[f64; 3]> {
    let mut x: Vec<[f64; 3]> = reference_nodes(PYRAMID2)
        .unwrap()
        .iter()
        .map(|r| [0, 1, 2].map(|i| (0..3).map(|j| a[3 * i + j] * r[j]).sum()))
        .collect();
    for (k, m) in moves.iter().enumerate() {
        for d in 0..3 {
            x[5 + k][d] += m[d];
        }
    }
    x
}

const ID: [f64; 9] = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0];

fn det3(a: &[f64; 9]) -> f64 {
    a[0] * (a[4] * a[8] - a[5] * a[7]) - a[1] * (a[3] * a[8] - a[5] * a[6])
        + a[2] * (a[3] * a[7] - a[4] * a[6])
}

/// ∫ det J over the pyramid by a 4-point Gauss–Legendre rule per collapsed coordinate
/// (exact to degree 7, above the degrees at hand, and computed through the public Jacobian only).
fn integrated(nodes: &[[f64; 3]]) -> f64 {
    let g: [(f64, f64); 4] = [
        (0.339_981_043_584_856, 0.652_145_154_862_546),
        (0.861_136_311_594_053, 0.347_854_845_137_454),
        (-0.339_981_043_584_856, 0.652_145_154_862_546),
        (-0.861_136_311_594_053, 0.347_854_845_137_454),
    ];
    let mut total = 0.0;
    for &(x, wx) in &g {
        for &(y, wy) in &g {
            for &(z, wz) in &g {
                let zeta = 0.5 * (1.0 + z);
                let t = 1.0 - zeta;
                let j = jacobian(PYRAMID2, nodes, [x * t, y * t, zeta]).unwrap();
                total += wx * wy * 0.5 * wz * t * t * j.det;
            }
        }
    }
    total
}

/// The mesh of one pyramid with its five faces (the base a 9-node quadrilateral, the sides
/// 6-node triangles) as boundary facets.
fn with_faces(nodes: &[[f64; 3]]) -> Mesh {
    let mut mesh = Mesh::new(Dim::Three, 2);
    mesh.nodes = nodes.to_vec();
    mesh.cells.push(PYRAMID2, &(0..14).collect::<Vec<u32>>());
    // Gmsh edge nodes: 0-1 5, 0-3 6, 0-4 7, 1-2 8, 1-4 9, 2-3 10, 2-4 11, 3-4 12; base 13
    let tri6 = CellType::new(Shape::Tri, 2);
    for f in [
        [0, 1, 4, 5, 9, 7],
        [3, 0, 4, 6, 7, 12],
        [1, 2, 4, 8, 11, 9],
        [2, 3, 4, 10, 12, 11],
    ] {
        mesh.boundary.push(tri6, &f);
    }
    mesh.boundary.push(
        CellType::new(Shape::Quad, 2),
        &[0, 3, 2, 1, 6, 10, 8, 5, 13],
    );
    mesh
}

/// Checks `x` is proved invalid and has the volume Gmsh 4.15 integrates for it (its
/// `getJacobians` at the Gauss12 points; Gmsh's minSJ of each is negative).
fn folded(x: &[[f64; 3]], gmsh_volume: f64) {
    let c = certify_cell(PYRAMID2, x, &CertifyParams::default()).unwrap();
    assert!(matches!(c, Certificate::Invalid { .. }), "{c:?}");
    let v = cell_volume(PYRAMID2, x).unwrap();
    assert!((v - gmsh_volume).abs() < 1e-12, "{v} vs Gmsh {gmsh_volume}");
}

#[test]
fn a_node_pushed_through_the_cell_is_refused() {
    // the node of edge 0-4 through the opposite faces (Gmsh's minSJ -3.08)
    let mut x = pyramid(&ID, &[]);
    x[7] = [1.2, 1.2, 0.5];
    folded(&x, 0.2);
    // the base's node above the apex (minSJ -8.12)
    let mut x = pyramid(&ID, &[]);
    x[13] = [0.0, 0.0, 1.5];
    folded(&x, -4.0 / 3.0);
    // a base edge node across the base's centre (minSJ -2.78)
    let mut x = pyramid(&ID, &[]);
    x[5] = [0.0, 1.1, 0.0];
    folded(&x, 0.633_333_333_333_333);
}

#[test]
fn a_curved_pyramid_encloses_its_volume() {
    // the base bowed down, a side edge bent: the faces enclose what the cell integrates
    let mut x = pyramid(&ID, &[]);
    x[5][2] -= 0.2;
    x[13][2] -= 0.15;
    x[9] = [0.6, -0.4, 0.55];
    assert!(
        certify_cell(PYRAMID2, &x, &CertifyParams::default())
            .unwrap()
            .is_valid()
    );
    let v = cell_volume(PYRAMID2, &x).unwrap();
    let e = enclosed_volume(&with_faces(&x)).unwrap();
    assert!((v - e).abs() < 1e-13, "{v} vs {e}");
    assert!((v - integrated(&x)).abs() < 1e-13);
    // Gmsh 4.15 integrates 1.64488888888889 (its minSJ 0.82)
    assert!((v - 1.644_888_888_888_89).abs() < 1e-12, "{v}");
}

/// A random matrix near 1.5 × the identity, well-conditioned.
fn matrix() -> impl Strategy<Value = [f64; 9]> {
    prop::array::uniform9(-1.0..1.0f64)
        .prop_filter("well-conditioned", |m| det3(&conditioned(*m)).abs() > 0.3)
}

fn conditioned(m: [f64; 9]) -> [f64; 9] {
    let mut a = m;
    for k in [0, 4, 8] {
        a[k] += 1.5;
    }
    a
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn a_straight_pyramid_is_its_linear_pyramid(m in matrix(), apex in prop::array::uniform3(-0.5..0.5f64)) {
        let a = conditioned(m);
        let mut x = pyramid(&a, &[]);
        // the apex moved: still straight-sided when the edge nodes follow
        for d in 0..3 { x[4][d] += apex[d]; }
        let linear: Vec<[f64; 3]> = x[..5].to_vec();
        let straight: Vec<[f64; 3]> = reference_nodes(PYRAMID2).unwrap().iter()
            .map(|r| {
                let w = shape_functions(PYRAMID1, *r).unwrap();
                [0, 1, 2].map(|d| (0..5).map(|j| w[j] * linear[j][d]).sum())
            })
            .collect();
        let params = CertifyParams::default();
        let c2 = certify_cell(PYRAMID2, &straight, &params).unwrap();
        let c1 = certify_cell(PYRAMID1, &linear, &params).unwrap();
        prop_assert_eq!(c2.is_valid(), c1.is_valid());
        let (v2, v1) = (cell_volume(PYRAMID2, &straight).unwrap(), cell_volume(PYRAMID1, &linear).unwrap());
        prop_assert!((v2 - v1).abs() <= 1e-12 * v1.abs().max(1.0), "{} vs {}", v2, v1);
        // the full expansion (no shortcut) agrees: its bounds hold the linear pyramid's
        let c = determinant_bernstein_coefficients(PYRAMID2, &straight).unwrap();
        let lo = c.iter().copied().fold(f64::INFINITY, f64::min);
        if let Certificate::Valid { min_coeff, .. } = c1 {
            prop_assert!(lo <= min_coeff + 1e-9);
        }
        prop_assert!((integrated(&straight) - v1).abs() <= 1e-12 * v1.abs().max(1.0));
    }

    #[test]
    fn an_affine_pyramid_has_a_constant_determinant(m in matrix()) {
        let a = conditioned(m);
        let x = pyramid(&a, &[]);
        let c = determinant_bernstein_coefficients(PYRAMID2, &x).unwrap();
        let d = det3(&a);
        // (relative to the determinant: its coefficients come out of some twenty products of
        // the corners, each rounded, and reach 12 where the case above failed at 1.1e-11)
        for v in &c {
            prop_assert!((v - d).abs() < 1e-11 * d.abs().max(1.0), "{} vs {}", v, d);
        }
        let cert = certify_cell(PYRAMID2, &x, &CertifyParams::default()).unwrap();
        prop_assert_eq!(cert.is_valid(), d > 0.0);
    }

    #[test]
    fn the_bounds_hold_the_determinant_and_the_volume_is_its_integral(
        m in matrix(),
        moves in prop::collection::vec(prop::array::uniform3(-0.35..0.35f64), 9),
        samples in prop::collection::vec(prop::array::uniform3(0.0..=1.0f64), 64),
    ) {
        let a = conditioned(m);
        let x = pyramid(&a, &moves);
        let c = determinant_bernstein_coefficients(PYRAMID2, &x).unwrap();
        let lo = c.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = c.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let slack = 1e-10 * hi.abs().max(lo.abs());
        let mut least = f64::INFINITY;
        for s in &samples {
            let d = jacobian(PYRAMID2, &x, inside(s[0], s[1], s[2])).unwrap().det;
            prop_assert!(d >= lo - slack && d <= hi + slack, "{} not in [{}, {}]", d, lo, hi);
            least = least.min(d);
        }
        let v = cell_volume(PYRAMID2, &x).unwrap();
        prop_assert!((v - integrated(&x)).abs() <= 1e-11 * v.abs().max(1.0), "{}", v);
        let e = enclosed_volume(&with_faces(&x)).unwrap();
        prop_assert!((v - e).abs() <= 1e-11 * v.abs().max(1.0), "{} vs {}", v, e);
        // the certificate never contradicts a sample
        let cert = certify_cell(PYRAMID2, &x, &CertifyParams { max_depth: 10, ..Default::default() }).unwrap();
        match cert {
            Certificate::Valid { min_coeff, max_coeff } => {
                prop_assert!(least >= min_coeff - slack);
                prop_assert!(min_coeff > 0.0 && max_coeff <= hi + slack);
            }
            Certificate::Invalid { .. } => prop_assert!(lo <= 0.0),
            Certificate::Undecided => {}
        }
    }
}
