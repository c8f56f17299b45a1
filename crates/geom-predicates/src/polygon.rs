//! Closed loops (polygons) in 2D: point in loop by the winding number, with every "which side
//! of this edge" decided by the exact [`orient2d`], so the answer is exact for points off the
//! boundary whatever the loop's orientation; and the signed area.

use crate::orient::orient2d;

/// The winding number of the closed loop `points` (last point joined back to the first)
/// around `p`: +1 per counter-clockwise turn, −1 per clockwise turn. Exact for `p` off the
/// loop; for `p` on an edge it may count that edge or not.
pub fn winding_number<P: Copy + Into<[f64; 2]>>(p: [f64; 2], points: &[P]) -> i64 {
    let n = points.len();
    let mut winding = 0i64;
    for i in 0..n {
        let a: [f64; 2] = points[i].into();
        let b: [f64; 2] = points[(i + 1) % n].into();
        if a[1] <= p[1] {
            if b[1] > p[1] && orient2d(a, b, p) > 0.0 {
                winding += 1;
            }
        } else if b[1] <= p[1] && orient2d(a, b, p) < 0.0 {
            winding -= 1;
        }
    }
    winding
}

/// Whether `p` lies inside the closed loop `points` (non-zero [`winding_number`]). For a
/// simple loop this is the usual inside, in either orientation.
#[inline]
pub fn point_in_loop<P: Copy + Into<[f64; 2]>>(p: [f64; 2], points: &[P]) -> bool {
    winding_number(p, points) != 0
}

/// The signed area of the closed polygon through `vertices` (shoelace formula), positive when
/// they run counter-clockwise; 0 for fewer than three. Summed relative to the first vertex: on
/// absolute coordinates the products `x_i·y_j` of a small polygon far from the origin cancel to
/// nothing (a 1e-9 thin cell at x ~ 1 rounds to 0). Not exact: use [`orient2d`] for a sign
/// that must be right.
pub fn polygon_area<P: Into<[f64; 2]>>(vertices: impl IntoIterator<Item = P>) -> f64 {
    let mut it = vertices.into_iter().map(Into::into);
    let Some(origin) = it.next() else { return 0.0 };
    let Some(second) = it.next() else { return 0.0 };
    let mut prev = [second[0] - origin[0], second[1] - origin[1]];
    let mut twice = 0.0;
    for p in it {
        let p = [p[0] - origin[0], p[1] - origin[1]];
        twice += prev[0] * p[1] - p[0] * prev[1];
        prev = p;
    }
    0.5 * twice
}
