//! Test meshes built by hand, exact and small, for the tests of this crate and of the others
//! (enable the cargo feature `testkit`: `mesh-io = { workspace = true, features = ["testkit"] }`
//! under `[dev-dependencies]`). Not part of the stable API.
//!
//! - [`annulus`]: a structured annulus of quadrilaterals, some cut into triangles, of order 1
//!   to 3, high-order nodes exactly on the circles, in Gmsh order; inner circle a wall,
//!   outer circle the far field; valid for `mesh_model::validate`.
//! - [`airfoil_ring`]: the same structure grown in thin layers around a real airfoil loop
//!   (read with [`selig_points`]), for tests on real coordinates.
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
    /// then outward, starting at angle 0) is cut when `triangle_mask[c % len]` is true. Empty: no triangle.
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
/// (`inner`, a wall), patch 1 the outer circle (`circle`, the far field). `cell_layer` is the
/// ring index counted from the wall and `cell_pipe` the wall facet below each cell.
///
/// # Panics
/// On parameters outside the documented ranges (a test bug, not input).
pub fn annulus(params: &AnnulusParams) -> Mesh {
    let p = params.order as usize;
    let (nr, na) = (params.radial_cells, params.angular_cells);
    assert!((1..=3).contains(&p) && nr >= 1 && na >= 3, "{params:?}");
    assert!(0.0 < params.inner_radius && params.inner_radius < params.outer_radius);
    let (r0, r1) = (params.inner_radius, params.outer_radius);
    ring(
        params.order,
        na,
        nr,
        &params.triangle_mask,
        ["inner", "circle"],
        |along, across| {
            let theta = TAU * along as f64 / (na * p) as f64;
            let r = r0 + (r1 - r0) * across as f64 / (nr * p) as f64;
            [r * theta.cos(), r * theta.sin()]
        },
    )
}

/// Shape and size of an [`airfoil_ring`].
#[derive(Debug, Clone, PartialEq)]
pub struct RingParams {
    /// Polynomial order of the cells, 1 to 3.
    pub order: u8,
    /// Number of cell layers.
    pub layers: usize,
    /// Total thickness of the layers along the vertex normals, in the loop's length units.
    pub thickness: f64,
    /// As in [`AnnulusParams::triangle_mask`].
    pub triangle_mask: Vec<bool>,
}

/// The points of a Selig `.dat` airfoil file: a title line, then `x y` per line (the first
/// point not repeated at the end).
///
/// # Panics
/// On a line that is not two numbers (a test bug: the fixtures are known files).
pub fn selig_points(text: &str) -> Vec<[f64; 2]> {
    text.lines()
        .skip(1)
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let v: Vec<f64> = l
                .split_whitespace()
                .map(|t| t.parse().unwrap_or_else(|_| panic!("bad line {l:?}")))
                .collect();
            assert_eq!(v.len(), 2, "bad line {l:?}");
            [v[0], v[1]]
        })
        .collect()
}

/// A structured ring of layers around a counter-clockwise closed loop (an airfoil), grown
/// along the vertex normals: the loop is the wall (patch `wall-loop`), the outer edge of the
/// last layer the far field (patch `circle`). High-order nodes are interpolated linearly
/// between loop points, so edges are straight; nodes carry the loop's own coordinates. Valid
/// for `mesh_model::validate` as long as the layers are thin against the loop's curvature.
///
/// # Panics
/// On fewer than 3 loop points, order outside 1..=3, no layer (test bugs).
pub fn airfoil_ring(points: &[[f64; 2]], params: &RingParams) -> Mesh {
    let n = points.len();
    let p = params.order as usize;
    assert!(n >= 3 && (1..=3).contains(&p) && params.layers >= 1);
    let normals: Vec<[f64; 2]> = (0..n)
        .map(|i| {
            let (a, b) = (points[(i + n - 1) % n], points[(i + 1) % n]);
            let t = [b[0] - a[0], b[1] - a[1]];
            let len = t[0].hypot(t[1]);
            [t[1] / len, -t[0] / len]
        })
        .collect();
    ring(
        params.order,
        n,
        params.layers,
        &params.triangle_mask,
        ["wall-loop", "circle"],
        |along, across| {
            let (i, f) = (along / p, (along % p) as f64 / p as f64);
            let j = (i + 1) % n;
            let h = params.thickness * across as f64 / (params.layers * p) as f64;
            [0, 1].map(|k| {
                let base = points[i][k] + f * (points[j][k] - points[i][k]);
                base + h * (normals[i][k] + f * (normals[j][k] - normals[i][k]))
            })
        },
    )
}

