//! How long a 2000 × 1500 px picture of a 100k-cell mesh takes (annulus of 50k quads with
//! layers and 50k triangles), whole and zoomed, edges only and coloured, PNG and SVG.
//!
//! Measured on the project's 2-core machine (`cargo bench -p mesh-draw`, bench profile):
//! PNG whole, edges only 133 ms; PNG whole, by layer 226 ms; PNG zoomed, by max angle 29 ms;
//! SVG whole, edges only 52 ms; SVG whole, by layer 119 ms (7.8 MB of SVG).

#[path = "../tests/common/mod.rs"]
mod common;

use criterion::Criterion;
use mesh_draw::{ColourBy, DrawParams, render_png, render_svg, view_around};

fn big_mesh() -> mesh_model::Mesh {
    common::annulus(&common::Annulus {
        around: 625,
        quad_rings: 80,
        tri_rings: 40,
        order: 1,
        jitter: 0.2,
    })
}

fn pictures(c: &mut Criterion) {
    let mesh = big_mesh();
    assert_eq!(mesh.cells.len(), 100_000);
    let whole = DrawParams {
        width_px: 2000,
        height_px: 1500,
        ..DrawParams::default()
    };
    let layers = DrawParams {
        colour: ColourBy::Layer,
        ..whole.clone()
    };
    let zoom = DrawParams {
        view: Some(view_around([common::R_WALL, 0.0], 0.05)),
        colour: ColourBy::MaxAngle,
        ..whole.clone()
    };
    let mut group = c.benchmark_group("100k cells, 2000x1500");
    group.sample_size(10);
    group.bench_function("png whole, edges", |b| b.iter(|| render_png(&mesh, &whole)));
    group.bench_function("png whole, by layer", |b| {
        b.iter(|| render_png(&mesh, &layers))
    });
    group.bench_function("png zoom, by max angle", |b| {
        b.iter(|| render_png(&mesh, &zoom))
    });
    group.bench_function("svg whole, edges", |b| b.iter(|| render_svg(&mesh, &whole)));
    group.bench_function("svg whole, by layer", |b| {
        b.iter(|| render_svg(&mesh, &layers))
    });
    group.finish();
}

/// Criterion's entry point, written out (the `criterion_group!` macro makes an undocumented
/// public function, which the workspace lints refuse).
fn main() {
    let mut c = Criterion::default().configure_from_args();
    pictures(&mut c);
    c.final_summary();
}
