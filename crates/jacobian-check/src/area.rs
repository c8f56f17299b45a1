//! The area of curved 2D cells and meshes: the integral of the Jacobian determinant over
//! the reference cell with a Gauss rule exact for its polynomial degree (2(p − 1) on a P_p
//! triangle, 2p − 1 per direction on a Q_p quadrilateral): the independent check of the area
//! `check_mesh` sums from the certificates' coefficients (`MeshValidity::measure`, what the
//! tool's report gives).
//!
//! Triangles use the collapsed (Duffy) product of Gauss–Legendre rules; quadrilaterals the
//! tensor product. The volume of 3D cells ([`cell_volume`]) needs no rule: it is the mean of
//! the determinant's Bernstein coefficients. The volume a curved 3D mesh's boundary
//! encloses ([`enclosed_volume`]) is its independent check. This module owns the area rules;
//! the Gauss–Legendre rule is the `gauss` module's, the reference cells' measures the
//! `measure` module's.

use std::sync::OnceLock;

use mesh_model::{CellType, Mesh, Shape};

use crate::error::JacobianError;
use crate::gauss::gauss_legendre;
use crate::jacobian::check_cell;
use crate::lagrange::basis;
use crate::matrix::{det, matrix_from_gradients};
use crate::measure::measure_from_coefficients;
use crate::types::{Feature, SLOTS, slot};

/// A quadrature rule on a 2D reference cell with the shape-function gradients at its points.
#[derive(Debug)]
struct AreaRule {
    weights: Vec<f64>,
    /// `grads[q · nodes + i]`.
    grads: Vec<[f64; 3]>,
    nodes: usize,
}

fn area_rule(ty: CellType) -> Result<&'static AreaRule, JacobianError> {
    static CACHE: [OnceLock<AreaRule>; SLOTS] = [const { OnceLock::new() }; SLOTS];
    let i = slot(ty, Feature::Area)?;
    let b = basis(ty)?;
    Ok(CACHE[i].get_or_init(|| {
        // Degree of the determinant: 2(p − 1) (triangle), 2p − 1 per direction (quad).
        // m Gauss points integrate degree 2m − 1; the collapsed triangle adds one degree.
        let m = ty.order as usize + 1;
        let g = gauss_legendre(m);
        let mut points = Vec::new();
        let mut weights = Vec::new();
        for &(a, wa) in &g {
            for &(c, wc) in &g {
                match ty.shape {
                    Shape::Tri => {
                        // (s, t) in [0, 1]² ↦ (s (1 − t), t), Jacobian (1 − t).
                        let (s, t) = (0.5 * (a + 1.0), 0.5 * (c + 1.0));
                        points.push([s * (1.0 - t), t, 0.0]);
                        weights.push(0.25 * wa * wc * (1.0 - t));
                    }
                    _ => {
                        points.push([a, c, 0.0]);
                        weights.push(wa * wc);
                    }
                }
            }
        }
        let nodes = ty.node_count();
        let mut grads = vec![[0.0; 3]; points.len() * nodes];
        for (q, p) in points.iter().enumerate() {
            b.gradients(*p, &mut grads[q * nodes..(q + 1) * nodes]);
        }
        AreaRule {
            weights,
            grads,
            nodes,
        }
    }))
}

/// The signed area of a 2D cell (positive when counter-clockwise), exact for its
/// polynomial map up to rounding.
///
/// # Errors
/// Unsupported type, wrong dimension, wrong node count, non-finite node.
pub fn cell_area(ty: CellType, nodes: &[[f64; 2]]) -> Result<f64, JacobianError> {
    check_cell(ty, nodes)?;
    let rule = area_rule(ty)?;
    Ok(rule
        .weights
        .iter()
        .enumerate()
        .map(|(q, w)| {
            let g = &rule.grads[q * rule.nodes..(q + 1) * rule.nodes];
            w * det(&matrix_from_gradients(nodes, g))
        })
        .sum())
}

/// The signed area of a curved 2D mesh: the sum of [`cell_area`] over its cells.
///
/// # Errors
/// A cell naming a missing node, a 3D cell, an unsupported type, a non-finite node.
pub fn integrate_area(mesh: &Mesh) -> Result<f64, JacobianError> {
    sum_over_cells(mesh, |n| mesh.xy(n), cell_area)
}

/// The sum of `measure` over the cells of `mesh`, each given its node coordinates by `at`.
/// The cells are measured in parallel, in chunks, and summed one after the other in cell
/// order: the same sum to the last bit, and the same first error, whatever the threads.
fn sum_over_cells<P>(
    mesh: &Mesh,
    at: impl Fn(u32) -> P + Sync,
    measure: impl Fn(CellType, &[P]) -> Result<f64, JacobianError> + Sync,
) -> Result<f64, JacobianError> {
    use rayon::prelude::*;
    const CHUNK: usize = 4096;
    let n = mesh.cells.len();
    let chunks: Vec<Result<Vec<f64>, JacobianError>> = (0..n.div_ceil(CHUNK))
        .into_par_iter()
        .map(|k| {
            let mut nodes = Vec::new();
            (k * CHUNK..n.min((k + 1) * CHUNK))
                .map(|i| {
                    let cell = mesh.cells.get(i);
                    if let Some(&node) =
                        cell.nodes.iter().find(|&&n| n as usize >= mesh.nodes.len())
                    {
                        return Err(JacobianError::NodeOutOfRange { cell: i, node });
                    }
                    nodes.clear();
                    nodes.extend(cell.nodes.iter().map(|&n| at(n)));
                    measure(cell.ty, &nodes)
                })
                .collect()
        })
        .collect();
    let mut total = 0.0;
    for chunk in chunks {
        for v in chunk? {
            total += v;
        }
    }
    Ok(total)
}

