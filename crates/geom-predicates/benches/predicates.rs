//! The hot predicates on pseudo-random inputs: orient2d/orient3d, segment_meet,
//! point_segment_distance, point_in_loop on a 1000-point loop, the sort-and-sweep on 2000
//! segment boxes and k-d tree nearest queries. Run: `cargo bench -p geom-predicates`.
//!
//! Measured (release, `-- --quick`, the 2-core development machine under load), per 1000
//! calls: orient2d 1.6 µs (5.3 µs on near-collinear triples), orient3d 4.6 µs, segment_meet
//! 9.4 µs, point_segment_distance 4.0 µs; point_in_loop on a 1000-point loop 0.82 µs;
//! sort-and-sweep over 2000 small random boxes 90 µs; 1000 k-d tree nearest queries among
//! 2000 points 108 µs.

// `criterion_group!` generates an undocumented public function.
#![allow(missing_docs)]

use criterion::{Criterion, criterion_group, criterion_main};
use geom_predicates::{
    Aabb, PointTree, SegmentMeet, for_each_overlapping_pair, orient2d, orient3d, point_in_loop,
    point_segment_distance, segment_meet,
};
use std::hint::black_box;

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

fn points2(n: usize) -> Vec<[f64; 2]> {
    randoms(2 * n).chunks(2).map(|c| [c[0], c[1]]).collect()
}

/// The sum of `f(i)` over a thousand calls, so that no call is optimised away.
fn sum1000(f: impl Fn(usize) -> f64) -> f64 {
    (0..1000).map(f).sum()
}

fn predicates(c: &mut Criterion) {
    let p = points2(3000);
    c.bench_function("orient2d x1000", |b| {
        b.iter(|| sum1000(|i| orient2d(p[i], p[i + 1], p[i + 2])))
    });
    // collinear triples force the exact stages
    let line: Vec<[f64; 2]> = (0..1002)
        .map(|i| [0.1 * i as f64, 0.3 * i as f64])
        .collect();
    c.bench_function("orient2d collinear x1000", |b| {
        b.iter(|| sum1000(|i| orient2d(line[i], line[i + 1], line[i + 2])))
    });
    let q: Vec<[f64; 3]> = randoms(3 * 1004)
        .chunks(3)
        .map(|c| [c[0], c[1], c[2]])
        .collect();
    c.bench_function("orient3d x1000", |b| {
        b.iter(|| sum1000(|i| orient3d(q[i], q[i + 1], q[i + 2], q[i + 3])))
    });
    c.bench_function("segment_meet x1000", |b| {
        b.iter(|| {
            (0..1000)
                .filter(|&i| {
                    segment_meet(p[i], p[i + 1], p[i + 2], p[i + 3]) != SegmentMeet::Disjoint
                })
                .count()
        })
    });
    c.bench_function("point_segment_distance x1000", |b| {
        b.iter(|| sum1000(|i| point_segment_distance(p[i], p[i + 1], p[i + 2])))
    });
    let circle: Vec<[f64; 2]> = (0..1000)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / 1000.0;
            [a.cos(), a.sin()]
        })
        .collect();
    c.bench_function("point_in_loop 1000-point loop", |b| {
        b.iter(|| point_in_loop(black_box([0.3, 0.2]), &circle))
    });
    let boxes: Vec<Aabb<2>> = (0..2000)
        .map(|i| Aabb::of_segment(p[i], [p[i][0] + 0.01, p[i][1] + 0.01], 0.0))
        .collect();
    c.bench_function("sort-and-sweep 2000 boxes", |b| {
        b.iter(|| {
            let mut n = 0usize;
            for_each_overlapping_pair(black_box(&boxes), |_, _| n += 1);
            n
        })
    });
    let tree = PointTree::new(&p[..2000]);
    c.bench_function("kd-tree nearest x1000 (2000 points)", |b| {
        b.iter(|| {
            (2000..3000)
                .map(|i| tree.nearest(p[i]).map_or(0, |(j, _)| j))
                .sum::<usize>()
        })
    });
}

criterion_group!(benches, predicates);
criterion_main!(benches);
