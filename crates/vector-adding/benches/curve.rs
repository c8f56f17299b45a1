//! Criterion benches of the curving on two built-in cases, NACA0012 and the 30P30N at its
//! first height of 5e-6 (mixed quadrilaterals and triangles, the default parameters):
//! `curve_mesh` at P2 and P3, `curve_mesh` followed by `jacobian_check::check_mesh` at P3,
//! and, for comparison, `afsf2d::grow_mesh` of the same linear mesh. Every linear mesh is
//! grown once, outside the timed loops. Figures: `benches/RESULTS.md`.

// criterion_group! generates an undocumented public function
#![allow(missing_docs)]

use criterion::{Criterion, criterion_group, criterion_main};
use jacobian_check::CertifyParams;
use test_cases::{Grown, grow, mesher_input, real_case};
use vector_adding::{Curved, CurvingParams};

fn curve(g: &Grown, order: u8) -> Curved {
    let params = CurvingParams {
        order,
        ..CurvingParams::default()
    };
    g.curve(&params).expect("the built-in cases curve")
}

fn curving(c: &mut Criterion) {
    for name in ["naca0012", "30p30n"] {
        let case = real_case(name);
        let g = grow(&case);
        let (loops, afsf) = mesher_input(&case);
        for order in [2, 3] {
            let curved = curve(&g, order);
            let phases: Vec<String> = curved
                .stats
                .timings_s
                .iter()
                .map(|(phase, s)| format!("{phase} {:.2} ms", s * 1e3))
                .collect();
            eprintln!(
                "{name} P{order}: {} cells, {} nodes, curved-edge fraction {:.4}; one run: {}",
                curved.mesh.cells.len(),
                curved.mesh.nodes.len(),
                curved.stats.curved_edge_fraction,
                phases.join(", ")
            );
        }
        let mut group = c.benchmark_group(name);
        group.sample_size(10);
        group.bench_function("grow_mesh (linear, for comparison)", |b| {
            b.iter(|| afsf2d::grow_mesh(&loops, &afsf).expect("the built-in cases mesh"))
        });
        for order in [2, 3] {
            group.bench_function(format!("curve_mesh P{order}"), |b| {
                b.iter(|| curve(&g, order))
            });
        }
        group.bench_function("curve_mesh + check_mesh P3", |b| {
            b.iter(|| {
                let curved = curve(&g, 3);
                let v = jacobian_check::check_mesh(&curved.mesh, &CertifyParams::default())
                    .expect("checkable");
                assert!(v.invalid_cells.is_empty() && v.undecided.is_empty());
                v
            })
        });
        group.finish();
    }
}

criterion_group!(benches, curving);
criterion_main!(benches);
