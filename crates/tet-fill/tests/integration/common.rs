//! Checks shared by the tests: positivity, face sharing, empty spheres, volumes.

use geom_predicates::{insphere, orient3d};
use std::collections::HashMap;

/// Six times the signed volume, positive for a positive tet (geom-predicates' convention).
pub fn volume6(p: &[[f64; 3]], t: [u32; 4]) -> f64 {
    let [a, b, c, d] = t.map(|v| p[v as usize]);
    let u = [0, 1, 2].map(|k| a[k] - d[k]);
    let v = [0, 1, 2].map(|k| b[k] - d[k]);
    let w = [0, 1, 2].map(|k| c[k] - d[k]);
    u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
        + u[2] * (v[0] * w[1] - v[1] * w[0])
}

/// The sum of the tets' volumes.
pub fn total_volume(p: &[[f64; 3]], tets: &[[u32; 4]]) -> f64 {
    tets.iter().map(|&t| volume6(p, t)).sum::<f64>() / 6.0
}

/// The faces of the tets (sorted corners) with, for each tet holding it, the exact side of its
/// apex (+1 or -1) relative to the sorted face.
pub fn faces(p: &[[f64; 3]], tets: &[[u32; 4]]) -> HashMap<[u32; 3], Vec<i8>> {
    let mut map: HashMap<[u32; 3], Vec<i8>> = HashMap::new();
    for t in tets {
        for i in 0..4 {
            let mut f = [0u32; 3];
            let mut n = 0;
            for (k, &v) in t.iter().enumerate() {
                if k != i {
                    f[n] = v;
                    n += 1;
                }
            }
            f.sort_unstable();
            let [a, b, c] = f.map(|v| p[v as usize]);
            let s = orient3d(a, b, c, p[t[i] as usize]);
            map.entry(f).or_default().push(if s > 0.0 { 1 } else { -1 });
        }
    }
    map
}

/// Every tet positive; every face in one tet or in two on opposite sides. Returns the faces
/// held by one tet.
pub fn check_valid(p: &[[f64; 3]], tets: &[[u32; 4]]) -> Vec<[u32; 3]> {
    for t in tets {
        let [a, b, c, d] = t.map(|v| p[v as usize]);
        assert!(orient3d(a, b, c, d) > 0.0, "tet {t:?} is not positive");
    }
    let mut boundary = Vec::new();
    for (f, sides) in faces(p, tets) {
        match sides.as_slice() {
            [_] => boundary.push(f),
            [x, y] => assert_ne!(x, y, "face {f:?}: its two tets overlap"),
            _ => panic!("face {f:?} is in {} tets", sides.len()),
        }
    }
    boundary
}

/// No point strictly inside any tet's circumsphere (exact; quadratic, for small sets).
pub fn check_empty_spheres(p: &[[f64; 3]], tets: &[[u32; 4]]) {
    for t in tets {
        let [a, b, c, d] = t.map(|v| p[v as usize]);
        for (i, &e) in p.iter().enumerate() {
            assert!(
                insphere(a, b, c, d, e) <= 0.0,
                "point {i} is inside the circumsphere of {t:?}"
            );
        }
    }
}

/// The boundary faces are supporting planes of the point set (the union is convex) and every
/// point is a corner: the tets tile the convex hull.
pub fn check_tiles_hull(p: &[[f64; 3]], tets: &[[u32; 4]], boundary: &[[u32; 3]]) {
    let faces = faces(p, tets);
    for f in boundary {
        let side = faces[f][0];
        let [a, b, c] = f.map(|v| p[v as usize]);
        for (i, &q) in p.iter().enumerate() {
            let s = orient3d(a, b, c, q);
            assert!(
                s == 0.0 || (s > 0.0) == (side > 0),
                "point {i} is beyond hull face {f:?}"
            );
        }
    }
    let mut used = vec![false; p.len()];
    for t in tets {
        for &v in t {
            used[v as usize] = true;
        }
    }
    assert!(used.iter().all(|&u| u), "a point is no tet's corner");
}

/// A fixed pseudo-random sequence in [0, 1) (xorshift).
pub fn randoms(n: usize, seed: u64) -> Vec<f64> {
    let mut s = seed | 1;
    (0..n)
        .map(|_| {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 11) as f64 / (1u64 << 53) as f64
        })
        .collect()
}
