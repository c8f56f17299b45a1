//! `cargo xtask mesh`: load the case, reserve every output file, run the stages, check the
//! result, write the meshes, the snapshot, the pictures and the report, put them all in place
//! together, print the summary. Bad input, an unwritable output or an interruption leaves
//! every output file as it was.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{Result, bail};
use boundary1d::BoundaryNodes;
use geom_curve::ClosedCurve;
use mesh_io::Format;
use mesh_model::{LayeredMesh, Mesh};

use crate::cli::MeshArgs;
use crate::outputs::{Output, Outputs};
use crate::pictures::{self, Colour, Picture};
use crate::progress::stage;
use crate::report::{LinearAngles, LoopReport, Report};
use crate::stages::Snapshot;
use crate::{Finished, airfoil, builtin, case, estimate, pipeline};

/// The files a run will write, reserved before any work.
pub(crate) struct Planned {
    pub(crate) outputs: Outputs,
    pub(crate) meshes: Vec<(PathBuf, Output)>,
    pub(crate) snapshot: Option<Output>,
    pub(crate) pictures: Vec<(Picture, Output)>,
    pub(crate) report: Option<(PathBuf, Output)>,
    /// `--binary`: the .msh outputs in binary MSH 4.1.
    pub(crate) binary: bool,
}

/// Runs `cargo xtask mesh` in a pool of `--threads` threads (default: one per core), entered
/// by this thread (see [`crate::pool`]).
pub fn run(args: &MeshArgs) -> Result<Finished> {
    crate::pool::in_pool(args.threads, || run_here(args))?
}

fn run_here(args: &MeshArgs) -> Result<Finished> {
    if args.list {
        for (name, about) in builtin::list() {
            println!("{name:<14} {about}");
        }
        return Ok(Finished::valid());
    }
    let total = Instant::now();
    let case = match load(args)? {
        case::AnyCase::Two(case) => case,
        case::AnyCase::Three(case) => return crate::mesh3d_cmd::run(args, &case, total),
    };
    let order = args.output.order.unwrap_or(case.order);
    let flags = OutputFlags {
        outs: &args.output.outs,
        report: args.output.report.as_deref(),
        snapshot: args.snapshot.as_deref(),
        pictures: &args.pictures,
    };
    let mut plan = plan(&flags, &case.file_stem(), &case.views)?;
    if args.binary {
        if !plan
            .meshes
            .iter()
            .any(|(p, _)| Format::from_path(p) == Some(Format::Msh))
        {
            bail!("--binary applies to .msh outputs: give --out FILE.msh");
        }
        plan.binary = true;
    }
    estimate::check_loops(&case, args.max_cells, args.quiet)?;

    let mut report = Report::new(&case.name, order);
    // reading the case and its geometry, checking every output flag
    report
        .timings_s
        .insert("setup", total.elapsed().as_secs_f64());
    let (mesh, snapshot, angles) = make(args, &case, order, &mut report)?;
    let snapshot = snapshot.as_ref().zip(args.snapshot.as_deref());
    let run = Run {
        pictures: &args.pictures,
        name: &case.name,
        quiet: args.quiet,
        total,
    };
    let report_path = check_and_write(plan, (&mesh, angles), snapshot, &run, &mut report);
    free_beside(mesh);
    let report_path = report_path?;
    Ok(report.finish(
        report_path.as_deref(),
        args.quiet,
        "the mesh was written but",
    ))
}

/// Drops `value` on a thread of its own: the final mesh of a million P3 cells takes some
/// 0.04 s to give its pages back, which the run need not wait for (when the process ends
/// first, the system takes them back). When no thread can be started it is dropped here.
fn free_beside<T: Send + 'static>(value: T) {
    let _ = std::thread::Builder::new()
        .name("free".into())
        .spawn(move || drop(value));
}

/// What the last steps of a run need to know of it.
pub(crate) struct Run<'a> {
    /// The picture flags.
    pub pictures: &'a crate::cli::PictureArgs,
    /// The case's name (the pictures' title).
    pub name: &'a str,
    /// `--quiet`.
    pub quiet: bool,
    /// When the run started.
    pub total: Instant,
}

