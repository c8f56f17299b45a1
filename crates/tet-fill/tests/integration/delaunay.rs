//! The unconstrained Delaunay tetrahedralisation: random sets and grids (co-spherical and
//! coplanar degeneracies), checked exactly.

use crate::common::*;
use geom_predicates::orient3d;
use proptest::prelude::*;
use tet_fill::{FillError, delaunay};

fn check_all(p: &[[f64; 3]]) -> Vec<[u32; 4]> {
    let tets = delaunay(p).unwrap();
    if tets.is_empty() {
        // no tet only when no four points span a volume
        for (i, j, k, l) in quads(p.len()) {
            assert_eq!(orient3d(p[i], p[j], p[k], p[l]), 0.0);
        }
        return tets;
    }
    let boundary = check_valid(p, &tets);
    check_empty_spheres(p, &tets);
    check_tiles_hull(p, &tets, &boundary);
    tets
}

/// Every quadruple of indices below `n` (for small `n`).
fn quads(n: usize) -> impl Iterator<Item = (usize, usize, usize, usize)> {
    (0..n).flat_map(move |i| {
        (i + 1..n)
            .flat_map(move |j| (j + 1..n).flat_map(move |k| (k + 1..n).map(move |l| (i, j, k, l))))
    })
}

fn grid(n: [usize; 3], h: f64) -> Vec<[f64; 3]> {
    let mut p = Vec::new();
    for i in 0..n[0] {
        for j in 0..n[1] {
            for k in 0..n[2] {
                p.push([i as f64 * h, j as f64 * h, k as f64 * h]);
            }
        }
    }
    p
}

#[test]
fn grids_tile_their_box() {
    for n in [[2, 2, 2], [3, 3, 3], [4, 3, 2], [5, 5, 5], [7, 2, 3]] {
        let p = grid(n, 0.1);
        let tets = check_all(&p);
        let exact = [0, 1, 2]
            .map(|k| (n[k] - 1) as f64 * 0.1)
            .iter()
            .product::<f64>();
        let v = total_volume(&p, &tets);
        assert!((v - exact).abs() <= 1e-12 * exact, "{n:?}: {v} vs {exact}");
    }
}

#[test]
fn a_larger_grid_and_random_set_are_valid() {
    let p = grid([12, 11, 10], 1.0);
    let tets = delaunay(&p).unwrap();
    let boundary = check_valid(&p, &tets);
    check_tiles_hull(&p, &tets, &boundary);
    assert!((total_volume(&p, &tets) - 990.0).abs() < 1e-9);
    let r = randoms(3 * 5000, 7);
    let p: Vec<[f64; 3]> = r.chunks(3).map(|c| [c[0], c[1], c[2]]).collect();
    let tets = delaunay(&p).unwrap();
    let boundary = check_valid(&p, &tets);
    check_tiles_hull(&p, &tets, &boundary);
}

#[test]
fn points_on_a_sphere() {
    // all co-spherical: any tetrahedralisation of the hull is Delaunay
    let n = 200;
    let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
    let p: Vec<[f64; 3]> = (0..n)
        .map(|i| {
            let z = 1.0 - 2.0 * (i as f64 + 0.5) / n as f64;
            let r = (1.0 - z * z).sqrt();
            let a = golden * i as f64;
            [r * a.cos(), r * a.sin(), z]
        })
        .collect();
    check_all(&p);
}

#[test]
fn bad_and_degenerate_inputs() {
    assert!(delaunay(&[]).unwrap().is_empty());
    let flat = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
    ];
    assert!(delaunay(&flat).unwrap().is_empty());
    let dup = [[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]];
    assert!(matches!(
        delaunay(&dup),
        Err(FillError::DuplicatePoint {
            first: 1,
            second: 3,
            ..
        })
    ));
    let nan = [[0.0; 3], [f64::NAN, 0.0, 0.0]];
    assert!(matches!(
        delaunay(&nan),
        Err(FillError::NonFinitePoint { index: 1, .. })
    ));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn random_sets_are_delaunay(pts in prop::collection::vec([0.0f64..1.0, 0.0f64..1.0, 0.0f64..1.0], 4..60)) {
        let mut p = pts;
        p.sort_by(|a, b| a.partial_cmp(b).unwrap());
        p.dedup();
        check_all(&p);
    }

    #[test]
    fn integer_sets_are_delaunay(pts in prop::collection::vec([0i32..4, 0i32..4, 0i32..3], 4..40)) {
        // small integer coordinates: many coplanar and co-spherical subsets
        let mut p: Vec<[f64; 3]> = pts.iter().map(|q| q.map(f64::from)).collect();
        p.sort_by(|a, b| a.partial_cmp(b).unwrap());
        p.dedup();
        check_all(&p);
    }
}
