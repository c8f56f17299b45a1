//! `cargo xtask move`: mesh a case (or read its snapshot), move its loops by a motion (rigid
//! motion with uniform scaling, Hicks–Henne bumps; `mesh_move`), refit the moved loops' C2
//! curves and put each boundary node on its moved curve at its own parameter `t`, move the
//! other linear nodes with the chosen mover, re-curve the moved layered mesh (Vector-Adding),
//! certify every cell and write the meshes, pictures and report as `mesh` does (all or
//! nothing). A bad motion — a non-finite value, an unknown loop, a scale ≤ 0, a body pushed
//! through another or out of the far field — is refused with one line before any work.

use std::time::Instant;

use anyhow::{Context, Result, bail, ensure};
use boundary1d::BoundaryNodes;
use geom_curve::{ClosedCurve, Point2, loops};
use mesh_model::{LayeredMesh, Role};
use mesh_move::motion::{IDENTITY, Mat2, resolve_motions};
use mesh_move::{
    BoundaryLoop, BoundaryMotion, HicksHenne, IdwParams, Kernel, LoopMotion, Method, Motion,
    RbfParams, RigidMotion, SpringMoveParams, Surface, move_loops,
};
use serde::{Deserialize, Serialize};

use crate::cli::{MotionArgs, MoveArgs, MoveMethod, RbfKernel};
use crate::mesh_cmd::{self, OutputFlags};
use crate::progress::stage;
use crate::report::Report;
use crate::stages::Snapshot;
use crate::{Finished, case, pipeline};

/// Runs `cargo xtask move`, in a pool of one thread per core entered by this thread (see
/// [`crate::pool`]).
pub fn run(args: &MoveArgs) -> Result<Finished> {
    crate::pool::in_pool(None, || run_here(args))?
}

