//! Plain geometric measures of linear 2D cells that several stages share: the largest
//! interior angle of a triangle, and the cut of a quad along its shorter diagonal (the
//! convention of the report's obtuse-angle histogram). No meshing decision is made here.

use crate::mesh::Mesh;

/// Largest interior angle of triangle `a b c`, degrees; 180 for a triangle with a zero-length
/// side (the worst value, so that degenerate cells stand out).
///
/// The largest angle lies opposite the longest side, so only the corners whose opposite side
/// is within a small margin of the longest (1e-6 relative, squared) are measured (one `atan2`
/// instead of three, nearly always): each measured the same way as every corner would be, so
/// the value is the largest of the three to the last bit. Sides too short or too long to
/// square, or not finite, measure every corner.
pub fn triangle_max_angle_deg(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    let corners = [a, b, c];
    if corners
        .iter()
        .enumerate()
        .any(|(i, p)| *p == corners[(i + 1) % 3])
    {
        return 180.0;
    }
    // the squared side opposite each corner
    let opposite = [0, 1, 2].map(|i| {
        let (q, r) = (corners[(i + 1) % 3], corners[(i + 2) % 3]);
        (r[0] - q[0]).powi(2) + (r[1] - q[1]).powi(2)
    });
    let longest = opposite[0].max(opposite[1]).max(opposite[2]);
    let sound = longest.is_normal() && longest > 1e-200 && longest < 1e200;
    let mut largest: f64 = 0.0;
    for (i, &side) in opposite.iter().enumerate() {
        if sound && side < longest * (1.0 - SIDE_MARGIN) {
            continue;
        }
        largest = largest.max(corner_angle_deg(corners, i));
    }
    largest
}

/// How much shorter (relatively, squared) than the longest side a side must be for its
/// opposite corner to be surely not the largest: its angle is then smaller by about 1e-6 rad
/// at least, far above the rounding of the measure (~1e-15, or ~1e-10 for a cell 1e-5 across
/// at coordinates near 20).
const SIDE_MARGIN: f64 = 1e-6;

/// The interior angle at corner `i` of `corners`, degrees (its sides of nonzero length).
fn corner_angle_deg(corners: [[f64; 2]; 3], i: usize) -> f64 {
    let p = corners[i];
    let q = corners[(i + 1) % 3];
    let r = corners[(i + 2) % 3];
    let u = [q[0] - p[0], q[1] - p[1]];
    let v = [r[0] - p[0], r[1] - p[1]];
    let cross = u[0] * v[1] - u[1] * v[0];
    let dot = u[0] * v[0] + u[1] * v[1];
    cross.abs().atan2(dot).to_degrees()
}

/// The two triangles of quad `k` (four corner nodes, counter-clockwise) cut along its shorter
/// diagonal (0–2 on a tie), both with the quad's orientation.
pub fn split_quad_shorter_diagonal(mesh: &Mesh, k: &[u32]) -> [[u32; 3]; 2] {
    let d = |a: u32, b: u32| {
        let (p, q) = (mesh.xy(a), mesh.xy(b));
        (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2)
    };
    if d(k[0], k[2]) <= d(k[1], k[3]) {
        [[k[0], k[1], k[2]], [k[0], k[2], k[3]]]
    } else {
        [[k[0], k[1], k[3]], [k[1], k[2], k[3]]]
    }
}

/// Largest interior angle of cell `i`, degrees, from its corners: a triangle's own; for a quad
/// the larger of its two triangles' values once cut along the shorter diagonal.
pub fn cell_max_angle_deg(mesh: &Mesh, i: usize) -> f64 {
    let k = mesh.cells.get(i).corners();
    let mut p = [[0.0; 2]; 4];
    for (q, &n) in p.iter_mut().zip(k) {
        *q = mesh.xy(n);
    }
    corners_max_angle_deg(&p[..k.len().min(4)])
}

