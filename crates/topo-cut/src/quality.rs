//! The quality measure of the cut: dihedral angles of tetrahedra.

use mesh_model::{Mesh, Shape};

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The six interior dihedral angles of the tetrahedron `p`, in degrees, at its edges in
/// Gmsh's edge order (`Shape::Tet.edges()`).
pub fn tet_dihedral_angles_deg(p: [[f64; 3]; 4]) -> [f64; 6] {
    let mut out = [0.0; 6];
    for (o, e) in out.iter_mut().zip(Shape::Tet.edges()) {
        let [i, j] = *e;
        let mut others = (0..4).filter(|&k| k != i && k != j);
        let (k, l) = (others.next().unwrap_or(0), others.next().unwrap_or(0));
        let axis = sub(p[j], p[i]);
        let aa = dot(axis, axis);
        // the other two corners seen along the edge: their components across it
        let across = |q: [f64; 3]| {
            let v = sub(q, p[i]);
            let t = dot(v, axis) / aa;
            [v[0] - t * axis[0], v[1] - t * axis[1], v[2] - t * axis[2]]
        };
        let (u, w) = (across(p[k]), across(p[l]));
        let c = dot(u, w) / (dot(u, u) * dot(w, w)).sqrt();
        *o = if c.is_finite() {
            c.clamp(-1.0, 1.0).acos().to_degrees()
        } else {
            180.0
        };
    }
    out
}

/// The largest dihedral angle of the mesh's tetrahedra, in degrees (0 without any).
pub fn max_dihedral_deg(mesh: &Mesh) -> f64 {
    mesh.cells
        .iter()
        .filter(|c| c.ty.shape == Shape::Tet)
        .map(|c| {
            let k = c.corners();
            let p = [0, 1, 2, 3].map(|j| mesh.nodes[k[j] as usize]);
            tet_dihedral_angles_deg(p).into_iter().fold(0.0, f64::max)
        })
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_regular_tetrahedron_has_its_dihedral_angle_everywhere() {
        let s = 1.0 / 2f64.sqrt();
        let p = [
            [1.0, 0.0, -s],
            [-1.0, 0.0, -s],
            [0.0, 1.0, s],
            [0.0, -1.0, s],
        ];
        let want = (1.0f64 / 3.0).acos().to_degrees();
        for a in tet_dihedral_angles_deg(p) {
            assert!((a - want).abs() < 1e-12, "{a}");
        }
        // the corner tetrahedron: three right angles at the edges through the corner
        let q = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ];
        let a = tet_dihedral_angles_deg(q);
        assert!(
            (a[0] - 90.0).abs() < 1e-12 && (a[3] - 90.0).abs() < 1e-12,
            "{a:?}"
        );
    }
}
