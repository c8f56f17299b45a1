//! `cargo xtask bench --vs-gmsh` and `--scaling`: whole processes timed from outside (wall
//! clock, and CPU time of the finished child from `getrusage`), medians of several runs.
//!
//! `--vs-gmsh` meshes the NACA0012 and the 30P30N at P3 with first heights 5e-5 and 5e-6,
//! ours (this binary's `mesh`) and Gmsh's (`tests/python/gmsh_bench.py`, embedded here and
//! run by the checkers' Python, `CHECKERS_VENV`), the two alternating run by run. Gmsh's mesh
//! size is first calibrated, untimed, to our cell count. `--scaling` times our P3 pipeline on
//! the NACA0012 made finer by `[boundary] max_spacing`, from about 10k to about 4M cells, and
//! then its 1M point at one thread and at two, alternating (two threads over one).
//! Both write their part of `docs/performance.md` (see [`crate::perf_doc`]). The case files
//! and meshes go to a temporary folder, removed at the end; the runs are deterministic (same
//! cases, same meshes, whatever the order).

use std::path::{Path, PathBuf};
use std::process::Command;

use anyhow::{Context, Result};
use serde_json::Value;

use crate::cli::BenchArgs;
use crate::perf_doc::{GmshSide, ScalingRow, VsRow};
use crate::runs::{Timed, Work, median, medians, mesh_process, timed};
use curvemesh::builtin;

use crate::perf_doc;

/// The rows of the comparison: (built-in case, first height).
const VS_ROWS: [(&str, f64); 4] = [
    ("naca0012", 5e-5),
    ("naca0012", 5e-6),
    ("30p30n", 5e-5),
    ("30p30n", 5e-6),
];
/// `--tiny`: one coarse row, to check that the command works.
const TINY_VS_ROWS: [(&str, f64); 1] = [("naca0012", 1e-3)];

/// The scaling points: `[boundary] max_spacing` of the NACA0012 (about 10k, 100k, 1M and 4M
/// P3 cells) and the most runs of each (the 4M point once).
const SCALING: [(f64, usize); 4] = [(1.0, usize::MAX), (0.1, usize::MAX), (0.01, 3), (0.0025, 1)];
/// `--tiny`: two small points.
const TINY_SCALING: [(f64, usize); 2] = [(1.0, 1), (0.5, 1)];

/// The scaling point timed at one thread and at two (the 1M point), and the most runs of each
/// (more than the scaling point's: on a shared host the ratio of two medians of three swung by
/// 0.1 from one run of the bench to the next).
const THREADS: (f64, usize) = (0.01, 9);
/// `--tiny`: the second small point.
const TINY_THREADS: (f64, usize) = (0.5, 1);

/// Runs `--vs-gmsh` and/or `--scaling` and writes their parts of the performance document.
pub fn run(args: &BenchArgs) -> Result<()> {
    let runs = args.runs.map_or(if args.tiny { 1 } else { 3 }, usize::from);
    let work = Work::new()?;
    let result = run_in(args, runs, &work);
    let _ = std::fs::remove_dir_all(&work.dir);
    result
}

fn run_in(args: &BenchArgs, runs: usize, work: &Work) -> Result<()> {
    if args.vs_gmsh {
        let rows: &[(&str, f64)] = if args.tiny { &TINY_VS_ROWS } else { &VS_ROWS };
        let gmsh = work.gmsh()?;
        if let Err(why) = &gmsh {
            println!("Gmsh's side skipped: {why}");
        }
        let mut table = Vec::new();
        for &(name, first_height) in rows {
            let row = vs_row(work, gmsh.as_ref().ok(), name, first_height, runs)?;
            println!("{}", perf_doc::vs_line(&row));
            table.push(row);
        }
        let skipped = gmsh.err();
        perf_doc::write_vs(&args.doc, &table, runs, skipped.as_deref())?;
    }
    if args.scaling {
        let points: &[(f64, usize)] = if args.tiny { &TINY_SCALING } else { &SCALING };
        let mut rows = Vec::new();
        for &(spacing, most) in points {
            let case = work.naca0012_at(spacing)?;
            let row = scaling_row(work, &case, spacing, runs.min(most))?;
            println!("{}", perf_doc::scaling_line(&row));
            rows.push(row);
        }
        perf_doc::write_scaling(&args.doc, &rows)?;
        let (spacing, most) = if args.tiny { TINY_THREADS } else { THREADS };
        let case = work.naca0012_at(spacing)?;
        let row = threads_row(work, &case, spacing, runs.min(most))?;
        println!("{}", perf_doc::threads_line(&row));
        perf_doc::write_threads(&args.doc, &row)?;
    }
    if args.three_d {
        crate::bench3d::run(work, runs, args.tiny, &args.doc)?;
    }
    println!("wrote {}", args.doc.display());
    Ok(())
}

/// One run of our `mesh` on `case` at P3: its times and its report.
fn ours(work: &Work, case: &Path) -> Result<(Timed, Value)> {
    mesh_process(work, case, &["--order", "3"])
}

/// Cells of a report (quads and triangles).
fn cells_of(report: &Value) -> u64 {
    ["quad", "tri"]
        .iter()
        .filter_map(|k| report["cells"][k].as_u64())
        .sum()
}

