//! Tet measures: dihedral angles, circumcentre and circumradius, edge lengths.

/// `b - a`.
#[inline]
pub(crate) fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [b[0] - a[0], b[1] - a[1], b[2] - a[2]]
}

#[inline]
pub(crate) fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[inline]
pub(crate) fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// The distance between two points.
#[inline]
pub(crate) fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    let d = sub(a, b);
    dot(d, d).sqrt()
}

/// The largest of a tet's six dihedral angles, in degrees (180 for a flat tet).
pub(crate) fn max_dihedral_deg(p: [[f64; 3]; 4]) -> f64 {
    // the outward normals of the faces opposite each corner; the dihedral angle at the edge
    // between faces i and j is π minus the angle between their outward normals
    let normals: Vec<[f64; 3]> = (0..4)
        .map(|i| {
            let f: Vec<usize> = (0..4).filter(|&k| k != i).collect();
            let n = cross(sub(p[f[0]], p[f[1]]), sub(p[f[0]], p[f[2]]));
            let towards = sub(p[f[0]], p[i]);
            let s = if dot(n, towards) > 0.0 { -1.0 } else { 1.0 };
            let len = dot(n, n).sqrt();
            if len == 0.0 {
                [0.0; 3]
            } else {
                n.map(|x| s * x / len)
            }
        })
        .collect();
    let mut worst: f64 = 0.0;
    for i in 0..4 {
        for j in i + 1..4 {
            let c = dot(normals[i], normals[j]).clamp(-1.0, 1.0);
            worst = worst.max(180.0 - c.acos().to_degrees());
        }
    }
    if normals.contains(&[0.0; 3]) {
        180.0
    } else {
        worst
    }
}

/// A shape measure in (0, 1]: 1 for the regular tet, towards 0 for flat ones (6√2 times the
/// volume over the cube of the root mean square edge); negative for inverted tets.
pub(crate) fn shape(p: [[f64; 3]; 4]) -> f64 {
    let v6 = dot(sub(p[3], p[0]), cross(sub(p[3], p[1]), sub(p[3], p[2])));
    let mut s2 = 0.0;
    for i in 0..4 {
        for j in i + 1..4 {
            let d = sub(p[i], p[j]);
            s2 += dot(d, d);
        }
    }
    let rms = (s2 / 6.0).sqrt();
    // orient3d's sign convention: positive tets have v6 > 0
    2f64.sqrt() * v6 / (rms * rms * rms)
}

/// The circumcentre of a tet (None when flat).
pub(crate) fn circumcentre(p: [[f64; 3]; 4]) -> Option<[f64; 3]> {
    let (a, b, c) = (sub(p[0], p[1]), sub(p[0], p[2]), sub(p[0], p[3]));
    let det = 2.0 * dot(a, cross(b, c));
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    let (la, lb, lc) = (dot(a, a), dot(b, b), dot(c, c));
    let num = [0, 1, 2].map(|k| la * cross(b, c)[k] + lb * cross(c, a)[k] + lc * cross(a, b)[k]);
    Some([0, 1, 2].map(|k| p[0][k] + num[k] / det))
}

/// The shortest and longest edge of a tet.
pub(crate) fn edge_range(p: [[f64; 3]; 4]) -> (f64, f64) {
    let mut lo = f64::INFINITY;
    let mut hi: f64 = 0.0;
    for i in 0..4 {
        for j in i + 1..4 {
            let d = dist(p[i], p[j]);
            lo = lo.min(d);
            hi = hi.max(d);
        }
    }
    (lo, hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn regular_tet_measures() {
        let s = 1.0 / 2f64.sqrt();
        let p = [
            [1.0, 0.0, -s],
            [-1.0, 0.0, -s],
            [0.0, 1.0, s],
            [0.0, -1.0, s],
        ];
        assert!((max_dihedral_deg(p) - 70.528_779).abs() < 1e-5);
        let c = circumcentre(p).unwrap();
        assert!(c.iter().all(|x| x.abs() < 1e-12));
        let corner = [[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        assert!((max_dihedral_deg(corner) - 90.0).abs() < 1e-9);
    }
}
