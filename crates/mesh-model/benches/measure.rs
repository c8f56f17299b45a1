//! Criterion bench of `mesh_model::measure::triangle_max_angle_deg`, the largest-angle measure
//! of the fill's flips, the gap checks and the report's histogram: 100 000 triangles of a
//! fixed pseudo-random set (from thin wall-layer slivers to near-equilateral cells, at
//! coordinates up to 20). Results: `benches/RESULTS.md`.

// criterion_group! generates an undocumented public function
#![allow(missing_docs)]

use criterion::{Criterion, criterion_group, criterion_main};

/// The triangles: a fixed linear congruential sequence, so every run measures the same set.
fn triangles(n: usize) -> Vec<[[f64; 2]; 3]> {
    let mut state: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut next = move || {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..n)
        .map(|_| {
            let a = [40.0 * next() - 20.0, 40.0 * next() - 20.0];
            let size = 10f64.powf(-6.0 * next());
            let aspect = 10f64.powf(-3.0 * next());
            let (c, s) = ((6.3 * next()).cos(), (6.3 * next()).sin());
            let b = [a[0] + size * c, a[1] + size * s];
            let t = next();
            let p = [
                a[0] + t * size * c - aspect * size * s,
                a[1] + t * size * s + aspect * size * c,
            ];
            [a, b, p]
        })
        .collect()
}

fn max_angle(c: &mut Criterion) {
    let set = triangles(100_000);
    c.bench_function("triangle_max_angle_deg_100k", |b| {
        b.iter(|| {
            set.iter()
                .map(|t| mesh_model::measure::triangle_max_angle_deg(t[0], t[1], t[2]))
                .sum::<f64>()
        })
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(20);
    targets = max_angle
}
criterion_main!(benches);
