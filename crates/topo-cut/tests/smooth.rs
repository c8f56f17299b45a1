//! The smoothing of the worst tetrahedra (`topo_cut::smooth`): on the octahedron cut into
//! eight tetrahedra around a free centre node pushed towards a face (its tetrahedron there
//! flat), the node moves back, every tetrahedron stays positive, the volume is kept, fixed
//! nodes stay, a node sliding across an edge moves only across it, and a mesh already under
//! the target is left to the bit.

use mesh_model::measure3d::{cell_volume, max_dihedral_deg};
use mesh_model::{CellType, Dim, Mesh, Shape, is_positive_tet};
use proptest::prelude::*;
use topo_cut::smooth::{Freedom, smooth_worst_tets};

/// The octahedron with corners ±1 on each axis (nodes 0–5: +x, −x, +y, −y, +z, −z) and its
/// centre node 6 at `centre`, cut into the eight tetrahedra from the centre.
fn octahedron(centre: [f64; 3]) -> Mesh {
    let mut mesh = Mesh::new(Dim::Three, 1);
    mesh.nodes = vec![
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
        centre,
    ];
    let tet = CellType::new(Shape::Tet, 1);
    for x in [0u32, 1] {
        for y in [2u32, 3] {
            for z in [4u32, 5] {
                // (x, y, z) turns positively when an even number of them are negative
                let flips = (x == 1) as u32 + (y == 3) as u32 + (z == 5) as u32;
                let k = if flips.is_multiple_of(2) {
                    [6, x, y, z]
                } else {
                    [6, y, x, z]
                };
                mesh.cells.push(tet, &k);
            }
        }
    }
    mesh
}

/// Whether every tetrahedron is positive (exact `orient3d`).
fn positive(mesh: &Mesh) -> bool {
    mesh.cells.iter().all(|c| {
        let x = |j: usize| mesh.nodes[c.corners()[j] as usize];
        is_positive_tet(x(0), x(1), x(2), x(3))
    })
}

fn volume(mesh: &Mesh) -> f64 {
    (0..mesh.cells.len()).map(|i| cell_volume(mesh, i)).sum()
}

fn freedom(centre: Freedom) -> Vec<Freedom> {
    let mut f = vec![Freedom::Fixed; 7];
    f[6] = centre;
    f
}

#[test]
fn a_node_pushed_onto_a_face_moves_back() {
    let mut mesh = octahedron([0.33, 0.33, 0.32]);
    assert!(positive(&mesh));
    let before = max_dihedral_deg(&mesh);
    assert!(before > 170.0, "{before}");
    let s = smooth_worst_tets(&mut mesh, &freedom(Freedom::Free), 150.0);
    assert!(positive(&mesh));
    assert!(s.moves > 0);
    assert_eq!(s.before_deg, before);
    assert_eq!(s.after_deg, max_dihedral_deg(&mesh));
    assert!(s.after_deg <= 150.0, "{s:?}");
    assert!((volume(&mesh) - 4.0 / 3.0).abs() < 1e-12);
    assert_eq!(mesh.nodes[..6], octahedron([0.0; 3]).nodes[..6]);
}

#[test]
fn fixed_nodes_stay_and_a_sliding_node_moves_across_its_edge() {
    let start = [0.3, 0.3, 0.32];
    let mut mesh = octahedron(start);
    let s = smooth_worst_tets(&mut mesh, &freedom(Freedom::Fixed), 150.0);
    assert_eq!((s.moves, mesh.nodes[6]), (0, start));
    // sliding across the z axis: z stays, and the lean off the axis stays within 15°
    let e = [0.0, 0.0, 1.0];
    let s = smooth_worst_tets(&mut mesh, &freedom(Freedom::Across(e)), 150.0);
    let p = mesh.nodes[6];
    assert!(s.moves > 0 && s.after_deg < s.before_deg, "{s:?}");
    assert!((p[2] - start[2]).abs() < 1e-15, "{p:?}");
    let shift = ((p[0] - start[0]).powi(2) + (p[1] - start[1]).powi(2)).sqrt();
    assert!(shift <= 15f64.to_radians().tan() + 1e-12, "{shift}");
    assert!(positive(&mesh));
}

#[test]
fn a_mesh_under_the_target_is_left_to_the_bit() {
    let mut mesh = octahedron([0.05, -0.02, 0.01]);
    let nodes = mesh.nodes.clone();
    let s = smooth_worst_tets(&mut mesh, &freedom(Freedom::Free), 150.0);
    assert_eq!((s.moves, s.over_before, s.over_after), (0, 0, 0));
    assert_eq!(mesh.nodes, nodes);
}

proptest! {
    /// Anywhere inside the octahedron, the smoothing keeps every tetrahedron positive and
    /// the volume, never makes the worst angle worse and never brings two nodes together.
    #[test]
    fn never_worse_never_inverted(a in 0.0f64..1.0, b in 0.0f64..1.0, c in 0.0f64..1.0, s in 0.0f64..0.999) {
        // a point of the face x + y + z = 1 (barycentric a, b, c), scaled inside
        let sum = a + b + c + 1e-9;
        let centre = [s * a / sum, s * b / sum, s * c / sum];
        let mut mesh = octahedron(centre);
        prop_assume!(positive(&mesh));
        let before = max_dihedral_deg(&mesh);
        let out = smooth_worst_tets(&mut mesh, &freedom(Freedom::Free), 150.0);
        // no node comes nearer another than half the shorter of their shortest edges before
        let d = |a: [f64; 3], b: [f64; 3]| (0..3).map(|i| (a[i] - b[i]).powi(2)).sum::<f64>().sqrt();
        let start = octahedron(centre).nodes;
        let shortest = (0..6).map(|j| d(start[6], start[j])).fold(f64::INFINITY, f64::min);
        for j in 0..6 {
            prop_assert!(d(mesh.nodes[6], mesh.nodes[j]) >= 0.5 * shortest.min(2f64.sqrt()) - 1e-15);
        }
        prop_assert!(positive(&mesh));
        prop_assert!(out.after_deg <= before);
        prop_assert!((volume(&mesh) - 4.0 / 3.0).abs() < 1e-12);
    }
}
