//! The measured parts of `docs/performance.md`, written by `cargo xtask bench --vs-gmsh
//! --scaling`: the comparison with Gmsh, the scaling table with its fitted exponent, and the
//! scaling plot (an SVG written here, `figures/performance-scaling.svg` beside the document).
//! Each part sits between its two marker comments and is replaced on the next run; the
//! rest of the document (written by hand) is kept.

use std::fmt::Write as _;
use std::path::Path;

use anyhow::{Context, Result};

/// Median wall and CPU seconds of one process.
#[derive(Debug, Clone, Copy)]
pub struct Times {
    /// Wall-clock seconds.
    pub wall_s: f64,
    /// User plus system CPU seconds (every thread).
    pub cpu_s: f64,
}

/// What Gmsh's side of a row did (its last run).
#[derive(Debug, Clone)]
pub enum GmshSide {
    /// A written P3 mesh: its cells, its elements left with minSJ <= 0, its steps.
    Meshed {
        /// Triangles and quadrangles.
        cells: u64,
        /// Elements with minSJ <= 0 at the end.
        invalid: u64,
        /// Each step with the invalid elements after it (JSON).
        steps: String,
    },
    /// No mesh: Gmsh's error, or how its process ended.
    Failed(String),
}

/// One row of the comparison.
#[derive(Debug, Clone)]
pub struct VsRow {
    /// The built-in case.
    pub case: String,
    /// The first layer's height.
    pub first_height: f64,
    /// Our cells.
    pub cells: u64,
    /// Our times.
    pub ours: Times,
    /// Gmsh's result and times, when Gmsh ran.
    pub gmsh: Option<(GmshSide, Times)>,
}

/// One point of the scaling study.
#[derive(Debug, Clone)]
pub struct ScalingRow {
    /// `[boundary] max_spacing` of the NACA0012.
    pub max_spacing: f64,
    /// Runs the medians are of.
    pub runs: usize,
    /// Cells (P3).
    pub cells: u64,
    /// Nodes (P3).
    pub nodes: u64,
    /// Median times.
    pub time: Times,
    /// Median peak resident memory in bytes.
    pub peak_bytes: f64,
}

/// One point of the scaling study at one thread and at two.
pub struct ThreadsRow {
    /// `[boundary] max_spacing` of the NACA0012.
    pub max_spacing: f64,
    /// Cells (P3).
    pub cells: u64,
    /// Runs at each thread count the medians are of.
    pub runs: usize,
    /// Median times at `--threads 1` and at `--threads 2`.
    pub one: Times,
    pub two: Times,
    /// The least and the greatest wall time at `--threads 2`.
    pub two_range: (f64, f64),
    /// The host's cross-core round trip after each two-thread run ([`crate::probe`]), in
    /// nanoseconds: least, median, greatest.
    pub round_trip_ns: (f64, f64, f64),
}

const VS: &str = "vs-gmsh";
const SCALING: &str = "scaling";
const THREADS: &str = "threads";
const PLOT: &str = "figures/performance-scaling.svg";

/// One printed line of the comparison.
pub fn vs_line(r: &VsRow) -> String {
    let mut line = format!(
        "{:<9} {:>6.0e}  ours {:>8} cells {:>7.3} s CPU {:>7.3} s wall",
        r.case, r.first_height, r.cells, r.ours.cpu_s, r.ours.wall_s
    );
    if let Some((side, t)) = &r.gmsh {
        let _ = write!(
            line,
            "  |  Gmsh {}  {:.3} s CPU {:.3} s wall  ratio {:.1}x CPU",
            gmsh_cells(side, r.cells),
            t.cpu_s,
            t.wall_s,
            t.cpu_s / r.ours.cpu_s
        );
    }
    line
}

