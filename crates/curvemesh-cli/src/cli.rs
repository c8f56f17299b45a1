//! Command-line flags of every subcommand, in one place. Flags whose values are lists of
//! numbers (`--view x0,y0,x1,y1`, `--png FILE@VIEW`) accept values that start with a minus
//! sign. Errors become one line and exit status 1 in [`crate::exit`]. `cargo xtask`
//! takes the same [`Command`]s beside its development tasks.

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand};

/// Curved (high-order) viscous mesh generation: Spring-Field and Vector-Adding.
#[derive(Debug, Parser)]
#[command(name = "curvemesh", bin_name = "curvemesh", version, long_about = None)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Mesh a case: boundary curves, 1D boundary mesh, then the layered domain mesh.
    Mesh(MeshArgs),
    /// Check a mesh file, 2D or 3D: structure, orientation, conformity, angles (3D: dihedral
    /// angles, volumes), the certified Jacobian at P2/P3; draw it on request.
    Quality(QualityArgs),
    /// Move the bodies of a meshed case (rigid motion, Hicks-Henne bumps) and re-curve the
    /// moved mesh: same topology, every cell certified.
    Move(MoveArgs),
}

/// Flags of `cargo xtask mesh`.
#[derive(Debug, Args)]
pub struct MeshArgs {
    /// A case file (.toml), the name of a built-in case (see --list), or airfoil coordinate
    /// files (.dat, Selig or Lednicer; several for a multi-element airfoil, each a wall named
    /// after its file, placed by its own coordinates). Default: the 30P30N.
    #[arg(value_name = "CASE | FILE.dat...")]
    pub case: Vec<String>,

    /// For .dat inputs: how the airfoil is placed and meshed.
    #[command(flatten)]
    pub airfoil: AirfoilArgs,

    /// List the built-in cases and exit.
    #[arg(long)]
    pub list: bool,

    /// The order, the mesh files and the report.
    #[command(flatten)]
    pub output: OutputArgs,

    /// Save the intermediate stages (boundary nodes, the layered linear mesh with its layers,
    /// pipes and node parents) to this binary snapshot, for later stages or inspection.
    #[arg(long, value_name = "FILE.bin")]
    pub snapshot: Option<PathBuf>,

    /// Pictures of the mesh.
    #[command(flatten)]
    pub pictures: PictureArgs,

    /// Refuse a case expected to make more cells than this (the estimate is made from the
    /// boundary mesh, before the domain is meshed).
    #[arg(long, value_name = "N", allow_hyphen_values = true,
          default_value_t = curvemesh::estimate::DEFAULT_MAX_CELLS)]
    pub max_cells: u64,

    /// Write the .msh outputs as binary MSH 4.1, for large meshes: about 3/4 the size of text
    /// and faster to write and read. Gmsh reads it; PyFR (3.1) reads text .msh only.
    #[arg(long)]
    pub binary: bool,

    /// Threads for the parallel stages (the layers' solves and checks, the fill, the curving,
    /// the certification, the writers); default: every core (or RAYON_NUM_THREADS). The
    /// files written are the same whatever the number.
    #[arg(long, value_name = "N", allow_hyphen_values = true,
          value_parser = clap::value_parser!(u16).range(1..))]
    pub threads: Option<u16>,

    /// No summary table on stdout and no progress on stderr; errors are still printed.
    #[arg(long, short)]
    pub quiet: bool,
}

/// Flags of `cargo xtask move`.
#[derive(Debug, Args)]
pub struct MoveArgs {
    /// A case file (.toml) or the name of a built-in case: it is meshed first with its own
    /// parameters, then moved.
    #[arg(value_name = "CASE")]
    pub case: String,

    /// Start from this snapshot of the case written by `cargo xtask mesh CASE --snapshot
    /// FILE.bin` (its boundary nodes and layered linear mesh) instead of meshing the case.
    #[arg(long, value_name = "FILE.bin")]
    pub snapshot: Option<PathBuf>,