fn run_here(args: &MoveArgs) -> Result<Finished> {
    let total = Instant::now();
    let case = case::load(&args.case)?;
    let order = args.output.order.unwrap_or(case.order);
    check_flags(args)?;
    let motions = motions(&args.motion, &case)?;
    let moved = moved_geometry(&case, &motions)?;
    let flags = OutputFlags {
        outs: &args.output.outs,
        report: args.output.report.as_deref(),
        snapshot: None,
        pictures: &args.pictures,
    };
    let plan = mesh_cmd::plan(&flags, &format!("{}-moved", case.file_stem()), &case.views)?;

    let mut report = Report::new(&case.name, order);
    let (nodes, layered) = start(args, &case, &mut report)?;
    let boundary = boundary_targets(&moved, &nodes, &layered)?;
    let t = Instant::now();
    let progress = stage(args.quiet, "moving the linear nodes");
    let method = method(args);
    let linear = mesh_move::move_layered(&layered, &boundary, &method)
        .map_err(|e| anyhow::anyhow!("moving the mesh: {e}"))?;
    drop(progress);
    report.timings_s.insert("move", t.elapsed().as_secs_f64());
    let moved_layered = LayeredMesh {
        mesh: linear.mesh,
        layering: layered.layering.clone(),
    };
    let comparison = mesh_move::compare(&layered.mesh, &moved_layered.mesh)
        .map_err(|e| anyhow::anyhow!("comparing the meshes: {e}"))?;
    let mut decisions = None;
    let mesh = if linear.stats.inverted_cells > 0 {
        // an inverted linear mesh cannot be curved: it is written as it is, and fails
        report.order = 1;
        report.notes.push(format!(
            "the mover inverted {} linear cells: the moved linear mesh is written, not curved",
            linear.stats.inverted_cells
        ));
        moved_layered.mesh.clone()
    } else if order == 1 {
        mesh_cmd::linear_at_order(&moved_layered, args.output.triangles, &mut report)
    } else {
        let curved = curve_keeping(
            (&case, &moved),
            &nodes,
            (&layered, &moved_layered),
            (order, args.output.triangles),
            args.quiet,
            &mut report,
        )?;
        decisions = Some(curved.decisions);
        curved.mesh
    };
    let sensitivities = match &args.sensitivities {
        Some(_) if linear.stats.inverted_cells == 0 => {
            let t = Instant::now();
            let progress = stage(args.quiet, "mesh sensitivities");
            let balance = balance_at(&layered, &moved_layered, &boundary)?;
            let at = crate::move_sens::At {
                case: &case,
                motions: &motions,
                nodes: &nodes,
                moved: &moved_layered,
                balance: &balance,
                curving: decisions.as_ref().map(|d| (d, order)),
            };
            let vars = crate::move_sens::variables(&motions);
            let columns = crate::move_sens::sensitivities(&at, &vars)?;
            drop(progress);
            report
                .timings_s
                .insert("sensitivities", t.elapsed().as_secs_f64());
            Some(columns)
        }
        _ => None,
    };
    let movement = MovementReport::new(
        &motions,
        args,
        &linear.stats,
        &comparison,
        (&layered.mesh, &moved_layered.mesh),
    );
    let summary = movement.summary();
    report.movement = Some(movement);
    let run = mesh_cmd::Run {
        pictures: &args.pictures,
        name: &case.name,
        quiet: args.quiet,
        total,
    };
    let linear_mesh = &moved_layered.mesh;
    let report_path = mesh_cmd::check_and_write(
        plan,
        (&mesh, crate::report::LinearAngles::Of(linear_mesh)),
        None,
        &run,
        &mut report,
    )?;
    // written only with a valid mesh
    let valid = report.problems.is_empty();
    if let (Some(path), Some(columns), true) = (&args.sensitivities, &sensitivities, valid) {
        {
            let xy: Vec<[f64; 2]> = (0..mesh.nodes.len() as u32).map(|k| mesh.xy(k)).collect();
            mesh_io::sensitivities::write_sensitivities(path, &xy, columns)
                .map_err(|e| anyhow::anyhow!("--sensitivities {}: {e}", path.display()))?;
        }
    }
    let finished = report.finish(
        report_path.as_deref(),
        args.quiet,
        "the moved mesh was written but",
    );
    if !args.quiet {
        print!("{summary}");
    }
    Ok(finished)
}

/// `--smooth` and `--sensitivities` need the springs; the sensitivities are a CSV file.
fn check_flags(args: &MoveArgs) -> Result<()> {
    ensure!(
        args.method == MoveMethod::Springs || (args.sensitivities.is_none() && !args.smooth),
        "--smooth and --sensitivities need --method springs (the smooth balance)"
    );
    if let Some(path) = &args.sensitivities {
        ensure!(
            path.extension().is_some_and(|e| e == "csv"),
            "--sensitivities {}: the sensitivities are CSV: give a .csv file name",
            path.display()
        );
    }
    Ok(())
}

/// The smooth balance of the original mesh's shape field linearised at the moved nodes, the
/// boundary nodes fixed: what `--sensitivities` differentiates.
fn balance_at(
    original: &LayeredMesh,
    moved: &LayeredMesh,
    boundary: &BoundaryMotion,
) -> Result<mesh_move::Sensitivity> {
    let field = mesh_move::ShapeField::of(original, SpringMoveParams::smooth().shape)
        .map_err(|e| anyhow::anyhow!("sensitivities: {e}"))?;
    let x: Vec<[f64; 2]> = (0..moved.mesh.nodes.len() as u32)
        .map(|k| moved.mesh.xy(k))
        .collect();
    let mut fixed = vec![false; x.len()];
    boundary
        .nodes
        .iter()
        .for_each(|&k| fixed[k as usize] = true);
    field
        .linearise(&x, &fixed)
        .map_err(|e| anyhow::anyhow!("sensitivities: {e}"))
}

