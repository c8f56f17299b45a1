//! Plain geometric measures of linear 3D cells and surface facets that several stages share:
//! the dihedral angles of a tetrahedron (the cut's quality target and the report's table 7),
//! the volume of a standard cell by the divergence theorem over its faces (quadrilateral
//! faces fanned from their centroid, so that neighbours and the surfaces around the domain
//! measure each face alike), the largest corner angle of a polygon in space, the angle
//! between two vectors, the corner scaled Jacobian of prisms and hexahedra, and a histogram
//! over bins. No meshing decision is made here.

use geom_predicates::vector::{cross3, dot, sub};

use crate::cell::Shape;
use crate::mesh::Mesh;

/// The six interior dihedral angles of the tetrahedron `p`, in degrees, at its edges in
/// Gmsh's edge order (`Shape::Tet.edges()`).
pub fn tet_dihedral_angles_deg(p: [[f64; 3]; 4]) -> [f64; 6] {
    let mut out = [0.0; 6];
    for (o, e) in out.iter_mut().zip(Shape::Tet.edges()) {
        *o = degrees_of_cosine(dihedral_cosine(p, *e));
    }
    out
}

/// The largest of [`tet_dihedral_angles_deg`], by one arc cosine: that of the least cosine
/// (the cut compares millions of pieces by it; the arc cosines were a sixth of a P2 wing's run).
pub fn tet_max_dihedral_deg_of(p: [[f64; 3]; 4]) -> f64 {
    let mut least = 1.0f64;
    for e in Shape::Tet.edges() {
        let c = dihedral_cosine(p, *e);
        if !c.is_finite() {
            return 180.0;
        }
        least = least.min(c);
    }
    degrees_of_cosine(least)
}

/// The cosine of the interior dihedral angle of the tetrahedron `p` at its edge `i j`
/// (not finite when the tetrahedron is flat there).
fn dihedral_cosine(p: [[f64; 3]; 4], [i, j]: [usize; 2]) -> f64 {
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
    dot(u, w) / (dot(u, u) * dot(w, w)).sqrt()
}

/// The angle of cosine `c` in degrees; 180 when `c` is not finite (a flat tetrahedron).
fn degrees_of_cosine(c: f64) -> f64 {
    if c.is_finite() {
        c.clamp(-1.0, 1.0).acos().to_degrees()
    } else {
        180.0
    }
}

/// The largest dihedral angle of tetrahedron `i` of `mesh` (its corners), in degrees.
pub fn tet_max_dihedral_deg(mesh: &Mesh, i: usize) -> f64 {
    let k = mesh.cells.get(i).corners();
    tet_max_dihedral_deg_of([0, 1, 2, 3].map(|j| mesh.nodes[k[j] as usize]))
}

/// The largest dihedral angle of the mesh's tetrahedra, in degrees (0 without any).
pub fn max_dihedral_deg(mesh: &Mesh) -> f64 {
    (0..mesh.cells.len())
        .filter(|&i| mesh.cells.get(i).ty.shape == Shape::Tet)
        .map(|i| tet_max_dihedral_deg(mesh, i))
        .fold(0.0, f64::max)
}

/// The corner determinants of the linear prism or hexahedron `p` (Gmsh's node order: the
/// bottom face's `m` corners, then the top's, each above its bottom corner; `p.len()` is
/// `2m`), bottom corners first. At a corner `o` of the bottom or the top face, with `next`
/// and `prev` its neighbours on that face: det(next − o, prev − o, e), `e` the extrusion
/// edge of that corner's column (bottom corner to top corner) — positive at every corner of
/// a valid cell. With `normalised`, each is divided by the product of its three edges'
/// lengths: the **edge-normalised corner scaled Jacobian**, in [−1, 1], 1 at every corner of
/// a box, the sine of the face's corner angle at a right prism's corner, 0 where an edge has
/// no length.
pub fn corner_determinants(p: &[[f64; 3]], normalised: bool) -> Vec<f64> {
    let m = p.len() / 2;
    let len = |v: [f64; 3]| dot(v, v).sqrt();
    let mut out = Vec::with_capacity(2 * m);
    for face in [0, m] {
        for i in 0..m {
            let o = p[face + i];
            let a = sub(p[face + (i + 1) % m], o);
            let b = sub(p[face + (i + m - 1) % m], o);
            let e = sub(p[m + i], p[i]);
            let d = dot(cross3(a, b), e);
            out.push(if normalised {
                let q = d / (len(a) * len(b) * len(e));
                if q.is_finite() { q } else { 0.0 }
            } else {
                d
            });
        }
    }
    out
}

