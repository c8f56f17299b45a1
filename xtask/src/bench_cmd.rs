//! `cargo xtask bench`: times each stage of the pipeline on the built-in cases, in this
//! (release) build on one thread (the certification's parallel loop runs in a one-thread
//! pool here), and prints the median of several runs: curves, boundary, the linear mesh, and
//! at P3 the curving and the certification of every cell, with their share of the linear
//! time. The criterion benches of each crate measure the pieces; this measures what a user
//! waits for.

use std::time::Instant;

use anyhow::{Result, bail};
use mesh_model::Shape;

use crate::cli::BenchArgs;
use curvemesh::{builtin, load::load_2d as load_case, pipeline};
use curvemesh_cli::Outcome;

use crate::runs::median;

/// Runs `cargo xtask bench`.
pub fn run(args: &BenchArgs) -> Result<Outcome> {
    if args.vs_gmsh || args.scaling || args.three_d {
        crate::bench_vs::run(args)?;
        return Ok(Outcome::Valid);
    }
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
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build()?;
    println!(
        "{:<12} {:>10} {:>12} {:>10} {:>9} {:>9} {:>9} {:>11} {:>12} {:>8}   (median of {runs} runs, one thread)",
        "case",
        "curves ms",
        "boundary ms",
        "linear ms",
        "nodes",
        "quads",
        "triangles",
        "P3 curve ms",
        "P3 certify ms",
        "share %"
    );
    pool.install(|| bench_cases(&names, runs))?;
    Ok(Outcome::Valid)
}

/// Times every case and prints its row.
fn bench_cases(names: &[String], runs: usize) -> Result<()> {
    for name in names {
        let case = load_case(name)?;
        let (mut curve_s, mut boundary_s, mut linear_s) = (vec![], vec![], vec![]);
        let (mut curving_s, mut certify_s) = (vec![], vec![]);
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
            let m = &grown.layered.mesh;
            counts = (m.nodes.len(), m.count(Shape::Quad), m.count(Shape::Tri));
            let t = Instant::now();
            let layered = std::borrow::Cow::Borrowed(&grown.layered);
            let curved = pipeline::curved_mesh(&case, &curves, &nodes, layered, 3, false)?;
            curving_s.push(t.elapsed().as_secs_f64());
            let t = Instant::now();
            let validity = jacobian_check::check_mesh(&curved.mesh, &Default::default())?;
            certify_s.push(t.elapsed().as_secs_f64());
            if !validity.invalid_cells.is_empty() {
                bail!(
                    "{name}: {} invalid cells at P3",
                    validity.invalid_cells.len()
                );
            }
        }
        let linear = median(&mut linear_s);
        let (curving, certify) = (median(&mut curving_s), median(&mut certify_s));
        println!(
            "{name:<12} {:>10.3} {:>12.3} {:>10.1} {:>9} {:>9} {:>9} {:>11.1} {:>12.1} {:>8.1}",
            median(&mut curve_s) * 1e3,
            median(&mut boundary_s) * 1e3,
            linear * 1e3,
            counts.0,
            counts.1,
            counts.2,
            curving * 1e3,
            certify * 1e3,
            100.0 * (curving + certify) / linear
        );
    }
    Ok(())
}