    /// The motion.
    #[command(flatten)]
    pub motion: MotionArgs,

    /// How the nodes inside the domain follow the moved boundary.
    #[arg(long, value_enum, default_value_t = MoveMethod::Springs)]
    pub method: MoveMethod,

    /// Ask for a smooth function of the motion: the spring mover always is (its shape
    /// balance converged by Newton's method); refused with `--method idw|rbf`. Kept for
    /// scripts written when it was an option.
    #[arg(long, hide = true)]
    pub smooth: bool,

    /// Write the motion as a sequence: N + 1 meshes from none of it to all of it in N equal
    /// steps (angles, translations and bump amplitudes times k/N, scale factors to the power
    /// k/N), each moved from the original mesh (no drift), same topology; every output name
    /// gets `-000` … `-N` before its extension.
    #[arg(long, value_name = "N")]
    pub steps: Option<usize>,

    /// Also write the mesh sensitivities to this CSV file: every node of the written mesh
    /// (linear and high-order) with its derivative with respect to each design variable of
    /// the motion (each moved loop's rotation, translation x and y, scale, and each bump's
    /// amplitude), from the linearised balance of the spring mover.
    #[arg(long, value_name = "FILE.csv")]
    pub sensitivities: Option<PathBuf>,

    /// The radial basis function of `--method rbf`.
    #[arg(long, value_enum, default_value_t = RbfKernel::WendlandC2)]
    pub kernel: RbfKernel,

    /// Support radius of the Wendland C2 kernel of `--method rbf` (default: the mesh's
    /// bounding-box diagonal, so every boundary node acts everywhere).
    #[arg(long, value_name = "R", allow_hyphen_values = true)]
    pub radius: Option<f64>,

    /// The order, the mesh files (default out/CASE-moved.msh) and the report.
    #[command(flatten)]
    pub output: OutputArgs,

    /// Pictures of the moved mesh.
    #[command(flatten)]
    pub pictures: PictureArgs,

    /// No summary table on stdout and no progress on stderr; errors are still printed.
    #[arg(long, short)]
    pub quiet: bool,
}

/// The order and the files of the mesh made by `mesh` or `move`.
#[derive(Debug, Args)]
pub struct OutputArgs {
    /// Polynomial order of the cells, overriding the case: 1 (linear), 2 or 3.
    #[arg(long, value_name = "P", allow_hyphen_values = true,
          value_parser = clap::value_parser!(u8).range(1..=i64::from(curvemesh::case::MAX_ORDER)))]
    pub order: Option<u8>,

    /// Output mesh file; the format follows the extension: .msh (Gmsh 4.1 ASCII), .vtu (VTK
    /// XML, Lagrange cells for P2/P3) or .su2 (linear). May be given several times.
    /// Default: out/CASE.msh (`move`: out/CASE-moved.msh); at an --order other than the
    /// case's, out/CASE-pN.msh, so that no mesh of the case's own order is replaced.
    #[arg(long = "out", value_name = "FILE")]
    pub outs: Vec<PathBuf>,

    /// Write the JSON report (cells, layers, timings, quality; `move`: the movement) to this
    /// file. Default when no --out is given: out/CASE.json (`move`: out/CASE-moved.json;
    /// out/CASE-pN.json at an --order other than the case's).
    #[arg(long, value_name = "FILE.json")]
    pub report: Option<PathBuf>,

    /// Cut every quad along its shorter diagonal into two triangles.
    #[arg(long)]
    pub triangles: bool,
}

/// The motion of `cargo xtask move`: a motion file, or the flags of one loop's motion.
#[derive(Debug, Args)]
pub struct MotionArgs {
    /// The motion of every loop from a TOML file (`[[motion]]` tables, see the README);
    /// not with the flags below.
    #[arg(long, value_name = "FILE.toml")]
    pub motion: Option<PathBuf>,