/// The area enclosed by the boundary facets of a 2D mesh (the domain on their left), along
/// their curved (Lagrange) shape: ½∮(x dy − y dx) by 4-point Gauss quadrature, exact for
/// lines of order 1 to 3. Equal to [`integrate_area`] up to rounding when the cells tile the
/// domain exactly — the independent check that a curved mesh is conforming and leaves no gap.
///
/// # Errors
/// A facet naming a missing node, a facet that is not a line of order 1 to 3.
pub fn enclosed_area(mesh: &Mesh) -> Result<f64, JacobianError> {
    const GAUSS: [(f64, f64); 4] = [
        (0.069_431_844_202_973_71, 0.173_927_422_568_726_9),
        (0.330_009_478_207_571_9, 0.326_072_577_431_273_1),
        (0.669_990_521_792_428_1, 0.326_072_577_431_273_1),
        (0.930_568_155_797_026_3, 0.173_927_422_568_726_9),
    ];
    let mut total = 0.0;
    for (i, f) in mesh.boundary.iter().enumerate() {
        let p = f.ty.order as usize;
        if f.ty.shape != mesh_model::Shape::Line || !(1..=3).contains(&p) {
            return Err(JacobianError::Unsupported {
                ty: f.ty,
                what: "the enclosed area (boundary lines of order 1 to 3)",
            });
        }
        if let Some(&node) = f.nodes.iter().find(|&&n| n as usize >= mesh.nodes.len()) {
            return Err(JacobianError::NodeOutOfRange { cell: i, node });
        }
        // Gmsh line order: the two ends, then the inner nodes from the first end
        let at = |j: usize| -> [f64; 2] {
            match j {
                0 => mesh.xy(f.nodes[0]),
                j if j == p => mesh.xy(f.nodes[1]),
                j => mesh.xy(f.nodes[1 + j]),
            }
        };
        for (s, w) in GAUSS {
            let (mut x, mut dx) = ([0.0; 2], [0.0; 2]);
            let (l, dl) = crate::lagrange::equispaced_line(p, s);
            for j in 0..=p {
                let v = at(j);
                for d in 0..2 {
                    x[d] += l[j] * v[d];
                    dx[d] += dl[j] * v[d];
                }
            }
            total += 0.5 * w * (x[0] * dx[1] - x[1] * dx[0]);
        }
    }
    Ok(total)
}

/// The signed volume of a 3D cell, exact for its map up to rounding: the integral of the
/// Jacobian determinant is the mean of its Bernstein coefficients times the reference
/// volume (`measure_from_coefficients`). A straight-sided high-order cell is its order-1
/// cell, as [`crate::check_mesh`] measures it; a curved high-order pyramid is integrated by an
/// exact Gauss rule on its collapsed box (the `pyramid` module).
///
/// # Errors
/// Unsupported type, a 2D type, wrong node count, non-finite node.
pub fn cell_volume(ty: CellType, nodes: &[[f64; 3]]) -> Result<f64, JacobianError> {
    check_cell(ty, nodes)?;
    if crate::straight::is_straight(ty, nodes)?.is_some() {
        let linear = CellType::new(ty.shape, 1);
        return cell_volume(linear, &nodes[..ty.shape.corners()]);
    }
    if ty.shape == Shape::Pyramid && ty.order >= 2 {
        return Ok(crate::pyramid::volume(nodes));
    }
    let c = crate::certify::determinant_bernstein_coefficients(ty, nodes)?;
    Ok(measure_from_coefficients(ty.shape, &c))
}

/// The signed volume of a curved 3D mesh: the sum of [`cell_volume`] over its cells.
///
/// # Errors
/// A cell naming a missing node, a 2D cell, an unsupported type, a non-finite node.
pub fn integrate_volume(mesh: &Mesh) -> Result<f64, JacobianError> {
    sum_over_cells(mesh, |n| mesh.nodes[n as usize], cell_volume)
}

