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

/// The region's volume from its facets (divergence theorem; normals point into the region).
pub fn region_volume(p: &[[f64; 3]], facets: &[[u32; 3]]) -> f64 {
    -facets
        .iter()
        .map(|f| {
            let [a, b, c] = f.map(|v| p[v as usize]);
            a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                + a[2] * (b[0] * c[1] - b[1] * c[0])
        })
        .sum::<f64>()
        / 6.0
}

/// The fill conforms: input points first and unchanged, tets valid, the faces held by one tet
/// exactly the input facets with that tet on the normal's side, volumes balanced.
pub fn check_fill(points: &[[f64; 3]], facets: &[[u32; 3]], out: &tet_fill::Fill) {
    assert!(out.points.len() >= points.len());
    for (a, b) in points.iter().zip(&out.points) {
        assert_eq!(a.map(f64::to_bits), b.map(f64::to_bits));
    }
    let boundary = check_valid(&out.points, &out.tets);
    let mut apex: HashMap<[u32; 3], u32> = HashMap::new();
    for t in &out.tets {
        for i in 0..4 {
            let mut f: Vec<u32> = (0..4).filter(|&k| k != i).map(|k| t[k]).collect();
            f.sort_unstable();
            apex.insert([f[0], f[1], f[2]], t[i]);
        }
    }
    let mut wanted: Vec<[u32; 3]> = facets
        .iter()
        .map(|f| {
            let mut k = *f;
            k.sort_unstable();
            k
        })
        .collect();
    wanted.sort_unstable();
    let mut got = boundary.clone();
    got.sort_unstable();
    assert_eq!(got.len(), wanted.len(), "boundary faces vs input facets");
    assert_eq!(
        got, wanted,
        "the fill's boundary faces are the input facets"
    );
    for f in facets {
        let mut k = *f;
        k.sort_unstable();
        let x = out.points[apex[&k] as usize];
        let [a, b, c] = f.map(|v| out.points[v as usize]);
        assert!(
            orient3d(a, b, c, x) < 0.0,
            "facet {f:?}: its tet is on the wrong side"
        );
    }
    let (v, want) = (
        total_volume(&out.points, &out.tets),
        region_volume(points, facets),
    );
    assert!(
        (v - want).abs() <= 1e-9 * want.abs(),
        "volume {v} vs {want}"
    );
}

/// Appends a surface: `points`, and `facets` offset to follow the points already there; the
/// facets flipped when `flip`.
pub fn append(
    points: &mut Vec<[f64; 3]>,
    facets: &mut Vec<[u32; 3]>,
    (p, f): (Vec<[f64; 3]>, Vec<[u32; 3]>),
    flip: bool,
) {
    let base = points.len() as u32;
    points.extend(p);
    facets.extend(f.into_iter().map(|[a, b, c]| {
        if flip {
            [a + base, c + base, b + base]
        } else {
            [a + base, b + base, c + base]
        }
    }));
}

/// An axis-aligned box, each face an `n × n` grid of squares split in two (alternating
/// diagonals), facets counter-clockwise seen from outside.
pub fn grid_box(lo: [f64; 3], hi: [f64; 3], n: usize) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    box_grid(lo, hi, [n; 3], true, |p| p)
}

/// A box's faces as grids of `n[axis]` cells along each axis, every cell split in two
/// (alternating diagonals when `alternate`, else all alike), each point then moved by `map`;
/// facets counter-clockwise seen from outside.
pub fn box_grid(
    lo: [f64; 3],
    hi: [f64; 3],
    n: [usize; 3],
    alternate: bool,
    map: impl Fn([f64; 3]) -> [f64; 3],
) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let mut points: Vec<[f64; 3]> = Vec::new();
    let mut index: HashMap<[usize; 3], u32> = HashMap::new();
    let mut id = |g: [usize; 3], points: &mut Vec<[f64; 3]>| {
        *index.entry(g).or_insert_with(|| {
            points.push(map(
                [0, 1, 2].map(|k| lo[k] + (hi[k] - lo[k]) * g[k] as f64 / n[k] as f64)
            ));
            (points.len() - 1) as u32
        })
    };
    let mut facets = Vec::new();
    for axis in 0..3 {
        let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
        for side in [0, n[axis]] {
            for i in 0..n[u] {
                for j in 0..n[v] {
                    let at = |di: usize, dj: usize| {
                        let mut g = [0; 3];
                        g[axis] = side;
                        g[u] = i + di;
                        g[v] = j + dj;
                        g
                    };
                    let q = [at(0, 0), at(1, 0), at(1, 1), at(0, 1)].map(|g| id(g, &mut points));
                    // (u, v, axis) is right-handed: q turns counter-clockwise seen from +axis
                    let q = if side == n[axis] {
                        q
                    } else {
                        [q[0], q[3], q[2], q[1]]
                    };
                    if !alternate || (i + j) % 2 == 0 {
                        facets.push([q[0], q[1], q[2]]);
                        facets.push([q[0], q[2], q[3]]);
                    } else {
                        facets.push([q[0], q[1], q[3]]);
                        facets.push([q[1], q[2], q[3]]);
                    }
                }
            }
        }
    }
    (points, facets)
}