/// The common builder: `along` cells around a closed ring (counter-clockwise), `across` cells
/// outward from the wall. `position(along, across)` maps lattice indices (`order` steps per
/// cell; `along` in `0..along·order`, `across` in `0..=across·order`) to the plane. Nodes are numbered around, with the outward index fastest.
fn ring(
    order: u8,
    along: usize,
    across: usize,
    triangle_mask: &[bool],
    names: [&str; 2],
    position: impl Fn(usize, usize) -> [f64; 2],
) -> Mesh {
    let p = order as usize;
    let across_nodes = across * p + 1;
    let along_nodes = along * p;
    let node = |s: usize, t: usize| ((s % along_nodes) * across_nodes + t) as u32;

    let mut mesh = Mesh::new(Dim::Two, order);
    mesh.nodes = Vec::with_capacity(across_nodes * along_nodes);
    for s in 0..along_nodes {
        for t in 0..across_nodes {
            let [x, y] = position(s, t);
            mesh.nodes.push([x, y, 0.0]);
        }
    }

    let tri = CellType::new(Shape::Tri, order);
    let quad = CellType::new(Shape::Quad, order);
    let tri_ref = gmsh_reference_nodes(tri).unwrap_or_default();
    let quad_ref = gmsh_reference_nodes(quad).unwrap_or_default();
    // Lattice offset (in steps) of the reference point (u, v) of the affine map that sends
    // (0, 0), (1, 0), (0, 1) to `corners` (cell units, `along` then `across`).
    let place = |corners: [[f64; 2]; 3], u: f64, v: f64| {
        let at = |k: usize| {
            corners[0][k]
                + u * (corners[1][k] - corners[0][k])
                + v * (corners[2][k] - corners[0][k])
        };
        (
            (at(0) * p as f64).round() as usize,
            (at(1) * p as f64).round() as usize,
        )
    };
    // In (along, across) cell units the counter-clockwise corners of a cell are
    // (1, 0), (0, 0), (0, 1), (1, 1): `along` runs counter-clockwise and `across` outward,
    // a left-handed pair.
    let (c0, c1, c2, c3) = ([1.0, 0.0], [0.0, 0.0], [0.0, 1.0], [1.0, 1.0]);
    mesh.cells = Cells::with_capacity(2 * along * across, quad.node_count());
    let mut nodes = Vec::with_capacity(16);
    for k in 0..across {
        for i in 0..along {
            let c = k * along + i;
            let cut = !triangle_mask.is_empty() && triangle_mask[c % triangle_mask.len()];
            let pieces: Vec<(CellType, Vec<(usize, usize)>)> = if cut {
                [[c0, c1, c2], [c0, c2, c3]]
                    .into_iter()
                    .map(|k| (tri, tri_ref.iter().map(|r| place(k, r[0], r[1])).collect()))
                    .collect()
            } else {
                let offsets = quad_ref
                    .iter()
                    .map(|r| place([c0, c1, c3], (r[0] + 1.0) / 2.0, (r[1] + 1.0) / 2.0))
                    .collect();
                vec![(quad, offsets)]
            };
            for (ty, offsets) in pieces {
                nodes.clear();
                nodes.extend(offsets.iter().map(|&(ds, dt)| node(i * p + ds, k * p + dt)));
                mesh.cells.push(ty, &nodes);
                mesh.cell_layer.push(k as u32);
                mesh.cell_pipe.push((along - 1 - i) as u32);
            }
        }
    }

    let line = CellType::new(Shape::Line, order);
    mesh.patches = vec![
        Patch {
            name: names[0].into(),
            role: Role::Wall,
        },
        Patch {
            name: names[1].into(),
            role: Role::Farfield,
        },
    ];
    // The wall, clockwise: from s = (i+1)p down to ip, for i = along−1 … 0.
    for i in (0..along).rev() {
        let (from, to) = ((i + 1) * p, i * p);
        nodes.clear();
        nodes.extend([node(from, 0), node(to, 0)]);
        nodes.extend((1..p).map(|k| node(from - k, 0)));
        mesh.boundary.push(line, &nodes);
        mesh.boundary_patch.push(0);
    }
    // The outer edge, counter-clockwise.
    let t = across * p;
    for i in 0..along {
        let (from, to) = (i * p, (i + 1) * p);
        nodes.clear();
        nodes.extend([node(from, t), node(to, t)]);
        nodes.extend((1..p).map(|k| node(from + k, t)));
        mesh.boundary.push(line, &nodes);
        mesh.boundary_patch.push(1);
    }
    mesh
}

