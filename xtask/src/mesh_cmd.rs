//! `cargo xtask mesh`: load the case, run the stages, check the result, write the files, the
//! pictures and the report, print the summary. Every check of the input happens before the
//! first file is written, so bad input leaves nothing behind.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{Context, Result, bail};
use mesh_io::Format;

use crate::cli::MeshArgs;
use crate::pictures::{self, Colour};
use crate::progress::stage;
use crate::report::{LoopReport, Report};
use crate::stages::Snapshot;
use crate::{Outcome, builtin, case, pipeline};

/// Runs `cargo xtask mesh`.
pub fn run(args: &MeshArgs) -> Result<Outcome> {
    if args.list {
        for (name, about) in builtin::list() {
            println!("{name:<14} {about}");
        }
        return Ok(Outcome::Valid);
    }
    let total = Instant::now();
    let spec = args.case.as_deref().unwrap_or(builtin::DEFAULT);
    let case = case::load(spec)?;
    let order = args.order.unwrap_or(case.curving.order);
    let (outs, report_path) = outputs(args, &case.name)?;
    let pictures = pictures::parse(&args.pictures, &case.views)?;

    let mut report = Report::new(&case.name, order);

    let t = Instant::now();
    let progress = stage(args.quiet, "boundary curves and 1D mesh");
    let curves = pipeline::curves(&case)?;
    let nodes = pipeline::boundary_nodes(&case, &curves)?;
    drop(progress);
    report
        .timings_s
        .insert("boundary", t.elapsed().as_secs_f64());
    for ((input, curve_nodes), _) in case.loops.iter().zip(&nodes).zip(&curves) {
        report.loops.push(loop_report(input, curve_nodes));
    }

    let t = Instant::now();
    let progress = stage(args.quiet, "linear layered mesh (AFSF)");
    let grown = pipeline::linear_mesh(&case, &nodes)?;
    drop(progress);
    report.timings_s.insert("linear", t.elapsed().as_secs_f64());
    report.layers = Some(grown.stats.layers);
    if !grown.stats.all_converged {
        report.notes.push(
            "some layers' spring solves ran out of iterations (the mesh passed its checks)".into(),
        );
    }
    let snapshot = args.snapshot.as_ref().map(|path| {
        let stages = Snapshot {
            case: case.name.clone(),
            boundary: nodes.clone(),
            mesh: grown.mesh.clone(),
            node_parent: grown.node_parent.clone(),
            node_layer: grown.node_layer.clone(),
        };
        (path, stages)
    });
    let mesh = if order > 1 {
        let t = Instant::now();
        let progress = stage(args.quiet, "curving (Vector-Adding)");
        let curved = pipeline::curved_mesh(&case, &curves, &nodes, &grown, order, args.triangles)?;
        drop(progress);
        report
            .timings_s
            .insert("curving", t.elapsed().as_secs_f64());
        report.curved_edge_fraction = Some(curved.stats.curved_edge_fraction);
        report.curving = Some(curved.stats);
        curved.mesh
    } else {
        // a linear mesh has no curved edge
        report.curved_edge_fraction = Some(0.0);
        if args.triangles {
            afsf2d::cut_quads_shorter_diagonal(&grown.mesh)
        } else {
            grown.mesh
        }
    };
    report.describe(&mesh);
    let t = Instant::now();
    let progress = stage(args.quiet, "certified validity");
    let scaled_jacobian = report.certify(&mesh)?;
    drop(progress);
    report
        .timings_s
        .insert("validity", t.elapsed().as_secs_f64());

    let t = Instant::now();
    let progress = stage(args.quiet, "writing");
    for out in &outs {
        pictures::create_parent(out)?;
        mesh_io::write(out, &mesh).with_context(|| format!("writing {}", out.display()))?;
        report.files.push(out.display().to_string());
    }
    if let Some((path, stages)) = &snapshot {
        pictures::create_parent(path)?;
        mesh_io::snapshot::save(path, stages)
            .with_context(|| format!("writing {}", path.display()))?;
        report.files.push(path.display().to_string());
    }
    report.timings_s.insert("write", t.elapsed().as_secs_f64());
    let t = Instant::now();
    let drawn = pictures::draw_all(
        &mesh,
        &pictures,
        &args.pictures,
        Colour::Layer,
        &case.name,
        &scaled_jacobian,
    )?;
    report.files.extend(drawn);
    drop(progress);
    if !pictures.is_empty() {
        report
            .timings_s
            .insert("pictures", t.elapsed().as_secs_f64());
    }
    report
        .timings_s
        .insert("total", total.elapsed().as_secs_f64());
    report.finish(report_path.as_deref(), args.quiet)
}

/// The mesh files and the report to write; checked before any work is done.
fn outputs(args: &MeshArgs, name: &str) -> Result<(Vec<PathBuf>, Option<PathBuf>)> {
    let defaulted = args.outs.is_empty();
    let outs = if defaulted {
        vec![PathBuf::from(format!("out/{name}.msh"))]
    } else {
        args.outs.clone()
    };
    for out in &outs {
        if Format::from_path(out).is_none() {
            bail!(
                "--out {}: unknown extension: use .msh (Gmsh), .vtu (VTK) or .su2 (SU2)",
                out.display()
            );
        }
    }
    let report = match &args.report {
        Some(r) if r.extension().is_none_or(|e| e != "json") => {
            bail!(
                "--report {}: the report is JSON: give a .json file name",
                r.display()
            )
        }
        Some(r) => Some(r.clone()),
        None if defaulted => Some(PathBuf::from(format!("out/{name}.json"))),
        None => None,
    };
    Ok((outs, report))
}

fn loop_report(input: &case::LoopInput, nodes: &boundary1d::BoundaryNodes) -> LoopReport {
    let n = nodes.points.len();
    let lengths = (0..n).map(|i| (nodes.points[(i + 1) % n] - nodes.points[i]).norm());
    let (min, max) = lengths.fold((f64::INFINITY, 0.0f64), |(lo, hi), l| {
        (lo.min(l), hi.max(l))
    });
    LoopReport {
        name: input.name.clone(),
        role: input.role.name(),
        nodes: n,
        corners: nodes.is_corner.iter().filter(|&&c| c).count(),
        spacing_min: min,
        spacing_max: max,
    }
}
