//! The Delaunay tetrahedralisation of 100k random points in a cube (the fill's core), and the
//! whole fill (recovery, region, refinement, sliver removal) of a sphere inside a sphere 20
//! times larger, timed as tets per second. Run: `cargo bench -p tet-fill -- --quick`.

// `criterion_group!` generates an undocumented public function.
#![allow(missing_docs)]

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use std::hint::black_box;
use tet_fill::{FillInput, FillOptions, delaunay, fill};

#[allow(dead_code)]
#[path = "../tests/integration/common.rs"]
mod common;

fn bench_delaunay(c: &mut Criterion) {
    let points: Vec<[f64; 3]> = common::randoms(300_000, 0x9e37_79b9_7f4a_7c15)
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

fn bench_fill(c: &mut Criterion) {
    // an icosphere of level 4 (5120 facets) inside one of level 2, 20 times larger
    let (mut points, mut facets) = (Vec::new(), Vec::new());
    common::append(
        &mut points,
        &mut facets,
        common::icosphere([0.0; 3], 20.0, 2),
        true,
    );
    common::append(
        &mut points,
        &mut facets,
        common::icosphere([0.1, -0.05, 0.02], 1.0, 4),
        false,
    );
    let input = FillInput {
        points: &points,
        facets: &facets,
    };
    let options = FillOptions::default();
    let out = fill(&input, &options).unwrap();
    println!(
        "sphere in sphere: {} tets, {} points added, largest dihedral {:.1}°",
        out.tets.len(),
        out.points.len() - points.len(),
        out.max_dihedral_deg
    );
    let mut group = c.benchmark_group("fill");
    group.sample_size(10);
    group.throughput(Throughput::Elements(out.tets.len() as u64));
    group.bench_function("sphere level 4 in sphere level 2", |b| {
        b.iter(|| fill(black_box(&input), &options).unwrap())
    });
    group.finish();
}

criterion_group!(benches, bench_delaunay, bench_fill);
criterion_main!(benches);