/// The smallest edge-normalised corner scaled Jacobian ([`corner_determinants`]) of cell `i`
/// of `mesh`, if it is a prism or a hexahedron.
pub fn min_corner_scaled_jacobian(mesh: &Mesh, i: usize) -> Option<f64> {
    let c = mesh.cells.get(i);
    if !matches!(c.ty.shape, Shape::Prism | Shape::Hex) {
        return None;
    }
    let p: Vec<[f64; 3]> = c
        .corners()
        .iter()
        .map(|&v| mesh.nodes[v as usize])
        .collect();
    corner_determinants(&p, true).into_iter().reduce(f64::min)
}

/// Six times the signed volume of the cone from `o` over the polygon `p` (fanned from its
/// centroid). Summed over the outward faces of a closed polyhedron it is six times its
/// volume, whatever `o`.
pub fn cone_volume6(p: &[[f64; 3]], o: [f64; 3]) -> f64 {
    let n = p.len() as f64;
    let mut c = [0.0; 3];
    for q in p {
        (0..3).for_each(|d| c[d] += (q[d] - o[d]) / n);
    }
    (0..p.len())
        .map(|i| dot(c, cross3(sub(p[i], o), sub(p[(i + 1) % p.len()], o))))
        .sum()
}

/// The volume of 3D cell `i` of `mesh` from its corners: the divergence theorem over its
/// outward faces (`Shape::faces`), quadrilaterals fanned from their centroid. Positive for a
/// cell in Gmsh's orientation; 0 for a cell that is not 3D.
pub fn cell_volume(mesh: &Mesh, i: usize) -> f64 {
    let c = mesh.cells.get(i);
    if c.ty.shape.dim() != 3 {
        return 0.0;
    }
    let k = c.corners();
    let o = mesh.nodes[k[0] as usize];
    let mut face = Vec::with_capacity(4);
    let mut sum = 0.0;
    for f in c.ty.shape.faces() {
        face.clear();
        face.extend(f.iter().map(|&j| mesh.nodes[k[j] as usize]));
        sum += cone_volume6(&face, o);
    }
    sum / 6.0
}

/// The angle between two vectors in degrees, in [0, 180] (0 when one is zero).
pub fn angle_deg(a: [f64; 3], b: [f64; 3]) -> f64 {
    let x = cross3(a, b);
    dot(x, x).sqrt().atan2(dot(a, b)).to_degrees()
}

/// The largest corner angle of the polygon `p` in space, degrees (each corner between its two
/// sides; 180 at a corner with a zero-length side).
pub fn polygon_max_angle_deg(p: &[[f64; 3]]) -> f64 {
    let n = p.len();
    (0..n)
        .map(|i| {
            let (a, b) = (sub(p[(i + n - 1) % n], p[i]), sub(p[(i + 1) % n], p[i]));
            if dot(a, a) == 0.0 || dot(b, b) == 0.0 {
                180.0
            } else {
                angle_deg(a, b)
            }
        })
        .fold(0.0, f64::max)
}

