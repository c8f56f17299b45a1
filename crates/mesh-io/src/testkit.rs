//! Test meshes built by hand, exact and small, for the tests of this crate and of the others
//! (enable the cargo feature `testkit`: `mesh-io = { workspace = true, features = ["testkit"] }`
//! under `[dev-dependencies]`). Not part of the stable API.
//!
//! - [`annulus`]: a structured annulus of quadrilaterals, some cut into triangles, of order 1
//!   to 3, high-order nodes exactly on the circles, in Gmsh order; inner circle a wall,
//!   outer circle the far field; valid for `mesh_model::validate`.
//! - [`reference_cells_3d`]: one of each 3D cell type (Gmsh's reference cells side by side, not
//!   a conforming mesh) with a few boundary facets, to exercise the 3D type tables.

use std::f64::consts::TAU;

use mesh_model::{CellType, Cells, Dim, Mesh, Patch, Role, Shape};

use crate::node_order::gmsh_reference_nodes;

/// Shape and size of the [`annulus`].
#[derive(Debug, Clone, PartialEq)]
pub struct AnnulusParams {
    /// Polynomial order of the cells, 1 to 3.
    pub order: u8,
    /// Number of cells across the ring (≥ 1).
    pub radial_cells: usize,
    /// Number of cells around the ring (≥ 3).
    pub angular_cells: usize,
    /// Radius of the inner circle (the wall), in length units (> 0).
    pub inner_radius: f64,
    /// Radius of the outer circle (the far field), in length units (> `inner_radius`).
    pub outer_radius: f64,
    /// Which quadrilaterals are cut into two triangles: cell `c` (numbered around the ring,
    /// then outward) is cut when `triangle_mask[c % len]` is true. Empty: no triangle.
    pub triangle_mask: Vec<bool>,
}

impl Default for AnnulusParams {
    /// Order 2, 3 × 8 cells, radii 1 and 2, every third cell cut into triangles.
    fn default() -> Self {
        AnnulusParams {
            order: 2,
            radial_cells: 3,
            angular_cells: 8,
            inner_radius: 1.0,
            outer_radius: 2.0,
            triangle_mask: vec![true, false, false],
        }
    }
}

