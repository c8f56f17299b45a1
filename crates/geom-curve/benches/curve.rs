//! Curve construction and queries on the 30P30N main element (644 points), and the loop
//! checks on 1000-point loops. Run: `cargo bench -p geom-curve`.
//!
//! Measured (release, the 2-core development machine): construction 0.28 ms; point +
//! curvature 32 ns per call; `t_at_arc_length` 0.25 µs; `closest_point` 4.6 µs (half near,
//! half 3 chords away); `validate_loop` on a 1000-point circle 27 µs; `check_loops_disjoint`
//! on the three 30P30N elements 34 µs.

// `criterion_group!` generates an undocumented public function.
#![allow(missing_docs)]

use criterion::{Criterion, criterion_group, criterion_main};
use geom_curve::loops::{check_loops_disjoint, validate_loop};
use geom_curve::{ClosedCurve, CurveParams, LoopCheckParams, Point2, circle_points};
use std::hint::black_box;

use testkit::fixtures::selig as load;

fn curve(c: &mut Criterion) {
    let main = load("30p30n/main.dat");
    let params = CurveParams::default();
    c.bench_function("construct 30p30n main (644 points)", |b| {
        b.iter(|| ClosedCurve::new(black_box(&main), &params).expect("valid"))
    });
    let curve = ClosedCurve::new(&main, &params).expect("valid");
    let n = curve.segment_count() as f64;
    c.bench_function("evaluate point+curvature x1000", |b| {
        b.iter(|| {
            let mut sum = 0.0;
            for j in 0..1000 {
                let t = n * f64::from(j) / 1000.0;
                sum += curve.point(t).x + curve.curvature(t);
            }
            sum
        })
    });
    let total = curve.total_length();
    c.bench_function("t_at_arc_length x1000", |b| {
        b.iter(|| {
            let mut sum = 0.0;
            for j in 0..1000 {
                sum += curve.t_at_arc_length(total * f64::from(j) / 1000.0);
            }
            sum
        })
    });
    c.bench_function("closest_point x100 (near and far)", |b| {
        b.iter(|| {
            let mut sum = 0.0;
            for j in 0..100 {
                let angle = std::f64::consts::TAU * f64::from(j) / 100.0;
                let radius = if j % 2 == 0 { 0.05 } else { 3.0 };
                let p = Point2::new(0.5 + radius * angle.cos(), radius * angle.sin());
                sum += curve.closest_point(black_box(p)).2;
            }
            sum
        })
    });
}

fn loop_checks(c: &mut Criterion) {
    let circle = circle_points(Point2::origin(), 1.0, 1000).expect("valid");
    c.bench_function("validate_loop circle 1000 points", |b| {
        b.iter(|| validate_loop(black_box(&circle), &LoopCheckParams::default()))
    });
    let elements = [
        load("30p30n/slat.dat"),
        load("30p30n/main.dat"),
        load("30p30n/flap.dat"),
    ];
    c.bench_function("check_loops_disjoint 30p30n", |b| {
        b.iter(|| check_loops_disjoint(black_box(&elements)))
    });
}

criterion_group!(benches, curve, loop_checks);
criterion_main!(benches);
