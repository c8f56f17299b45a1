//! Benchmarks of the certified check: 100 000 mildly curved P3 triangles (and P2 quads),
//! certified one by one as the curving stage does. Results in `benches/RESULTS.md`.

// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use criterion::{Criterion, criterion_group, criterion_main};
use jacobian_check::{Certificate, CertifyParams, certify_cell, reference_nodes, sampled_check};
use mesh_model::{CellType, Shape};
use std::hint::black_box;

/// `count` cells of type `ty`: the reference cell scaled, shifted, and with every
/// non-corner node moved by up to `amplitude` (0.02 in the benches) (relative to the cell size) in a
/// deterministic pseudo-random direction.
fn curved_cells(ty: CellType, count: usize, amplitude: f64) -> Vec<Vec<[f64; 2]>> {
    let reference = reference_nodes(ty).unwrap();
    let mut state = 0x9E37_79B9_7F4A_7C15u64;
    let mut unit = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    (0..count)
        .map(|c| {
            let size = 0.01 * (1.0 + 0.5 * unit());
            let origin = [(c % 1000) as f64 * 0.01, (c / 1000) as f64 * 0.01];
            reference
                .iter()
                .enumerate()
                .map(|(i, x)| {
                    let bump = if i < ty.shape.corners() {
                        0.0
                    } else {
                        amplitude
                    };
                    [
                        origin[0] + size * (x[0] + bump * unit()),
                        origin[1] + size * (x[1] + bump * unit()),
                    ]
                })
                .collect()
        })
        .collect()
}

fn certify_100k(c: &mut Criterion) {
    let params = CertifyParams::default();
    let mut group = c.benchmark_group("certify");
    group.sample_size(10);
    for (ty, name) in [
        (CellType::new(Shape::Tri, 3), "100k_p3_triangles"),
        (CellType::new(Shape::Quad, 2), "100k_p2_quads"),
    ] {
        let cells = curved_cells(ty, 100_000, 0.02);
        let mut tally = [0usize; 3];
        for n in &cells {
            tally[match certify_cell(ty, n, &params).unwrap() {
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
                    .filter(|n| certify_cell(ty, n, &params).unwrap().is_valid())
                    .count();
                black_box(valid)
            })
        });
    }
    // The dissertation's check: 861 sample points per triangle (41 per edge), on 10k cells.
    let ty = CellType::new(Shape::Tri, 3);
    let cells = curved_cells(ty, 10_000, 0.02);
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

criterion_group!(benches, certify_100k);
criterion_main!(benches);