/// The moved layered mesh curved as the original one is (`vector_adding::curve_mesh_keeping`
/// with the original curving's decisions): a small motion flips no decision; the decisions
/// that had to change (a cell the kept decision would leave invalid) are counted in the
/// report and the first ones named in its notes.
fn curve_keeping(
    (case, moved): (&case::Case, &MovedGeometry),
    nodes: &[BoundaryNodes],
    (original, layered): (&LayeredMesh, &LayeredMesh),
    (order, triangles): (u8, bool),
    quiet: bool,
    report: &mut Report,
) -> Result<vector_adding::Curved> {
    let t = Instant::now();
    let progress = stage(
        quiet,
        "curving (Vector-Adding, the original's decisions kept)",
    );
    let curves = pipeline::curves(case)?;
    let original = std::borrow::Cow::Borrowed(original);
    let before = pipeline::curved_mesh(case, &curves, nodes, original, order, triangles)?;
    let (curved, changes) = vector_adding::curve_mesh_keeping(
        layered,
        &pipeline::loop_curves(&moved.curves, nodes),
        &pipeline::curving_params(&moved.case, order, triangles),
        &before.decisions,
    )
    .map_err(|e| anyhow::anyhow!("curving: {e}"))?;
    drop(progress);
    report
        .timings_s
        .insert("curving", t.elapsed().as_secs_f64());
    report.curved_edge_fraction = Some(curved.stats.curved_edge_fraction);
    report.curving = Some(curved.stats.clone());
    report.curving_decisions_changed = Some(changes.len());
    for change in changes.iter().take(5) {
        report.notes.push(format!(
            "curving decision changed by the motion: {change:?}"
        ));
    }
    Ok(curved)
}

/// The mover of `--method` (and `--kernel`, `--radius`, `--smooth`).
fn method(args: &MoveArgs) -> Method {
    match args.method {
        MoveMethod::Springs if args.smooth || args.sensitivities.is_some() => {
            Method::Springs(SpringMoveParams::smooth())
        }
        MoveMethod::Springs => Method::Springs(SpringMoveParams::default()),
        MoveMethod::Idw => Method::Idw(IdwParams::default()),
        MoveMethod::Rbf => Method::Rbf(RbfParams {
            kernel: match args.kernel {
                RbfKernel::WendlandC2 => Kernel::WendlandC2,
                RbfKernel::ThinPlate => Kernel::ThinPlateSpline,
            },
            support_radius: args.radius,
        }),
    }
}

/// The boundary nodes and the layered linear mesh of the case: meshed with the case's own
/// parameters, or read from `--snapshot` (checked to be this case's: every boundary node on
/// its curve).
fn start(
    args: &MoveArgs,
    case: &case::Case,
    report: &mut Report,
) -> Result<(Vec<BoundaryNodes>, LayeredMesh)> {
    let Some(path) = &args.snapshot else {
        let (_, nodes, grown) =
            mesh_cmd::grow(case, args.quiet, crate::estimate::DEFAULT_MAX_CELLS, report)?;
        return Ok((nodes, grown.layered));
    };
    let snapshot: Snapshot =
        mesh_io::snapshot::load(path).with_context(|| format!("--snapshot {}", path.display()))?;
    let at = || format!("--snapshot {}", path.display());
    ensure!(
        snapshot.case == case.name,
        "{}: made from case '{}', not '{}'",
        at(),
        snapshot.case,
        case.name
    );
    let curves = pipeline::curves(case)?;
    ensure!(
        snapshot.boundary.len() == curves.len(),
        "{}: {} boundary loops, the case has {}",
        at(),
        snapshot.boundary.len(),
        curves.len()
    );
    for ((curve, bn), input) in curves.iter().zip(&snapshot.boundary).zip(&case.loops) {
        let tolerance = 1e-9 * curve.total_length();
        let off =
            bn.t.iter()
                .zip(&bn.points)
                .any(|(&t, p)| (curve.point(t) - p).norm() > tolerance);
        ensure!(
            !off && bn.t.len() == bn.points.len(),
            "{}: its boundary nodes of loop '{}' are not on the case's curve (made from another \
             version of the case?)",
            at(),
            input.name
        );
    }
    report.layers = (snapshot.layered.layering.node_layer.iter())
        .filter(|&&l| l != mesh_model::NONE)
        .max()
        .copied();
    Ok((snapshot.boundary, snapshot.layered))
}

