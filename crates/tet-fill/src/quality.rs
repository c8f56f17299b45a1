//! Tet measures: dihedral angles, circumcentre and circumradius, edge lengths.

/// `b - a`.
#[inline]
pub(crate) fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [b[0] - a[0], b[1] - a[1], b[2] - a[2]]
}

pub(crate) use geom_predicates::vector::{cross3 as cross, dist, dot};

/// The largest of a tet's six dihedral angles, in degrees (180 for a flat tet), either
/// orientation: no allocation, one `acos`.
pub(crate) fn max_dihedral_deg(p: [[f64; 3]; 4]) -> f64 {
    180.0 - dihedral_rank(p).acos().to_degrees()
}

/// Minus the cosine of a tet's largest dihedral angle, either orientation: in [-1, 1],
/// increasing with the angle, 1 for a flat tet — what comparisons of angles need, without the
/// `acos` (a third of the angle's cost).
pub(crate) fn dihedral_rank(p: [[f64; 3]; 4]) -> f64 {
    // the faces' normals, all outward (a positive tet) or all inward (`FACE` orients every
    // face alike); the dihedral angle at the edge between faces i and j is π minus the angle
    // between their outward normals, so the largest angle is where two normals align most
    let mut normals = [[0.0; 3]; 4];
    let mut inverse = [0.0; 4];
    for i in 0..4 {
        let [a, b, c] = crate::mesh::FACE[i].map(|k| p[k]);
        normals[i] = cross(sub(a, b), sub(a, c));
        let len = dot(normals[i], normals[i]).sqrt();
        if len == 0.0 || !len.is_finite() {
            return 1.0;
        }
        inverse[i] = 1.0 / len;
    }
    let mut most = -1.0f64;
    for i in 0..4 {
        for j in i + 1..4 {
            most = most.max(dot(normals[i], normals[j]) * inverse[i] * inverse[j]);
        }
    }
    most.clamp(-1.0, 1.0)
}

/// [`dihedral_rank`] of a tet whose largest dihedral angle is `deg` degrees.
pub(crate) fn rank_of_deg(deg: f64) -> f64 {
    -deg.to_radians().cos()
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
    let (bc, ca, ab) = (cross(b, c), cross(c, a), cross(a, b));
    let det = 2.0 * dot(a, bc);
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    let (la, lb, lc) = (dot(a, a), dot(b, b), dot(c, c));
    let num = [0, 1, 2].map(|k| la * bc[k] + lb * ca[k] + lc * ab[k]);
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
        let rank = dihedral_rank(corner);
        assert!((rank - rank_of_deg(90.0)).abs() < 1e-12);
        assert!(rank_of_deg(150.0) > rank && rank > dihedral_rank(p));
    }
}