    /// The loop the flags move (default: the wall, when the case has one).
    #[arg(long = "loop", value_name = "NAME")]
    pub loop_name: Option<String>,

    /// Rotation in degrees, counter-clockwise, about --about.
    #[arg(long, value_name = "DEG", allow_hyphen_values = true)]
    pub rotate: Option<f64>,

    /// Centre of the rotation and of the scaling (default 0,0).
    #[arg(long, value_name = "X,Y", allow_hyphen_values = true, value_parser = parse_pair)]
    pub about: Option<[f64; 2]>,

    /// Translation, applied after the scaling and the rotation.
    #[arg(long, value_name = "DX,DY", allow_hyphen_values = true, value_parser = parse_pair)]
    pub translate: Option<[f64; 2]>,

    /// Uniform scale factor about --about (> 0), applied first.
    #[arg(long, value_name = "S", allow_hyphen_values = true)]
    pub scale: Option<f64>,

    /// A Hicks-Henne bump of the wall, applied before the rigid motion:
    /// `POSITION,AMPLITUDE[,WIDTH][,upper|lower]` — peak position along the chord in (0, 1),
    /// amplitude in chords (positive outward), width exponent (default 3), surface (default
    /// upper). May be given several times.
    #[arg(
        long = "bump",
        value_name = "P,A[,W][,SIDE]",
        allow_hyphen_values = true
    )]
    pub bumps: Vec<String>,
}

/// The movers of `cargo xtask move --method`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum MoveMethod {
    /// The Spring-Field on the mesh's own layers: the near-wall layers keep their original
    /// shape, the rest follows (mesh-move's spring mover).
    Springs,
    /// Rotation-aware inverse-distance weighting (Witteveen & Bijl).
    Idw,
    /// Radial basis functions with a linear polynomial (de Boer et al.), see --kernel.
    Rbf,
}

/// The kernels of `--method rbf`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum RbfKernel {
    /// Wendland C2, support --radius (default the bounding-box diagonal: global).
    WendlandC2,
    /// The thin-plate spline r² ln r.
    ThinPlate,
}

/// `X,Y` as two numbers.
fn parse_pair(text: &str) -> Result<[f64; 2], String> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    let &[x, y] = parts.as_slice() else {
        return Err(format!("give two numbers X,Y, got {text:?}"));
    };
    let num = |v: &str| {
        v.parse::<f64>()
            .map_err(|_| format!("{v:?} is not a number (in {text:?})"))
    };
    Ok([num(x)?, num(y)?])
}

/// Flags for airfoil `.dat` inputs (`cargo xtask mesh A.dat [B.dat ...]`).
#[derive(Debug, Args)]
pub struct AirfoilArgs {
    /// Angle of attack in degrees, positive nose up: every element rotates about the quarter
    /// chord (x_min + c/4, y of the leading edge), c the x-extent of all elements (.dat only;
    /// default 0).
    #[arg(long, value_name = "DEG", allow_hyphen_values = true)]
    pub aoa: Option<f64>,

    /// Far-field circle radius in chords, about the quarter chord (.dat only; default 30).
    #[arg(long, value_name = "R", allow_hyphen_values = true)]
    pub farfield: Option<f64>,

    /// Target y+ of the first layer. First height y = y+ c / (Re sqrt(Cf/2)),
    /// Cf = 0.026 / Re^(1/7): the flat-plate skin friction (Schlichting, White) at x = c, for
    /// U = 1 and nu = c / Re (.dat only; default 1).
    #[arg(long, value_name = "Y", allow_hyphen_values = true)]
    pub yplus: Option<f64>,

    /// Reynolds number based on the chord, for --yplus (.dat only; default 1e6).
    #[arg(long, value_name = "RE", allow_hyphen_values = true)]
    pub re: Option<f64>,

