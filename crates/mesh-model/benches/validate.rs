//! Criterion bench of `mesh_model::validate` on a 2D grid of 500 × 500 quadrilaterals (every
//! other row split into triangles) with its boundary facets: the structural walk, the exact
//! orientation of every cell and the conformity of every edge, as the report runs it on a
//! finished mesh. Results: `benches/RESULTS.md`.

// criterion_group! generates an undocumented public function
#![allow(missing_docs)]

use criterion::{Criterion, criterion_group, criterion_main};
use mesh_model::{CellType, Dim, Mesh, Patch, Role, Shape};

/// The grid on the unit square, counter-clockwise cells and boundary lines.
fn grid(n: usize) -> Mesh {
    let mut m = Mesh::new(Dim::Two, 1);
    let id = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    for j in 0..=n {
        for i in 0..=n {
            m.nodes
                .push([i as f64 / n as f64, j as f64 / n as f64, 0.0]);
        }
    }
    let (tri, quad) = (CellType::new(Shape::Tri, 1), CellType::new(Shape::Quad, 1));
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            if j % 2 == 0 {
                m.cells.push(tri, &[a, b, c]);
                m.cells.push(tri, &[a, c, d]);
            } else {
                m.cells.push(quad, &[a, b, c, d]);
            }
        }
    }
    m.patches.push(Patch {
        name: "box".into(),
        role: Role::Farfield,
    });
    let line = CellType::new(Shape::Line, 1);
    let ring = (0..n)
        .map(|i| (id(i, 0), id(i + 1, 0)))
        .chain((0..n).map(|j| (id(n, j), id(n, j + 1))))
        .chain((0..n).map(|i| (id(n - i, n), id(n - i - 1, n))))
        .chain((0..n).map(|j| (id(0, n - j), id(0, n - j - 1))));
    for (a, b) in ring {
        m.boundary.push(line, &[a, b]);
        m.boundary_patch.push(0);
    }
    m
}

fn validate(c: &mut Criterion) {
    let mesh = grid(500);
    assert!(mesh_model::validate(&mesh).is_empty());
    c.bench_function("validate_grid_375k_cells", |b| {
        b.iter(|| mesh_model::validate(std::hint::black_box(&mesh)))
    });
}

criterion_group!(benches, validate);
criterion_main!(benches);
