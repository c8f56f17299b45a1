//! Criterion bench of the two cuts on a layered cube-sphere with merged children.

// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use criterion::{Criterion, criterion_group, criterion_main};

use testkit::layered as fixture;

fn bench(c: &mut Criterion) {
    for quads in [false, true] {
        let mut spec = fixture::Spec::new(16, quads, 20);
        spec.merge = fixture::Merge::Shrink(0.65 * 2.0);
        let poly = fixture::poly(&spec);
        let name = if quads { "hex" } else { "prism" };
        c.bench_function(&format!("cut_to_tets/{name}/{}", poly.cell_count()), |b| {
            b.iter(|| topo_cut::cut_to_tets(&poly).expect("cut"))
        });
        c.bench_function(&format!("cut_to_mixed/{name}/{}", poly.cell_count()), |b| {
            b.iter(|| topo_cut::cut_to_mixed(&poly).expect("cut"))
        });
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
