//! The measure `check_mesh` returns (`MeshValidity::measure`: the sum of the cells' areas or
//! volumes from the Bernstein coefficients their certificates start from) against the
//! independent integrals: `cell_area` / `integrate_area` (Gauss quadrature) and
//! `enclosed_area` (the boundary) in 2D, `cell_volume` / `integrate_volume` in 3D — on every
//! cell type, straight-sided, mildly curved, folded, subdivided and undecided.

use jacobian_check::{
    Certificate, CertifyParams, cell_area, cell_volume, certify_cell, check_mesh, enclosed_area,
    integrate_area, reference_nodes, shape_functions, supported_types,
};
use mesh_io::testkit::{AnnulusParams, annulus};
use mesh_model::{CellType, Dim, Mesh, polygon_area};

/// A xorshift generator of numbers in [−1, 1).
struct Noise(u64);

impl Noise {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }
}

/// A cell of type `ty` in dimension `D`: its corners the reference corners moved by up to
/// 0.15 and shifted by `offset`; the other nodes where the order-1 map of those corners
/// puts them (a straight-sided cell, bilinear or trilinear where the shape is), then moved
/// by up to `amplitude`.
fn random_cell<const D: usize>(
    ty: CellType,
    amplitude: f64,
    offset: f64,
    noise: &mut Noise,
) -> Vec<[f64; D]> {
    let reference = reference_nodes(ty).unwrap();
    let linear = CellType::new(ty.shape, 1);
    let n = ty.shape.corners();
    let corners: Vec<[f64; D]> = reference[..n]
        .iter()
        .map(|x| std::array::from_fn(|d| x[d] + offset + 0.15 * noise.next()))
        .collect();
    let mut out = corners.clone();
    for x in &reference[n..] {
        let w = shape_functions(linear, *x).unwrap();
        out.push(std::array::from_fn(|d| {
            (0..n).map(|j| w[j] * corners[j][d]).sum::<f64>() + amplitude * noise.next()
        }));
    }
    out
}

/// A mesh of the one cell `nodes` of type `ty`.
fn one_cell<const D: usize>(ty: CellType, nodes: &[[f64; D]]) -> Mesh {
    let dim = if D == 2 { Dim::Two } else { Dim::Three };
    let mut mesh = Mesh::new(dim, ty.order);
    mesh.nodes = nodes
        .iter()
        .map(|x| std::array::from_fn(|d| if d < D { x[d] } else { 0.0 }))
        .collect();
    let ids: Vec<u32> = (0..nodes.len() as u32).collect();
    mesh.cells.push(ty, &ids);
    mesh
}

#[test]
fn every_2d_cell_measures_as_its_quadrature_whatever_its_verdict() {
    let shallow = CertifyParams {
        max_depth: 0,
        ..CertifyParams::default()
    };
    let mut noise = Noise(0x9E37_79B9_7F4A_7C15);
    // how often each verdict was met (valid, invalid, undecided), and valid cells that
    // needed subdivision (undecided without it)
    let (mut tally, mut subdivided) = ([0usize; 3], 0);
    for ty in supported_types().filter(|t| t.shape.dim() == 2) {
        for amplitude in [0.0, 0.02, 0.3, 1.0] {
            for _ in 0..60 {
                let x = random_cell::<2>(ty, amplitude, 5.0, &mut noise);
                let exact = cell_area(ty, &x).unwrap();
                let mesh = one_cell(ty, &x);
                for params in [CertifyParams::default(), shallow] {
                    let v = check_mesh(&mesh, &params).unwrap();
                    assert!(
                        (v.measure - exact).abs() <= 1e-13,
                        "{ty:?} at {amplitude}: {} vs {exact}",
                        v.measure
                    );
                    tally[match certify_cell(ty, &x, &params).unwrap() {
                        Certificate::Valid { .. } => 0,
                        Certificate::Invalid { .. } => 1,
                        Certificate::Undecided => 2,
                    }] += 1;
                }
                let deep = certify_cell(ty, &x, &CertifyParams::default()).unwrap();
                let flat = certify_cell(ty, &x, &shallow).unwrap();
                if deep.is_valid() && flat == Certificate::Undecided {
                    subdivided += 1;
                }
                if amplitude == 0.0 {
                    // straight-sided: the shoelace area of its corners, exactly its map's
                    let corners = polygon_area(x[..ty.shape.corners()].iter().copied());
                    assert!((exact - corners).abs() <= 1e-13, "{ty:?}");
                }
            }
        }
    }
    eprintln!("verdicts {tally:?}, subdivided {subdivided}");
    assert!(
        tally.iter().all(|&t| t > 20) && subdivided > 20,
        "verdicts {tally:?}, subdivided {subdivided}"
    );
}

#[test]
fn every_3d_cell_measures_as_cell_volume() {
    let mut noise = Noise(0x2545_F491_4F6C_DD1D);
    for ty in supported_types().filter(|t| t.shape.dim() == 3) {
        for amplitude in [0.0, 0.05, 0.4] {
            for _ in 0..20 {
                let x = random_cell::<3>(ty, amplitude, 2.0, &mut noise);
                let exact = cell_volume(ty, &x).unwrap();
                let v = check_mesh(&one_cell(ty, &x), &CertifyParams::default()).unwrap();
                if amplitude == 0.0 {
                    // the shortcut's order-1 cell: the same volume up to rounding
                    assert!(
                        (v.measure - exact).abs() <= 1e-13,
                        "{ty:?}: {} vs {exact}",
                        v.measure
                    );
                } else {
                    // curved: the same coefficients, the same sum
                    assert_eq!(v.measure.to_bits(), exact.to_bits(), "{ty:?}");
                }
            }
        }
    }
}

#[test]
fn a_curved_mesh_measures_its_integrated_and_enclosed_area_whatever_the_threads() {
    for order in [1, 2, 3] {
        // many cells (chunks of the parallel check), triangles and quadrilaterals
        let mesh = annulus(&AnnulusParams {
            order,
            radial_cells: 3,
            angular_cells: 3000,
            inner_radius: 1.0,
            outer_radius: 2.0,
            triangle_mask: vec![true, false, false],
        });
        let cells = integrate_area(&mesh).unwrap();
        let boundary = enclosed_area(&mesh).unwrap();
        let mut first = None;
        for threads in [1, 2, 3] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let v = pool
                .install(|| check_mesh(&mesh, &CertifyParams::default()))
                .unwrap();
            let m = v.measure;
            assert_eq!(m.to_bits(), *first.get_or_insert(m.to_bits()), "P{order}");
            for (what, other) in [("cells", cells), ("boundary", boundary)] {
                assert!(
                    (m - other).abs() <= 1e-12 * other,
                    "P{order}: measure {m} vs {what} {other}"
                );
            }
        }
    }
}
