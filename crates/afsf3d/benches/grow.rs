//! Growth of 30 layers from a sphere (1 280 triangles) and a cube (6×8×8 quads), and of 15
//! layers from the step (480 quads) thick enough to merge children in layer 13.

// criterion_group! generates an undocumented public function
#![allow(missing_docs)]

use afsf3d::{LayerParams, grow_layers};
use criterion::{Criterion, criterion_group, criterion_main};
use geom_surface::Surface;

fn bench(c: &mut Criterion) {
    let params = LayerParams::default();
    let mut g = c.benchmark_group("grow_layers");
    g.sample_size(10);
    let sphere = Surface::sphere(1.0, 3);
    g.bench_function("sphere_30_layers", |b| {
        b.iter(|| grow_layers(&sphere, &params).expect("grows"))
    });
    let cube = Surface::cube(1.0, 8, false);
    g.bench_function("cube_30_layers", |b| {
        b.iter(|| grow_layers(&cube, &params).expect("grows"))
    });
    let step = Surface::step(1);
    let merging = LayerParams {
        first_height: 3e-3,
        layers: 15,
        ..LayerParams::default()
    };
    g.bench_function("step_15_layers_merging", |b| {
        b.iter(|| grow_layers(&step, &merging).expect("grows"))
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
