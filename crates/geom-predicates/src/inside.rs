//! Point in a closed loop by the winding number, with every "which side of this edge" decided
//! by the exact [`orient2d`], so the answer is exact for points off the boundary whatever the
//! loop's orientation.

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
