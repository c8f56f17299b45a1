//! Plain geometric measures of linear 2D cells that several stages share: the largest
//! interior angle of a triangle, and the cut of a quad along its shorter diagonal (the
//! convention of the report's obtuse-angle histogram). No meshing decision is made here.

use crate::cell::Shape;
use crate::mesh::Mesh;

/// Largest interior angle of triangle `a b c`, degrees; 180 for a triangle with a zero-length
/// side (the worst value, so that degenerate cells stand out).
pub fn triangle_max_angle_deg(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
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
        let cross = u[0] * v[1] - u[1] * v[0];
        let dot = u[0] * v[0] + u[1] * v[1];
        largest = largest.max(cross.abs().atan2(dot).to_degrees());
    }
    largest
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
    let cell = mesh.cells.get(i);
    let k = cell.corners();
    let tri = |t: [u32; 3]| triangle_max_angle_deg(mesh.xy(t[0]), mesh.xy(t[1]), mesh.xy(t[2]));
    match cell.ty.shape {
        Shape::Quad => {
            let [a, b] = split_quad_shorter_diagonal(mesh, k);
            tri(a).max(tri(b))
        }
        _ => tri([k[0], k[1], k[2]]),
    }
}
