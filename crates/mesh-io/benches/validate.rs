//! `mesh_model::validate` (structure, orientation, conformity by the counting-sort topology),
//! as the report and the writers call it, on linear annuli of 100k and 400k quads built in
//! memory by `testkit::annulus` (kept here, beside the test meshes, rather than in mesh-model).
//!
//! Run: `cargo bench -p mesh-io --features testkit --bench validate`. Results: RESULTS.md.
// `criterion_group!` generates an undocumented public function.
#![allow(missing_docs)]

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use mesh_io::testkit::{AnnulusParams, annulus};

fn validate(c: &mut Criterion) {
    let mut g = c.benchmark_group("validate");
    g.sample_size(10);
    for (name, radial_cells, angular_cells) in [("100k_quads", 80, 1250), ("400k_quads", 160, 2500)]
    {
        let m = annulus(&AnnulusParams {
            order: 1,
            radial_cells,
            angular_cells,
            inner_radius: 1.0,
            outer_radius: 30.0,
            triangle_mask: vec![false],
        });
        assert!(mesh_model::validate(&m).is_empty(), "{name} is valid");
        g.bench_function(name, |b| {
            b.iter(|| mesh_model::validate(black_box(&m)).len())
        });
    }
    g.finish();
}

criterion_group!(benches, validate);
criterion_main!(benches);