/// The case with its loops moved, their curves refitted, and each loop's linear part (scale ·
/// rotation; the identity for a loop that stays or is only bumped).
pub(crate) struct MovedGeometry {
    pub case: case::Case,
    pub curves: Vec<ClosedCurve>,
    linear: Vec<Mat2>,
}

/// The motions checked against the case (values, names) and the moved loops checked (none
/// crossing itself or another, walls inside the far field), then the moved curves fitted —
/// all before any meshing.
pub(crate) fn moved_geometry(case: &case::Case, motions: &[LoopMotion]) -> Result<MovedGeometry> {
    let bad = |e: mesh_move::MoveError| anyhow::anyhow!("bad motion: {e}");
    let loops: Vec<BoundaryLoop> = case
        .loops
        .iter()
        .map(|l| BoundaryLoop {
            name: l.name.clone(),
            role: l.role,
            points: l.points.clone(),
        })
        .collect();
    let moved = move_loops(&loops, motions).map_err(bad)?;
    let names: Vec<(&str, Role)> = loops.iter().map(|l| (l.name.as_str(), l.role)).collect();
    let linear = resolve_motions(&names, motions)
        .map_err(bad)?
        .into_iter()
        .map(|m| m.map_or(IDENTITY, Motion::linear))
        .collect();
    let mut moved_case = case.clone();
    for (input, l) in moved_case.loops.iter_mut().zip(moved) {
        let ccw = |p: &[[f64; 2]]| {
            let pts: Vec<Point2<f64>> = p.iter().map(|q| Point2::new(q[0], q[1])).collect();
            loops::is_counter_clockwise(&pts)
        };
        ensure!(
            ccw(&input.points) == ccw(&l.points),
            "bad motion: loop '{}' is turned inside out by its bumps",
            input.name
        );
        input.points = l.points;
    }
    let curves = pipeline::curves(&moved_case).map_err(|e| anyhow::anyhow!("bad motion: {e:#}"))?;
    Ok(MovedGeometry {
        case: moved_case,
        curves,
        linear,
    })
}

/// Where every boundary node goes: on its loop's moved curve at its parameter `t` (the
/// boundary nodes of loop `l` are the mesh nodes after those of loops `0..l`).
pub(crate) fn boundary_targets(
    moved: &MovedGeometry,
    nodes: &[BoundaryNodes],
    layered: &LayeredMesh,
) -> Result<BoundaryMotion> {
    let mut out = BoundaryMotion {
        nodes: Vec::new(),
        targets: Vec::new(),
        linear: Vec::new(),
    };
    for ((curve, bn), linear) in moved.curves.iter().zip(nodes).zip(&moved.linear) {
        for &t in &bn.t {
            let p = curve.point(t);
            out.nodes.push(out.nodes.len() as u32);
            out.targets.push([p.x, p.y]);
            out.linear.push(*linear);
        }
    }
    ensure!(
        out.nodes.len() <= layered.mesh.nodes.len(),
        "the layered mesh has fewer nodes than the boundary"
    );
    Ok(out)
}

