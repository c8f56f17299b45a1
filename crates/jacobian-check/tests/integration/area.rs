//! The area of curved meshes by exact quadrature: exact for straight cells, converging at
//! the rate of the boundary interpolation on P1–P3 annuli with nodes on the circles.

use std::f64::consts::PI;

use jacobian_check::{JacobianError, cell_area, integrate_area, reference_nodes};
use mesh_io::testkit::{AnnulusParams, annulus};
use mesh_model::{CellType, Shape, polygon_area};

fn ring(order: u8, angular_cells: usize) -> mesh_model::Mesh {
    annulus(&AnnulusParams {
        order,
        radial_cells: 2,
        angular_cells,
        inner_radius: 1.0,
        outer_radius: 2.0,
        triangle_mask: vec![true, false, false],
    })
}

#[test]
fn straight_cells_have_their_polygon_area() {
    for ty in [
        CellType::new(Shape::Tri, 1),
        CellType::new(Shape::Tri, 2),
        CellType::new(Shape::Tri, 3),
        CellType::new(Shape::Quad, 1),
        CellType::new(Shape::Quad, 2),
        CellType::new(Shape::Quad, 3),
    ] {
        // A general (non-parallelogram) quadrilateral is bilinear, not affine: map the
        // reference nodes through the bilinear map of its corners.
        let corners = [[0.0, 0.0], [3.0, 0.5], [2.5, 2.0], [0.2, 1.5]];
        let nodes: Vec<[f64; 2]> = reference_nodes(ty)
            .unwrap()
            .iter()
            .map(|x| match ty.shape {
                Shape::Tri => {
                    let l = [1.0 - x[0] - x[1], x[0], x[1]];
                    [0, 1].map(|k| (0..3).map(|i| l[i] * corners[i][k]).sum())
                }
                _ => {
                    let w = [
                        (1.0 - x[0]) * (1.0 - x[1]) / 4.0,
                        (1.0 + x[0]) * (1.0 - x[1]) / 4.0,
                        (1.0 + x[0]) * (1.0 + x[1]) / 4.0,
                        (1.0 - x[0]) * (1.0 + x[1]) / 4.0,
                    ];
                    [0, 1].map(|k| (0..4).map(|i| w[i] * corners[i][k]).sum())
                }
            })
            .collect();
        let exact = polygon_area(corners[..ty.shape.corners()].iter().copied());
        let got = cell_area(ty, &nodes).unwrap();
        assert!((got - exact).abs() < 1e-13, "{ty:?}: {got} vs {exact}");
    }
}

#[test]
fn linear_mesh_area_is_the_shoelace_area() {
    let mesh = ring(1, 12);
    let a = integrate_area(&mesh).unwrap();
    assert!((a - mesh.linear_area()).abs() < 1e-12);
}

#[test]
fn the_area_is_summed_in_cell_order_whatever_the_threads() {
    // many chunks of cells: measured in parallel, summed one after the other
    let mesh = ring(3, 6000);
    let mut sequential = 0.0;
    for c in mesh.cells.iter() {
        let nodes: Vec<[f64; 2]> = c.nodes.iter().map(|&k| mesh.xy(k)).collect();
        sequential += cell_area(c.ty, &nodes).unwrap();
    }
    for threads in [1, 2, 3] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let a = pool.install(|| integrate_area(&mesh)).unwrap();
        assert_eq!(a.to_bits(), sequential.to_bits(), "{threads} threads");
    }
}

#[test]
fn the_first_bad_cell_is_the_one_named() {
    let mut mesh = ring(2, 6000);
    let n = mesh.nodes.len() as u32;
    // two cells naming a missing node, far apart (in different chunks): the first is named
    for cell in [5000, 11000] {
        mesh.cells.nodes_mut(cell)[0] = n + cell as u32;
    }
    match integrate_area(&mesh) {
        Err(JacobianError::NodeOutOfRange { cell, .. }) => assert_eq!(cell, 5000),
        other => panic!("{other:?}"),
    }
}

/// Observed convergence rates of the area error of the annulus (exact 3π) under halving
/// of the angular cell size.
fn rates(order: u8) -> Vec<f64> {
    let errors: Vec<f64> = [8, 16, 32, 64]
        .iter()
        .map(|&n| (integrate_area(&ring(order, n)).unwrap() - 3.0 * PI).abs())
        .collect();
    errors.windows(2).map(|e| (e[0] / e[1]).log2()).collect()
}

#[test]
fn annulus_area_converges_at_the_interpolation_rate() {
    // Polynomial interpolation of a circle at p + 1 equispaced nodes per arc leaves an
    // area error of order h^(p+1) for odd p and h^(p+2) for even p (the error polynomial
    // integrates to a higher order by symmetry): rates 2, 4, 4 for P1, P2, P3.
    for (order, expected) in [(1, 2.0), (2, 4.0), (3, 4.0)] {
        let r = rates(order);
        let last = *r.last().unwrap();
        assert!(
            (last - expected).abs() < 0.15,
            "P{order}: rates {r:?}, expected {expected}"
        );
    }
    // And the curved meshes are far closer than the linear one.
    let err = |o| (integrate_area(&ring(o, 16)).unwrap() - 3.0 * PI).abs();
    assert!(
        err(2) < 1e-2 * err(1) && err(3) < err(2),
        "{} {} {}",
        err(1),
        err(2),
        err(3)
    );
}

#[test]
fn three_dimensional_cells_are_an_error() {
    let mesh = mesh_io::testkit::reference_cells_3d(1);
    assert!(matches!(
        integrate_area(&mesh),
        Err(JacobianError::WrongDimension { .. })
    ));
}

#[test]
fn the_enclosed_area_of_a_curved_annulus_equals_its_cells_area() {
    for order in [1, 2, 3] {
        let mesh = mesh_io::testkit::annulus(&mesh_io::testkit::AnnulusParams {
            order,
            ..Default::default()
        });
        let cells = jacobian_check::integrate_area(&mesh).unwrap();
        let boundary = jacobian_check::enclosed_area(&mesh).unwrap();
        assert!(
            (cells - boundary).abs() <= 1e-12 * cells,
            "P{order}: cells {cells} vs boundary {boundary}"
        );
    }
}
