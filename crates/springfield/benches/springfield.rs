//! Criterion benches of the 2D Spring-Field solve: a ring of two moving layers over a fixed
//! circle of `N` wall nodes (the shape of one layer step of the linear mesher, at the size of
//! the 1M-cell NACA0012 case), its nodes pushed off balance, solved by
//! `solve_model_active` with one thread and with every thread; and the model's set-up
//! (per-node spring index and influence table) alone.

// criterion_group! generates an undocumented public function
#![allow(missing_docs)]

use criterion::{Criterion, criterion_group, criterion_main};
use springfield::{
    AngleSpring, ExtrusionSpring, ForceModel, NeighbourSpring, SolverParams, SpringField2d,
    SpringParams, SpringSet2d, solve_model_active,
};

/// Wall nodes around the ring.
const N: usize = 16_000;

/// Positions (wall, layer 1, layer 2, each of `N` nodes, clockwise so that the outside is on
/// the left), the moving flags, the scales and the springs.
fn ring() -> (Vec<[f64; 2]>, Vec<bool>, Vec<f64>, SpringSet2d) {
    let heights = [0.0, 0.004, 0.0092];
    let ideal = [0.0, 0.004, 0.0052];
    let mut seed = 7u64;
    let mut noise = || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 1e-3
    };
    let mut pos = Vec::with_capacity(3 * N);
    for (k, &h) in heights.iter().enumerate() {
        for i in 0..N {
            let t = -std::f64::consts::TAU * i as f64 / N as f64;
            let r = 1.0 + h;
            let (dx, dy) = if k == 0 {
                (0.0, 0.0)
            } else {
                (noise(), noise())
            };
            pos.push([r * t.cos() + dx, r * t.sin() + dy]);
        }
    }
    let at = |k: usize, i: usize| (k * N + i % N) as u32;
    let mut set = SpringSet2d::default();
    for (k, &ideal_k) in ideal.iter().enumerate().skip(1) {
        for i in 0..N {
            set.extrusion.push(ExtrusionSpring {
                lower: at(k - 1, i),
                upper: at(k, i),
                ideal_length: ideal_k,
                lower_share: 1.0 / 1.3,
            });
            set.neighbour.push(NeighbourSpring {
                left: at(k, i + N - 1),
                centre: at(k, i),
                right: at(k, i + 1),
                parent: at(k - 1, i),
                left_share: 0.5,
            });
            set.angle.push(AngleSpring {
                left: at(k - 1, i + N - 1),
                centre: at(k - 1, i),
                right: at(k - 1, i + 1),
                child: at(k, i),
                offset_rad: 0.0,
                ideal_length: ideal_k,
            });
        }
    }
    let movable: Vec<bool> = (0..3 * N).map(|g| g >= N).collect();
    let scale: Vec<f64> = (0..3 * N).map(|g| ideal[(g / N).max(1)]).collect();
    (pos, movable, scale, set)
}

fn spring_solve(c: &mut Criterion) {
    let (pos, movable, scale, set) = ring();
    let params = SpringParams::default();
    let solver = SolverParams::default();
    let solve = || {
        let mut x = pos.clone();
        let model = SpringField2d::new(&set, &params, x.len());
        solve_model_active(&mut x, &scale, &movable, &model, &solver).expect("the ring solves")
    };
    let outcome = solve();
    eprintln!(
        "ring of {N}: {} iterations, converged {}",
        outcome.iterations, outcome.converged
    );
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("a thread pool");
        c.bench_function(&format!("ring{N}_solve_{threads}_threads"), |b| {
            b.iter(|| pool.install(solve))
        });
        c.bench_function(&format!("ring{N}_model_setup_{threads}_threads"), |b| {
            b.iter(|| {
                pool.install(|| {
                    let model = SpringField2d::new(&set, &params, pos.len());
                    model.influence(pos.len())
                })
            })
        });
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10);
    targets = spring_solve
}
criterion_main!(benches);