/// Largest interior angle, degrees, of a triangle or a quad (four corners,
/// counter-clockwise) cut along its shorter diagonal (0–2 on a tie), as
/// [`cell_max_angle_deg`] measures a cell.
pub fn corners_max_angle_deg(p: &[[f64; 2]]) -> f64 {
    if p.len() == 4 {
        let d = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2);
        if d(p[0], p[2]) <= d(p[1], p[3]) {
            triangle_max_angle_deg(p[0], p[1], p[2]).max(triangle_max_angle_deg(p[0], p[2], p[3]))
        } else {
            triangle_max_angle_deg(p[0], p[1], p[3]).max(triangle_max_angle_deg(p[1], p[2], p[3]))
        }
    } else {
        triangle_max_angle_deg(p[0], p[1], p[2])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The measure as it was: every corner's angle, the largest kept.
    fn every_corner(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
        let corners = [a, b, c];
        let mut largest: f64 = 0.0;
        for i in 0..3 {
            let p = corners[i];
            let q = corners[(i + 1) % 3];
            let r = corners[(i + 2) % 3];
            let u = [q[0] - p[0], q[1] - p[1]];
            let v = [r[0] - p[0], r[1] - p[1]];
            if (u[0] == 0.0 && u[1] == 0.0) || (v[0] == 0.0 && v[1] == 0.0) {
                return 180.0;
            }
            largest = largest.max(corner_angle_deg(corners, i));
        }
        largest
    }

    fn same(a: [f64; 2], b: [f64; 2], c: [f64; 2]) {
        for (p, q, r) in [(a, b, c), (b, c, a), (c, a, b), (a, c, b)] {
            let (new, old) = (triangle_max_angle_deg(p, q, r), every_corner(p, q, r));
            assert_eq!(
                new.to_bits(),
                old.to_bits(),
                "{p:?} {q:?} {r:?}: {new} vs {old}"
            );
        }
    }

    #[test]
    fn special_triangles_measure_as_before() {
        let s3 = 3f64.sqrt() / 2.0;
        same([0.0, 0.0], [1.0, 0.0], [0.5, s3]); // equilateral: every corner measured
        same([0.0, 0.0], [1.0, 0.0], [0.0, 1.0]); // right isosceles
        same([0.0, 0.0], [1.0, 0.0], [1.0, 0.0]); // a side without length
        same([0.0, 0.0], [1.0, 0.0], [2.0, 0.0]); // flat
        same([0.0, 0.0], [1e-170, 0.0], [0.0, 1e-170]); // too small to square
        same([0.0, 0.0], [f64::NAN, 0.0], [0.0, 1.0]);
        same([0.0, 0.0], [f64::INFINITY, 0.0], [0.0, 1.0]);
        // thin near-isosceles cells of a wall layer, far from the origin
        same([20.0, 0.0], [20.0 + 1e-5, 0.0], [20.0 + 5e-6, 5e-6 + 1e-17]);
    }

    proptest! {
        #[test]
        fn the_largest_angle_is_the_one_measured_before(
            a in prop::array::uniform2(-20.0f64..20.0),
            d in prop::array::uniform2(-1.0f64..1.0),
            e in prop::array::uniform2(-1.0f64..1.0),
            scale in -7i32..1,
            isosceles in any::<bool>(),
            nudge in -4i64..4,
        ) {
            let h = 10f64.powi(scale);
            let b = [a[0] + h * d[0], a[1] + h * d[1]];
            let c = if isosceles {
                // c on the bisector of a b, a few ulps off: two sides within rounding
                let m = [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
                let n = [-(b[1] - a[1]), b[0] - a[0]];
                let t = e[0];
                let x = m[0] + t * n[0];
                [f64::from_bits((x.to_bits() as i64 + nudge) as u64), m[1] + t * n[1]]
            } else {
                [a[0] + h * e[0], a[1] + h * e[1]]
            };
            same(a, b, c);
        }
    }
}