/// One printed line of the scaling study.
pub fn scaling_line(r: &ScalingRow) -> String {
    format!(
        "max_spacing {:<7} {:>9} cells {:>8.3} s wall {:>8.3} s CPU {:>6.0} B/cell (median of {})",
        r.max_spacing,
        r.cells,
        r.time.wall_s,
        r.time.cpu_s,
        r.peak_bytes / r.cells as f64,
        r.runs
    )
}

/// The printed line of the threads point.
pub fn threads_line(r: &ThreadsRow) -> String {
    format!(
        "threads  max_spacing {}: one {:.3} s wall, two {:.3} s wall ({:.3}-{:.3}): {:.2}x \
         (median of {}); cross-core round trip {:.0} ns ({:.0}-{:.0})",
        r.max_spacing,
        r.one.wall_s,
        r.two.wall_s,
        r.two_range.0,
        r.two_range.1,
        r.one.wall_s / r.two.wall_s,
        r.runs,
        r.round_trip_ns.1,
        r.round_trip_ns.0,
        r.round_trip_ns.2
    )
}

/// Writes the threads point into the document at `doc`.
pub fn write_threads(doc: &Path, r: &ThreadsRow) -> Result<()> {
    replace_part(doc, THREADS, &threads_markdown(r))
}

/// The threads point as Markdown.
fn threads_markdown(r: &ThreadsRow) -> String {
    format!(
        "Measured by `cargo xtask bench --scaling`: the scaling study's NACA0012 at max_spacing \
         {} ({} P3 cells), `cargo xtask mesh CASE --order 3 --threads 1` and `--threads 2` \
         alternating, {} runs of each (medians).\n\n| threads | wall | CPU |\n|---|---|---|\n\
         | 1 | {:.3} s | {:.3} s |\n| 2 | {:.3} s | {:.3} s |\n\nTwo threads over one: \
         **{:.2}×** in wall time. The two-thread runs took {:.3}–{:.3} s. The host's \
         cross-core round trip (a cache line passed to another thread and back, timed after \
         each two-thread run) was {:.0} ns (median; {:.0}–{:.0} ns): where it is high (the \
         host's two virtual cores placed apart, or one of them held), data handed from one \
         thread to the other is slow and two-thread runs are slower.\n",
        r.max_spacing,
        r.cells,
        r.runs,
        r.one.wall_s,
        r.one.cpu_s,
        r.two.wall_s,
        r.two.cpu_s,
        r.one.wall_s / r.two.wall_s,
        r.two_range.0,
        r.two_range.1,
        r.round_trip_ns.1,
        r.round_trip_ns.0,
        r.round_trip_ns.2
    )
}

fn gmsh_cells(side: &GmshSide, ours: u64) -> String {
    match side {
        GmshSide::Meshed { cells, invalid, .. } => {
            let diff = 100.0 * (*cells as f64 - ours as f64) / ours as f64;
            format!("{cells} cells ({diff:+.1} %), {invalid} with minSJ <= 0")
        }
        GmshSide::Failed(why) => format!("no mesh ({why})"),
    }
}