/// The last steps of a run: describes `mesh` in the report, with the angle figures of
/// `linear` (of the linear mesh under it, the same at every order and with --triangles) and
/// certifies every cell, while the meshes and the snapshot are written (both at once, on two
/// threads when there are two: the files do not depend on it); then draws the pictures and
/// writes the report ([`finish`]). Returns the path of the report, if one was written.
pub(crate) fn check_and_write(
    mut plan: Planned,
    (mesh, linear): (&Mesh, LinearAngles<'_>),
    snapshot: Option<(&Snapshot, &std::path::Path)>,
    run: &Run<'_>,
    report: &mut Report,
) -> Result<Option<PathBuf>> {
    let progress = stage(run.quiet, "certified validity, writing");
    let (checked, written) = rayon::join(
        || -> Result<Vec<f64>> {
            report.describe_over(mesh, linear);
            let t = Instant::now();
            let scaled_jacobian = report.certify(mesh)?;
            report
                .timings_s
                .insert("validity", t.elapsed().as_secs_f64());
            Ok(scaled_jacobian)
        },
        || write_meshes(&mut plan, mesh, snapshot),
    );
    drop(progress);
    // (a failed check is told before a failed write, as when they ran one after the other)
    let scaled_jacobian = checked?;
    let (wrote, seconds) = written?;
    for (path, format) in wrote {
        report.wrote_mesh(&path, format, mesh.order);
    }
    report.timings_s.insert("write", seconds);
    finish(plan, mesh, run, &scaled_jacobian, report)
}

/// Writes the meshes and the snapshot (with its path) into the reserved outputs of `plan`.
/// Returns each mesh file written with its format, and the seconds it took.
fn write_meshes(
    plan: &mut Planned,
    mesh: &Mesh,
    snapshot: Option<(&Snapshot, &std::path::Path)>,
) -> Result<(Vec<(PathBuf, Format)>, f64)> {
    let t = Instant::now();
    let wrote = write_mesh_files(plan, mesh)?;
    if let (Some(output), Some((stages, path))) = (plan.snapshot, snapshot) {
        plan.outputs
            .write_with(output, |w| mesh_io::snapshot::save_to(w, stages, path))?;
    }
    Ok((wrote, t.elapsed().as_secs_f64()))
}

/// Draws the pictures and writes the report of a run into the reserved outputs of `plan`,
/// then puts every output in place together. Returns the path of the report, if one was
/// written.
fn finish(
    mut plan: Planned,
    mesh: &Mesh,
    run: &Run<'_>,
    scaled_jacobian: &[f64],
    report: &mut Report,
) -> Result<Option<PathBuf>> {
    let t = Instant::now();
    let progress = stage(run.quiet, "pictures");
    pictures::draw_all(
        mesh,
        &plan.pictures,
        run.pictures,
        Colour::Layer,
        run.name,
        scaled_jacobian,
        &mut plan.outputs,
    )?;
    drop(progress);
    if !plan.pictures.is_empty() {
        report
            .timings_s
            .insert("pictures", t.elapsed().as_secs_f64());
    }
    commit(plan, run, report)
}

/// Writes `mesh` into every reserved mesh output of `plan`, each in its format (`.msh` binary
/// with `--binary`). Returns each file written with its format.
fn write_mesh_files(plan: &mut Planned, mesh: &Mesh) -> Result<Vec<(PathBuf, Format)>> {
    let mut wrote = Vec::new();
    for (path, output) in &plan.meshes {
        let binary = plan.binary && Format::from_path(path) == Some(Format::Msh);
        plan.outputs.write_with(*output, |w| {
            if binary {
                mesh_io::msh::write_binary_to(w, mesh, path)
            } else {
                mesh_io::write_to(w, path, mesh)
            }
        })?;
        if let Some(format) = Format::from_path(path) {
            wrote.push((path.clone(), format));
        }
    }
    Ok(wrote)
}

/// Writes `mesh` into every reserved mesh output of `plan` ([`write_mesh_files`]) and records
/// each file in the report (the 3D run; the 2D one writes while it certifies).
pub(crate) fn write_and_record(plan: &mut Planned, mesh: &Mesh, report: &mut Report) -> Result<()> {
    for (path, format) in write_mesh_files(plan, mesh)? {
        report.wrote_mesh(&path, format, mesh.order);
    }
    Ok(())
}

/// The end of a run: the files, the total time and the peak memory into the report, the
/// report written, every output put in place. Returns the path of the report, if written.
pub(crate) fn commit(
    mut plan: Planned,
    run: &Run<'_>,
    report: &mut Report,
) -> Result<Option<PathBuf>> {
    report.files = plan.outputs.files();
    report
        .timings_s
        .insert("total", run.total.elapsed().as_secs_f64());
    report.peak_memory_bytes = crate::resources::peak_memory_bytes();
    if let Some((_, output)) = &plan.report {
        plan.outputs.write_bytes(*output, &report.json()?)?;
    }
    plan.outputs.commit()?;
    Ok(plan.report.map(|(p, _)| p))
}

/// The case named on the command line: a case file or built-in case (2D or 3D), or airfoil
/// `.dat` files; the airfoil flags are refused with anything but `.dat` files.
fn load(args: &MeshArgs) -> Result<case::AnyCase> {
    let dats = args.case.iter().filter(|c| airfoil::is_dat(c)).count();
    if dats > 0 {
        if dats < args.case.len() {
            bail!(
                "give either airfoil .dat files or one case, not both: {}",
                args.case.join(" ")
            );
        }
        return airfoil::case(&args.case, &args.airfoil).map(case::AnyCase::Two);
    }
    let a = &args.airfoil;
    let given = [
        ("--aoa", a.aoa.is_some()),
        ("--farfield", a.farfield.is_some()),
        ("--yplus", a.yplus.is_some()),
        ("--re", a.re.is_some()),
        ("--merge-walls", a.merge_walls),
    ];
    if let Some((flag, _)) = given.into_iter().find(|f| f.1) {
        bail!("{flag} applies to airfoil .dat files only (a case file sets its own geometry)");
    }
    match args.case.as_slice() {
        [] => case::load_any(builtin::DEFAULT),
        [one] => case::load_any(one),
        more => bail!(
            "one case at a time (several files only as airfoil .dat files): {}",
            more.join(" ")
        ),
    }
}

/// The flags that name the outputs of a run.
pub(crate) struct OutputFlags<'a> {
    /// `--out`, each.
    pub outs: &'a [PathBuf],
    /// `--report`.
    pub report: Option<&'a std::path::Path>,
    /// `--snapshot` (written).
    pub snapshot: Option<&'a std::path::Path>,
    /// `--png`, `--svg` and their options.
    pub pictures: &'a crate::cli::PictureArgs,
}

