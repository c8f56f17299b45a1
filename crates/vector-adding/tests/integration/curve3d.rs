//! The 3D curving on a sphere grown by `afsf3d` and cut by `topo-cut` (tetrahedra, and the
//! mixed cut, all prisms without merged children), at P2 and P3: every cell certified valid,
//! the wall's high-order nodes on the sphere, the volume of the curved mesh closer to the
//! exact volume between the sphere and the outer front than the linear mesh's (and at P3
//! than the P2 mesh's); pyramids on flat and curved walls; bad input refused.

use afsf3d::{LayerParams, grow_layers};
use geom_surface::Surface;
use jacobian_check::{CertifyParams, check_mesh, integrate_volume};
use mesh_model::{CellType, Dim, Mesh, Role, Shape};
use vector_adding::{
    CurvingError, CurvingParams, SphereProjector, SurfaceProjector, curve_mesh_3d,
};

const R: f64 = 1.0;

fn grown(layers: usize) -> afsf3d::Grown3d {
    grown_on(3, 0.01, layers)
}

fn grown_on(refinement: u32, first_height: f64, layers: usize) -> afsf3d::Grown3d {
    let sphere = Surface::sphere(R, refinement);
    let params = LayerParams {
        first_height,
        growth: 1.3,
        layers,
        ..LayerParams::default()
    };
    grow_layers(&sphere, &params).unwrap()
}

fn p2() -> CurvingParams {
    order(2)
}

fn order(order: u8) -> CurvingParams {
    CurvingParams {
        order,
        ..CurvingParams::default()
    }
}

const SPHERE: SphereProjector = SphereProjector {
    centre: [0.0; 3],
    radius: R,
};

/// Curves `linear` to order `p`, checks every cell certified valid and the wall nodes on
/// the sphere; returns the curved mesh.
fn curved_and_valid(linear: &Mesh, g: &afsf3d::Grown3d, p: u8) -> vector_adding::Curved3d {
    let curved = curve_mesh_3d(linear, &g.columns, &SPHERE, &order(p)).unwrap();
    let mesh = &curved.mesh;
    assert_eq!(mesh.order, p);
    assert!(mesh.cells.types().iter().all(|t| t.order == p));
    assert_eq!(mesh.cells.len(), linear.cells.len());
    assert!(
        mesh_model::validate(mesh).is_empty(),
        "{:?}",
        mesh_model::validate(mesh).first()
    );
    // every cell certified valid
    let v = check_mesh(mesh, &CertifyParams::default()).unwrap();
    assert!(
        v.invalid_cells.is_empty() && v.undecided.is_empty() && v.uncertified.is_empty(),
        "{v:?} {:?}",
        curved.stats
    );
    // the wall facets' high-order nodes on the sphere
    let mut on_wall = 0;
    for (f, facet) in mesh.boundary.iter().enumerate() {
        if mesh.patches[mesh.boundary_patch[f] as usize].role != Role::Wall {
            continue;
        }
        let corners = facet.ty.shape.corners();
        for &n in &facet.nodes[corners..] {
            let x = mesh.nodes[n as usize];
            let r = (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]).sqrt();
            assert!((r - R).abs() < 1e-12, "node {n} at radius {r}");
            on_wall += 1;
        }
    }
    assert!(on_wall > 0);
    assert!(curved.stats.wall_edges > 0 && curved.stats.curved_edges > curved.stats.wall_edges);
    curved
}

/// Curves `linear` to P2 and P3 and checks each valid, the P2 volume error under a hundredth
/// of the linear mesh's, the P3 one under a tenth of the P2 one (25 times less here).
fn check_curved(linear: &Mesh, g: &afsf3d::Grown3d) {
    let e2 = check_curved_at(linear, g, 2, integrate_volume(linear).unwrap(), 0.01);
    let p2 = curved_and_valid(linear, g, 2);
    let e3 = check_curved_at(linear, g, 3, integrate_volume(&p2.mesh).unwrap(), 0.1);
    println!("volume errors: P2 {e2:.3e}, P3 {e3:.3e}");
}