/// The motions asked for: the motion file, or the flags' motion of one loop.
fn motions(args: &MotionArgs, case: &case::Case) -> Result<Vec<LoopMotion>> {
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
        return motion_file(path);
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

/// The rigid motion of the values given (the others at the identity's), `None` when none is.
fn rigid(
    scale: Option<f64>,
    rotate_deg: Option<f64>,
    about: Option<[f64; 2]>,
    translate: Option<[f64; 2]>,
) -> Option<RigidMotion> {
    let given = scale.is_some() || rotate_deg.is_some() || about.is_some() || translate.is_some();
    given.then(|| RigidMotion {
        scale: scale.unwrap_or(1.0),
        rotate_deg: rotate_deg.unwrap_or(0.0),
        about: about.unwrap_or([0.0, 0.0]),
        translate: translate.unwrap_or([0.0, 0.0]),
    })
}

/// The wall of a case with one wall.
fn default_loop(case: &case::Case) -> Result<String> {
    let walls: Vec<&str> = case
        .loops
        .iter()
        .filter(|l| l.role == Role::Wall)
        .map(|l| l.name.as_str())
        .collect();
    match walls.as_slice() {
        [one] => Ok((*one).to_string()),
        _ => bail!(
            "--loop NAME is needed: case '{}' has {} wall loops ({})",
            case.name,
            walls.len(),
            walls.join(", ")
        ),
    }
}

/// `POSITION,AMPLITUDE[,WIDTH][,upper|lower]`.
fn parse_bump(text: &str) -> Result<HicksHenne> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    ensure!(
        (2..=4).contains(&parts.len()),
        "give POSITION,AMPLITUDE[,WIDTH][,upper|lower]"
    );
    let num = |v: &str, what: &str| {
        v.parse::<f64>()
            .map_err(|_| anyhow::anyhow!("{what} {v:?} is not a number"))
    };
    let mut bump = HicksHenne::new(
        num(parts[0], "position")?,
        num(parts[1], "amplitude")?,
        Surface::Upper,
    );
    for (i, part) in parts.iter().enumerate().skip(2) {
        match *part {
            "upper" => bump.surface = Surface::Upper,
            "lower" => bump.surface = Surface::Lower,
            v if i == 2 => bump.width = num(v, "width")?,
            v => bail!("the surface is upper or lower, got {v:?}"),
        }
    }
    Ok(bump)
}

/// The motion file: `[[motion]]` tables (see the README).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct MotionFile {
    motion: Vec<LoopMotionSpec>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct LoopMotionSpec {
    #[serde(rename = "loop")]
    loop_name: String,
    scale: Option<f64>,
    rotate_deg: Option<f64>,
    about: Option<[f64; 2]>,
    translate: Option<[f64; 2]>,
    #[serde(default)]
    bump: Vec<BumpSpec>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct BumpSpec {
    position: f64,
    amplitude: f64,
    width: Option<f64>,
    surface: Option<SurfaceSpec>,
}

#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(rename_all = "lowercase")]
enum SurfaceSpec {
    Upper,
    Lower,
}

/// The motions of a motion file.
fn motion_file(path: &std::path::Path) -> Result<Vec<LoopMotion>> {
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("cannot read motion file {}", path.display()))?;
    let file: MotionFile = case::from_toml(&text, &path.display().to_string())?;
    ensure!(
        !file.motion.is_empty(),
        "{}: no [[motion]] table",
        path.display()
    );
    Ok(file
        .motion
        .into_iter()
        .map(|m| {
            let rigid = rigid(m.scale, m.rotate_deg, m.about, m.translate);
            let bumps = m
                .bump
                .iter()
                .map(|b| {
                    let surface = match b.surface {
                        Some(SurfaceSpec::Lower) => Surface::Lower,
                        _ => Surface::Upper,
                    };
                    let bump = HicksHenne::new(b.position, b.amplitude, surface);
                    // the width exponent defaults in one place, `HicksHenne::new`
                    HicksHenne {
                        width: b.width.unwrap_or(bump.width),
                        ..bump
                    }
                })
                .collect();
            LoopMotion {
                loop_name: m.loop_name,
                motion: Motion { rigid, bumps },
            }
        })
        .collect())
}

