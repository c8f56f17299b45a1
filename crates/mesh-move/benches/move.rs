//! Criterion benches of the baseline movers on the NACA0012 built-in case (its linear mesh
//! grown once, outside the timed loops): the wall rotated by 30° about the quarter chord,
//! moved by inverse-distance weighting and by Wendland C2 radial basis functions.

// criterion_group! generates an undocumented public function
#![allow(missing_docs)]

use criterion::{Criterion, criterion_group, criterion_main};
use mesh_move::{
    IdwParams, LoopMotion, Method, Motion, RbfParams, RigidMotion, boundary_motion, move_mesh,
};

fn movers(c: &mut Criterion) {
    let mesh = test_cases::real_case("naca0012").grow().output.mesh;
    let turn = LoopMotion {
        loop_name: "naca0012".into(),
        motion: Motion::rigid(RigidMotion::rotation(-30.0, [0.25, 0.0])),
    };
    let boundary = boundary_motion(&mesh, &[turn]).expect("a valid motion");
    let mut group = c.benchmark_group("naca0012 30°");
    group.sample_size(10);
    for (name, method) in [
        ("idw", Method::Idw(IdwParams::default())),
        ("rbf wendland", Method::Rbf(RbfParams::default())),
    ] {
        group.bench_function(name, |b| {
            b.iter(|| move_mesh(&mesh, &boundary, &method).expect("moves"))
        });
    }
    group.finish();
}

criterion_group!(benches, movers);
criterion_main!(benches);
