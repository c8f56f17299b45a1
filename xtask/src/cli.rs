//! The flags of `cargo xtask`: the `curvemesh` commands ([`curvemesh_cli::cli::Command`],
//! forwarded as they are) and the development tasks, `bench` and `figures`.

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand};

/// Curved (high-order) viscous mesh generation: Spring-Field and Vector-Adding.
#[derive(Debug, Parser)]
#[command(name = "cargo xtask", bin_name = "cargo xtask", version, long_about = None)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
// parsed once per run: the size of the largest variant costs nothing
#[allow(clippy::large_enum_variant)]
pub enum Command {
    /// The commands of `curvemesh`.
    #[command(flatten)]
    Tool(curvemesh_cli::cli::Command),
    /// Time each stage of the pipeline on the built-in cases (release build, one thread).
    Bench(BenchArgs),
    /// Regenerate every figure of the README and the user guide (docs/figures) from real runs.
    Figures(FiguresArgs),
}

/// Flags of `cargo xtask bench`.
#[derive(Debug, Args)]
pub struct BenchArgs {
    /// Fewer repetitions: a quick look rather than a measurement.
    #[arg(long)]
    pub quick: bool,

    /// Only these built-in cases (default: all).
    #[arg(long = "case", value_name = "NAME")]
    pub cases: Vec<String>,

    /// Whole runs side by side with Gmsh (its Python package in the checkers' venv,
    /// CHECKERS_VENV; skipped with a message when missing): NACA0012 and 30P30N at P3, first
    /// heights 5e-5 and 5e-6, alternating, medians of --runs; writes the table into --doc.
    #[arg(long)]
    pub vs_gmsh: bool,

    /// Whole runs of our P3 pipeline at about 10k, 100k, 1M and 4M cells (the 1M point at most
    /// 3 times, the 4M point once): wall and CPU time, peak memory, the fitted exponent and a
    /// plot; then the 1M point at --threads 1 and 2, alternating (at most 3 runs each), and
    /// two threads over one; writes them into --doc.
    #[arg(long)]
    pub scaling: bool,

    /// Whole runs of the built-in 3D cases and of the built-in wing made long enough for about
    /// 1M tetrahedra: wall and CPU time, each stage's time, peak memory; writes the table into
    /// --doc.
    #[arg(long = "3d")]
    pub three_d: bool,

    /// Runs of each process for --vs-gmsh, --scaling and --3d (default 3).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..))]
    pub runs: Option<u16>,

    /// --vs-gmsh, --scaling and --3d on a tiny configuration (one coarse row, two small points,
    /// the step, one run): checks that the commands work; the times mean nothing.
    #[arg(long)]
    pub tiny: bool,

    /// The document --vs-gmsh, --scaling and --3d write their parts into (between marker comments;
    /// the rest is kept), its plot in figures/ beside it.
    #[arg(long, value_name = "FILE.md", default_value = "docs/performance.md")]
    pub doc: PathBuf,
}

/// Flags of `cargo xtask figures`.
#[derive(Debug, Args)]
pub struct FiguresArgs {
    /// The folder the pictures go to (made if missing); run from the repository root.
    #[arg(long, value_name = "DIR", default_value = "docs/figures")]
    pub dir: PathBuf,

    /// Print nothing but errors.
    #[arg(long, short)]
    pub quiet: bool,
}