/// One of each 3D cell type of the given order (1 to 3): Gmsh's reference tetrahedron,
/// pyramid, prism and hexahedron, shifted apart along x, with their nodes in Gmsh order. The
/// bottom face of the hexahedron (a quadrilateral, patch `floor`, a wall) and of the
/// tetrahedron (a triangle, patch `box`, far field) are boundary facets. Not a conforming
/// mesh: for format tests only.
///
/// # Panics
/// If `order` is not 1 to 3.
pub fn reference_cells_3d(order: u8) -> Mesh {
    assert!((1..=3).contains(&order), "order {order}");
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
                // Face (0, 2, 1) with its edge nodes (0-2, 2-1, 1-0) and face node.
                let local: &[u32] = match order {
                    1 => &[0, 2, 1],
                    2 => &[0, 2, 1, 6, 5, 4],
                    _ => &[0, 2, 1, 9, 8, 7, 6, 5, 4, 16],
                };
                let facet: Vec<u32> = local.iter().map(|&i| start + i).collect();
                mesh.boundary.push(CellType::new(Shape::Tri, order), &facet);
                mesh.boundary_patch.push(1);
            }
            Shape::Hex => {
                // Face (0, 3, 2, 1) with its edge nodes (0-3, 3-2, 2-1, 1-0) and face nodes.
                let local: &[u32] = match order {
                    1 => &[0, 3, 2, 1],
                    2 => &[0, 3, 2, 1, 9, 13, 11, 8, 20],
                    _ => &[0, 3, 2, 1, 10, 11, 19, 18, 15, 14, 9, 8, 32, 33, 34, 35],
                };
                let facet: Vec<u32> = local.iter().map(|&i| start + i).collect();
                mesh.boundary
                    .push(CellType::new(Shape::Quad, order), &facet);
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
    fn rings_around_real_airfoils_are_valid() {
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../fixtures/geometry/");
        for (file, thickness) in [("naca0012.dat", 2e-3), ("rae2822.dat", 2e-3)] {
            let text = std::fs::read_to_string(format!("{dir}{file}")).unwrap();
            let points = selig_points(&text);
            assert!(points.len() > 60, "{file}");
            for order in 1..=3 {
                let m = airfoil_ring(
                    &points,
                    &RingParams {
                        order,
                        layers: 2,
                        thickness,
                        triangle_mask: vec![false, true],
                    },
                );
                assert_eq!(mesh_model::validate(&m), vec![], "{file} P{order}");
                // The wall nodes are the file's points, exactly.
                for (k, pt) in points.iter().enumerate() {
                    assert_eq!(
                        m.xy((k * order as usize * (2 * order as usize + 1)) as u32),
                        *pt
                    );
                }
            }
        }
    }

    #[test]
    fn reference_cells_have_their_types() {
        for order in 1..=3 {
            let m = reference_cells_3d(order);
            assert_eq!(m.cells.len(), 4);
            assert_eq!(m.boundary.len(), 2);
            assert!(m.cells.types().iter().all(|t| t.order == order));
            // each facet's nodes where its reference facet's, mapped by its corners, put them
            for f in m.boundary.iter() {
                let refs = gmsh_reference_nodes(f.ty).unwrap();
                let c: Vec<[f64; 3]> = f.corners().iter().map(|&n| m.nodes[n as usize]).collect();
                for (r, &n) in refs.iter().zip(f.nodes) {
                    let w = if f.ty.shape == Shape::Tri {
                        vec![1.0 - r[0] - r[1], r[0], r[1]]
                    } else {
                        let (u, v) = (0.5 * (r[0] + 1.0), 0.5 * (r[1] + 1.0));
                        vec![(1.0 - u) * (1.0 - v), u * (1.0 - v), u * v, (1.0 - u) * v]
                    };
                    let at = [0, 1, 2].map(|d| (0..c.len()).map(|j| w[j] * c[j][d]).sum::<f64>());
                    let x = m.nodes[n as usize];
                    assert!((0..3).all(|d| (x[d] - at[d]).abs() < 1e-12), "{f:?}");
                }
            }
        }
    }
}