/// An icosphere (the icosahedron's faces split `level` times, projected), facets
/// counter-clockwise seen from outside.
pub fn icosphere(centre: [f64; 3], radius: f64, level: usize) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let mut p: Vec<[f64; 3]> = vec![
        [-1.0, t, 0.0],
        [1.0, t, 0.0],
        [-1.0, -t, 0.0],
        [1.0, -t, 0.0],
        [0.0, -1.0, t],
        [0.0, 1.0, t],
        [0.0, -1.0, -t],
        [0.0, 1.0, -t],
        [t, 0.0, -1.0],
        [t, 0.0, 1.0],
        [-t, 0.0, -1.0],
        [-t, 0.0, 1.0],
    ];
    let mut f: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..level {
        let mut mid: HashMap<(u32, u32), u32> = HashMap::new();
        let mut next = Vec::new();
        for &[a, b, c] in &f {
            let mut m = |x: u32, y: u32| {
                *mid.entry((x.min(y), x.max(y))).or_insert_with(|| {
                    let (px, py) = (p[x as usize], p[y as usize]);
                    p.push([0, 1, 2].map(|k| (px[k] + py[k]) / 2.0));
                    (p.len() - 1) as u32
                })
            };
            let (ab, bc, ca) = (m(a, b), m(b, c), m(c, a));
            next.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        f = next;
    }
    let p = p
        .into_iter()
        .map(|q| {
            let l = (q[0] * q[0] + q[1] * q[1] + q[2] * q[2]).sqrt();
            [0, 1, 2].map(|k| centre[k] + radius * q[k] / l)
        })
        .collect();
    (p, f)
}

/// A tet's circumradius over its shortest edge.
pub fn radius_edge(p: &[[f64; 3]], t: [u32; 4]) -> f64 {
    let q = t.map(|v| p[v as usize]);
    let d = |a: [f64; 3], b: [f64; 3]| {
        ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
    };
    // the circumcentre solves 2 (q_i - q_0) · c = |q_i|² - |q_0|²
    let r = |i: usize| [0, 1, 2].map(|k| q[i][k] - q[0][k]);
    let (a, b, c) = (r(1), r(2), r(3));
    let cross = |u: [f64; 3], v: [f64; 3]| {
        [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ]
    };
    let dot = |u: [f64; 3], v: [f64; 3]| u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
    let det = 2.0 * dot(a, cross(b, c));
    let num = [0, 1, 2].map(|k| {
        dot(a, a) * cross(b, c)[k] + dot(b, b) * cross(c, a)[k] + dot(c, c) * cross(a, b)[k]
    });
    let radius = dot(num, num).sqrt() / det.abs();
    let mut short = f64::INFINITY;
    for i in 0..4 {
        for j in i + 1..4 {
            short = short.min(d(q[i], q[j]));
        }
    }
    radius / short
}

/// A tet's largest dihedral angle in degrees: at each edge, the angle between the other two
/// corners' offsets perpendicular to it.
pub fn max_dihedral(p: &[[f64; 3]], t: [u32; 4]) -> f64 {
    let q = t.map(|v| p[v as usize]);
    let sub = |a: [f64; 3], b: [f64; 3]| [0, 1, 2].map(|k| a[k] - b[k]);
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let mut worst: f64 = 0.0;
    for i in 0..4 {
        for j in i + 1..4 {
            // the edge shared by the faces opposite i and j, and the two other corners
            let e: Vec<usize> = (0..4).filter(|&k| k != i && k != j).collect();
            let axis = sub(q[e[1]], q[e[0]]);
            // the components of the other corners perpendicular to the edge
            let perp = |x: [f64; 3]| {
                let d = sub(x, q[e[0]]);
                let s = dot(d, axis) / dot(axis, axis);
                [0, 1, 2].map(|k| d[k] - s * axis[k])
            };
            let (u, w) = (perp(q[i]), perp(q[j]));
            let c = dot(u, w) / (dot(u, u) * dot(w, w)).sqrt();
            let angle = if c.is_finite() {
                c.clamp(-1.0, 1.0).acos().to_degrees()
            } else {
                180.0
            };
            worst = worst.max(angle);
        }
    }
    worst
}
