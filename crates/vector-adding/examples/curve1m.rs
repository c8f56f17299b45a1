//! temporary: the 1M case's curving, alternating 1 and 2 threads
#![allow(missing_docs)]
use std::time::Instant;
fn main() {
    let mut case = test_cases::real_case("naca0012");
    case.boundary.max_spacing = 0.01;
    let g = test_cases::grow(&case);
    eprintln!("cells {}", g.output.layered.mesh.cells.len());
    let params = g.curving_params(3, false);
    let pools: Vec<_> = [1, 2]
        .iter()
        .map(|&t| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(t)
                .build()
                .unwrap()
        })
        .collect();
    for round in 0..7 {
        for (k, pool) in pools.iter().enumerate() {
            let t0 = Instant::now();
            let c = pool.install(|| g.curve(&params).unwrap());
            let total = t0.elapsed().as_secs_f64();
            let laps: Vec<String> = c
                .stats
                .timings_s
                .iter()
                .map(|(p, s)| format!("{p} {:.3}", s))
                .collect();
            println!(
                "round {round} t{} total {total:.3} | {}",
                k + 1,
                laps.join(" ")
            );
            drop(c);
        }
    }
}
