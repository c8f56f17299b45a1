//! The mesher on two threads gives the mesh of one thread to the last bit, on fronts long
//! enough that every per-layer part with a parallel path takes it: the plan's directions
//! (8192 nodes or more in a loop), the verification (8192 cells or more, some failing) with
//! the next step's closing made beside it (and dropped when the verification fails), and the
//! solve's assembly (4096 active nodes or more).

use crate::common;

use afsf2d::{AfsfOutput, AfsfParams, FrontLoop, grow_mesh};
use common::circle;
use mesh_model::Role;

/// A wall circle of 9000 nodes, its radius jittered (so that the springs have work and some
/// cells fail), in a far-field circle just outside it (a thin annulus, so the fill is small),
/// a few layers grown in a pool of `threads` threads.
fn annulus_in_pool(threads: usize) -> AfsfOutput {
    let n = 9000;
    let wall: Vec<[f64; 2]> = (0..n)
        .map(|i| {
            let t = std::f64::consts::TAU * i as f64 / n as f64;
            let r = 1.0 + 3e-4 * ((i * 7919 % 13) as f64 - 6.0) / 6.0;
            [r * t.cos(), r * t.sin()]
        })
        .collect();
    let loops = vec![
        FrontLoop::new(wall, Role::Wall, "wall"),
        circle([0.0, 0.0], 1.006, 9000, Role::Farfield, "farfield"),
    ];
    let params = AfsfParams {
        first_height: 2e-4,
        growth: 1.3,
        max_layers: 6,
        ..AfsfParams::default()
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a thread pool");
    pool.install(|| grow_mesh(&loops, &params).expect("the annulus meshes"))
}

/// Layer steps undone and redone (a moved cell failed the verification).
fn retries(out: &AfsfOutput) -> u32 {
    out.stats.layer_stats.iter().map(|l| l.retries).sum()
}

#[test]
fn two_threads_grow_the_same_mesh_as_one() {
    let one = annulus_in_pool(1);
    let two = annulus_in_pool(2);
    let layered = one
        .layered
        .mesh
        .cell_layer
        .iter()
        .filter(|&&l| l >= 3)
        .count();
    eprintln!(
        "{} cells, {layered} above layer 3, {} iterations, {} retries, {} frozen edges",
        one.layered.mesh.cell_layer.len(),
        one.stats.iterations,
        retries(&one),
        one.stats
            .layer_stats
            .iter()
            .map(|l| l.frozen_edges)
            .sum::<usize>()
    );
    assert!(layered > 8192, "{layered} cells above layer 3");
    // a step undone: the verification found failing cells (the parallel path's list)
    assert!(retries(&one) > 0);
    assert_eq!(retries(&one), retries(&two));
    assert!(
        one.stats.iterations > 20,
        "{} iterations",
        one.stats.iterations
    );
    let bits = |o: &AfsfOutput| -> Vec<u64> {
        o.layered
            .mesh
            .nodes
            .iter()
            .flatten()
            .map(|v| v.to_bits())
            .collect()
    };
    assert!(bits(&one) == bits(&two), "node coordinates differ");
    assert_eq!(one.layered.mesh, two.layered.mesh);
    assert_eq!(one.stats.iterations, two.stats.iterations);
}
