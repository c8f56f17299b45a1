//! Writing a ~100k-cell mesh (a P2 annulus of quadrilaterals and triangles, built in memory)
//! to `.msh`, `.vtu` and `.su2`, into memory and into a file (atomic write included), and a
//! 267k-cell P3 annulus (116 MB of `.msh`: large enough for the file to be synced behind the
//! writer) into memory and into a file over an existing one, on rayon's default pool (all
//! cores; `RAYON_NUM_THREADS=1` for one).
//!
//! Run: `cargo bench -p mesh-io --features testkit --bench write`.
// `criterion_group!` generates an undocumented public function.
#![allow(missing_docs)]

use std::hint::black_box;

use std::path::Path;

use criterion::measurement::WallTime;
use criterion::{BenchmarkGroup, Criterion, criterion_group, criterion_main};
use mesh_io::testkit::{AnnulusParams, annulus};
use mesh_model::Mesh;

fn big_mesh() -> Mesh {
    // 80 × 1000 cells, every third cut into two triangles: 106 667 cells.
    annulus(&AnnulusParams {
        order: 2,
        radial_cells: 80,
        angular_cells: 1000,
        inner_radius: 1.0,
        outer_radius: 30.0,
        triangle_mask: vec![true, false, false],
    })
}

fn writers(c: &mut Criterion) {
    let mesh = big_mesh();
    let dir = tempfile::tempdir().expect("temporary directory");
    let mut g = c.benchmark_group("write_100k_p2");
    g.sample_size(10);
    msh_to_memory(&mut g, &mesh, 64 << 20);
    g.bench_function("vtu_to_memory", |b| {
        b.iter(|| {
            let mut out = Vec::with_capacity(64 << 20);
            mesh_io::vtu::write_to(&mut out, black_box(&mesh), "m.vtu".as_ref()).unwrap();
            out.len()
        })
    });
    g.bench_function("su2_to_memory", |b| {
        b.iter(|| {
            let mut out = Vec::with_capacity(16 << 20);
            mesh_io::su2::write_to(&mut out, black_box(&mesh), "m.su2".as_ref()).unwrap();
            out.len()
        })
    });
    let msh = dir.path().join("m.msh");
    msh_file(&mut g, &mesh, &msh);
    let vtu = dir.path().join("m.vtu");
    g.bench_function("vtu_file", |b| {
        b.iter(|| mesh_io::write(&vtu, black_box(&mesh)).unwrap())
    });
    g.bench_function("msh_read", |b| {
        b.iter(|| mesh_io::read_msh(&msh).unwrap().cells.len())
    });
    g.finish();
}

/// The P3 `.msh` of 266 667 cells, into memory and into a file that replaces the last one
/// (the final sync and the rename included, as in a run of `cargo xtask mesh`).
fn large_p3(c: &mut Criterion) {
    let mesh = annulus(&AnnulusParams {
        order: 3,
        radial_cells: 200,
        angular_cells: 1000,
        inner_radius: 1.0,
        outer_radius: 30.0,
        triangle_mask: vec![true, false, false],
    });
    let dir = tempfile::tempdir().expect("temporary directory");
    let mut g = c.benchmark_group("write_267k_p3");
    g.sample_size(10);
    msh_to_memory(&mut g, &mesh, 128 << 20);
    msh_file(&mut g, &mesh, &dir.path().join("m.msh"));
    g.finish();
}

/// `msh_to_memory`: `mesh` as `.msh` into a `Vec` of `capacity` bytes.
fn msh_to_memory(g: &mut BenchmarkGroup<'_, WallTime>, mesh: &Mesh, capacity: usize) {
    g.bench_function("msh_to_memory", |b| {
        b.iter(|| {
            let mut out = Vec::with_capacity(capacity);
            mesh_io::msh::write_to(&mut out, black_box(mesh), "m.msh".as_ref()).unwrap();
            out.len()
        })
    });
}

/// `msh_file`: `mesh` written to `path` atomically, over the file written before.
fn msh_file(g: &mut BenchmarkGroup<'_, WallTime>, mesh: &Mesh, path: &Path) {
    g.bench_function("msh_file", |b| {
        b.iter(|| mesh_io::write(path, black_box(mesh)).unwrap())
    });
}

criterion_group!(benches, writers, large_p3);
criterion_main!(benches);