/// The comparison table as Markdown.
fn vs_markdown(rows: &[VsRow], runs: usize, skipped: Option<&str>) -> String {
    let mut s = format!(
        "Measured by `cargo xtask bench --vs-gmsh` ({} cores seen; median of {runs} runs of \
         each whole process, ours and Gmsh's alternating; CPU is user + system time of every \
         thread). Ours: `cargo xtask mesh CASE --order 3` writing the `.msh` and the report, \
         every cell certified. Gmsh {}: `tests/python/gmsh_bench.py` (boundary-layer field of \
         quadrangles, `setOrder(3)`, its high-order optimisers only while some element has \
         minSJ <= 0, the `.msh` written), its size calibrated untimed to our cell count.\n\n",
        std::thread::available_parallelism().map_or(1, usize::from),
        "4.15"
    );
    if let Some(why) = skipped {
        let _ = writeln!(s, "Gmsh's side was skipped: {why}.\n");
    }
    s.push_str(
        "| case, P3 | first height | our cells | ours CPU | ours wall | Gmsh | Gmsh CPU | \
         Gmsh wall | ratio CPU | ratio wall |\n|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        let (gmsh, times) = match &r.gmsh {
            Some((side, t)) => (gmsh_cells(side, r.cells), Some(t)),
            None => ("not run".to_string(), None),
        };
        let seconds = |v: Option<f64>| v.map_or("—".to_string(), |v| format!("{v:.3} s"));
        let ratio =
            |a: Option<f64>, b: f64| a.map_or("—".to_string(), |a| format!("{:.1}×", a / b));
        let _ = writeln!(
            s,
            "| {} | {:e} | {} | {:.3} s | {:.3} s | {gmsh} | {} | {} | {} | {} |",
            r.case,
            r.first_height,
            r.cells,
            r.ours.cpu_s,
            r.ours.wall_s,
            seconds(times.map(|t| t.cpu_s)),
            seconds(times.map(|t| t.wall_s)),
            ratio(times.map(|t| t.cpu_s), r.ours.cpu_s),
            ratio(times.map(|t| t.wall_s), r.ours.wall_s),
        );
    }
    let steps: Vec<String> = rows
        .iter()
        .filter_map(|r| match &r.gmsh {
            Some((GmshSide::Meshed { steps, .. }, _)) => {
                Some(format!("{} {:e}: {steps}", r.case, r.first_height))
            }
            _ => None,
        })
        .collect();
    if !steps.is_empty() {
        let _ = writeln!(
            s,
            "\nGmsh's steps, each with its elements left with minSJ <= 0: {}.",
            steps.join("; ")
        );
    }
    s
}

/// The fitted exponent `b` of `time = a n^b` over `rows` (least squares in logs).
pub fn exponent(points: &[(f64, f64)]) -> Option<f64> {
    if points.len() < 2 {
        return None;
    }
    let logs: Vec<(f64, f64)> = points.iter().map(|(n, t)| (n.ln(), t.ln())).collect();
    let k = logs.len() as f64;
    let (mx, my) = logs
        .iter()
        .fold((0.0, 0.0), |(a, b), (x, y)| (a + x / k, b + y / k));
    let sxy: f64 = logs.iter().map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = logs.iter().map(|(x, _)| (x - mx) * (x - mx)).sum();
    (sxx > 0.0).then(|| sxy / sxx)
}

/// The scaling table as Markdown, with the fitted exponents and the plot.
fn scaling_markdown(rows: &[ScalingRow]) -> String {
    let mut s = String::from(
        "Measured by `cargo xtask bench --scaling`: our P3 pipeline on the NACA0012 (first \
         height 5e-5) made finer by `[boundary] max_spacing`, whole processes (`cargo xtask mesh \
         CASE --order 3`, the `.msh` and the report written, every thread the machine has); \
         peak memory is the run's own `peak_memory_bytes` (`getrusage`, the `VmHWM` of \
         `/proc/self/status`).\n\n| max_spacing | cells | nodes | runs | wall | CPU | µs per \
         cell (wall) | peak memory | bytes per cell |\n|---|---|---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {:.3} s | {:.3} s | {:.2} | {:.0} MiB | {:.0} |",
            r.max_spacing,
            r.cells,
            r.nodes,
            r.runs,
            r.time.wall_s,
            r.time.cpu_s,
            1e6 * r.time.wall_s / r.cells as f64,
            r.peak_bytes / 1048576.0,
            r.peak_bytes / r.cells as f64,
        );
    }
    let fit = |pick: fn(&ScalingRow) -> f64, from: usize| {
        let points: Vec<(f64, f64)> = rows
            .iter()
            .skip(from)
            .map(|r| (r.cells as f64, pick(r)))
            .collect();
        exponent(&points).map_or("—".to_string(), |b| format!("{b:.2}"))
    };
    let _ = writeln!(
        s,
        "\nFitted exponent b of time ∝ cells^b (least squares in logs): wall {}, CPU {} over \
         every point; wall {}, CPU {} from the second point on.\n\n![wall and CPU time \
         against cells, log-log]({PLOT})",
        fit(|r| r.time.wall_s, 0),
        fit(|r| r.time.cpu_s, 0),
        fit(|r| r.time.wall_s, 1),
        fit(|r| r.time.cpu_s, 1),
    );
    s
}

