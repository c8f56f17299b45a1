//! The processes the bench studies time: the work folder with the built-in cases written out
//! (edited where a study changes a key), our `mesh` run as a child process with its wall
//! and CPU time and its report, Gmsh's Python found, and medians.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use anyhow::{Context, Result, bail};
use curvemesh::builtin;
use curvemesh_cli::resources;
use serde_json::Value;

use crate::perf_doc;

/// Gmsh's side, embedded so that the command works from any folder.
const GMSH_SCRIPT: &str = include_str!("../../tests/python/gmsh_bench.py");

/// One timed process.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Timed {
    pub(crate) wall_s: f64,
    pub(crate) cpu_s: f64,
}

/// The temporary folder of the cases and meshes, and this binary.
pub(crate) struct Work {
    pub(crate) dir: PathBuf,
    pub(crate) exe: PathBuf,
}

impl Work {
    pub(crate) fn new() -> Result<Work> {
        let dir = std::env::temp_dir().join(format!("curvemesh-bench-{}", std::process::id()));
        for path in ["cases", "geometry/30p30n"] {
            std::fs::create_dir_all(dir.join(path))
                .with_context(|| format!("cannot make {}", dir.display()))?;
        }
        Ok(Work {
            dir,
            exe: std::env::current_exe().context("cannot find this program's path")?,
        })
    }

    /// The scaling study's case: the built-in NACA0012 with `[boundary] max_spacing` set.
    pub(crate) fn naca0012_at(&self, spacing: f64) -> Result<PathBuf> {
        let spacing = format!("max_spacing = {spacing}");
        self.case("naca0012", &[("max_spacing = 1.0", &spacing)])
    }

    /// Writes built-in case `name` with each `(from, to)` line replaced (its data files
    /// beside it) and returns its path.
    pub(crate) fn case(&self, name: &str, edits: &[(&str, &str)]) -> Result<PathBuf> {
        let mut text = builtin::case_text(name)
            .with_context(|| format!("no built-in case {name}"))?
            .to_string();
        for (from, to) in edits {
            if !text.contains(from) {
                bail!("built-in case {name} has no line {from:?} to change");
            }
            text = text.replacen(from, to, 1);
        }
        for line in text.lines() {
            let Some(file) = line
                .strip_prefix("file = \"")
                .and_then(|l| l.strip_suffix('"'))
            else {
                continue;
            };
            let data = builtin::data_file(file).with_context(|| format!("no data file {file}"))?;
            let path = self.dir.join("cases").join(file);
            std::fs::write(&path, data)
                .with_context(|| format!("cannot write {}", path.display()))?;
        }
        let stem: String = edits
            .iter()
            .map(|(_, to)| to.replace([' ', '='], ""))
            .collect();
        let path = self.dir.join("cases").join(format!("{name}{stem}.toml"));
        std::fs::write(&path, text).with_context(|| format!("cannot write {}", path.display()))?;
        Ok(path)
    }

    /// The checkers' Python with Gmsh and the script's path, or why Gmsh's side is skipped.
    pub(crate) fn gmsh(&self) -> Result<std::result::Result<(PathBuf, PathBuf), String>> {
        let venv = std::env::var_os("CHECKERS_VENV").map_or_else(
            || Path::new(env!("CARGO_MANIFEST_DIR")).join("../.venv-checkers"),
            PathBuf::from,
        );
        let python = venv.join("bin/python");
        let found = Command::new(&python)
            .args(["-c", "import gmsh"])
            .output()
            .is_ok_and(|o| o.status.success());
        if !found {
            return Ok(Err(format!(
                "no Python with Gmsh at {} (bash tests/python/install.sh, or set CHECKERS_VENV)",
                python.display()
            )));
        }
        let script = self.dir.join("gmsh_bench.py");
        std::fs::write(&script, GMSH_SCRIPT)
            .with_context(|| format!("cannot write {}", script.display()))?;
        Ok(Ok((python, script)))
    }
}

/// Runs `command` to its end: its wall and CPU time, its stdout.
pub(crate) fn timed(command: &mut Command) -> Result<(Timed, std::process::Output)> {
    let cpu = resources::children_cpu_s();
    let t = Instant::now();
    let out = command
        .output()
        .with_context(|| format!("cannot run {command:?}"))?;
    let wall_s = t.elapsed().as_secs_f64();
    let cpu_s = resources::children_cpu_s()
        .zip(cpu)
        .map_or(f64::NAN, |(after, before)| after - before);
    Ok((Timed { wall_s, cpu_s }, out))
}

/// One run of our `mesh` on `case` with the `extra` flags, writing a `.msh` and the report:
/// its times and its report.
pub(crate) fn mesh_process(work: &Work, case: &Path, extra: &[&str]) -> Result<(Timed, Value)> {
    let msh = work.dir.join("ours.msh");
    let report = work.dir.join("ours.json");
    // the last run's mesh removed first, untimed: writing over a file of some 500 MB costs
    // system time, and its pages still being written back costs CPU, that a fresh file does
    // not
    let _ = std::fs::remove_file(&msh);
    let (time, out) = timed(
        Command::new(&work.exe)
            .arg("mesh")
            .args(extra)
            .args(["-q", "--out"])
            .arg(&msh)
            .arg("--report")
            .arg(&report)
            .arg(case),
    )?;
    if !out.status.success() {
        bail!(
            "{} failed: {}",
            case.display(),
            String::from_utf8_lossy(&out.stderr).trim()
        );
    }
    let text = std::fs::read_to_string(&report)?;
    Ok((time, serde_json::from_str(&text)?))
}

/// The medians of the wall and CPU times.
pub(crate) fn medians(runs: &[Timed]) -> perf_doc::Times {
    let mut wall: Vec<f64> = runs.iter().map(|t| t.wall_s).collect();
    let mut cpu: Vec<f64> = runs.iter().map(|t| t.cpu_s).collect();
    perf_doc::Times {
        wall_s: median(&mut wall),
        cpu_s: median(&mut cpu),
    }
}

/// The median of `v` (NaN when empty).
pub(crate) fn median(v: &mut [f64]) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}