/// The `movement` block of the report of `move`.
#[derive(Debug, Serialize)]
pub struct MovementReport {
    /// Each loop's motion.
    pub motion: Vec<LoopMotionReport>,
    /// `--method`: `springs`, `idw` or `rbf`.
    pub method: String,
    /// `--kernel` (`rbf` only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub kernel: Option<String>,
    /// Largest displacement of any linear node.
    pub largest_displacement: f64,
    /// Largest displacement of a boundary node.
    pub largest_boundary_displacement: f64,
    /// RBF only: the interpolant's largest miss at a boundary node.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rbf_residual: Option<f64>,
    /// Linear cells inverted by the mover.
    pub inverted_linear_cells: usize,
    /// Springs only: the solves (iterations, convergence, the Newton balance of `--smooth`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub springs: Option<SpringsReport>,
    /// The linear mesh before the move.
    pub before: Side,
    /// The linear mesh after the move.
    pub after: Side,
    /// Min over cells of scaled Jacobian after / before (linear cells).
    pub worst_cell_ratio: f64,
    /// The cell where it is reached.
    pub worst_cell: usize,
    /// First-layer cells: largest relative height change and wall-normal angle change (°).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub first_layer: Option<[f64; 2]>,
    /// What `before`, `after` and `worst_cell_ratio` are about.
    pub of: &'static str,
}

/// The spring mover's solves in the report.
#[derive(Debug, Serialize)]
pub struct SpringsReport {
    /// Explicit spring solves (1, or one per layer plus one).
    pub solves: usize,
    /// Their iterations, summed.
    pub iterations: usize,
    /// True when every explicit solve reached its tolerance.
    pub converged: bool,
    /// The last solve's largest node move over the node's extrusion length.
    pub residual: f64,
    /// Node moves made by the worst-cell polish.
    pub polished: usize,
    /// `--smooth`: the shape balance by Newton's method.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub newton: Option<NewtonReport>,
}

/// The Newton solve of the shape balance in the report.
#[derive(Debug, Serialize)]
pub struct NewtonReport {
    /// Newton steps.
    pub iterations: usize,
    /// True when the last full step was within the tolerance (10⁻¹⁰ of a node's scale).
    pub converged: bool,
    /// The last step over the node's length scale.
    pub residual: f64,
    /// Steps whose matrix needed a diagonal shift (not positive definite).
    pub shifted: usize,
    /// Cholesky factorisations (failed ones of the shifts included).
    pub factorisations: usize,
    /// Energy evaluations of the line search.
    pub energy_evaluations: usize,
}

fn springs_report(s: &mesh_move::SpringStats) -> SpringsReport {
    SpringsReport {
        solves: s.solves,
        iterations: s.iterations,
        converged: s.converged,
        residual: s.residual,
        polished: s.polished,
        newton: s.newton.map(|n| NewtonReport {
            iterations: n.iterations,
            converged: n.converged,
            residual: n.residual,
            shifted: n.shifted,
            factorisations: n.factorisations,
            energy_evaluations: n.energy_evaluations,
        }),
    }
}