/// A structured annulus mesh (see [`AnnulusParams`]).
///
/// Nodes lie on a polar lattice with `order` steps per cell in each direction, so every edge
/// of constant radius is an exact circular arc through its nodes and every radial edge is
/// straight. Cells are counter-clockwise; boundary facets run with the domain on their left
/// (the outer circle counter-clockwise, the inner one clockwise). Patch 0 is the inner circle
/// (`inner`, a wall), patch 1 the outer circle (`outer`, the far field). `cell_layer` is the
/// ring index counted from the wall and `cell_pipe` the wall facet below each cell.
///
/// # Panics
/// On parameters outside the documented ranges (a test bug, not input).
pub fn annulus(params: &AnnulusParams) -> Mesh {
    let p = params.order as usize;
    let (nr, na) = (params.radial_cells, params.angular_cells);
    assert!((1..=3).contains(&p) && nr >= 1 && na >= 3, "{params:?}");
    assert!(0.0 < params.inner_radius && params.inner_radius < params.outer_radius);
    let radial_nodes = nr * p + 1;
    let angular_nodes = na * p;
    let node = |a: usize, b: usize| ((b % angular_nodes) * radial_nodes + a) as u32;

    let mut mesh = Mesh::new(Dim::Two, params.order);
    mesh.nodes = Vec::with_capacity(radial_nodes * angular_nodes);
    for b in 0..angular_nodes {
        let theta = TAU * b as f64 / angular_nodes as f64;
        for a in 0..radial_nodes {
            let r = params.inner_radius
                + (params.outer_radius - params.inner_radius) * a as f64 / (nr * p) as f64;
            mesh.nodes.push([r * theta.cos(), r * theta.sin(), 0.0]);
        }
    }

    let tri = CellType::new(Shape::Tri, params.order);
    let quad = CellType::new(Shape::Quad, params.order);
    let tri_ref = gmsh_reference_nodes(tri).unwrap_or_default();
    let quad_ref = gmsh_reference_nodes(quad).unwrap_or_default();
    // Lattice offset (in steps) of a reference point mapped by `corners` (cell units).
    let place = |corners: [[f64; 2]; 3], s: f64, t: f64| {
        let u = corners[0][0]
            + s * (corners[1][0] - corners[0][0])
            + t * (corners[2][0] - corners[0][0]);
        let v = corners[0][1]
            + s * (corners[1][1] - corners[0][1])
            + t * (corners[2][1] - corners[0][1]);
        (
            (u * p as f64).round() as usize,
            (v * p as f64).round() as usize,
        )
    };
    mesh.cells = Cells::with_capacity(2 * nr * na, quad.node_count());
    let mut nodes = Vec::with_capacity(16);
    for i in 0..nr {
        for j in 0..na {
            let c = i * na + j;
            let cut = !params.triangle_mask.is_empty()
                && params.triangle_mask[c % params.triangle_mask.len()];
            let (a0, b0) = (i * p, j * p);
            let pieces: Vec<(CellType, Vec<(usize, usize)>)> = if cut {
                [
                    [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]],
                    [[0.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
                ]
                .into_iter()
                .map(|k| (tri, tri_ref.iter().map(|r| place(k, r[0], r[1])).collect()))
                .collect()
            } else {
                let k = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
                let offsets = quad_ref
                    .iter()
                    .map(|r| place(k, (r[0] + 1.0) / 2.0, (r[1] + 1.0) / 2.0))
                    .collect();
                vec![(quad, offsets)]
            };
            for (ty, offsets) in pieces {
                nodes.clear();
                nodes.extend(offsets.iter().map(|&(da, db)| node(a0 + da, b0 + db)));
                mesh.cells.push(ty, &nodes);
                mesh.cell_layer.push(i as u32);
                mesh.cell_pipe.push((na - 1 - j) as u32);
            }
        }
    }

    let line = CellType::new(Shape::Line, params.order);
    mesh.patches = vec![
        Patch {
            name: "inner".into(),
            role: Role::Wall,
        },
        Patch {
            name: "outer".into(),
            role: Role::Farfield,
        },
    ];
    // Inner circle, clockwise: from b = (j+1)p down to jp, for j = na−1 … 0.
    for j in (0..na).rev() {
        let (from, to) = ((j + 1) * p, j * p);
        nodes.clear();
        nodes.extend([node(0, from), node(0, to)]);
        nodes.extend((1..p).map(|k| node(0, from - k)));
        mesh.boundary.push(line, &nodes);
        mesh.boundary_patch.push(0);
    }
    // Outer circle, counter-clockwise.
    for j in 0..na {
        let (from, to) = (j * p, (j + 1) * p);
        nodes.clear();
        nodes.extend([node(nr * p, from), node(nr * p, to)]);
        nodes.extend((1..p).map(|k| node(nr * p, from + k)));
        mesh.boundary.push(line, &nodes);
        mesh.boundary_patch.push(1);
    }
    mesh
}

/// One of each 3D cell type of the given order (1 or 2): Gmsh's reference tetrahedron,
/// pyramid, prism and hexahedron, shifted apart along x, with their nodes in Gmsh order. The
/// bottom face of the hexahedron (a quadrilateral, patch `floor`, a wall) and of the
/// tetrahedron (a triangle, patch `box`, far field) are boundary facets. Not a conforming
/// mesh: for format tests only.
///
/// # Panics
/// If `order` is not 1 or 2.
pub fn reference_cells_3d(order: u8) -> Mesh {
    assert!(order == 1 || order == 2, "order {order}");
    let mut mesh = Mesh::new(Dim::Three, order);
    for (k, shape) in [Shape::Tet, Shape::Pyramid, Shape::Prism, Shape::Hex]
        .into_iter()
        .enumerate()
    {
        let ty = CellType::new(shape, order);
        let start = mesh.nodes.len() as u32;
        let shift = 3.0 * k as f64;
        for r in gmsh_reference_nodes(ty).unwrap_or_default() {
            mesh.nodes.push([r[0] + shift, r[1], r[2]]);
        }
        let nodes: Vec<u32> = (start..start + ty.node_count() as u32).collect();
        mesh.cells.push(ty, &nodes);
        match shape {
            Shape::Tet => {
                // Face (0, 2, 1) with its edge nodes (0-2, 2-1, 1-0) for order 2.
                let n = |i: u32| start + i;
                let (ty, facet) = if order == 1 {
                    (CellType::new(Shape::Tri, 1), vec![n(0), n(2), n(1)])
                } else {
                    (
                        CellType::new(Shape::Tri, 2),
                        vec![n(0), n(2), n(1), n(6), n(5), n(4)],
                    )
                };
                mesh.boundary.push(ty, &facet);
                mesh.boundary_patch.push(1);
            }
            Shape::Hex => {
                // Face (0, 3, 2, 1) with its edge nodes (0-3, 3-2, 2-1, 1-0) and face node.
                let n = |i: u32| start + i;
                let (ty, facet) = if order == 1 {
                    (CellType::new(Shape::Quad, 1), vec![n(0), n(3), n(2), n(1)])
                } else {
                    (
                        CellType::new(Shape::Quad, 2),
                        vec![n(0), n(3), n(2), n(1), n(9), n(13), n(11), n(8), n(20)],
                    )
                };
                mesh.boundary.push(ty, &facet);
                mesh.boundary_patch.push(0);
            }
            _ => {}
        }
    }
    mesh.patches = vec![
        Patch {
            name: "floor".into(),
            role: Role::Wall,
        },
        Patch {
            name: "box".into(),
            role: Role::Farfield,
        },
    ];
    mesh
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn annuli_of_every_order_are_valid_and_have_the_ring_area() {
        for order in 1..=3 {
            for mask in [vec![], vec![true], vec![true, false, false]] {
                let params = AnnulusParams {
                    order,
                    triangle_mask: mask.clone(),
                    ..AnnulusParams::default()
                };
                let m = annulus(&params);
                assert_eq!(mesh_model::validate(&m), vec![], "P{order} {mask:?}");
                // The linear cells fill the inscribed polygon ring.
                let n = params.angular_cells as f64;
                let ring = 0.5 * n * (TAU / n).sin() * (2.0f64.powi(2) - 1.0);
                assert!((m.linear_area() - ring).abs() < 1e-12, "P{order}");
            }
        }
    }

    #[test]
    fn high_order_nodes_of_constant_radius_edges_lie_on_the_circles() {
        let m = annulus(&AnnulusParams {
            order: 3,
            ..AnnulusParams::default()
        });
        for (j, f) in m.boundary.iter().enumerate() {
            let r = if m.boundary_patch[j] == 0 { 1.0 } else { 2.0 };
            for &v in f.nodes {
                let [x, y] = m.xy(v);
                assert!((x.hypot(y) - r).abs() < 1e-14, "facet {j} node {v}");
            }
        }
    }

    #[test]
    fn reference_cells_have_their_types() {
        for order in 1..=2 {
            let m = reference_cells_3d(order);
            assert_eq!(m.cells.len(), 4);
            assert_eq!(m.boundary.len(), 2);
            assert!(m.cells.types().iter().all(|t| t.order == order));
        }
    }
}