    /// The first layer's height, instead of the one --yplus and --re give (.dat only; the
    /// case file's `[layers] first_height`).
    #[arg(long, value_name = "H", allow_hyphen_values = true)]
    pub first_height: Option<f64>,

    /// The ratio of one layer's height to the one below (.dat only; default 1.3, the case
    /// file's `[layers] growth`).
    #[arg(long, value_name = "G", allow_hyphen_values = true)]
    pub growth: Option<f64>,

    /// The most layers grown from any boundary (.dat only; the case file's `[layers]
    /// max_layers`).
    #[arg(long, value_name = "N", allow_hyphen_values = true)]
    pub layers: Option<u32>,

    /// One boundary group `wall` for all the elements instead of one per element (.dat only;
    /// case files say `merge_walls = true`).
    #[arg(long)]
    pub merge_walls: bool,
}

/// Flags of `cargo xtask quality`.
#[derive(Debug, Args)]
pub struct QualityArgs {
    /// The mesh to check (Gmsh MSH 4.1 ASCII).
    pub mesh: PathBuf,

    /// Write the JSON report to this file.
    #[arg(long, value_name = "FILE.json")]
    pub report: Option<PathBuf>,

    /// Pictures of the mesh.
    #[command(flatten)]
    pub pictures: PictureArgs,

    /// No summary table on stdout.
    #[arg(long, short)]
    pub quiet: bool,
}

/// Picture flags, shared by `mesh`, `move` and `quality`.
#[derive(Debug, Args)]
pub struct PictureArgs {
    /// Draw the mesh to a PNG picture; `FILE@VIEW` picks the view: `all`, `walls`, a view
    /// named in the case's `[views]` (built-in cases: `le`, `te`, and for the 30P30N
    /// `slat-cove`, `flap-gap`) or `x0,y0,x1,y1`. May be given several times.
    #[arg(long = "png", value_name = "FILE[@VIEW]", allow_hyphen_values = true)]
    pub pngs: Vec<String>,

    /// Draw the mesh to an SVG picture (edges shorter than a pixel are skipped); `FILE@VIEW`
    /// as for --png. May be given several times.
    #[arg(long = "svg", value_name = "FILE[@VIEW]", allow_hyphen_values = true)]
    pub svgs: Vec<String>,

    /// The view of pictures given without `@VIEW` (default: all); `x0,y0,x1,y1` may start
    /// with a minus sign.
    #[arg(long, value_name = "VIEW", allow_hyphen_values = true)]
    pub view: Option<String>,

    /// What colours the cells in pictures (default: layer for `mesh`; angle for `quality`,
    /// since a .msh file keeps no layer index; type for 3D slices).
    #[arg(long, value_enum)]
    pub colour: Option<Colour>,

    /// 3D cases and meshes: the plane the pictures cut through the volume, `x=C`, `y=C` or
    /// `z=C` (default: z through the middle of the mesh); views are in the plane's
    /// coordinates ((y, z) for x, (z, x) for y, (x, y) for z).
    #[arg(long, value_name = "AXIS=VALUE", allow_hyphen_values = true)]
    pub slice: Option<String>,

    /// Width of PNG pictures in pixels (the height is three quarters of it).
    #[arg(long, value_name = "PX", default_value_t = 2000, allow_hyphen_values = true,
          value_parser = clap::value_parser!(u32).range(64..=16384))]
    pub width: u32,
}

/// What the cells are coloured by (`--colour`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Colour {
    /// Edges only.
    None,
    /// Layer index counted from the boundary each cell grew from.
    Layer,
    /// Largest interior angle (quads cut along the shorter diagonal).
    Angle,
    /// Certified scaled Jacobian (min J / max J) of each cell.
    Jacobian,
    /// 3D slices: the type of the cell each polygon lies in (tet, pyramid, prism, hex).
    Type,
    /// 3D slices: the largest dihedral angle of the tetrahedron each polygon lies in (other
    /// cells without a value).
    Dihedral,
}
