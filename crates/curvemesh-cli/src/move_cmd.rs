//! `curvemesh move`: load a 2D case, read its motion (a motion file, or the flags of one
//! loop's motion), check it against the case, reserve every output, move the case with the
//! library (meshed first, or from `--snapshot`), draw the pictures, write the report and
//! the sensitivities, print the summary. A bad motion is refused with one line before any
//! work; the outputs are written all together or not at all.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result, ensure};
use curvemesh::movement::motion::{self, default_loop, parse_bump, rigid};
use curvemesh::movement::{MoveOptions, Moved, Mover};
use curvemesh::{Case, Snapshot};
use mesh_move::{LoopMotion, Motion};

use crate::cli::{MotionArgs, MoveArgs, MoveMethod, RbfKernel};
use crate::outcome::Finished;
use crate::pictures::{self, Colour};
use crate::plan::{OutputFlags, default_stem, plan};
use crate::progress::{Spinners, stage};
use crate::{pool, resources, summary};

/// Runs `curvemesh move`, in a pool of one thread per core entered by this thread (see
/// [`crate::pool`]).
pub fn run(args: &MoveArgs) -> Result<Finished> {
    pool::in_pool(None, || run_here(args))?
}

fn run_here(args: &MoveArgs) -> Result<Finished> {
    let total = Instant::now();
    let case = curvemesh::load::load_2d(&args.case)?;
    let options = options(args);
    options.check()?;
    check_csv(args)?;
    let motions = motions(&args.motion, &case)?;
    let flags = OutputFlags {
        outs: &args.output.outs,
        report: args.output.report.as_deref(),
        snapshot: None,
        pictures: &args.pictures,
    };
    let stem = default_stem(
        &format!("{}-moved", case.file_stem()),
        options.order,
        case.order,
    );
    let mut planned = plan(&flags, &stem, &case.views)?;
    let at = args
        .snapshot
        .as_ref()
        .map(|p| format!("--snapshot {}", p.display()));
    let start = match (&args.snapshot, &at) {
        (Some(path), Some(at)) => {
            let snapshot: Snapshot = mesh_io::snapshot::load(path).with_context(|| at.clone())?;
            Some((snapshot, at.as_str()))
        }
        _ => None,
    };
    let mut spinners = Spinners::new(args.quiet);
    if let Some(steps) = args.steps {
        drop(planned);
        return run_steps(
            args,
            &case,
            (&motions, start, &options, steps),
            &stem,
            &mut spinners,
        );
    }
    let plan = Some(&mut planned.plan);
    let moved =
        curvemesh::movement::move_into(&case, &motions, start, &options, &mut spinners, plan)?;
    let Moved {
        mesh,
        mut report,
        scaled_jacobian,
        fill_cells,
        sensitivities,
    } = moved;
    if !planned.pictures.is_empty() {
        let t = Instant::now();
        let progress = stage(args.quiet, "pictures");
        pictures::draw_all(
            (&mesh, fill_cells),
            &planned.pictures,
            &args.pictures,
            Colour::Layer,
            &case.name,
            &scaled_jacobian,
            &mut planned.plan.outputs,
        )?;
        drop(progress);
        report
            .timings_s
            .insert("pictures", t.elapsed().as_secs_f64());
    }
    report
        .timings_s
        .insert("total", total.elapsed().as_secs_f64());
    report.peak_memory_bytes = resources::peak_memory_bytes();
    let report_path = planned.plan.commit(&mut report)?;
    // written only with a valid mesh
    if let (Some(path), Some(columns), true) =
        (&args.sensitivities, &sensitivities, report.is_valid())
    {
        let xy: Vec<[f64; 2]> = (0..mesh.nodes.len() as u32).map(|k| mesh.xy(k)).collect();
        mesh_io::sensitivities::write_sensitivities(path, &xy, columns)
            .map_err(|e| anyhow::anyhow!("--sensitivities {}: {e}", path.display()))?;
    }
    if !args.quiet {
        print!("{}", summary::table(&report));
        if let Some(movement) = &report.movement {
            print!("{}", movement.summary());
        }
    }
    let verdict = report.verdict(report_path.as_deref(), &failed_subject(&report));
    Ok(Finished::of(verdict))
}

/// The start of a failed move's line: the cells its mover inverted, the cause of the moved
/// mesh's failure, when it inverted some; else only that the moved mesh was written.
fn failed_subject(report: &curvemesh::Report) -> String {
    match report
        .movement
        .as_ref()
        .filter(|m| m.inverted_linear_cells > 0)
    {
        Some(m) => format!(
            "the {} mover inverted {} linear cells (the motion leaves too little room between \
             the walls, or turns a body further than this mover follows): the moved linear \
             mesh was written but",
            m.method, m.inverted_linear_cells
        ),
        None => "the moved mesh was written but".into(),
    }
}

