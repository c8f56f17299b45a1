//! `mesh_model::validate` (structure, orientation, conformity by the counting-sort topology)
//! on structured quad grids of 100k and 400k cells, built in memory.
//!
//! Measured (2-core box, shared): 8.1 ms and 88 ms; with glibc keeping freed memory
//! (`MALLOC_MMAP_THRESHOLD_=4000000000 MALLOC_TRIM_THRESHOLD_=8000000000`) 8.3 ms and 39 ms:
//! the rest of the 400k figure is page faults of the topology's fresh large buffers, and the
//! work itself is linear (counting sort, no hashing); beyond that the 400k mesh leaves the
//! caches.
//!
//! Run: `cargo bench -p mesh-model --bench validate`.
// `criterion_group!` generates an undocumented public function.
#![allow(missing_docs)]

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use mesh_model::{CellType, Dim, Mesh, Patch, Role, Shape};

/// An `nx × ny` grid of unit quads, its outline one far-field patch.
fn grid(nx: u32, ny: u32) -> Mesh {
    let mut m = Mesh::new(Dim::Two, 1);
    let at = |i: u32, j: u32| j * (nx + 1) + i;
    for j in 0..=ny {
        for i in 0..=nx {
            m.nodes.push([f64::from(i), f64::from(j), 0.0]);
        }
    }
    let quad = CellType::new(Shape::Quad, 1);
    for j in 0..ny {
        for i in 0..nx {
            m.cells.push(
                quad,
                &[at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)],
            );
        }
    }
    let line = CellType::new(Shape::Line, 1);
    let mut outline = Vec::new();
    outline.extend((0..nx).map(|i| [at(i, 0), at(i + 1, 0)]));
    outline.extend((0..ny).map(|j| [at(nx, j), at(nx, j + 1)]));
    outline.extend((0..nx).rev().map(|i| [at(i + 1, ny), at(i, ny)]));
    outline.extend((0..ny).rev().map(|j| [at(0, j + 1), at(0, j)]));
    for f in outline {
        m.boundary.push(line, &f);
        m.boundary_patch.push(0);
    }
    m.patches.push(Patch {
        name: "farfield".into(),
        role: Role::Farfield,
    });
    m
}

fn validate(c: &mut Criterion) {
    let mut g = c.benchmark_group("validate");
    g.sample_size(10);
    for (name, nx, ny) in [("100k_quads", 400, 250), ("400k_quads", 800, 500)] {
        let m = grid(nx, ny);
        assert!(mesh_model::validate(&m).is_empty(), "{name} is valid");
        g.bench_function(name, |b| {
            b.iter(|| mesh_model::validate(black_box(&m)).len())
        });
    }
    g.finish();
}

criterion_group!(benches, validate);
criterion_main!(benches);