/// Curves `linear` to order `p`, checks it (`curved_and_valid`), its volumes agree, and its
/// volume error is under `ratio` times the error of `below`, the volume at order p − 1;
/// returns its volume error.
fn check_curved_at(linear: &Mesh, g: &afsf3d::Grown3d, p: u8, below: f64, ratio: f64) -> f64 {
    let curved = curved_and_valid(linear, g, p);
    let mesh = &curved.mesh;
    // the volume between the true sphere and the (straight) outer front
    let exact = g.front.enclosed_volume() - 4.0 / 3.0 * std::f64::consts::PI * R.powi(3);
    let curved_volume = integrate_volume(mesh).unwrap();
    // the volume `check_mesh` takes from the certificates' coefficients: the same integral
    let measure = check_mesh(mesh, &CertifyParams::default()).unwrap().measure;
    let enclosed = jacobian_check::enclosed_volume(mesh).unwrap();
    for (of, other) in [("the cells", curved_volume), ("the boundary", enclosed)] {
        assert!(
            (measure - other).abs() <= 1e-12 * other.abs(),
            "certified volume {measure} vs {of}' {other}"
        );
    }
    let (e1, e2) = ((below - exact).abs(), (curved_volume - exact).abs());
    println!(
        "P{} volume error {e1:.3e}, P{p} {e2:.3e}; {:?}",
        p - 1,
        curved.stats
    );
    assert!(
        e2 < ratio * e1,
        "P{} error {e1}, P{p} error {e2} ({:?})",
        p - 1,
        curved.stats
    );
    e2
}

#[test]
fn a_coarse_sphere_under_thin_layers_curves_up_to_its_outer_front_and_stays_valid() {
    // 80 facets, whose bulge (~0.05) is as thick as all the layers: no pipe can stop
    let g = grown_on(1, 0.01, 4);
    for linear in [
        topo_cut::cut_to_tets(&g.mesh).unwrap(),
        topo_cut::cut_to_mixed(&g.mesh).unwrap(),
    ] {
        for p in [2, 3] {
            let curved = curved_and_valid(&linear, &g, p);
            println!("P{p}: {:?}", curved.stats);
            assert_eq!(curved.stats.stops.invalid, 0);
        }
    }
}

#[test]
fn a_sphere_cut_to_tetrahedra_is_curved_and_certified() {
    let g = grown(6);
    let linear = topo_cut::cut_to_tets(&g.mesh).unwrap();
    check_curved(&linear, &g);
}

#[test]
fn a_sphere_of_prisms_is_curved_and_certified() {
    let g = grown(6);
    let linear = topo_cut::cut_to_mixed(&g.mesh).unwrap();
    assert_eq!(linear.count(Shape::Prism), linear.cells.len());
    check_curved(&linear, &g);
}

#[test]
fn bad_input_is_refused_with_a_clear_error() {
    let g = grown(2);
    let linear = topo_cut::cut_to_tets(&g.mesh).unwrap();
    // order 4
    assert!(matches!(
        curve_mesh_3d(&linear, &g.columns, &SPHERE, &order(4)),
        Err(CurvingError::BadParameter { name: "order", .. })
    ));
    // a node in no column
    let short: Vec<Vec<u32>> = g.columns[1..].to_vec();
    let e = curve_mesh_3d(&linear, &short, &SPHERE, &p2()).unwrap_err();
    assert!(e.to_string().contains("in no column"), "{e}");
    // a column naming a node that does not exist
    let mut bad = g.columns.clone();
    bad[0].push(u32::MAX - 1);
    assert!(matches!(
        curve_mesh_3d(&linear, &bad, &SPHERE, &p2()),
        Err(CurvingError::BadLayers(_))
    ));
    // a 2D mesh
    let flat = Mesh::new(Dim::Two, 1);
    assert!(matches!(
        curve_mesh_3d(&flat, &[], &SPHERE, &p2()),
        Err(CurvingError::Unsupported3d(_))
    ));
}

/// A flat wall: every point is on it.
struct Flat;

impl vector_adding::SurfaceProjector for Flat {
    fn project(&self, p: [f64; 3], _facet: usize) -> [f64; 3] {
        p
    }
}

#[test]
fn a_pyramid_on_a_flat_wall_stays_straight_and_is_certified() {
    let pyramid = one_pyramid();
    let columns = vec![vec![0, 4], vec![1], vec![2], vec![3]];
    let curved = curve_mesh_3d(&pyramid, &columns, &Flat, &p2()).unwrap();
    let mesh = &curved.mesh;
    assert_eq!(mesh.cells.get(0).nodes.len(), 14);
    let v = check_mesh(mesh, &CertifyParams::default()).unwrap();
    assert!(
        v.invalid_cells.is_empty() && v.min_scaled_jacobian > 0.0,
        "{v:?}"
    );
    let volume = integrate_volume(mesh).unwrap();
    assert!((volume - 1.0 / 3.0).abs() < 1e-12, "{volume}");
    // the base's centre node
    assert_eq!(
        mesh.nodes[mesh.cells.get(0).nodes[13] as usize],
        [0.5, 0.5, 0.0]
    );
}