/// Checks every output flag and reserves every output file (meshes, snapshot, pictures,
/// report), so that a bad flag, an unwritable folder or two outputs on one file are refused
/// before any work. Without `--out`, the mesh and the report go to `out/STEM.msh` and
/// `out/STEM.json`; `views` are the case's named views.
pub(crate) fn plan(
    flags: &OutputFlags<'_>,
    stem: &str,
    views: &std::collections::BTreeMap<String, [f64; 4]>,
) -> Result<Planned> {
    plan_with(flags, stem, || pictures::parse(flags.pictures, views))
}

/// [`plan`] with the pictures parsed by `pictures` (after the mesh and report flags).
pub(crate) fn plan_with(
    flags: &OutputFlags<'_>,
    stem: &str,
    pictures: impl FnOnce() -> Result<Vec<Picture>>,
) -> Result<Planned> {
    let (outs, report_path) = outputs(flags, stem)?;
    let pictures = pictures()?;
    let mut outputs = Outputs::new();
    let meshes = outs
        .into_iter()
        .map(|p| outputs.reserve("--out", &p).map(|o| (p, o)))
        .collect::<Result<Vec<_>>>()?;
    let snapshot = match flags.snapshot {
        Some(p) => Some(outputs.reserve("--snapshot", p)?),
        None => None,
    };
    let picture_outputs = pictures::reserve(&pictures, &mut outputs)?;
    let report = match report_path {
        Some(p) => {
            let o = outputs.reserve("--report", &p)?;
            Some((p, o))
        }
        None => None,
    };
    Ok(Planned {
        outputs,
        meshes,
        snapshot,
        pictures: pictures.into_iter().zip(picture_outputs).collect(),
        report,
        binary: false,
    })
}