/// The volume enclosed by the boundary facets of a 3D mesh (turned out of the domain), along
/// their curved (Lagrange) shape: ⅓∮ x·n dA by Gauss quadrature exact for triangles and
/// quadrilaterals of order 1 to 3 (x·(x_u × x_v) has degree 4 on a P2 triangle, taken by
/// the collapsed 3 × 3 rule; degree 5 per direction on a Q2 quadrilateral, 3 × 3 Gauss; at
/// order 3 degree 7 on the triangle, 8 per direction on the quadrilateral, 5 × 5 Gauss).
/// Equal to [`integrate_volume`] up to rounding when the cells tile the domain exactly —
/// the independent check that a curved 3D mesh is conforming and leaves no gap.
///
/// # Errors
/// A facet naming a missing node, a facet that is not a triangle or quadrilateral of order 1
/// to 3.
pub fn enclosed_volume(mesh: &Mesh) -> Result<f64, JacobianError> {
    let (g3, g5) = (gauss_legendre(3), gauss_legendre(5));
    let origin = mesh.nodes.first().copied().unwrap_or_default();
    let mut total = 0.0;
    let mut x = Vec::new();
    for (i, f) in mesh.boundary.iter().enumerate() {
        let ty = f.ty;
        if !matches!(ty.shape, Shape::Tri | Shape::Quad) || !(1..=3).contains(&ty.order) {
            return Err(JacobianError::Unsupported {
                ty,
                what: "the enclosed volume (boundary triangles and quadrilaterals of order 1 to 3)",
            });
        }
        let g = if ty.order < 3 { &g3 } else { &g5 };
        if let Some(&node) = f.nodes.iter().find(|&&n| n as usize >= mesh.nodes.len()) {
            return Err(JacobianError::NodeOutOfRange { cell: i, node });
        }
        x.clear();
        x.extend(f.nodes.iter().map(|&n| {
            let p = mesh.nodes[n as usize];
            [0, 1, 2].map(|d| p[d] - origin[d])
        }));
        for &(a, wa) in g {
            for &(b, wb) in g {
                // a point of the reference cell and its weight
                let (xi, w) = match ty.shape {
                    Shape::Tri => {
                        let (s, t) = (0.5 * (a + 1.0), 0.5 * (b + 1.0));
                        ([s, (1.0 - s) * t, 0.0], 0.25 * wa * wb * (1.0 - s))
                    }
                    _ => ([a, b, 0.0], wa * wb),
                };
                total += w * flux(ty, &x, xi)?;
            }
        }
    }
    Ok(total / 3.0)
}

/// x·(x_u × x_v) at reference point `xi` of the facet with nodes `x`.
fn flux(ty: CellType, x: &[[f64; 3]], xi: [f64; 3]) -> Result<f64, JacobianError> {
    let n = crate::lagrange::shape_functions(ty, xi)?;
    let dn = crate::lagrange::shape_gradients(ty, xi)?;
    let (mut p, mut u, mut v) = ([0.0; 3], [0.0; 3], [0.0; 3]);
    for (j, xj) in x.iter().enumerate() {
        for d in 0..3 {
            p[d] += n[j] * xj[d];
            u[d] += dn[j][0] * xj[d];
            v[d] += dn[j][1] * xj[d];
        }
    }
    let c = [
        u[1] * v[2] - u[2] * v[1],
        u[2] * v[0] - u[0] * v[2],
        u[0] * v[1] - u[1] * v[0],
    ];
    Ok(p[0] * c[0] + p[1] * c[1] + p[2] * c[2])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_enclosed_volume_of_curved_tetrahedra_is_their_integrated_volume() {
        // a P2 tetrahedron with a bowed edge, its four faces as boundary facets
        let ty = CellType::new(Shape::Tet, 2);
        let mut nodes = crate::reference_nodes(ty).unwrap();
        nodes[4][1] -= 0.2; // edge 0-1 bows out of the cell
        nodes[9][0] += 0.1; // and edge 3-1
        let mut mesh = Mesh::new(mesh_model::Dim::Three, 2);
        mesh.nodes = nodes;
        let ids: Vec<u32> = (0..10).collect();
        mesh.cells.push(ty, &ids);
        // faces with their edge nodes (Gmsh edge order 0-1, 1-2, 2-0, 3-0, 3-2, 3-1)
        let tri6 = CellType::new(Shape::Tri, 2);
        for f in [
            [0, 2, 1, 6, 5, 4],
            [0, 1, 3, 4, 9, 7],
            [0, 3, 2, 7, 8, 6],
            [3, 1, 2, 9, 5, 8],
        ] {
            mesh.boundary.push(tri6, &f);
        }
        let enclosed = enclosed_volume(&mesh).unwrap();
        let integrated = integrate_volume(&mesh).unwrap();
        assert!(
            (enclosed - integrated).abs() < 1e-14,
            "{enclosed} vs {integrated}"
        );
        assert!(
            (integrated - 1.0 / 6.0).abs() > 1e-3,
            "the bow changed the volume"
        );
        // a linear unit cube of one hexahedron's faces
        let mut cube = Mesh::new(mesh_model::Dim::Three, 1);
        cube.nodes = crate::reference_nodes(CellType::new(Shape::Hex, 1)).unwrap();
        for f in Shape::Hex.faces() {
            let k: Vec<u32> = f.iter().map(|&j| j as u32).collect();
            cube.boundary.push(CellType::new(Shape::Quad, 1), &k);
        }
        assert!((enclosed_volume(&cube).unwrap() - 8.0).abs() < 1e-13);
    }
}