/// One loop's motion in the report.
#[derive(Debug, Serialize)]
pub struct LoopMotionReport {
    /// The loop.
    #[serde(rename = "loop")]
    pub loop_name: String,
    /// Scale, rotation (degrees), centre, translation.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rigid: Option<RigidReport>,
    /// Each bump: position, amplitude, width, surface.
    pub bumps: Vec<(f64, f64, f64, &'static str)>,
}

/// A rigid motion in the report.
#[derive(Debug, Serialize)]
pub struct RigidReport {
    scale: f64,
    rotate_deg: f64,
    about: [f64; 2],
    translate: [f64; 2],
}

/// Quality of one linear mesh.
#[derive(Debug, Serialize)]
pub struct Side {
    /// As in `quality`.
    pub max_angle_deg: f64,
    /// As in `quality`.
    pub obtuse_hist: [usize; 5],
    /// Least scaled Jacobian of the linear cells (corners).
    pub min_scaled_jacobian: f64,
}

const MOVEMENT_OF: &str = "the linear meshes before and after the move (cell corners; quads \
    cut along the shorter diagonal for the angles); the moved mesh's certified figures at its \
    order are under quality";

impl MovementReport {
    fn new(
        motions: &[LoopMotion],
        args: &MoveArgs,
        stats: &mesh_move::MoveStats,
        c: &mesh_move::Comparison,
        (before, after): (&mesh_model::Mesh, &mesh_model::Mesh),
    ) -> MovementReport {
        let side = |m: &mesh_model::Mesh, sj: f64| {
            let a = afsf2d::max_angle_histogram(m);
            Side {
                max_angle_deg: a.max_angle_deg,
                obtuse_hist: a.histogram,
                min_scaled_jacobian: sj,
            }
        };
        let rbf = args.method == MoveMethod::Rbf;
        MovementReport {
            motion: motions.iter().map(loop_motion_report).collect(),
            method: value_name(args.method),
            kernel: rbf.then(|| value_name(args.kernel)),
            largest_displacement: stats.largest_displacement,
            largest_boundary_displacement: stats.largest_boundary_displacement,
            rbf_residual: rbf.then_some(stats.interpolation_residual),
            inverted_linear_cells: stats.inverted_cells,
            springs: stats.springs.as_ref().map(springs_report),
            before: side(before, c.min_before),
            after: side(after, c.min_after),
            worst_cell_ratio: c.worst_cell_ratio,
            worst_cell: c.worst_cell,
            first_layer: c.first_layer.map(|d| [d.height, d.angle_deg]),
            of: MOVEMENT_OF,
        }
    }

    /// The lines printed after the summary table.
    fn summary(&self) -> String {
        format!(
            "moved by {}: largest displacement {:.4e}, worst-cell ratio {:.3}, min scaled \
             Jacobian (linear) {:.3} -> {:.3}, max angle {:.1} -> {:.1} deg\n",
            self.method,
            self.largest_displacement,
            self.worst_cell_ratio,
            self.before.min_scaled_jacobian,
            self.after.min_scaled_jacobian,
            self.before.max_angle_deg,
            self.after.max_angle_deg,
        )
    }
}

/// A flag value as typed on the command line (`idw`, `thin-plate`).
fn value_name<E: clap::ValueEnum>(value: E) -> String {
    value
        .to_possible_value()
        .map_or_else(String::new, |v| v.get_name().to_string())
}

fn loop_motion_report(m: &LoopMotion) -> LoopMotionReport {
    LoopMotionReport {
        loop_name: m.loop_name.clone(),
        rigid: m.motion.rigid.map(|r| RigidReport {
            scale: r.scale,
            rotate_deg: r.rotate_deg,
            about: r.about,
            translate: r.translate,
        }),
        bumps: m
            .motion
            .bumps
            .iter()
            .map(|b| {
                let side = match b.surface {
                    Surface::Upper => "upper",
                    Surface::Lower => "lower",
                };
                (b.position, b.amplitude, b.width, side)
            })
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bump_syntax() {
        let b = parse_bump("0.3,0.01").unwrap();
        assert_eq!((b.position, b.amplitude, b.width), (0.3, 0.01, 3.0));
        assert_eq!(b.surface, Surface::Upper);
        let b = parse_bump("0.3, -0.01, 2, lower").unwrap();
        assert_eq!((b.width, b.surface), (2.0, Surface::Lower));
        assert_eq!(
            parse_bump("0.5,0.01,lower").unwrap().surface,
            Surface::Lower
        );
        assert!(parse_bump("0.5").is_err());
        assert!(parse_bump("0.5,0.01,side").is_err());
        assert!(parse_bump("0.5,0.01,2,3").is_err());
    }
}