/// Writes the comparison into the document at `doc`.
pub fn write_vs(doc: &Path, rows: &[VsRow], runs: usize, skipped: Option<&str>) -> Result<()> {
    replace_part(doc, VS, &vs_markdown(rows, runs, skipped))
}

/// Writes the scaling study into the document at `doc`, and its plot beside it.
pub fn write_scaling(doc: &Path, rows: &[ScalingRow]) -> Result<()> {
    let plot = doc.parent().unwrap_or(Path::new(".")).join(PLOT);
    if let Some(dir) = plot.parent() {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot make {}", dir.display()))?;
    }
    std::fs::write(&plot, svg_plot(rows))
        .with_context(|| format!("cannot write {}", plot.display()))?;
    replace_part(doc, SCALING, &scaling_markdown(rows))
}

/// Replaces what lies between `<!-- NAME:begin -->` and `<!-- NAME:end -->` in `doc` by
/// `body` (the part is appended when missing; the document is made when missing).
pub(crate) fn replace_part(doc: &Path, name: &str, body: &str) -> Result<()> {
    let old = match std::fs::read_to_string(doc) {
        Ok(text) => text,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => "# Performance\n".to_string(),
        Err(e) => return Err(e).with_context(|| format!("cannot read {}", doc.display())),
    };
    let (begin, end) = (
        format!("<!-- {name}:begin -->"),
        format!("<!-- {name}:end -->"),
    );
    let part = format!("{begin}\n{body}{end}");
    let text = match (old.find(&begin), old.find(&end)) {
        (Some(b), Some(e)) if b < e => format!("{}{part}{}", &old[..b], &old[e + end.len()..]),
        _ => format!("{}\n{part}\n", old.trim_end()),
    };
    if let Some(dir) = doc.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot make {}", dir.display()))?;
    }
    let tmp = doc.with_extension("md.tmp");
    std::fs::write(&tmp, text).with_context(|| format!("cannot write {}", tmp.display()))?;
    std::fs::rename(&tmp, doc).with_context(|| format!("cannot write {}", doc.display()))
}

