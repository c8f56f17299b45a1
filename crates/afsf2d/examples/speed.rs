//! Timing aid: meshes every built-in case (boundary nodes as the pipeline makes them) at
//! growth 1.3, 1.4 and 1.5 and prints the median time of `REPS` runs (default 5), the share
//! of the spring solve, the total solver iterations and the largest angle after cutting.
//! With `LAYERS=1` it also lists each layer's iterations and whether its solve converged;
//! `RELAX=ω` and `WAKE=f` override the solver's relaxation and wake fraction.
//!
//! `cargo run --release -p afsf2d --example speed -- [CASE...]`

#[path = "../tests/integration/common/real.rs"]
mod real;

use afsf2d::{grow_mesh, max_angle_histogram};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let names: Vec<&str> = if args.is_empty() {
        real::real_cases()
    } else {
        args.iter().map(String::as_str).collect()
    };
    let reps: usize = std::env::var("REPS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(5);
    let show_layers = std::env::var("LAYERS").is_ok();
    let mut total_median = 0.0;
    for name in names {
        let case = real::real_case(name);
        for growth in [1.3, 1.4, 1.5] {
            let h = case.layers.first_height;
            let (loops, mut params) = real::mesher_input(&real::with_layers(&case, h, growth));
            let env = |k: &str| std::env::var(k).ok().and_then(|v| v.parse::<f64>().ok());
            if let Some(v) = env("RELAX") {
                params.solver.relaxation = v;
            }
            if let Some(v) = env("WAKE") {
                params.solver.wake_fraction = v;
            }
            let mut times = Vec::new();
            let mut last = None;
            for _ in 0..reps {
                let t = std::time::Instant::now();
                let out = grow_mesh(&loops, &params).expect("the case meshes");
                times.push(t.elapsed().as_secs_f64() * 1e3);
                last = Some(out);
            }
            times.sort_by(f64::total_cmp);
            let median = times[reps / 2];
            total_median += median;
            let out = last.expect("at least one run");
            let q = max_angle_histogram(&out.layered.mesh);
            let s = &out.stats;
            let unconverged = s.layer_stats.iter().filter(|l| !l.converged).count();
            println!(
                "{name:12} G{growth}: {median:7.1} ms (solve {:5.1} plan {:4.1} verify {:4.1} fill {:4.1} ms) iters {:5} unconv {:2}/{:2} tris {:6} max {:.1} hist {:?}",
                s.timings.solve * 1e3,
                s.timings.plan_and_closing * 1e3,
                s.timings.verify * 1e3,
                s.timings.fill * 1e3,
                s.iterations,
                unconverged,
                s.layers,
                q.triangles,
                q.max_angle_deg,
                q.histogram
            );
            if show_layers {
                for l in &s.layer_stats {
                    println!(
                        "    layer {:3} cells {:5} iters {:4} conv {} retries {}",
                        l.layer, l.cells, l.iterations, l.converged, l.retries
                    );
                }
            }
        }
    }
    println!("sum of medians: {total_median:.1} ms");
}
