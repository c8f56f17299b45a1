//! The fraction of a high-order mesh's edges that are curved: an edge is curved when one of
//! its inner nodes lies off the straight chord between its ends (beyond rounding).

use mesh_model::Mesh;
use mesh_model::topology::Edges;

/// Curved edges over all edges, each edge counted once however many cells share it; 0 for a
/// linear mesh or a mesh without cells. Edges are read in Gmsh's node order: the corners,
/// then `order − 1` nodes per edge in the shape's edge order.
pub fn curved_edge_fraction(mesh: &Mesh) -> f64 {
    if mesh.cells.types().iter().all(|t| t.order < 2) {
        return 0.0;
    }
    let edges = Edges::build(mesh.cells.shapes_and_corners(), []);
    let (mut total, mut curved) = (0usize, 0usize);
    for e in 0..edges.len() as u32 {
        let (mut high_order, mut bent) = (false, false);
        for u in edges.cells(e) {
            let cell = mesh.cells.get(u.cell as usize);
            let p = cell.ty.order as usize;
            if p < 2 {
                continue;
            }
            high_order = true;
            let (k, j) = (cell.nodes, u.local as usize);
            let [a, b] = cell.ty.shape.edges()[j];
            let first = cell.ty.shape.corners() + j * (p - 1);
            bent = bent || off_chord(mesh, k[a], k[b], &k[first..first + p - 1]);
        }
        total += high_order as usize;
        curved += bent as usize;
    }
    if total == 0 {
        return 0.0;
    }
    curved as f64 / total as f64
}

/// Whether an inner node of edge a → b (listed from a) is off its place on the chord.
fn off_chord(mesh: &Mesh, a: u32, b: u32, inner: &[u32]) -> bool {
    let (xa, xb) = (mesh.nodes[a as usize], mesh.nodes[b as usize]);
    let length = (0..3).map(|d| (xb[d] - xa[d]).powi(2)).sum::<f64>().sqrt();
    let n = inner.len() + 1;
    inner.iter().enumerate().any(|(i, &v)| {
        let s = (i + 1) as f64 / n as f64;
        let x = mesh.nodes[v as usize];
        let off = (0..3)
            .map(|d| (x[d] - (xa[d] + s * (xb[d] - xa[d]))).powi(2))
            .sum::<f64>()
            .sqrt();
        off > 1e-9 * length
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use mesh_model::{CellType, Dim, Shape};

    #[test]
    fn one_bent_edge_of_a_two_triangle_square() {
        // two P2 triangles sharing the diagonal; only the bottom edge bends
        let mut m = Mesh::new(Dim::Two, 2);
        for v in [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]] {
            m.nodes.push([v[0], v[1], 0.0]);
        }
        let mid = |m: &mut Mesh, x: f64, y: f64| {
            m.nodes.push([x, y, 0.0]);
            (m.nodes.len() - 1) as u32
        };
        let bottom = mid(&mut m, 0.5, -0.1);
        let right = mid(&mut m, 1.0, 0.5);
        let diag = mid(&mut m, 0.5, 0.5);
        let top = mid(&mut m, 0.5, 1.0);
        let left = mid(&mut m, 0.0, 0.5);
        let tri = CellType::new(Shape::Tri, 2);
        m.cells.push(tri, &[0, 1, 2, bottom, right, diag]);
        m.cells.push(tri, &[0, 2, 3, diag, top, left]);
        assert!((curved_edge_fraction(&m) - 0.2).abs() < 1e-15);
    }
}
