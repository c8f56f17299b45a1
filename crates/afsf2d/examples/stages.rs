//! Timing aid for the linear stage alone: meshes one case file (boundary nodes as the pipeline
//! makes them) `REPS` times (default 3) with `THREADS` threads (default 1) and prints each
//! run's time and the mesher's own phase timers (`AfsfStats::timings`), then the medians.
//!
//! `THREADS=2 cargo run --release -p afsf2d --example stages -- fixtures/cases/naca0012.toml`
//!
//! With `ANGLES=1` it also prints the angles of the last run's mesh: the fill triangles'
//! smallest and largest corner angles (and how many have an angle of 120° or more), and the
//! smallest corner angle and largest angle (quads cut along the shorter diagonal) of all cells.

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
    let mut last = None;
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
        last = Some(out);
    }
    if let (Some(out), true) = (last, std::env::var("ANGLES").is_ok()) {
        print_angles(&spec, &out.layered);
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

/// The corner angles (degrees) of the polygon `p`.
fn corner_angles(p: &[[f64; 2]]) -> impl Iterator<Item = f64> + '_ {
    let n = p.len();
    (0..n).map(move |i| {
        let (a, b, c) = (p[(i + n - 1) % n], p[i], p[(i + 1) % n]);
        let (u, v) = ([a[0] - b[0], a[1] - b[1]], [c[0] - b[0], c[1] - b[1]]);
        (u[0] * v[1] - u[1] * v[0])
            .abs()
            .atan2(u[0] * v[0] + u[1] * v[1])
            .to_degrees()
    })
}

/// Prints the fill triangles' angles and the whole mesh's (see the module documentation).
fn print_angles(spec: &str, layered: &mesh_model::LayeredMesh) {
    let mesh = &layered.mesh;
    let corners = |i: usize| -> Vec<[f64; 2]> {
        mesh.cells
            .get(i)
            .corners()
            .iter()
            .map(|&g| {
                let p = mesh.nodes[g as usize];
                [p[0], p[1]]
            })
            .collect()
    };
    let (mut fill_min, mut fill_max, mut fill_bad) = (f64::INFINITY, 0.0f64, 0);
    for i in layered.layering.layered_cells..mesh.cells.len() {
        let worst = mesh_model::measure::cell_max_angle_deg(mesh, i);
        fill_bad += usize::from(worst >= 120.0);
        fill_max = fill_max.max(worst);
        fill_min = corner_angles(&corners(i)).fold(fill_min, f64::min);
    }
    let (mut all_min, mut all_max) = (f64::INFINITY, 0.0f64);
    for i in 0..mesh.cells.len() {
        all_max = all_max.max(mesh_model::measure::cell_max_angle_deg(mesh, i));
        all_min = corner_angles(&corners(i)).fold(all_min, f64::min);
    }
    println!(
        "{spec} angles: fill {} triangles, min {fill_min:.2} max {fill_max:.2}, {fill_bad} with 120 or more; all cells min {all_min:.2} max {all_max:.2}",
        mesh.cells.len() - layered.layering.layered_cells
    );
}
