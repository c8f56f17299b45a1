//! Criterion benches of the baseline movers on two built-in cases (their linear meshes grown
//! once, outside the timed loops): the NACA0012 wall pitched by 30° about the quarter chord,
//! and the 30P30N flap turned by 10° about its leading edge, each moved by inverse-distance
//! weighting and by radial basis functions (Wendland C2 on the NACA0012, the thin-plate spline
//! on the 30P30N, where the global Wendland system is singular).

// criterion_group! generates an undocumented public function
#![allow(missing_docs)]

use criterion::{Criterion, criterion_group, criterion_main};
use mesh_move::{
    IdwParams, Kernel, LoopMotion, Method, Motion, RbfParams, RigidMotion, Section,
    boundary_motion, move_mesh,
};

fn bench(c: &mut Criterion, group: &str, case: &str, motion: LoopMotion, rbf: Kernel) {
    let mesh = test_cases::grow(&test_cases::real_case(case))
        .output
        .layered
        .mesh;
    let boundary = boundary_motion(&mesh, &[motion]).expect("a valid motion");
    let mut group = c.benchmark_group(group);
    group.sample_size(10);
    let rbf = RbfParams {
        kernel: rbf,
        ..RbfParams::default()
    };
    for (name, method) in [
        ("idw", Method::Idw(IdwParams::default())),
        ("rbf", Method::Rbf(rbf)),
    ] {
        group.bench_function(name, |b| {
            b.iter(|| move_mesh(&mesh, &boundary, &method).expect("moves"))
        });
    }
    group.finish();
}

fn movers(c: &mut Criterion) {
    let pitch = LoopMotion {
        loop_name: "naca0012".into(),
        motion: Motion::rigid(RigidMotion::rotation(-30.0, [0.25, 0.0])),
    };
    bench(
        c,
        "naca0012 pitch 30°",
        "naca0012",
        pitch,
        Kernel::WendlandC2,
    );
    let flap = test_cases::real_case("30p30n")
        .loops
        .into_iter()
        .find(|l| l.name == "flap")
        .expect("a flap")
        .points;
    let hinge = flap[Section::of_loop(&flap).expect("a chord").leading_edge];
    let deflect = LoopMotion {
        loop_name: "flap".into(),
        motion: Motion::rigid(RigidMotion::rotation(-10.0, hinge)),
    };
    bench(
        c,
        "30p30n flap 10°",
        "30p30n",
        deflect,
        Kernel::ThinPlateSpline,
    );
}

criterion_group!(benches, movers);
criterion_main!(benches);