/// Runs the stages: curves, boundary mesh (then the cell estimate), the layered linear mesh,
/// and the curving when `order` > 1. Returns the final mesh and, when `--snapshot` is given,
/// the stages to save, and the angle figures of the linear layered mesh (its quads uncut),
/// computed beside the curving's decisions, before the curving lets go of the linear mesh
/// (which it does before it builds the curved mesh, the peak of the run's memory).
fn make(
    args: &MeshArgs,
    case: &case::Case,
    order: u8,
    report: &mut Report,
) -> Result<(Mesh, Option<Snapshot>, LinearAngles<'static>)> {
    // the layered part's edge table is made beside the fill when the curving will want it
    // and there is a second thread to make it
    let ahead = order > 1 && rayon::current_num_threads() > 1;
    let (curves, nodes, (grown, ahead)) =
        grow_ahead(case, (args.quiet, args.max_cells), ahead, report)?;
    let snapshot = args.snapshot.as_ref().map(|_| Snapshot {
        case: case.name.clone(),
        boundary: nodes.clone(),
        layered: grown.layered.clone(),
    });
    let (mesh, angles) = at_order(
        case,
        (&curves, &nodes),
        (grown.layered, ahead),
        (order, args.output.triangles),
        args.quiet,
        report,
    )?;
    Ok((mesh, snapshot, angles))
}

/// The angle figures of the linear mesh `linear`.
fn angles_of(linear: &Mesh) -> afsf2d::AngleStats {
    afsf2d::max_angle_histogram(linear)
}

/// The first stages: curves, boundary mesh (then the cell estimate, refused above
/// `max_cells`), the layered linear mesh; their timings, loops and notes go to `report`.
pub(crate) fn grow(
    case: &case::Case,
    quiet: bool,
    max_cells: u64,
    report: &mut Report,
) -> Result<(Vec<ClosedCurve>, Vec<BoundaryNodes>, afsf2d::AfsfOutput)> {
    grow_ahead(case, (quiet, max_cells), false, report)
        .map(|(curves, nodes, (grown, _))| (curves, nodes, grown))
}

/// What [`grow_ahead`] makes: the curves, the boundary nodes, the linear mesh and, when
/// asked for, its layered part's edge table made beside its fill.
type Grown = (
    Vec<ClosedCurve>,
    Vec<BoundaryNodes>,
    (afsf2d::AfsfOutput, Option<pipeline::Ahead>),
);

/// [`grow`]; with `ahead`, the layered part's edge table is made beside the fill, for the
/// curving.
fn grow_ahead(
    case: &case::Case,
    (quiet, max_cells): (bool, u64),
    ahead: bool,
    report: &mut Report,
) -> Result<Grown> {
    let t = Instant::now();
    let progress = stage(quiet, "boundary curves and 1D mesh");
    let curves = pipeline::curves(case)?;
    let nodes = pipeline::boundary_nodes(case, &curves)?;
    drop(progress);
    report
        .timings_s
        .insert("boundary", t.elapsed().as_secs_f64());
    for (input, curve_nodes) in case.loops.iter().zip(&nodes) {
        report.loops.push(loop_report(input, curve_nodes));
    }
    let expected = estimate::cells(case, &nodes);
    report.estimated_cells = Some(expected);
    let boundary_nodes = nodes.iter().map(|n| n.points.len()).sum();
    estimate::check_cells(expected, boundary_nodes, max_cells, quiet)?;

    let t = Instant::now();
    let progress = stage(quiet, "linear layered mesh (AFSF)");
    let (grown, made_ahead) = pipeline::linear_mesh_ahead(case, &nodes, ahead)?;
    drop(progress);
    report.timings_s.insert("linear", t.elapsed().as_secs_f64());
    report.layers = Some(grown.stats.layers);
    if !grown.stats.all_converged {
        report.notes.push(
            "some layers' spring solves ran out of iterations (the mesh passed its checks)".into(),
        );
    }
    if grown.stats.bare_wall_facets > 0 {
        report.notes.push(format!(
            "{} wall facets have no layers: a gap narrower than the first layer, where the \
             filled region meets the wall directly (lower [layers] first_height to layer them)",
            grown.stats.bare_wall_facets
        ));
    }
    Ok((curves, nodes, (grown, made_ahead)))
}