/// A wall bulging out of the cell below the plane z = 0: a parabolic cylinder along y.
struct Bulge;

impl vector_adding::SurfaceProjector for Bulge {
    fn project(&self, p: [f64; 3], _facet: usize) -> [f64; 3] {
        [p[0], p[1], -0.4 * p[0] * (1.0 - p[0])]
    }
}

#[test]
fn a_pyramid_on_a_curved_wall_is_curved_to_p3_and_certified() {
    let pyramid = one_pyramid();
    let columns = vec![vec![0, 4], vec![1], vec![2], vec![3]];
    let curved = curve_mesh_3d(&pyramid, &columns, &Bulge, &order(3)).unwrap();
    let mesh = &curved.mesh;
    let cell = mesh.cells.get(0);
    assert_eq!(cell.nodes.len(), 30);
    // Gmsh's edge 0-1 nodes (5, 6) and the base's four nodes (25-28) on the wall
    for j in [5, 6, 25, 26, 27, 28] {
        let x = mesh.nodes[cell.nodes[j] as usize];
        assert!(
            (x[2] - Bulge.project(x, 0)[2]).abs() < 1e-15,
            "node {j}: {x:?}"
        );
    }
    let v = check_mesh(mesh, &CertifyParams::default()).unwrap();
    assert!(
        v.invalid_cells.is_empty() && v.undecided.is_empty() && v.min_scaled_jacobian > 0.0,
        "{v:?}"
    );
    // the bulge adds to the straight pyramid's third (less than its own 1/15: the side
    // edges 1-4, over the bowed wall edge 0-1, bow down with it)
    let volume = integrate_volume(mesh).unwrap();
    assert!(volume > 1.0 / 3.0 + 0.01 && volume < 0.4, "{volume}");
}

#[test]
fn a_pyramid_on_a_curved_wall_is_curved_and_certified() {
    let pyramid = one_pyramid();
    let columns = vec![vec![0, 4], vec![1], vec![2], vec![3]];
    let curved = curve_mesh_3d(&pyramid, &columns, &Bulge, &p2()).unwrap();
    let mesh = &curved.mesh;
    let cell = mesh.cells.get(0);
    // the wall edges 0-1 and 2-3 bow down, the base's centre follows (Coons point)
    assert_eq!(mesh.nodes[cell.nodes[5] as usize], [0.5, 0.0, -0.1]);
    assert_eq!(mesh.nodes[cell.nodes[10] as usize], [0.5, 1.0, -0.1]);
    assert_eq!(mesh.nodes[cell.nodes[13] as usize], [0.5, 0.5, -0.1]);
    let v = check_mesh(mesh, &CertifyParams::default()).unwrap();
    assert!(
        v.invalid_cells.is_empty() && v.undecided.is_empty() && v.min_scaled_jacobian > 0.0,
        "{v:?}"
    );
    // the bulge adds to the straight pyramid's third
    let volume = integrate_volume(mesh).unwrap();
    assert!(volume > 1.0 / 3.0 + 0.01, "{volume}");
}

/// A unit-square pyramid in layer 0 on wall facet 0 (its apex in layer 1).
fn one_pyramid() -> Mesh {
    let mut pyramid = Mesh::new(Dim::Three, 1);
    pyramid.nodes = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.5, 0.5, 1.0],
    ];
    pyramid
        .cells
        .push(CellType::new(Shape::Pyramid, 1), &[0, 1, 2, 3, 4]);
    pyramid.cell_layer = vec![0];
    pyramid.cell_pipe = vec![0];
    // the base is wall facet 0 (facing out of the cell)
    pyramid.patches = vec![mesh_model::Patch {
        name: "wall".into(),
        role: Role::Wall,
    }];
    pyramid
        .boundary
        .push(CellType::new(Shape::Quad, 1), &[0, 3, 2, 1]);
    pyramid.boundary_patch = vec![0];
    pyramid
}
