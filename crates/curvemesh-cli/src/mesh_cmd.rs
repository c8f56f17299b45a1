//! `curvemesh mesh`: load the case (a case file, a built-in, or airfoil `.dat` files), reserve
//! every output file, mesh it with the library (the meshes and the snapshot written beside
//! the certification), draw the pictures, write the report, put every output in place
//! together, print the summary. Bad input, an unwritable output or an interruption leaves
//! every output file as it was; a mesh that fails validation is written and exits 2.

use std::time::Instant;

use anyhow::{Result, bail};
use curvemesh::airfoil::{self, AirfoilOptions};
use curvemesh::case3d::{Case3d, check_order};
use curvemesh::{AnyCase, Meshed, Options, builtin};
use mesh_draw::slice::Plane;
use mesh_io::Format;

use crate::cli::MeshArgs;
use crate::outcome::Finished;
use crate::pictures::{self, Colour};
use crate::plan::{OutputFlags, Planned, default_stem, plan, plan_with};
use crate::progress::{Spinners, stage};
use crate::{pool, resources, summary};

/// Runs `curvemesh mesh` in a pool of `--threads` threads (default: one per core), entered
/// by this thread (see [`crate::pool`]).
pub fn run(args: &MeshArgs) -> Result<Finished> {
    pool::in_pool(args.threads, || run_here(args))?
}

fn run_here(args: &MeshArgs) -> Result<Finished> {
    if args.list {
        for (name, about) in builtin::list() {
            println!("{name:<14} {about}");
        }
        return Ok(Finished::valid());
    }
    let total = Instant::now();
    let case = load(args)?;
    // (the plane 3D pictures cut, parsed with them)
    let (planned, plane) = match &case {
        AnyCase::Two(case) => (plan_2d(args, case)?, None),
        AnyCase::Three(case) => plan_3d(args, case)?,
    };
    let Planned {
        mut plan,
        pictures: drawn,
    } = planned;
    let options = Options {
        order: args.output.order,
        triangles: args.output.triangles,
        max_cells: args.max_cells,
        snapshot: args.snapshot.is_some(),
    };
    // reading the case and its geometry, checking every output flag
    let setup = total.elapsed().as_secs_f64();
    let mut spinners = Spinners::new(args.quiet);
    let meshed = curvemesh::mesh_into(&case, &options, &mut spinners, Some(&mut plan))?;
    let Meshed {
        mesh,
        mut report,
        scaled_jacobian,
        linear,
        fill_cells,
        ..
    } = meshed;
    report.timings_s.insert("setup", setup);
    let name = report.case.clone();
    if !drawn.is_empty() {
        let t = Instant::now();
        let progress = stage(args.quiet, "pictures");
        match &case {
            AnyCase::Two(_) => pictures::draw_all(
                (&mesh, fill_cells),
                &drawn,
                &args.pictures,
                Colour::Layer,
                &name,
                &scaled_jacobian,
                &mut plan.outputs,
            )?,
            AnyCase::Three(_) => {
                // the slices cut the linear cells
                let cut = linear.as_ref().unwrap_or(&mesh);
                pictures::draw_slices(cut, &drawn, &args.pictures, plane, &name, &mut plan.outputs)?
            }
        }
        drop(progress);
        report
            .timings_s
            .insert("pictures", t.elapsed().as_secs_f64());
    }
    free_beside(mesh);
    report
        .timings_s
        .insert("total", total.elapsed().as_secs_f64());
    report.peak_memory_bytes = resources::peak_memory_bytes();
    let report_path = plan.commit(&mut report)?;
    if !args.quiet {
        print!("{}", summary::table(&report));
    }
    let verdict = report.verdict(report_path.as_deref(), "the mesh was written but");
    Ok(Finished::of(verdict))
}

/// Drops `value` on a thread of its own: the final mesh of a million P3 cells takes some
/// 0.04 s to give its pages back, which the run need not wait for (when the process ends
/// first, the system takes them back). When no thread can be started it is dropped here.
fn free_beside<T: Send + 'static>(value: T) {
    let _ = std::thread::Builder::new()
        .name("free".into())
        .spawn(move || drop(value));
}