/// The mesh of the run at `order` (quads cut when `triangles`): `layered` curved by
/// Vector-Adding with its boundary nodes on `curves` at the `t` of `nodes` (the curving
/// takes it, to let go of what it no longer needs; `ahead`: its layered part's edge table,
/// made beside its fill), or itself at order 1; with the angle
/// figures of `layered`: taken beside the curving's decisions (within its time, so none of
/// their own), or before the copy at order 1 (with their time, which goes to `describe`).
fn at_order(
    case: &case::Case,
    (curves, nodes): (&[ClosedCurve], &[BoundaryNodes]),
    (layered, ahead): (LayeredMesh, Option<pipeline::Ahead>),
    (order, triangles): (u8, bool),
    quiet: bool,
    report: &mut Report,
) -> Result<(Mesh, LinearAngles<'static>)> {
    if order == 1 {
        let t = Instant::now();
        let angles = angles_of(&layered.mesh);
        let seconds = t.elapsed().as_secs_f64();
        return Ok((
            if triangles {
                linear_at_order(&layered, triangles, report)
            } else {
                report.curved_edge_fraction = Some(0.0);
                layered.mesh
            },
            LinearAngles::Given { angles, seconds },
        ));
    }
    let t = Instant::now();
    let progress = stage(quiet, "curving (Vector-Adding)");
    let (curved, angles) = pipeline::curved_mesh_with(
        case,
        (curves, nodes),
        (layered, ahead),
        (order, triangles),
        angles_of,
    )?;
    drop(progress);
    report
        .timings_s
        .insert("curving", t.elapsed().as_secs_f64());
    report.curved_edge_fraction = Some(curved.stats.curved_edge_fraction);
    report.curving = Some(curved.stats);
    let seconds = 0.0;
    Ok((curved.mesh, LinearAngles::Given { angles, seconds }))
}

/// The mesh of the run at order 1: `layered`'s own (a copy), its quads cut when `triangles`.
pub(crate) fn linear_at_order(layered: &LayeredMesh, triangles: bool, report: &mut Report) -> Mesh {
    // a linear mesh has no curved edge
    report.curved_edge_fraction = Some(0.0);
    if triangles {
        afsf2d::cut_quads_shorter_diagonal(&layered.mesh)
    } else {
        layered.mesh.clone()
    }
}

/// The mesh files and the report to write, by flags or by default (under `out/`, named after
/// the case's `stem`); checked before any work is done.
fn outputs(flags: &OutputFlags<'_>, stem: &str) -> Result<(Vec<PathBuf>, Option<PathBuf>)> {
    let defaulted = flags.outs.is_empty();
    let outs = if defaulted {
        vec![PathBuf::from(format!("out/{stem}.msh"))]
    } else {
        flags.outs.to_vec()
    };
    for out in &outs {
        if Format::from_path(out).is_none() {
            bail!(
                "--out {}: unknown extension: use .msh (Gmsh), .vtu (VTK) or .su2 (SU2)",
                out.display()
            );
        }
    }
    let report = match flags.report {
        Some(r) if r.extension().is_none_or(|e| e != "json") => {
            bail!(
                "--report {}: the report is JSON: give a .json file name",
                r.display()
            )
        }
        Some(r) => Some(r.to_path_buf()),
        None if defaulted => Some(PathBuf::from(format!("out/{stem}.json"))),
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
