//! `curvemesh quality MESH.msh`: reads a mesh file and reports what `mesh` would report of
//! it — counts, structural problems, largest angles, certified validity — and draws it on
//! request. Exit status 2 when the mesh fails validation.

use std::time::Instant;

use anyhow::{Context, Result, bail};
use curvemesh::outputs::Outputs;

use crate::cli::QualityArgs;
use crate::outcome::Finished;
use crate::pictures::{self, Colour};
use crate::{pool, summary};

/// Runs `curvemesh quality`, in a pool of one thread per core entered by this thread (see
/// [`crate::pool`]).
pub fn run(args: &QualityArgs) -> Result<Finished> {
    pool::in_pool(None, || run_here(args))?
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
    let name = args
        .mesh
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("mesh");
    let origin = args.mesh.display().to_string();
    let (mut report, scaled_jacobian) = curvemesh::quality::check(&mesh, name, &origin)?;
    report.timings_s.insert("read", read_s);
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
    if !args.quiet {
        print!("{}", summary::table(&report));
    }
    Ok(Finished::of(
        report.verdict(args.report.as_deref(), &origin),
    ))
}
