//! `cargo xtask bench --3d`: whole 3D runs (`cargo xtask mesh CASE`, the `.msh` and the report
//! written) of the built-in 3D cases and of the built-in wing made long enough for about one
//! million tetrahedra, medians of `--runs`: wall and CPU time from outside (as `--scaling`),
//! each stage's time from the run's own report (`timings_s`), its peak memory and the bytes per
//! cell. Writes its table into `--doc` between `<!-- 3d:begin -->` and `<!-- 3d:end -->`. The
//! timing and the temporary case files are [`crate::bench_vs`]'s.

use std::fmt::Write as _;

use anyhow::Result;
use serde_json::Value;

use crate::runs::{Timed, Work, median, mesh_process};

use crate::perf_doc::{self, Times};

/// A row to run: (label, built-in case, `(from, to)` line edits of its case file).
type Spec = (
    &'static str,
    &'static str,
    &'static [(&'static str, &'static str)],
);

/// The rows.
const ROWS: [Spec; 7] = [
    ("sphere", "sphere", &[]),
    ("cube", "cube", &[]),
    ("step", "step", &[]),
    ("wing", "wing", &[]),
    ("wing, P2", "wing", &[("[cut]", P2)]),
    // the built-in wing 3.5 times as long: about 0.85M tetrahedra (the 1M-tet size)
    ("wing, span 7", "wing", &[("span = 2.0", "span = 7.0")]),
    (
        "wing, span 7, P2",
        "wing",
        &[("span = 2.0", "span = 7.0"), ("[cut]", P2)],
    ),
];
/// The edit that curves a case to P2 (put before its `[cut]` table).
const P2: &str = "[curving]\norder = 2\n\n[cut]";
/// `--tiny`: the smallest case, to check that the command works.
const TINY_ROWS: [Spec; 1] = [("step", "step", &[])];

/// The stages shown, in pipeline order (those no row has are left out).
const STAGES: [&str; 9] = [
    "surface", "check", "grow", "cut", "curving", "validate", "volume", "measure", "write",
];

/// One measured case.
struct Row {
    label: &'static str,
    /// Cells by type, e.g. "38400 prisms".
    cells: String,
    cell_count: u64,
    runs: usize,
    time: Times,
    /// Median seconds of each stage of [`STAGES`] (NaN when the report has none).
    stages: Vec<f64>,
    peak_bytes: f64,
}

/// Runs `--3d` and writes its part of `doc`.
pub fn run(work: &Work, runs: usize, tiny: bool, doc: &std::path::Path) -> Result<()> {
    let rows: &[Spec] = if tiny { &TINY_ROWS } else { &ROWS };
    let mut table = Vec::new();
    for &(label, name, edits) in rows {
        let case = work.case(name, edits)?;
        let (mut times, mut reports) = (Vec::new(), Vec::new());
        for _ in 0..runs.max(1) {
            let (time, report) = mesh_process(work, &case, &[])?;
            times.push(time);
            reports.push(report);
        }
        let row = row(label, &times, &reports);
        println!(
            "3d {:<14} {:>24} wall {:>8.3} s  CPU {:>8.3} s  peak {:>6.0} MiB",
            row.label,
            row.cells,
            row.time.wall_s,
            row.time.cpu_s,
            row.peak_bytes / 1048576.0
        );
        table.push(row);
    }
    perf_doc::replace_part(doc, "3d", &markdown(&table, runs))
}

/// The row of one case from its runs.
fn row(label: &'static str, times: &[Timed], reports: &[Value]) -> Row {
    let report = &reports[0];
    let mut parts = Vec::new();
    let mut cell_count = 0;
    for (key, name) in [
        ("tet", "tets"),
        ("pyramid", "pyramids"),
        ("prism", "prisms"),
        ("hex", "hexes"),
    ] {
        let n = report["cells"][key].as_u64().unwrap_or(0);
        if n > 0 {
            parts.push(format!("{n} {name}"));
            cell_count += n;
        }
    }
    let of = |f: &dyn Fn(&Value) -> Option<f64>| {
        let mut v: Vec<f64> = reports.iter().filter_map(f).collect();
        median(&mut v)
    };
    Row {
        label,
        cells: parts.join(", "),
        cell_count,
        runs: times.len(),
        time: crate::runs::medians(times),
        stages: STAGES
            .iter()
            .map(|s| of(&|r: &Value| r["timings_s"][*s].as_f64()))
            .collect(),
        peak_bytes: of(&|r: &Value| r["peak_memory_bytes"].as_f64()),
    }
}

/// The table, with the stage columns some row has.
fn markdown(rows: &[Row], runs: usize) -> String {
    let shown: Vec<usize> = (0..STAGES.len())
        .filter(|&i| rows.iter().any(|r| r.stages[i].is_finite()))
        .collect();
    let mut s = format!(
        "Measured by `cargo xtask bench --3d`: whole runs of `cargo xtask mesh CASE` (the `.msh` \
         and the report written, every thread the machine has), median of {runs} runs; the \
         stages' seconds are each run's own report (`timings_s`), the peak memory its \
         `peak_memory_bytes`.\n\n| case | cells | wall | CPU | peak memory | bytes per cell |"
    );
    for &i in &shown {
        let _ = write!(s, " {} |", STAGES[i]);
    }
    s.push_str("\n|---|---|---|---|---|---|");
    s.push_str(&"---|".repeat(shown.len()));
    s.push('\n');
    for r in rows {
        let _ = write!(
            s,
            "| {} | {} | {:.2} s | {:.2} s | {:.0} MiB | {:.0} |",
            r.label,
            r.cells,
            r.time.wall_s,
            r.time.cpu_s,
            r.peak_bytes / 1048576.0,
            r.peak_bytes / r.cell_count.max(1) as f64
        );
        for &i in &shown {
            if r.stages[i].is_finite() {
                let _ = write!(s, " {:.2} s |", r.stages[i]);
            } else {
                s.push_str(" — |");
            }
        }
        s.push('\n');
    }
    let _ = writeln!(s, "\nRuns per row: {}.", rows.first().map_or(0, |r| r.runs));
    s
}
