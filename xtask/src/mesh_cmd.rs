//! `cargo xtask mesh`: load the case, run the stages, check the result, write the files and the
//! report, print the summary. Every check of the input happens before the first file is
//! written, so bad input leaves nothing behind.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result, bail};
use mesh_io::Format;
use mesh_model::{Role, Shape};

use crate::cli::MeshArgs;
use crate::report::{LoopReport, Quality, Report};
use crate::{Outcome, builtin, case, pipeline, summary};

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

    let mut report = Report {
        case: case.name.clone(),
        dimension: 2,
        order,
        ..Report::default()
    };

    let t = Instant::now();
    let curves = pipeline::curves(&case)?;
    let nodes = pipeline::boundary_nodes(&case, &curves)?;
    report
        .timings_s
        .insert("boundary", t.elapsed().as_secs_f64());

    let t = Instant::now();
    let grown = pipeline::linear_mesh(&case, &nodes)?;
    report.timings_s.insert("linear", t.elapsed().as_secs_f64());
    report.layers = Some(grown.stats.layers);
    let mut mesh = grown.mesh;
    if args.triangles {
        mesh = afsf2d::cut_quads_shorter_diagonal(&mesh);
    }
    if order > 1 {
        report.notes.push(format!(
            "order {order} asked for: curving (Vector-Adding) is not implemented yet, the mesh \
             written is linear"
        ));
        report.order = 1;
    }
    let angles = afsf2d::max_angle_histogram(&mesh);
    report.quality = Some(Quality {
        max_angle_deg: angles.max_angle_deg,
        obtuse_hist: angles.histogram,
    });
    report.area = Some(mesh.linear_area());

    report.nodes = mesh.nodes.len();
    for shape in [Shape::Tri, Shape::Quad] {
        report.cells.insert(shape.name(), mesh.count(shape));
    }
    for (role, name) in [(Role::Wall, "wall"), (Role::Farfield, "farfield")] {
        let n = mesh
            .boundary_patch
            .iter()
            .filter(|&&p| mesh.patches[p as usize].role == role)
            .count();
        if n > 0 {
            report.boundary_facets.insert(name, n);
        }
    }
    for ((input, curve_nodes), curve) in case.loops.iter().zip(&nodes).zip(&curves) {
        report.loops.push(loop_report(input, curve_nodes, curve));
    }
    report.problems = mesh_model::validate(&mesh)
        .iter()
        .map(ToString::to_string)
        .collect();

    let t = Instant::now();
    for out in &outs {
        create_parent(out)?;
        mesh_io::write(out, &mesh).with_context(|| format!("writing {}", out.display()))?;
        report.files.push(out.display().to_string());
    }
    report.timings_s.insert("write", t.elapsed().as_secs_f64());
    report
        .timings_s
        .insert("total", total.elapsed().as_secs_f64());
    if let Some(path) = &report_path {
        report.files.push(path.display().to_string());
        create_parent(path)?;
        let json = serde_json::to_string_pretty(&report)?;
        mesh_io::atomic::write_atomic(path, |w| {
            w.write_all(json.as_bytes())
                .map_err(|source| mesh_io::IoError::Io {
                    path: path.clone(),
                    source,
                })
        })
        .with_context(|| format!("writing {}", path.display()))?;
    }
    if !args.quiet {
        print!("{}", summary::table(&report));
    }
    Ok(if report.problems.is_empty() {
        Outcome::Valid
    } else {
        Outcome::Invalid
    })
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

fn create_parent(path: &Path) -> Result<()> {
    match path.parent() {
        Some(dir) if !dir.as_os_str().is_empty() && !dir.exists() => std::fs::create_dir_all(dir)
            .with_context(|| format!("cannot create the folder {}", dir.display())),
        _ => Ok(()),
    }
}

fn loop_report(
    input: &case::LoopInput,
    nodes: &boundary1d::BoundaryNodes,
    _curve: &geom_curve::ClosedCurve,
) -> LoopReport {
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
