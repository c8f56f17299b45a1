//! Criterion benches of the linear mesher: NACA0012 in a 20-chord far field at about 30k
//! triangles (after cutting quads), first height 5e-5, growth 1.3: the whole mesher, and its
//! fill stage alone (the fill's own timer, `AfsfStats::timings.fill`), and the obtuse-angle
//! histogram of the mesh it makes (`max_angle_histogram`, the report's figure); and in a far
//! field of 2000 nodes, the fill, the closing test (with the planning) and the verification
//! (their broad phase, docs/performance.md, "Plan, closing and verification").
//!
//! Measured (release, one thread, this machine): see docs/afsf.md.

// criterion_group! generates an undocumented public function
#![allow(missing_docs)]

use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};

#[path = "../tests/integration/common/mod.rs"]
mod common;

fn naca0012_30k(c: &mut Criterion) {
    let loops = common::naca0012(0.005);
    let params = afsf2d::AfsfParams {
        first_height: 5e-5,
        growth: 1.3,
        ..afsf2d::AfsfParams::default()
    };
    let out = afsf2d::grow_mesh(&loops, &params).expect("NACA0012 meshes");
    let q = afsf2d::max_angle_histogram(&out.layered.mesh);
    eprintln!("{}", common::summary("naca0012 bench case", &out, &q));
    c.bench_function("naca0012_30k_triangles", |b| {
        b.iter(|| afsf2d::grow_mesh(&loops, &params).expect("NACA0012 meshes"))
    });
    // a fill of some 20k triangles: the same wall in a far field of 2000 nodes
    let mut far = loops.clone();
    far[1] = common::circle(
        [0.5, 0.0],
        20.0,
        2000,
        mesh_model::Role::Farfield,
        "farfield",
    );
    let big = afsf2d::grow_mesh(&far, &params).expect("NACA0012 meshes");
    eprintln!("far-field fill: {} triangles", big.stats.fill_triangles);
    bench_fill(c, "naca0012_far2000_fill", &far, &params);
    // the closing test (with the planning) and the verification of every layer step: their
    // broad phase over the fronts of the far-field circle
    bench_timer(c, "naca0012_far2000_closing", &far, &params, |t| {
        t.plan_and_closing
    });
    bench_timer(c, "naca0012_far2000_verify", &far, &params, |t| t.verify);
    // the building of each layer's nodes, cells and fronts from its plans
    bench_timer(c, "naca0012_far2000_build", &far, &params, |t| t.build);
    // the spring balances of every layer step (their set-up included)
    bench_timer(c, "naca0012_far2000_solve", &far, &params, |t| t.solve);
    // the report's obtuse-angle figure of that mesh (quads cut along the shorter diagonal)
    let mesh = &out.layered.mesh;
    c.bench_function("naca0012_30k_angle_histogram", |b| {
        b.iter(|| afsf2d::max_angle_histogram(mesh))
    });
    // the fill stage alone (with its peel rounds)
    bench_fill(c, "naca0012_30k_fill", &loops, &params);
}

/// The fill stage of meshing `loops`, as timed by the mesher itself.
fn bench_fill(
    c: &mut Criterion,
    name: &str,
    loops: &[afsf2d::FrontLoop],
    params: &afsf2d::AfsfParams,
) {
    bench_timer(c, name, loops, params, |t| t.fill);
}

/// A phase of meshing `loops`, as timed by the mesher itself (`phase` picks its timer).
fn bench_timer(
    c: &mut Criterion,
    name: &str,
    loops: &[afsf2d::FrontLoop],
    params: &afsf2d::AfsfParams,
    phase: fn(&afsf2d::Timings) -> f64,
) {
    c.bench_function(name, |b| {
        b.iter_custom(|iters| {
            (0..iters)
                .map(|_| {
                    let out = afsf2d::grow_mesh(loops, params).expect("NACA0012 meshes");
                    Duration::from_secs_f64(phase(&out.stats.timings))
                })
                .sum()
        })
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10);
    targets = naca0012_30k
}
criterion_main!(benches);
