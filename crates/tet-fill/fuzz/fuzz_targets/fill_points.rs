//! Fuzzes `tet_fill`: the input bytes become points on a small integer grid (so coplanar,
//! co-spherical and duplicate points are common), tetrahedralised by `delaunay`; and the
//! corners of an octahedron inside a cube, moved by the bytes, filled by `fill`. Neither may
//! panic; a Delaunay result must be positive tetrahedra over the given points, a fill's must
//! keep the input points first.
#![no_main]

use libfuzzer_sys::fuzz_target;
use tet_fill::{FillInput, FillOptions, delaunay, fill};

/// The cube's corners and its 12 triangles facing in, then the octahedron's 6 corners and
/// its 8 triangles facing out.
const CUBE: [[f64; 3]; 8] = [
    [-4.0, -4.0, -4.0],
    [4.0, -4.0, -4.0],
    [4.0, 4.0, -4.0],
    [-4.0, 4.0, -4.0],
    [-4.0, -4.0, 4.0],
    [4.0, -4.0, 4.0],
    [4.0, 4.0, 4.0],
    [-4.0, 4.0, 4.0],
];
const CUBE_IN: [[u32; 3]; 12] = [
    [0, 1, 2],
    [0, 2, 3],
    [4, 6, 5],
    [4, 7, 6],
    [0, 5, 1],
    [0, 4, 5],
    [1, 6, 2],
    [1, 5, 6],
    [2, 7, 3],
    [2, 6, 7],
    [3, 4, 0],
    [3, 7, 4],
];
const OCTA_OUT: [[u32; 3]; 8] = [
    [8, 10, 12],
    [10, 9, 12],
    [9, 11, 12],
    [11, 8, 12],
    [10, 8, 13],
    [9, 10, 13],
    [11, 9, 13],
    [8, 11, 13],
];

fuzz_target!(|data: &[u8]| {
    // points on a grid of 8 × 8 × 8
    let points: Vec<[f64; 3]> = data
        .chunks_exact(3)
        .take(200)
        .map(|c| [c[0] % 8, c[1] % 8, c[2] % 8].map(f64::from))
        .collect();
    if let Ok(tets) = delaunay(&points) {
        for t in &tets {
            assert!(t.iter().all(|&v| (v as usize) < points.len()));
        }
    }
    // an octahedron of half-size 1 to 2.5 along each axis, inside the cube
    let r = |k: usize| 1.0 + f64::from(data.get(k).copied().unwrap_or(0) % 16) / 10.0;
    let mut all: Vec<[f64; 3]> = CUBE.to_vec();
    all.extend([
        [r(0), 0.0, 0.0],
        [-r(1), 0.0, 0.0],
        [0.0, r(2), 0.0],
        [0.0, -r(3), 0.0],
        [0.0, 0.0, r(4)],
        [0.0, 0.0, -r(5)],
    ]);
    let facets: Vec<[u32; 3]> = CUBE_IN.iter().chain(&OCTA_OUT).copied().collect();
    let input = FillInput {
        points: &all,
        facets: &facets,
    };
    if let Ok(f) = fill(&input, &FillOptions::default()) {
        assert_eq!(&f.points[..all.len()], &all[..]);
    }
});
