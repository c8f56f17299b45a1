//! Criterion benches of the movers on two built-in cases (their layered linear meshes grown
//! once, outside the timed loops): the NACA0012 wall pitched by 30° about the quarter chord,
//! and the 30P30N flap turned by 10° about its leading edge, each moved by the spring mover
//! (the shape balance by Newton), the same with its shape field built once outside the loop
//! (`move_layered_in`: a prepared case's later moves), and the baselines:
//! inverse-distance weighting and radial basis functions (Wendland C2 on the
//! NACA0012, the thin-plate spline on the 30P30N, where the global Wendland system is
//! singular). Then the sensitivities at the smooth mover's result: the linearised balance
//! (one factorisation) and one design variable's response.

// criterion_group! generates an undocumented public function
#![allow(missing_docs)]

use criterion::{Criterion, criterion_group, criterion_main};
use mesh_move::{
    IdwParams, Kernel, LoopMotion, Method, Motion, RbfParams, RigidMotion, Section, ShapeField,
    SpringMoveParams, boundary_motion, move_layered, move_layered_in,
};

fn bench(c: &mut Criterion, group: &str, case: &str, motion: LoopMotion, rbf: Kernel) {
    let layered = test_cases::grow(&test_cases::real_case(case))
        .output
        .layered;
    let mesh = &layered.mesh;
    let boundary = boundary_motion(mesh, &[motion]).expect("a valid motion");
    let mut group = c.benchmark_group(group);
    group.sample_size(10);
    let rbf = RbfParams {
        kernel: rbf,
        ..RbfParams::default()
    };
    for (name, method) in [
        ("springs", Method::Springs(SpringMoveParams::default())),
        ("idw", Method::Idw(IdwParams::default())),
        ("rbf", Method::Rbf(rbf)),
    ] {
        group.bench_function(name, |b| {
            b.iter(|| move_layered(&layered, &boundary, &method).expect("moves"))
        });
    }
    let springs = Method::Springs(SpringMoveParams::default());
    let field = ShapeField::of(&layered, SpringMoveParams::default().shape).expect("a field");
    group.bench_function("springs, field given", |b| {
        b.iter(|| move_layered_in(&layered, &boundary, &springs, &field).expect("moves"))
    });
    // the sensitivities at the spring mover's balance: the boundary nodes held, the others respond
    let x = move_layered(&layered, &boundary, &springs)
        .expect("moves")
        .mesh;
    let x: Vec<[f64; 2]> = (0..x.nodes.len()).map(|i| x.xy(i as u32)).collect();
    let mut fixed = vec![false; x.len()];
    boundary
        .nodes
        .iter()
        .for_each(|&k| fixed[k as usize] = true);
    group.bench_function("sensitivities: linearise", |b| {
        b.iter(|| field.linearise(&x, &fixed).expect("stable"))
    });
    let lin = field.linearise(&x, &fixed).expect("stable");
    let d_boundary: Vec<[f64; 2]> = x.iter().map(|p| [-p[1], p[0]]).collect();
    group.bench_function("sensitivities: one variable", |b| {
        b.iter(|| lin.respond(&d_boundary))
    });
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