/// Counts `values` into the bins `(-∞, e₀], (e₀, e₁], …, (eₙ₋₁, ∞)` of the increasing upper
/// edges `edges` (`edges.len() + 1` counts; NaN falls in the last bin).
pub fn histogram(values: impl IntoIterator<Item = f64>, edges: &[f64]) -> Vec<usize> {
    let mut counts = vec![0; edges.len() + 1];
    for v in values {
        let bin = edges.iter().position(|&e| v <= e).unwrap_or(edges.len());
        counts[bin] += 1;
    }
    counts
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{CellType, Dim};
    use proptest::prelude::*;

    proptest! {
        /// The largest angle by the least cosine is the largest of the six angles, to the bit
        /// (flat and inverted tetrahedra too).
        #[test]
        fn the_largest_dihedral_is_the_largest_of_the_six(
            p in prop::array::uniform4(prop::array::uniform3(-1.0..1.0f64)),
            flat in any::<bool>(),
        ) {
            let mut p = p;
            if flat {
                p[3] = [0.5 * (p[0][0] + p[1][0]), 0.5 * (p[0][1] + p[1][1]), 0.5 * (p[0][2] + p[1][2])];
            }
            let six = tet_dihedral_angles_deg(p).into_iter().fold(0.0, f64::max);
            prop_assert_eq!(tet_max_dihedral_deg_of(p).to_bits(), six.to_bits());
        }
    }

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

    #[test]
    fn volumes_of_the_unit_cells() {
        let mut m = Mesh::new(Dim::Three, 1);
        m.nodes = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [1.0, 0.0, 1.0],
            [1.0, 1.0, 1.0],
            [0.0, 1.0, 1.0],
        ];
        m.cells
            .push(CellType::new(Shape::Hex, 1), &[0, 1, 2, 3, 4, 5, 6, 7]);
        m.cells.push(CellType::new(Shape::Tet, 1), &[0, 1, 3, 4]);
        m.cells
            .push(CellType::new(Shape::Prism, 1), &[0, 1, 3, 4, 5, 7]);
        m.cells
            .push(CellType::new(Shape::Pyramid, 1), &[0, 1, 2, 3, 4]);
        let v: Vec<f64> = (0..4).map(|i| cell_volume(&m, i)).collect();
        for (got, want) in v.iter().zip([1.0, 1.0 / 6.0, 0.5, 1.0 / 3.0]) {
            assert!((got - want).abs() < 1e-14, "{v:?}");
        }
        assert!((tet_max_dihedral_deg(&m, 1) - 90.0).abs() < 1e-12);
    }

    #[test]
    fn corner_scaled_jacobians_of_boxes_prisms_and_sheared_cells() {
        let mut m = Mesh::new(Dim::Three, 1);
        m.nodes = vec![
            [0.0, 0.0, 0.0],
            [2.0, 0.0, 0.0],
            [2.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 0.1],
            [2.0, 0.0, 0.1],
            [2.0, 1.0, 0.1],
            [0.0, 1.0, 0.1],
        ];
        m.cells
            .push(CellType::new(Shape::Hex, 1), &[0, 1, 2, 3, 4, 5, 6, 7]);
        m.cells
            .push(CellType::new(Shape::Prism, 1), &[0, 1, 3, 4, 5, 7]);
        m.cells.push(CellType::new(Shape::Tet, 1), &[0, 1, 3, 4]);
        assert_eq!(min_corner_scaled_jacobian(&m, 0), Some(1.0));
        // the prism's corners at 1 and 3: the sine of the triangle's angle there, 1/√5
        let want = 1.0 / 5f64.sqrt();
        let got = min_corner_scaled_jacobian(&m, 1).expect("a prism");
        assert!((got - want).abs() < 1e-15, "{got}");
        assert_eq!(min_corner_scaled_jacobian(&m, 2), None);
        // the top sheared by 45° along x: every corner 1/√2
        let mut p: Vec<[f64; 3]> = m.nodes.clone();
        p[4..].iter_mut().for_each(|q| q[0] += 0.1);
        for d in corner_determinants(&p, true) {
            assert!((d - 0.5f64.sqrt()).abs() < 1e-14, "{d}");
        }
        // inverted (top below bottom): negative everywhere; unnormalised: the volumes
        p[4..].iter_mut().for_each(|q| q[2] = -0.1);
        assert!(corner_determinants(&p, true).iter().all(|&d| d < 0.0));
        let dets = corner_determinants(&m.nodes, false);
        assert!(dets.iter().all(|&d| (d - 0.2).abs() < 1e-15), "{dets:?}");
    }

    #[test]
    fn angles_and_bins() {
        let sq = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        assert!((polygon_max_angle_deg(&sq) - 90.0).abs() < 1e-12);
        assert!((angle_deg([1.0, 0.0, 0.0], [0.0, 0.0, 2.0]) - 90.0).abs() < 1e-12);
        assert_eq!(
            histogram([5.0, 10.0, 10.5, 35.0, f64::NAN], &[10.0, 20.0, 30.0]),
            vec![2, 1, 0, 2]
        );
    }
}