/// A log-log plot of wall and CPU time against cells, with a line ∝ cells through the first
/// point for reference.
fn svg_plot(rows: &[ScalingRow]) -> String {
    let (w, h, m) = (640.0, 420.0, 60.0);
    let points = |pick: fn(&ScalingRow) -> f64| -> Vec<(f64, f64)> {
        rows.iter()
            .map(|r| ((r.cells as f64).log10(), pick(r).log10()))
            .filter(|(x, y)| x.is_finite() && y.is_finite())
            .collect()
    };
    let (wall, cpu) = (points(|r| r.time.wall_s), points(|r| r.time.cpu_s));
    let all: Vec<&(f64, f64)> = wall.iter().chain(&cpu).collect();
    let range = |f: fn(&(f64, f64)) -> f64| {
        let lo = all
            .iter()
            .map(|p| f(p))
            .fold(f64::INFINITY, f64::min)
            .floor();
        let hi = all
            .iter()
            .map(|p| f(p))
            .fold(f64::NEG_INFINITY, f64::max)
            .ceil();
        if lo.is_finite() && hi > lo {
            (lo, hi)
        } else {
            (0.0, 1.0)
        }
    };
    let ((x0, x1), (y0, y1)) = (range(|p| p.0), range(|p| p.1));
    let sx = |x: f64| m + (x - x0) / (x1 - x0) * (w - 2.0 * m);
    let sy = |y: f64| h - m - (y - y0) / (y1 - y0) * (h - 2.0 * m);
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" \
         font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"{w}\" height=\"{h}\" \
         fill=\"white\"/>\n"
    );
    let axis = |s: &mut String, lo: f64, hi: f64, x_axis: bool| {
        let mut e = lo;
        while e <= hi + 1e-9 {
            let label = format!("1e{e:.0}");
            if x_axis {
                let x = sx(e);
                let _ = writeln!(
                    s,
                    "<line x1=\"{x:.1}\" y1=\"{m}\" x2=\"{x:.1}\" y2=\"{:.1}\" stroke=\"#ddd\"/>\
                     <text x=\"{x:.1}\" y=\"{:.1}\" text-anchor=\"middle\">{label}</text>",
                    h - m,
                    h - m + 16.0
                );
            } else {
                let y = sy(e);
                let _ = writeln!(
                    s,
                    "<line x1=\"{m}\" y1=\"{y:.1}\" x2=\"{:.1}\" y2=\"{y:.1}\" stroke=\"#ddd\"/>\
                     <text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"end\">{label} s</text>",
                    w - m,
                    m - 6.0,
                    y + 4.0
                );
            }
            e += 1.0;
        }
    };
    axis(&mut s, x0, x1, true);
    axis(&mut s, y0, y1, false);
    let series = |s: &mut String, pts: &[(f64, f64)], colour: &str, dash: &str| {
        let path: Vec<String> = pts
            .iter()
            .map(|&(x, y)| format!("{:.1},{:.1}", sx(x), sy(y)))
            .collect();
        let _ = writeln!(
            s,
            "<polyline points=\"{}\" fill=\"none\" stroke=\"{colour}\" stroke-width=\"2\" \
             stroke-dasharray=\"{dash}\"/>",
            path.join(" ")
        );
        for &(x, y) in pts {
            let _ = writeln!(
                s,
                "<circle cx=\"{:.1}\" cy=\"{:.1}\" r=\"3.5\" fill=\"{colour}\"/>",
                sx(x),
                sy(y)
            );
        }
    };
    series(&mut s, &wall, "#1f77b4", "none");
    series(&mut s, &cpu, "#d62728", "none");
    if let (Some(&(xa, ya)), Some(&(xb, _))) = (wall.first(), wall.last()) {
        series(&mut s, &[(xa, ya), (xb, ya + xb - xa)], "#999", "5,4");
    }
    let _ = writeln!(
        s,
        "<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"middle\">P3 cells (NACA0012)</text>\n\
         <text x=\"{m}\" y=\"24\" fill=\"#1f77b4\">wall</text>\
         <text x=\"{:.1}\" y=\"24\" fill=\"#d62728\">CPU</text>\
         <text x=\"{:.1}\" y=\"24\" fill=\"#999\">∝ cells</text>\n</svg>",
        w / 2.0,
        h - 16.0,
        m + 50.0,
        m + 100.0
    );
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exponent_of_a_power_law() {
        let points: Vec<(f64, f64)> = [1e4, 1e5, 1e6]
            .iter()
            .map(|&n: &f64| (n, 3.0 * n.powf(1.25)))
            .collect();
        assert!((exponent(&points).unwrap() - 1.25).abs() < 1e-12);
        assert_eq!(exponent(&points[..1]), None);
    }

    #[test]
    fn a_part_is_replaced_and_the_rest_kept() {
        let dir = tempfile::tempdir().unwrap();
        let doc = dir.path().join("p.md");
        std::fs::write(&doc, "# P\n\nby hand\n").unwrap();
        replace_part(&doc, "x", "one\n").unwrap();
        replace_part(&doc, "x", "two\n").unwrap();
        let text = std::fs::read_to_string(&doc).unwrap();
        assert_eq!(
            text,
            "# P\n\nby hand\n<!-- x:begin -->\ntwo\n<!-- x:end -->\n"
        );
    }
}
