//! Boundary meshing of the 30P30N three elements (α = 165°, g = 1.3, l_extru = 5e-6,
//! δ = 0.05), curve construction included or not. Run: `cargo bench -p boundary1d`.
//! Figures are recorded in this crate's README.

// `criterion_group!` generates an undocumented public function.
#![allow(missing_docs)]

use boundary1d::{NodePlacement, SpacingParams, mesh_loops};
use criterion::{Criterion, criterion_group, criterion_main};
use geom_curve::{ClosedCurve, CurveParams};
use std::hint::black_box;

use testkit::fixtures::selig as load;

fn thirty_p_thirty_n(c: &mut Criterion) {
    let loops: Vec<_> = ["30p30n/slat.dat", "30p30n/main.dat", "30p30n/flap.dat"]
        .iter()
        .map(|name| load(name))
        .collect();
    let curves: Vec<ClosedCurve> = loops
        .iter()
        .map(|points| ClosedCurve::new(points, &CurveParams::default()).expect("valid"))
        .collect();
    for (label, medial_axis, placement) in [
        ("medial, on curve", true, NodePlacement::OnCurve),
        ("no medial, on curve", false, NodePlacement::OnCurve),
        ("medial, on polyline", true, NodePlacement::OnPolyline),
    ] {
        let params = SpacingParams {
            growth: 1.3,
            refine_angle_deg: 165.0,
            max_spacing: 0.05,
            first_height: 5e-6,
            medial_axis,
            placement,
            ..SpacingParams::default()
        };
        c.bench_function(&format!("mesh_loops 30p30n ({label})"), |b| {
            b.iter(|| mesh_loops(black_box(&curves), &params).expect("meshes"))
        });
    }
    let params = SpacingParams {
        growth: 1.3,
        refine_angle_deg: 165.0,
        max_spacing: 0.05,
        first_height: 5e-6,
        medial_axis: true,
        placement: NodePlacement::OnCurve,
        ..SpacingParams::default()
    };
    c.bench_function("curves + mesh_loops 30p30n (medial, on curve)", |b| {
        b.iter(|| {
            let curves: Vec<ClosedCurve> = loops
                .iter()
                .map(|points| ClosedCurve::new(points, &CurveParams::default()).expect("valid"))
                .collect();
            mesh_loops(&curves, &params).expect("meshes")
        })
    });
}

criterion_group!(benches, thirty_p_thirty_n);
criterion_main!(benches);
