//! Benchmarks of the certified check: 100 000 mildly curved P3 triangles (and P2 quads),
//! certified one by one as the curving stage does; 10 000 mildly curved prisms (P1, P2),
//! linear pyramids and P2 tets; the areas of 100 000 P3 quadrilaterals and triangles by
//! quadrature (`cell_area`, the independent check of the report's `area`); `check_mesh`
//! and `integrate_area` of a 120 000-cell P3 annulus. Results in `benches/RESULTS.md`.

// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use criterion::{Criterion, criterion_group, criterion_main};
use jacobian_check::{
    Certificate, CertifyParams, cell_area, certify_cell, check_mesh, integrate_area,
    reference_nodes, sampled_check,
};
use mesh_model::{CellType, Shape};
use std::hint::black_box;

/// `count` cells of type `ty` in dimension `D`: the reference cell scaled, shifted, and with
/// every non-corner node moved by up to `amplitude` (relative to the cell size; 0.02 or 0.05
/// in the benches), the corners by `corner_share` of it, in pseudo-random directions drawn
/// from `seed`.
fn curved_cells<const D: usize>(
    ty: CellType,
    count: usize,
    amplitude: f64,
    corner_share: f64,
    seed: u64,
) -> Vec<Vec<[f64; D]>> {
    let reference = reference_nodes(ty).unwrap();
    let mut state = seed;
    let mut unit = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    (0..count)
        .map(|c| {
            let size = 0.01 * (1.0 + 0.5 * unit());
            // cells side by side on a grid of 1000 (2D) or 100 (3D) per row
            let row: usize = if D == 2 { 1000 } else { 100 };
            let origin: [f64; D] =
                std::array::from_fn(|d| (c / row.pow(d as u32) % row) as f64 * 0.01);
            reference
                .iter()
                .enumerate()
                .map(|(i, x)| {
                    let bump = if i < ty.shape.corners() {
                        corner_share * amplitude
                    } else {
                        amplitude
                    };
                    std::array::from_fn(|d| origin[d] + size * (x[d] + bump * unit()))
                })
                .collect()
        })
        .collect()
}

/// Prints how `cells` certify, then benches certifying them all.
fn bench_certify<const D: usize>(
    group: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    ty: CellType,
    name: &str,
    cells: &[Vec<[f64; D]>],
    params: &CertifyParams,
) {
    let mut tally = [0usize; 3];
    for n in cells {
        tally[match certify_cell(ty, n, params).unwrap() {
            Certificate::Valid { .. } => 0,
            Certificate::Invalid { .. } => 1,
            Certificate::Undecided => 2,
        }] += 1;
    }
    println!("{name}: valid, invalid, undecided = {tally:?}");
    group.bench_function(name, |b| {
        b.iter(|| {
            let valid = cells
                .iter()
                .filter(|n| certify_cell(ty, n, params).unwrap().is_valid())
                .count();
            black_box(valid)
        })
    });
}

const SEED_2D: u64 = 0x9E37_79B9_7F4A_7C15;
const SEED_3D: u64 = 0x2545_F491_4F6C_DD1D;

fn certify_100k(c: &mut Criterion) {
    let params = CertifyParams::default();
    let mut group = c.benchmark_group("certify");
    group.sample_size(10);
    for (ty, name) in [
        (CellType::new(Shape::Tri, 3), "100k_p3_triangles"),
        (CellType::new(Shape::Quad, 2), "100k_p2_quads"),
    ] {
        let cells = curved_cells::<2>(ty, 100_000, 0.02, 0.0, SEED_2D);
        bench_certify(&mut group, ty, name, &cells, &params);
    }
    // The dissertation's check: 861 sample points per triangle (41 per edge), on 10k cells.
    let ty = CellType::new(Shape::Tri, 3);
    let cells = curved_cells::<2>(ty, 10_000, 0.02, 0.0, SEED_2D);
    group.bench_function("10k_p3_triangles_sampled_861_points", |b| {
        b.iter(|| {
            let positive = cells
                .iter()
                .filter(|n| sampled_check(ty, n, 41).unwrap().all_positive())
                .count();
            black_box(positive)
        })
    });
    group.finish();
}

/// The certificates of the 3D types added for the 3D curving: prisms and linear pyramids.
fn certify_10k_3d(c: &mut Criterion) {
    let params = CertifyParams::default();
    let mut group = c.benchmark_group("certify3d");
    group.sample_size(10);
    for (ty, name) in [
        (CellType::new(Shape::Prism, 1), "10k_p1_prisms"),
        (CellType::new(Shape::Prism, 2), "10k_p2_prisms"),
        (CellType::new(Shape::Pyramid, 1), "10k_p1_pyramids"),
        (CellType::new(Shape::Tet, 2), "10k_p2_tets"),
    ] {
        let cells = curved_cells::<3>(ty, 10_000, 0.05, 0.2, SEED_3D);
        bench_certify(&mut group, ty, name, &cells, &params);
    }
    group.finish();
}

/// The area of 100k mildly curved P3 cells, one by one (the report's `area` at 1M cells).
fn area_100k(c: &mut Criterion) {
    let mut group = c.benchmark_group("area");
    group.sample_size(10);
    for (ty, name) in [
        (CellType::new(Shape::Quad, 3), "100k_p3_quads"),
        (CellType::new(Shape::Tri, 3), "100k_p3_triangles"),
    ] {
        let cells = curved_cells::<2>(ty, 100_000, 0.02, 0.0, SEED_2D);
        group.bench_function(name, |b| {
            b.iter(|| {
                let area: f64 = cells.iter().map(|n| cell_area(ty, n).unwrap()).sum();
                black_box(area)
            })
        });
    }
    group.finish();
}

/// What the report's certification of a curved 2D mesh costs: `check_mesh` (which also sums
/// the cells' areas from their certificates, `MeshValidity::measure`) and `integrate_area`
/// (the same area by quadrature, the independent check the report no longer runs), on an
/// annulus of 120 000 P3 cells (a third of the quadrilaterals cut into triangles; every cell
/// curved, so none takes the straight-sided shortcut), on the threads rayon is given.
fn mesh_area(c: &mut Criterion) {
    let mesh = mesh_io::testkit::annulus(&mesh_io::testkit::AnnulusParams {
        order: 3,
        radial_cells: 10,
        angular_cells: 9000,
        inner_radius: 1.0,
        outer_radius: 2.0,
        triangle_mask: vec![false, false, true],
    });
    let mut group = c.benchmark_group("mesh_area");
    group.sample_size(10);
    let params = CertifyParams::default();
    group.bench_function("check_mesh_120k_p3", |b| {
        b.iter(|| black_box(check_mesh(&mesh, &params).unwrap()))
    });
    group.bench_function("integrate_area_120k_p3", |b| {
        b.iter(|| black_box(integrate_area(&mesh).unwrap()))
    });
    group.finish();
}

criterion_group!(benches, certify_100k, certify_10k_3d, area_100k, mesh_area);
criterion_main!(benches);
