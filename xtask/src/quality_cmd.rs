//! `cargo xtask quality MESH.msh`: reads a mesh file and reports what `mesh` would report of
//! it — counts, structural problems, largest angles, area — and draws it on request. Exit
//! status 2 when the mesh fails validation.

use std::time::Instant;

use anyhow::{Context, Result, bail};
use mesh_model::Dim;

use crate::Finished;
use crate::cli::QualityArgs;
use crate::outputs::Outputs;
use crate::pictures::{self, Colour};
use crate::report::Report;

/// Runs `cargo xtask quality`, in a pool of one thread per core entered by this thread (see
/// [`crate::pool`]).
pub fn run(args: &QualityArgs) -> Result<Finished> {
    crate::pool::in_pool(None, || run_here(args))?
}

fn run_here(args: &QualityArgs) -> Result<Finished> {
    let total = Instant::now();
    if let Some(r) = &args.report
        && r.extension().is_none_or(|e| e != "json")
    {
        bail!(
            "--report {}: the report is JSON: give a .json file name",
            r.display()
        );
    }
    let pics = pictures::parse(&args.pictures, &Default::default())?;
    let mut outputs = Outputs::new();
    let picture_outputs = pictures::reserve(&pics, &mut outputs)?;
    let report_output = match &args.report {
        Some(r) => Some(outputs.reserve("--report", r)?),
        None => None,
    };
    let t = Instant::now();
    let mesh = mesh_io::read_msh(&args.mesh)
        .with_context(|| format!("reading {}", args.mesh.display()))?;
    let read_s = t.elapsed().as_secs_f64();
    if mesh.dim != Dim::Two || mesh.cells.is_empty() {
        bail!(
            "{}: has no 2D cells to check (a surface or boundary-only mesh)",
            args.mesh.display()
        );
    }
    let name = args
        .mesh
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("mesh");
    let mut report = Report::new(name, mesh.order);
    report.timings_s.insert("read", read_s);
    if mesh.order > 1 {
        report
            .notes
            .push("angles are those of the linear cells under the curved ones".to_string());
    }
    report.describe(&mesh);
    let t = Instant::now();
    let scaled_jacobian = report.certify(&mesh)?;
    report
        .timings_s
        .insert("validity", t.elapsed().as_secs_f64());
    report.curved_edge_fraction = Some(jacobian_check::curved_edge_fraction(&mesh));
    let pics: Vec<_> = pics.into_iter().zip(picture_outputs).collect();
    pictures::draw_all(
        &mesh,
        &pics,
        &args.pictures,
        Colour::Angle,
        name,
        &scaled_jacobian,
        &mut outputs,
    )?;
    report.files = outputs.files();
    report
        .timings_s
        .insert("total", total.elapsed().as_secs_f64());
    if let Some(output) = report_output {
        outputs.write_bytes(output, &report.json()?)?;
    }
    outputs.commit()?;
    let subject = args.mesh.display().to_string();
    Ok(report.finish(args.report.as_deref(), args.quiet, &subject))
}