/// One row of the comparison: ours and Gmsh's, alternating, `runs` times each.
fn vs_row(
    work: &Work,
    gmsh: Option<&(PathBuf, PathBuf)>,
    name: &str,
    first_height: f64,
    runs: usize,
) -> Result<VsRow> {
    let h = format!("first_height = {first_height:e}");
    let builtin_line = builtin::case_text(name)
        .and_then(|t| t.lines().find(|l| l.starts_with("first_height = ")))
        .context("no first_height in the built-in case")?;
    let case = work.case(name, &[(builtin_line, &h)])?;
    // the warm-up run: our cell count, which Gmsh's size is calibrated to
    let (_, report) = ours(work, &case)?;
    let cells = cells_of(&report);
    let gmsh_run = gmsh
        .map(|g| GmshRun::calibrated(g, work, name, first_height, cells))
        .transpose()?;
    let (mut us, mut them) = (Vec::new(), Vec::new());
    let mut side = None;
    for _ in 0..runs {
        us.push(ours(work, &case)?.0);
        if let Some(g) = &gmsh_run {
            let (time, result) = g.run()?;
            them.push(time);
            side = Some(result);
        }
    }
    Ok(VsRow {
        case: name.to_string(),
        first_height,
        cells,
        ours: medians(&us),
        gmsh: side.map(|s| (s, medians(&them))),
    })
}

/// Gmsh's side of one row, its size calibrated.
struct GmshRun {
    command: Vec<std::ffi::OsString>,
    python: PathBuf,
}

impl GmshRun {
    fn calibrated(
        (python, script): &(PathBuf, PathBuf),
        work: &Work,
        name: &str,
        first_height: f64,
        cells: u64,
    ) -> Result<GmshRun> {
        let mut command: Vec<std::ffi::OsString> = vec![script.into()];
        let geometry = work.dir.join("geometry");
        let dats: &[&str] = match name {
            "30p30n" => &["30p30n/slat.dat", "30p30n/main.dat", "30p30n/flap.dat"],
            _ => &["naca0012.dat"],
        };
        for dat in dats {
            command.push("--dat".into());
            command.push(geometry.join(dat).into());
        }
        command.push("--first-height".into());
        command.push(format!("{first_height:e}").into());
        let out = Command::new(python)
            .args(&command)
            .arg("--calibrate")
            .arg(cells.to_string())
            .output()?;
        let line: Value = serde_json::from_slice(&out.stdout).unwrap_or(Value::Null);
        // a geometry Gmsh cannot mesh keeps size 1: the timed runs then report its failure
        let size = line["size"].as_f64().unwrap_or(1.0);
        command.push("--size".into());
        command.push(size.to_string().into());
        command.push("--out".into());
        command.push(work.dir.join("gmsh.msh").into());
        Ok(GmshRun {
            command,
            python: python.clone(),
        })
    }

    /// One timed run: its times and what it printed (or how it ended).
    fn run(&self) -> Result<(Timed, GmshSide)> {
        let (time, out) = timed(Command::new(&self.python).args(&self.command))?;
        let line: Value = serde_json::from_slice(&out.stdout).unwrap_or(Value::Null);
        let side = match (line["cells"].as_u64(), out.status.code()) {
            (Some(cells), _) => GmshSide::Meshed {
                cells,
                invalid: line["invalid"].as_u64().unwrap_or(0),
                steps: line["done"].to_string(),
            },
            (None, _) if line["failed"].is_string() => {
                GmshSide::Failed(line["failed"].as_str().unwrap_or_default().to_string())
            }
            (None, code) => GmshSide::Failed(match code {
                Some(c) => format!("exit status {c}: {}", last_line(&out.stderr)),
                None => format!("aborted: {}", last_line(&out.stderr)),
            }),
        };
        Ok((time, side))
    }
}

fn last_line(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes)
        .lines()
        .last()
        .unwrap_or_default()
        .trim()
        .to_string()
}

/// One scaling point: our run on `case`, `runs` times.
fn scaling_row(work: &Work, case: &Path, spacing: f64, runs: usize) -> Result<ScalingRow> {
    let mut times = Vec::new();
    let mut reports = Vec::new();
    for _ in 0..runs.max(1) {
        let (time, report) = ours(work, case)?;
        times.push(time);
        reports.push(report);
    }
    let report = &reports[0];
    let mut peaks: Vec<f64> = reports
        .iter()
        .filter_map(|r| r["peak_memory_bytes"].as_f64())
        .collect();
    Ok(ScalingRow {
        max_spacing: spacing,
        runs: times.len(),
        cells: cells_of(report),
        nodes: report["nodes"].as_u64().unwrap_or(0),
        time: medians(&times),
        peak_bytes: if peaks.is_empty() {
            f64::NAN
        } else {
            median(&mut peaks)
        },
    })
}

/// The threads point: our run on `case` at `--threads 1` and at `--threads 2`, alternating,
/// `runs` times each.
fn threads_row(
    work: &Work,
    case: &Path,
    spacing: f64,
    runs: usize,
) -> Result<perf_doc::ThreadsRow> {
    let (mut one, mut two, mut cells) = (Vec::new(), Vec::new(), 0);
    let mut round_trips = Vec::new();
    for _ in 0..runs.max(1) {
        let (time, report) = mesh_process(work, case, &["--order", "3", "--threads", "1"])?;
        cells = cells_of(&report);
        one.push(time);
        two.push(mesh_process(work, case, &["--order", "3", "--threads", "2"])?.0);
        // the host's cross-core latency just after the two-thread run
        round_trips.push(crate::probe::round_trip_ns());
    }
    let mut two_walls: Vec<f64> = two.iter().map(|t| t.wall_s).collect();
    let (least, _, greatest) = spread(&mut two_walls);
    Ok(perf_doc::ThreadsRow {
        max_spacing: spacing,
        cells,
        runs: one.len(),
        one: medians(&one),
        two: medians(&two),
        two_range: (least, greatest),
        round_trip_ns: spread(&mut round_trips),
    })
}

/// The least, the median and the greatest of `values` (not empty; sorted on the way).
fn spread(values: &mut [f64]) -> (f64, f64, f64) {
    let middle = median(values);
    (values[0], middle, values[values.len() - 1])
}
