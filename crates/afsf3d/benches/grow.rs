//! Growth of 30 layers from a sphere (1 280 triangles) and a cube (6×8×8 quads), of 15
//! layers from the step (480 quads) thick enough to merge children in layer 13, and of 15
//! layers from a torus (radii 1 and 0.3, 2 400 triangles) with and without the fronts'
//! facets kept in shape (`reshape`).

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
    let torus = torus(1.0, 0.3, 60, 20);
    let stack = LayerParams {
        first_height: 2e-3,
        layers: 15,
        ..LayerParams::default()
    };
    g.bench_function("torus_15_layers_reshaped", |b| {
        b.iter(|| grow_layers(&torus, &stack).expect("grows"))
    });
    let plain = LayerParams {
        reshape: false,
        ..stack
    };
    g.bench_function("torus_15_layers_plain", |b| {
        b.iter(|| grow_layers(&torus, &plain).expect("grows"))
    });
    g.finish();
}

/// A torus about z (radii `big` and `small`), `n` × `m` quads of its angles each split into
/// two triangles, counter-clockwise seen from outside.
fn torus(big: f64, small: f64, n: u32, m: u32) -> Surface {
    let tau = std::f64::consts::TAU;
    let nodes = (0..n)
        .flat_map(|i| (0..m).map(move |j| (i, j)))
        .map(|(i, j)| {
            let (u, v) = (
                tau * f64::from(i) / f64::from(n),
                tau * f64::from(j) / f64::from(m),
            );
            let r = big + small * v.cos();
            [r * u.cos(), r * u.sin(), small * v.sin()]
        })
        .collect();
    let at = |i: u32, j: u32| (i % n) * m + j % m;
    let tris: Vec<[u32; 3]> = (0..n)
        .flat_map(|i| (0..m).map(move |j| (i, j)))
        .flat_map(|(i, j)| {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            [[a, b, c], [a, c, d]]
        })
        .collect();
    Surface::from_triangles(nodes, &tris)
}

criterion_group!(benches, bench);
criterion_main!(benches);
