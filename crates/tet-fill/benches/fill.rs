//! The Delaunay tetrahedralisation of 100k random points in a cube (the fill's core), timed
//! as tets per second. Run: `cargo bench -p tet-fill -- --quick`.

// `criterion_group!` generates an undocumented public function.
#![allow(missing_docs)]

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use std::hint::black_box;
use tet_fill::delaunay;

/// A fixed pseudo-random sequence in [0, 1) (xorshift), so runs compare.
fn randoms(n: usize) -> Vec<f64> {
    let mut s = 0x9e37_79b9_7f4a_7c15u64;
    (0..n)
        .map(|_| {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 11) as f64 / (1u64 << 53) as f64
        })
        .collect()
}

fn bench_delaunay(c: &mut Criterion) {
    let points: Vec<[f64; 3]> = randoms(300_000)
        .chunks(3)
        .map(|c| [c[0], c[1], c[2]])
        .collect();
    let tets = delaunay(&points).unwrap().len();
    let mut group = c.benchmark_group("delaunay");
    group.sample_size(10);
    group.throughput(Throughput::Elements(tets as u64));
    group.bench_function("100k random points", |b| {
        b.iter(|| delaunay(black_box(&points)).unwrap())
    });
    group.finish();
}

criterion_group!(benches, bench_delaunay);
criterion_main!(benches);