/// The outputs of a 2D run, reserved (`--binary` only with a `.msh` output); the loops'
/// length checked against `--max-cells` before any output is made.
fn plan_2d(args: &MeshArgs, case: &curvemesh::Case) -> Result<Planned> {
    let flags = OutputFlags {
        outs: &args.output.outs,
        report: args.output.report.as_deref(),
        snapshot: args.snapshot.as_deref(),
        pictures: &args.pictures,
    };
    let stem = default_stem(&case.file_stem(), args.output.order, case.order);
    let mut planned = plan(&flags, &stem, &case.views)?;
    if args.binary {
        let msh = |p: &std::path::PathBuf| Format::from_path(p) == Some(Format::Msh);
        if !planned.plan.meshes.iter().any(|(p, _)| msh(p)) {
            bail!("--binary applies to .msh outputs: give --out FILE.msh");
        }
        planned.plan.binary = true;
    }
    Ok(planned)
}

/// The outputs of a 3D run, reserved after the order and the flags that mean nothing in 3D
/// are refused, with the plane the pictures cut.
fn plan_3d(args: &MeshArgs, case: &Case3d) -> Result<(Planned, Option<Plane>)> {
    let order = args.output.order.unwrap_or(case.order);
    check_order(order, &format!("--order {order}"))?;
    refuse_2d_flags(args)?;
    let flags = OutputFlags {
        outs: &args.output.outs,
        report: args.output.report.as_deref(),
        snapshot: None,
        pictures: &args.pictures,
    };
    let stem = curvemesh::source::file_stem_of(&case.name);
    let stem = default_stem(&stem, args.output.order, case.order);
    let mut plane = None;
    let mut planned = plan_with(&flags, &stem, || {
        let (pictures, p) = pictures::parse_3d(&args.pictures)?;
        plane = p;
        Ok(pictures)
    })?;
    planned.plan.binary = args.binary;
    Ok((planned, plane))
}

/// Refuses the flags of 2D runs that mean nothing in 3D, before any work.
fn refuse_2d_flags(args: &MeshArgs) -> Result<()> {
    let given = [
        ("--snapshot", args.snapshot.is_some()),
        ("--triangles", args.output.triangles),
    ];
    if let Some((flag, _)) = given.into_iter().find(|f| f.1) {
        bail!("{flag} applies to 2D cases (this case has dimension = 3)");
    }
    Ok(())
}

/// The case named on the command line: a case file or built-in case (2D or 3D), or airfoil
/// `.dat` files; the airfoil flags are refused with anything but `.dat` files.
fn load(args: &MeshArgs) -> Result<AnyCase> {
    let dats = args
        .case
        .iter()
        .filter(|c| airfoil::is_coordinate_file(c))
        .count();
    if dats > 0 {
        if dats < args.case.len() {
            bail!(
                "give either airfoil coordinate files (.dat, .txt) or one case, not both: {}",
                args.case.join(" ")
            );
        }
        let a = &args.airfoil;
        let options = AirfoilOptions {
            aoa: a.aoa,
            farfield: a.farfield,
            yplus: a.yplus,
            re: a.re,
            merge_walls: a.merge_walls,
            first_height: a.first_height,
            growth: a.growth,
            layers: a.layers,
        };
        return Ok(AnyCase::Two(airfoil::case(&args.case, &options)?));
    }
    let a = &args.airfoil;
    let given = [
        ("--aoa", a.aoa.is_some()),
        ("--farfield", a.farfield.is_some()),
        ("--yplus", a.yplus.is_some()),
        ("--re", a.re.is_some()),
        ("--first-height", a.first_height.is_some()),
        ("--growth", a.growth.is_some()),
        ("--layers", a.layers.is_some()),
        ("--merge-walls", a.merge_walls),
    ];
    if let Some((flag, _)) = given.into_iter().find(|f| f.1) {
        // a misspelt or missing airfoil file is the likelier mistake than a flag given to a case
        if let [one] = args.case.as_slice()
            && builtin::case_text(one).is_none()
            && !std::path::Path::new(one).is_file()
        {
            bail!(
                "{one}: no such file (with {flag}, give airfoil coordinates as a .dat or .txt \
                 file)"
            );
        }
        bail!(
            "{flag} applies to airfoil coordinate files (.dat, .txt) only (a case file sets its \
             own geometry)"
        );
    }
    match args.case.as_slice() {
        [] => Ok(curvemesh::load(builtin::DEFAULT)?),
        [one] => Ok(curvemesh::load(one)?),
        more => bail!(
            "one case at a time (several files only as airfoil .dat files): {}",
            more.join(" ")
        ),
    }
}
