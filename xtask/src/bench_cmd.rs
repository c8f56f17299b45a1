//! `cargo xtask bench`: times each stage of the pipeline on the built-in cases, in this
//! (release) build on one thread, and prints the median of several runs. The criterion benches
//! of each crate measure the pieces; this measures what a user waits for.

use std::time::Instant;

use anyhow::{Result, bail};
use mesh_model::Shape;

use crate::cli::BenchArgs;
use crate::{Outcome, builtin, case, pipeline};

/// Runs `cargo xtask bench`.
pub fn run(args: &BenchArgs) -> Result<Outcome> {
    let names: Vec<String> = if args.cases.is_empty() {
        builtin::names().into_iter().map(String::from).collect()
    } else {
        args.cases.clone()
    };
    for name in &names {
        if builtin::case_text(name).is_none() {
            bail!(
                "--case {name}: no such built-in case ({})",
                builtin::names().join(", ")
            );
        }
    }
    let runs = if args.quick { 3 } else { 11 };
    println!(
        "{:<12} {:>10} {:>12} {:>10} {:>9} {:>9} {:>9}   (median of {runs} runs, one thread)",
        "case", "curves ms", "boundary ms", "linear ms", "nodes", "quads", "triangles"
    );
    for name in &names {
        let case = case::load(name)?;
        let (mut curve_s, mut boundary_s, mut linear_s) = (vec![], vec![], vec![]);
        let mut counts = (0, 0, 0);
        for _ in 0..runs {
            let t = Instant::now();
            let curves = pipeline::curves(&case)?;
            curve_s.push(t.elapsed().as_secs_f64());
            let t = Instant::now();
            let nodes = pipeline::boundary_nodes(&case, &curves)?;
            boundary_s.push(t.elapsed().as_secs_f64());
            let t = Instant::now();
            let grown = pipeline::linear_mesh(&case, &nodes)?;
            linear_s.push(t.elapsed().as_secs_f64());
            let m = &grown.mesh;
            counts = (m.nodes.len(), m.count(Shape::Quad), m.count(Shape::Tri));
        }
        println!(
            "{name:<12} {:>10.3} {:>12.3} {:>10.1} {:>9} {:>9} {:>9}",
            median(&mut curve_s) * 1e3,
            median(&mut boundary_s) * 1e3,
            median(&mut linear_s) * 1e3,
            counts.0,
            counts.1,
            counts.2
        );
    }
    Ok(Outcome::Valid)
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}
