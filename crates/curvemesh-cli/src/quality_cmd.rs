//! `curvemesh quality MESH.msh`: reads a mesh file and reports what `mesh` would report of
//! it — counts, structural problems, largest angles (2D) or dihedral angles and volumes (3D),
//! certified validity — and draws it on request (3D: plane slices, `--slice`). Exit status 2
//! when the mesh fails validation.

use std::time::Instant;

use anyhow::{Context, Result, bail};
use curvemesh::outputs::Outputs;
use mesh_model::Dim;

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
    // 2D or 3D is known once the mesh is read; the flags of the other are refused then
    let pics = pictures::parse_files_only(&args.pictures)?;
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
    let plane = match mesh.dim {
        Dim::Two => {
            pictures::parse(&args.pictures, &Default::default())?;
            None
        }
        Dim::Three => pictures::parse_3d(&args.pictures)?.1,
    };
    let (mut report, scaled_jacobian) = curvemesh::quality::check(&mesh, name, &origin)?;
    report.timings_s.insert("read", read_s);
    let pics: Vec<_> = pics.into_iter().zip(picture_outputs).collect();
    match mesh.dim {
        // (a mesh read back has no layers: no fill to tell)
        Dim::Two => pictures::draw_all(
            (&mesh, 0),
            &pics,
            &args.pictures,
            Colour::Angle,
            name,
            &scaled_jacobian,
            &mut outputs,
        )?,
        // the slices cut the cells' corners (the linear cells under P2 ones)
        Dim::Three => {
            pictures::draw_slices(&mesh, &pics, &args.pictures, plane, name, &mut outputs)?;
        }
    }
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