/// `move --steps N`: the N + 1 meshes of the motion's sequence, each written with its own
/// outputs (every name with `-k` before its extension) as soon as it is made; one summary
/// line per step. The exit status is that of the worst step.
fn run_steps(
    args: &MoveArgs,
    case: &Case,
    (motions, start, options, steps): (
        &[LoopMotion],
        Option<(Snapshot, &str)>,
        &MoveOptions,
        usize,
    ),
    stem: &str,
    spinners: &mut Spinners,
) -> Result<Finished> {
    ensure!(
        args.pictures.pngs.is_empty() && args.pictures.svgs.is_empty(),
        "--png and --svg do not go with --steps: picture the steps one by one"
    );
    let width = steps.to_string().len().max(3);
    let mut failed: Option<String> = None;
    let mut write = |k: usize, moved: Moved| -> Result<()> {
        let tag = format!("-{k:0width$}");
        let outs: Vec<PathBuf> = args.output.outs.iter().map(|p| tagged(p, &tag)).collect();
        let report_path = args.output.report.as_deref().map(|p| tagged(p, &tag));
        let flags = OutputFlags {
            outs: &outs,
            report: report_path.as_deref(),
            snapshot: None,
            pictures: &args.pictures,
        };
        let mut planned = plan(&flags, &format!("{stem}{tag}"), &case.views)?;
        let Moved {
            mesh,
            mut report,
            sensitivities,
            ..
        } = moved;
        planned.plan.write_meshes(&mesh)?;
        let written = planned.plan.commit(&mut report)?;
        if let (Some(path), Some(columns), true) =
            (&args.sensitivities, &sensitivities, report.is_valid())
        {
            let path = tagged(path, &tag);
            let xy: Vec<[f64; 2]> = (0..mesh.nodes.len() as u32).map(|k| mesh.xy(k)).collect();
            mesh_io::sensitivities::write_sensitivities(&path, &xy, columns)
                .map_err(|e| anyhow::anyhow!("--sensitivities {}: {e}", path.display()))?;
        }
        let verdict = report.verdict(written.as_deref(), &failed_subject(&report));
        if !args.quiet {
            let movement = report.movement.as_ref();
            println!(
                "step {k}/{steps}: move {:.3} s, worst-cell ratio {:.3}, {}",
                report.timings_s.get("move").copied().unwrap_or(0.0),
                movement.map_or(f64::NAN, |m| m.worst_cell_ratio),
                verdict.as_deref().unwrap_or("certified")
            );
        }
        if failed.is_none() {
            failed = verdict;
        }
        Ok(())
    };
    let mut error: Option<anyhow::Error> = None;
    let run = curvemesh::movement::move_sequence(
        case,
        motions,
        start,
        (options, steps),
        spinners,
        &mut |k, moved| {
            write(k, moved).map_err(|e| {
                let line = format!("{e:#}");
                error = Some(e);
                curvemesh::Error::input(line)
            })
        },
    );
    if let Some(e) = error {
        return Err(e);
    }
    run?;
    Ok(Finished::of(failed))
}

/// `path` with `tag` before its extension (`out/a.msh`, `-003`: `out/a-003.msh`).
fn tagged(path: &Path, tag: &str) -> PathBuf {
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy())
        .unwrap_or_default();
    let name = match path.extension() {
        Some(ext) => format!("{stem}{tag}.{}", ext.to_string_lossy()),
        None => format!("{stem}{tag}"),
    };
    path.with_file_name(name)
}

/// The library's options of the flags.
fn options(args: &MoveArgs) -> MoveOptions {
    MoveOptions {
        order: args.output.order,
        triangles: args.output.triangles,
        mover: match args.method {
            MoveMethod::Springs => Mover::Springs,
            MoveMethod::Idw => Mover::Idw,
            MoveMethod::Rbf => Mover::Rbf,
        },
        kernel: match args.kernel {
            RbfKernel::WendlandC2 => curvemesh::movement::RbfKernel::WendlandC2,
            RbfKernel::ThinPlate => curvemesh::movement::RbfKernel::ThinPlate,
        },
        radius: args.radius,
        smooth: args.smooth,
        sensitivities: args.sensitivities.is_some(),
        ..MoveOptions::default()
    }
}

/// The sensitivities are a CSV file.
fn check_csv(args: &MoveArgs) -> Result<()> {
    if let Some(path) = &args.sensitivities {
        ensure!(
            path.extension().is_some_and(|e| e == "csv"),
            "--sensitivities {}: the sensitivities are CSV: give a .csv file name",
            path.display()
        );
    }
    Ok(())
}

/// The motions asked for: the motion file, or the flags' motion of one loop.
fn motions(args: &MotionArgs, case: &Case) -> Result<Vec<LoopMotion>> {
    let flags = args.rotate.is_some()
        || args.about.is_some()
        || args.translate.is_some()
        || args.scale.is_some()
        || !args.bumps.is_empty()
        || args.loop_name.is_some();
    if let Some(path) = &args.motion {
        ensure!(
            !flags,
            "give either --motion FILE.toml or the motion flags (--loop, --rotate, --about, \
             --translate, --scale, --bump), not both"
        );
        return Ok(motion::load_file(path)?);
    }
    let rigid = rigid(args.scale, args.rotate, args.about, args.translate);
    let bumps = args
        .bumps
        .iter()
        .map(|b| parse_bump(b).with_context(|| format!("--bump {b}")))
        .collect::<Result<Vec<_>>>()?;
    ensure!(
        rigid.is_some() || !bumps.is_empty(),
        "no motion given: use --rotate, --translate, --scale, --bump or --motion FILE.toml"
    );
    let loop_name = match &args.loop_name {
        Some(name) => name.clone(),
        None => default_loop(case)?,
    };
    Ok(vec![LoopMotion {
        loop_name,
        motion: Motion { rigid, bumps },
    }])
}
