//! Criterion bench of the two cuts on a layered cube-sphere with merged children.

// criterion_group! generates an undocumented public function.
#![allow(missing_docs)]

use criterion::{Criterion, criterion_group, criterion_main};

use testkit::layered as fixture;
use topo_cut::smooth::{Freedom, smooth_worst_tets};

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
        c.bench_function(
            &format!("cut_to_prisms/{name}/{}", poly.cell_count()),
            |b| b.iter(|| topo_cut::cut_to_prisms(&poly, &[]).expect("cut")),
        );
    }
    // the stages of cut_to_tets, to see where its time goes (improve is now only the fallback
    // when a piece stays inverted)
    let mut spec = fixture::Spec::new(16, false, 20);
    spec.merge = fixture::Merge::Shrink(1.3);
    let poly = fixture::poly(&spec);
    c.bench_function("stage/validate", |b| b.iter(|| poly.validate()));
    c.bench_function("stage/sweep_ranks", |b| {
        b.iter(|| topo_cut::order::sweep_ranks(&poly))
    });
    let ranks = topo_cut::order::sweep_ranks(&poly);
    c.bench_function("stage/improve", |b| {
        b.iter(|| {
            let mut rank = ranks.clone();
            topo_cut::improve::improve(&poly, &mut rank, 150.0, 4);
            rank
        })
    });
    c.bench_function("stage/refine", |b| {
        b.iter(|| {
            let mut cut = topo_cut::refine::Cut::from_ranks(&poly, &ranks);
            topo_cut::refine::refine(&poly, &mut cut, 150.0, 8, 1);
            topo_cut::refine::refine(&poly, &mut cut, 160.0, 8, 3);
            cut
        })
    });
    // the smoothing of the tetrahedral cut's worst tetrahedra (walls fixed), to a target
    // under which the cut leaves some
    let tets = topo_cut::cut_to_tets(&poly).expect("cut");
    let mut freedom = vec![Freedom::Free; tets.nodes.len()];
    for f in tets.boundary.iter() {
        for &v in f.corners() {
            freedom[v as usize] = Freedom::Fixed;
        }
    }
    let target = 145.0;
    let once = smooth_worst_tets(&mut tets.clone(), &freedom, target);
    c.bench_function(
        &format!("smooth_worst_tets/{}_over_{target}", once.over_before),
        |b| {
            b.iter(|| {
                let mut mesh = tets.clone();
                smooth_worst_tets(&mut mesh, &freedom, target)
            })
        },
    );
}

criterion_group!(benches, bench);
criterion_main!(benches);
