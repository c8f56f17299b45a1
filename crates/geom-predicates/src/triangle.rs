//! Segment–triangle and triangle–triangle intersection in 3D on closed sets, decided with the
//! exact [`orient3d`] (and [`orient2d`] on a coordinate plane when everything is coplanar).
//! Triangles must not be degenerate (three collinear corners); segments may be.

use crate::orient::{orient2d, orient3d};
use crate::segment::segments_meet;

/// Drops axis `k` of a 3D point.
#[inline]
fn drop_axis(p: [f64; 3], k: usize) -> [f64; 2] {
    match k {
        0 => [p[1], p[2]],
        1 => [p[0], p[2]],
        _ => [p[0], p[1]],
    }
}

/// Whether the closed 2D triangle `a b c` (either orientation) contains `p`.
fn in_triangle_2d(p: [f64; 2], a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> bool {
    let (s1, s2, s3) = (orient2d(a, b, p), orient2d(b, c, p), orient2d(c, a, p));
    (s1 >= 0.0 && s2 >= 0.0 && s3 >= 0.0) || (s1 <= 0.0 && s2 <= 0.0 && s3 <= 0.0)
}

/// Segment `p q` against triangle `a b c`, all in one plane: projected onto a coordinate plane
/// on which the triangle keeps a non-zero area (the projection is then one-to-one on the
/// common plane, so incidences are kept).
fn coplanar_segment_triangle(t: [[f64; 3]; 3], p: [f64; 3], q: [f64; 3]) -> bool {
    let Some(k) = (0..3)
        .find(|&k| orient2d(drop_axis(t[0], k), drop_axis(t[1], k), drop_axis(t[2], k)) != 0.0)
    else {
        return false; // degenerate triangle: outside the contract
    };
    let [a, b, c] = t.map(|x| drop_axis(x, k));
    let (p, q) = (drop_axis(p, k), drop_axis(q, k));
    in_triangle_2d(p, a, b, c)
        || in_triangle_2d(q, a, b, c)
        || segments_meet(p, q, a, b)
        || segments_meet(p, q, b, c)
        || segments_meet(p, q, c, a)
}

/// Whether the closed segment `p q` and the closed triangle `a b c` share a point (crossing,
/// touching an edge or corner, or lying in the triangle's plane across it). Exact.
pub fn segment_meets_triangle(
    p: [f64; 3],
    q: [f64; 3],
    a: [f64; 3],
    b: [f64; 3],
    c: [f64; 3],
) -> bool {
    let sp = orient3d(a, b, c, p);
    let sq = orient3d(a, b, c, q);
    if (sp > 0.0 && sq > 0.0) || (sp < 0.0 && sq < 0.0) {
        return false;
    }
    if sp == 0.0 && sq == 0.0 {
        return coplanar_segment_triangle([a, b, c], p, q);
    }
    // p and q on both sides (or one on the plane): the line p q passes through the closed
    // triangle exactly when it sees the three edges turning the same way (zeros allowed).
    let (e1, e2, e3) = (
        orient3d(p, q, a, b),
        orient3d(p, q, b, c),
        orient3d(p, q, c, a),
    );
    (e1 >= 0.0 && e2 >= 0.0 && e3 >= 0.0) || (e1 <= 0.0 && e2 <= 0.0 && e3 <= 0.0)
}

/// Whether the closed triangles `a` and `b` (three corners each) share a point. Exact: they
/// meet exactly when an edge of one meets the other (for coplanar triangles that includes one
/// lying inside the other, as an edge's end point inside).
pub fn triangles_meet(a: [[f64; 3]; 3], b: [[f64; 3]; 3]) -> bool {
    (0..3).any(|i| segment_meets_triangle(a[i], a[(i + 1) % 3], b[0], b[1], b[2]))
        || (0..3).any(|i| segment_meets_triangle(b[i], b[(i + 1) % 3], a[0], a[1], a[2]))
}
