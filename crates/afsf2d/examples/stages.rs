//! Timing aid for the linear stage alone: meshes one case file (boundary nodes as the pipeline
//! makes them) `REPS` times (default 3) with `THREADS` threads (default 1) and prints each
//! run's time and the mesher's own phase timers (`AfsfStats::timings`), then the medians.
//!
//! `THREADS=2 cargo run --release -p afsf2d --example stages -- fixtures/cases/naca0012.toml`

use afsf2d::grow_mesh;

fn main() {
    let spec = std::env::args().nth(1).unwrap_or_else(|| "naca0012".into());
    let env = |k: &str, d: usize| {
        std::env::var(k)
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(d)
    };
    let (reps, threads) = (env("REPS", 3), env("THREADS", 1));
    let case = test_cases::real_case(&spec);
    let (loops, params) = test_cases::mesher_input(&case);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a thread pool");
    let mut rows: Vec<[f64; 6]> = Vec::new();
    for _ in 0..reps {
        let t = std::time::Instant::now();
        let out = pool.install(|| grow_mesh(&loops, &params).expect("the case meshes"));
        let wall = t.elapsed().as_secs_f64();
        let s = &out.stats.timings;
        let row = [wall, s.plan_and_closing, s.build, s.solve, s.verify, s.fill];
        println!(
            "{spec} threads {threads}: {} cells, {} iterations, fill {} triangles ({} peeled), wall {:.3} s: plan+closing {:.3} build {:.3} solve {:.3} verify {:.3} fill {:.3}",
            out.layered.mesh.cells.len(),
            out.stats.iterations,
            out.stats.fill_triangles,
            out.stats.peeled_cells,
            row[0],
            row[1],
            row[2],
            row[3],
            row[4],
            row[5]
        );
        rows.push(row);
    }
    let median = |k: usize| {
        let mut v: Vec<f64> = rows.iter().map(|r| r[k]).collect();
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    println!(
        "median: wall {:.3} plan+closing {:.3} build {:.3} solve {:.3} verify {:.3} fill {:.3}",
        median(0),
        median(1),
        median(2),
        median(3),
        median(4),
        median(5)
    );
}
