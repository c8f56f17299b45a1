//! Moving a meshed 2D case (dissertation ch. 4): its loops moved by rigid motions and bumps
//! ([`motion`]), the moved loops' C2 curves refitted and each boundary node put on its moved
//! curve at its own parameter `t`, the other linear nodes moved by the chosen mover
//! (`mesh_move`), the moved layered mesh re-curved with the original curving's decisions, and
//! every cell certified — the same topology as the original mesh. With
//! [`MoveOptions::sensitivities`], the derivative of every node with respect to each design
//! variable of the motion ([`sensitivities`]).
//!
//! ```
//! use curvemesh::movement::{MoveOptions, motion, move_case};
//! let case = curvemesh::load::load_2d("naca0012")?;
//! let motions = motion::parse_str("[[motion]]\nloop = \"naca0012\"\nrotate_deg = 5.0\n", "pitch")?;
//! let options = MoveOptions { order: Some(2), ..Default::default() };
//! let moved = move_case(&case, &motions, None, &options, &mut curvemesh::Silent)?;
//! assert!(moved.report.is_valid(), "{:?}", moved.report.problems);
//! # Ok::<(), curvemesh::Error>(())
//! ```

pub mod measures;
pub mod motion;
pub mod report;
pub mod sensitivities;

use std::sync::OnceLock;

use boundary1d::BoundaryNodes;
use mesh_model::{LayeredMesh, Mesh};
use mesh_move::{
    BoundaryMotion, IdwParams, Kernel, LoopMotion, Method, RbfParams, SpringMoveParams,
};

use crate::case::Case;
use crate::error::{Result, ensure, input_error};
use crate::observer::{Observer, stage};
use crate::outputs::Plan;
use crate::report::{LinearAngles, Report};
use crate::stages::Snapshot;
use crate::{mesh2d, pipeline};
use motion::{MovedGeometry, boundary_targets, moved_geometry};
use report::MovementReport;

/// How the nodes inside the domain follow the moved boundary.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum Mover {
    /// The Spring-Field on the mesh's own layers: the near-wall layers keep their shape.
    #[default]
    Springs,
    /// Rotation-aware inverse-distance weighting (Witteveen & Bijl).
    Idw,
    /// Radial basis functions with a linear polynomial (de Boer et al.).
    Rbf,
}

impl Mover {
    /// The name in the report and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Mover::Springs => "springs",
            Mover::Idw => "idw",
            Mover::Rbf => "rbf",
        }
    }
}

/// The radial basis function of [`Mover::Rbf`].
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum RbfKernel {
    /// Wendland C2 with a support radius (default: the bounding-box diagonal, global).
    #[default]
    WendlandC2,
    /// The thin-plate spline r² ln r.
    ThinPlate,
}

impl RbfKernel {
    /// The name in the report and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            RbfKernel::WendlandC2 => "wendland-c2",
            RbfKernel::ThinPlate => "thin-plate",
        }
    }
}

/// How to move a case.
#[derive(Debug, Clone, PartialEq)]
pub struct MoveOptions {
    /// The moved mesh's order, 1 to 3; `None`: the case's.
    pub order: Option<u8>,
    /// Cut every quad along its shorter diagonal.
    pub triangles: bool,
    /// The mover of the inner nodes.
    pub mover: Mover,
    /// [`Mover::Rbf`]'s kernel.
    pub kernel: RbfKernel,
    /// [`RbfKernel::WendlandC2`]'s support radius (default: the bounding-box diagonal).
    pub radius: Option<f64>,
    /// Asks for a mover whose mesh is a smooth function of the motion: the spring mover,
    /// which always is (its shape balance converged by Newton's method); refused with IDW
    /// and RBF, as `sensitivities` is.
    pub smooth: bool,
    /// Also compute the mesh sensitivities ([`Moved::sensitivities`]).
    pub sensitivities: bool,
    /// Refuse a case expected to make more cells than this (when it is meshed first).
    pub max_cells: u64,
}

impl Default for MoveOptions {
    fn default() -> MoveOptions {
        MoveOptions {
            order: None,
            triangles: false,
            mover: Mover::default(),
            kernel: RbfKernel::default(),
            radius: None,
            smooth: false,
            sensitivities: false,
            max_cells: crate::estimate::DEFAULT_MAX_CELLS,
        }
    }
}

impl MoveOptions {
    /// Refuses options that do not go together.
    pub fn check(&self) -> Result<()> {
        ensure!(
            self.mover == Mover::Springs || (!self.sensitivities && !self.smooth),
            "--smooth and --sensitivities need --method springs (the smooth balance)"
        );
        Ok(())
    }

    /// The mover of `mesh_move`.
    fn method(&self) -> Method {
        match self.mover {
            Mover::Springs => Method::Springs(SpringMoveParams::default()),
            Mover::Idw => Method::Idw(IdwParams::default()),
            Mover::Rbf => Method::Rbf(RbfParams {
                kernel: match self.kernel {
                    RbfKernel::WendlandC2 => Kernel::WendlandC2,
                    RbfKernel::ThinPlate => Kernel::ThinPlateSpline,
                },
                support_radius: self.radius,
            }),
        }
    }
}

/// A moved case.
#[derive(Debug)]
pub struct Moved {
    /// The moved mesh: the original's topology, curved at its order (linear, and invalid,
    /// when the mover inverted a linear cell).
    pub mesh: Mesh,
    /// Its report, with the `movement` block.
    pub report: Report,
    /// Each cell's least scaled Jacobian (certified bound).
    pub scaled_jacobian: Vec<f64>,
    /// How many of [`Moved::mesh`]'s cells, the last ones, are the filled region's triangles
    /// (as [`crate::Meshed::fill_cells`]).
    pub fill_cells: usize,
    /// With [`MoveOptions::sensitivities`] and no inverted cell: for each design variable
    /// (`loop.rotate_deg`, `loop.translate_x`, …, `loop.bump1`), the derivative of every
    /// node of [`Moved::mesh`].
    pub sensitivities: Option<Vec<(String, Vec<[f64; 2]>)>>,
}

impl Moved {
    /// The transposed product for an adjoint solver: for `v` with one entry per node of
    /// [`Moved::mesh`] (say dJ/dX), `Σ_nodes v · dX/dα` for each design variable α, in the
    /// order of [`Moved::sensitivities`]; `None` without sensitivities or when `v` is not
    /// one entry per node. Computed from the forward sensitivities (one balance solve per
    /// variable), so it equals the forward product to rounding.
    pub fn transposed_product(&self, v: &[[f64; 2]]) -> Option<Vec<f64>> {
        let s = self.sensitivities.as_ref()?;
        if v.len() != self.mesh.nodes.len() {
            return None;
        }
        Some(
            s.iter()
                .map(|(_, d)| {
                    d.iter()
                        .zip(v)
                        .map(|(d, v)| d[0] * v[0] + d[1] * v[1])
                        .sum()
                })
                .collect(),
        )
    }
}

/// Moves `case` by `motions`: from its mesh made with its own parameters, or from `start`, a
/// snapshot of it (with where it came from, for messages; checked to be this case's). The
/// meshes are written into `plan`'s reserved outputs beside the certification.
pub fn move_case(
    case: &Case,
    motions: &[LoopMotion],
    start: Option<(Snapshot, &str)>,
    options: &MoveOptions,
    observer: &mut dyn Observer,
) -> Result<Moved> {
    move_into(case, motions, start, options, observer, None)
}

/// [`move_case`], writing the mesh files into `plan`'s reserved outputs beside the
/// certification; the caller commits the plan.
pub fn move_into(
    case: &Case,
    motions: &[LoopMotion],
    start: Option<(Snapshot, &str)>,
    options: &MoveOptions,
    observer: &mut dyn Observer,
    plan: Option<&mut Plan>,
) -> Result<Moved> {
    case.order_of(options.order)?;
    options.check()?;
    moved_geometry(case, motions)?;
    let unmoved = unmoved(case, start, options, observer)?;
    Ok(move_from(case, &unmoved, motions, options, observer, plan, &[])?.0)
}

/// A case prepared for many moves (a shape optimisation's designs, a solver's motions one
/// at a time): its unmoved layered mesh (meshed or read from a snapshot), the spring mover's
/// shape field with its Newton workspace (the matrix's pattern, ordering and symbolic
/// factorisation) and the unmoved mesh at the moves' order are made once; each
/// [`Prepared::move_by`] moves from that same unmoved mesh (no drift) and builds none of them
/// again. A move's balance is the one [`move_case`] finds (the same basin, to the Newton
/// solve's tolerance: the workspace keeps the last balance's diagonal shift).
///
/// ```
/// use curvemesh::movement::{MoveOptions, Prepared, motion};
/// let case = curvemesh::load::load_2d("naca0012")?;
/// let options = MoveOptions { order: Some(2), ..Default::default() };
/// let prepared = Prepared::new(&case, None, &options, &mut curvemesh::Silent)?;
/// for degrees in [2.0, -3.0] {
///     let text = format!("[[motion]]\nloop = \"naca0012\"\nrotate_deg = {degrees}\n");
///     let motions = motion::parse_str(&text, "pitch")?;
///     let moved = prepared.move_by(&motions, &mut curvemesh::Silent)?;
///     assert!(moved.report.is_valid(), "{:?}", moved.report.problems);
/// }
/// # Ok::<(), curvemesh::Error>(())
/// ```
pub struct Prepared {
    case: Case,
    unmoved: Unmoved,
    options: MoveOptions,
}

impl Prepared {
    /// `case` prepared for moves with `options`: meshed with its own parameters, or read
    /// from `start`, a snapshot of it (with where it came from, for messages).
    ///
    /// # Errors
    /// Those of [`move_case`] before any motion: bad options, a mesh that fails, a snapshot
    /// of another case.
    pub fn new(
        case: &Case,
        start: Option<(Snapshot, &str)>,
        options: &MoveOptions,
        observer: &mut dyn Observer,
    ) -> Result<Prepared> {
        case.order_of(options.order)?;
        options.check()?;
        let mut unmoved = unmoved(case, start, options, observer)?;
        if let Method::Springs(p) = options.method() {
            unmoved.field = Some(
                mesh_move::ShapeField::of(&unmoved.layered, p.shape)
                    .map_err(|e| input_error!("moving the mesh: {e}"))?,
            );
        }
        Ok(Prepared {
            case: case.clone(),
            unmoved,
            options: options.clone(),
        })
    }

    /// The case moved by `motions`, from the unmoved mesh, as [`move_case`] moves it.
    ///
    /// # Errors
    /// Those of [`move_case`] for the motions: a motion that moves a loop across another,
    /// a failed balance.
    pub fn move_by(&self, motions: &[LoopMotion], observer: &mut dyn Observer) -> Result<Moved> {
        moved_geometry(&self.case, motions)?;
        let (case, unmoved, options) = (&self.case, &self.unmoved, &self.options);
        Ok(move_from(case, unmoved, motions, options, observer, None, &[])?.0)
    }
}

/// Moves `case` by the motions `motions` scaled from 0 to their full amplitude in `steps`
/// equal steps (`steps + 1` meshes, the first the unmoved mesh; a rotation's angle, a
/// translation and a bump's amplitude scaled by `k / steps`, a scale factor raised to that
/// power), each moved from the same original mesh (no drift), the spring mover's balance
/// started from the previous step's nodes (fewer Newton steps, the same balance). `each` gets
/// each step's number and moved mesh, and its plan of outputs when it gives one.
pub fn move_sequence(
    case: &Case,
    motions: &[LoopMotion],
    start: Option<(Snapshot, &str)>,
    (options, steps): (&MoveOptions, usize),
    observer: &mut dyn Observer,
    each: &mut dyn FnMut(usize, Moved) -> Result<()>,
) -> Result<()> {
    case.order_of(options.order)?;
    options.check()?;
    ensure!(steps >= 1, "--steps must be at least 1, got {steps}");
    // the whole motion is checked before any meshing; each step's is checked again
    moved_geometry(case, motions)?;
    // one shape field for every step: its springs and its Newton workspace (pattern,
    // ordering, buffers) serve each step's balance
    let prepared = Prepared::new(case, start, options, observer)?;
    let unmoved = &prepared.unmoved;
    // the last three steps' balances, the latest first: the next one starts from their
    // parabola
    let mut last: Vec<Balanced> = Vec::with_capacity(3);
    for k in 0..=steps {
        let at = motion::scaled(motions, k as f64 / steps as f64);
        let (moved, balanced) = move_from(case, unmoved, &at, options, observer, None, &last)?;
        last.truncate(2);
        last.insert(0, balanced);
        each(k, moved)?;
    }
    Ok(())
}

/// The unmoved layered mesh a move starts from, with its boundary nodes and the report's
/// first lines: meshed from the case, or read from a snapshot.
struct Unmoved {
    nodes: Vec<BoundaryNodes>,
    layered: LayeredMesh,
    report: Report,
    /// The spring mover's shape field, kept across the steps of a sequence.
    field: Option<mesh_move::ShapeField>,
    /// The unmoved mesh at the moves' order (its curving decisions, which the moved meshes
    /// keep) and its cells' measures, made by the first move and kept for the next steps.
    baseline: OnceLock<UnmovedAtOrder>,
}

impl Unmoved {
    /// [`Unmoved::baseline`], made at the first call (`order` and `triangles` are a
    /// sequence's, the same at every step).
    fn baseline(&self, case: &Case, (order, triangles): (u8, bool)) -> Result<&UnmovedAtOrder> {
        if let Some(made) = self.baseline.get() {
            return Ok(made);
        }
        let made = if order == 1 {
            let mut scratch = Report::default();
            let mesh = mesh2d::linear_at_order(&self.layered, triangles, &mut scratch);
            (None, measures::Baseline::of(mesh))
        } else {
            let curves = pipeline::curves(case)?;
            let layered = std::borrow::Cow::Borrowed(&self.layered);
            let before =
                pipeline::curved_mesh(case, &curves, &self.nodes, layered, order, triangles)?;
            (Some(before.decisions), measures::Baseline::of(before.mesh))
        };
        Ok(self.baseline.get_or_init(|| made))
    }
}

fn unmoved(
    case: &Case,
    start: Option<(Snapshot, &str)>,
    options: &MoveOptions,
    observer: &mut dyn Observer,
) -> Result<Unmoved> {
    let order = case.order_of(options.order)?;
    let mut report = Report::new(&case.name, order);
    report.inputs = Some(mesh2d::inputs_of(case));
    let (nodes, layered) = match start {
        None => {
            let (_, nodes, grown) = mesh2d::grow(case, options.max_cells, observer, &mut report)?;
            (nodes, grown.layered)
        }
        Some((snapshot, origin)) => from_snapshot(case, snapshot, origin, &mut report)?,
    };
    Ok(Unmoved {
        nodes,
        layered,
        report,
        field: None,
        baseline: OnceLock::new(),
    })
}

/// A move's linear nodes and where its balance started (the fill; the nodes themselves when
/// there was no balance): the warm start of the next step of a sequence.
struct Balanced {
    start: Vec<[f64; 2]>,
    nodes: Vec<[f64; 2]>,
}

/// One move of `unmoved` by `motions` (the balance started from the corrections of the steps
/// before, `warm`, the latest first, when given): the moved case and its [`Balanced`] nodes.
fn move_from(
    case: &Case,
    unmoved: &Unmoved,
    motions: &[LoopMotion],
    options: &MoveOptions,
    observer: &mut dyn Observer,
    plan: Option<&mut Plan>,
    warm: &[Balanced],
) -> Result<(Moved, Balanced)> {
    let order = case.order_of(options.order)?;
    let moved = moved_geometry(case, motions)?;
    let mut report = unmoved.report.clone();
    let (nodes, layered) = (&unmoved.nodes, &unmoved.layered);
    let boundary = boundary_targets(&moved, nodes, layered)?;
    let (linear, seconds) = stage(observer, "moving the linear nodes", || {
        move_linear(unmoved, &boundary, &options.method(), warm)
    });
    let linear = linear?;
    report.timings_s.insert("move", seconds);
    let moved_layered = LayeredMesh {
        mesh: linear.mesh,
        layering: layered.layering.clone(),
    };
    let comparison = mesh_move::compare(&layered.mesh, &moved_layered.mesh)
        .map_err(|e| input_error!("comparing the meshes: {e}"))?;
    let inverted = linear.stats.inverted_cells > 0;
    let (mesh, decisions, unmoved_mesh) = at_order(
        (case, unmoved, &moved),
        (&moved_layered, linear.stats.inverted_cells),
        (order, options.triangles),
        observer,
        &mut report,
    )?;
    let sensitivities = if options.sensitivities && !inverted {
        let at = (
            motions,
            &nodes[..],
            &boundary,
            decisions.as_ref().map(|d| (d, order)),
        );
        let (columns, seconds) = stage(observer, "mesh sensitivities", || {
            sensitivities_at(case, layered, &moved_layered, at)
        });
        report.timings_s.insert("sensitivities", seconds);
        Some(columns?)
    } else {
        None
    };
    let method = options.method_names();
    let mut movement = MovementReport::new(
        motions,
        method,
        &linear.stats,
        &comparison,
        (&layered.mesh, &moved_layered.mesh),
    );
    movement.measures = unmoved_mesh.and_then(|(_, before)| measures::measures(before, &mesh));
    report.movement = Some(movement);
    let scaled_jacobian = mesh2d::certify_and_write(
        (&mesh, LinearAngles::Of(&moved_layered.mesh)),
        plan.map(|p| (p, None)),
        observer,
        &mut report,
    )?;
    let nodes: Vec<[f64; 2]> = (0..moved_layered.mesh.nodes.len() as u32)
        .map(|k| moved_layered.mesh.xy(k))
        .collect();
    let balanced = Balanced {
        start: linear.start.unwrap_or_else(|| nodes.clone()),
        nodes,
    };
    let moved = Moved {
        mesh,
        report,
        scaled_jacobian,
        fill_cells: crate::meshed::fill_cells(layered),
        sensitivities,
    };
    Ok((moved, balanced))
}

impl MoveOptions {
    /// The mover's and the kernel's names in the report (the kernel for RBF only).
    fn method_names(&self) -> (&'static str, Option<&'static str>) {
        let kernel = (self.mover == Mover::Rbf).then(|| self.kernel.name());
        (self.mover.name(), kernel)
    }
}

/// What the sensitivities are taken at: the motions, the boundary nodes, the boundary's
/// targets and the curving's decisions with the order (none at order 1).
type SensitivityAt<'a> = (
    &'a [LoopMotion],
    &'a [BoundaryNodes],
    &'a BoundaryMotion,
    Option<(&'a vector_adding::Decisions, u8)>,
);

/// The mesh sensitivities of the move of `original` to `moved`.
fn sensitivities_at(
    case: &Case,
    original: &LayeredMesh,
    moved: &LayeredMesh,
    (motions, nodes, boundary, curving): SensitivityAt<'_>,
) -> Result<Vec<(String, Vec<[f64; 2]>)>> {
    let balance = balance_at(original, moved, boundary)?;
    let at = sensitivities::At {
        case,
        motions,
        nodes,
        moved,
        balance: &balance,
        curving,
    };
    let vars = sensitivities::variables(motions);
    sensitivities::sensitivities(&at, &vars)
}

/// The smooth balance of the original mesh's shape field linearised at the moved nodes, the
/// boundary nodes fixed: what the sensitivities differentiate.
fn balance_at(
    original: &LayeredMesh,
    moved: &LayeredMesh,
    boundary: &BoundaryMotion,
) -> Result<mesh_move::Sensitivity> {
    let field = mesh_move::ShapeField::of(original, SpringMoveParams::default().shape)
        .map_err(|e| input_error!("sensitivities: {e}"))?;
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
        .map_err(|e| input_error!("sensitivities: {e}"))
}

/// The linear nodes of `unmoved` moved to `boundary` by `method`, the spring mover's balance
/// started from the steps before (`warm`) when given.
fn move_linear(
    unmoved: &Unmoved,
    boundary: &BoundaryMotion,
    method: &Method,
    warm: &[Balanced],
) -> Result<mesh_move::Moved> {
    let layered = &unmoved.layered;
    match warm {
        [w, before @ ..] => {
            let before: Vec<_> = before
                .iter()
                .map(|b| (&b.start[..], &b.nodes[..]))
                .collect();
            let warm = mesh_move::Warm {
                start: &w.start,
                balanced: &w.nodes,
                field: unmoved.field.as_ref(),
                before: &before,
            };
            mesh_move::move_layered_from(layered, boundary, method, warm)
        }
        [] => match &unmoved.field {
            Some(field) => mesh_move::move_layered_in(layered, boundary, method, field),
            None => mesh_move::move_layered(layered, boundary, method),
        },
    }
    .map_err(|e| input_error!("moving the mesh: {e}"))
}

/// The unmoved mesh at the moves' order (its curving decisions and its cells' measures).
type UnmovedAtOrder = (Option<vector_adding::Decisions>, measures::Baseline);

/// The moved linear mesh `moved_layered` at `order`: curved with the unmoved mesh's
/// decisions kept (and those decisions), as it is at order 1 — or, when the mover inverted
/// `inverted` of its cells, written linear as it is (it cannot be curved, and fails). With the
/// unmoved mesh at that order, to measure the moved one against.
fn at_order<'u>(
    (case, unmoved, moved): (&Case, &'u Unmoved, &MovedGeometry),
    (moved_layered, inverted): (&LayeredMesh, usize),
    (order, triangles): (u8, bool),
    observer: &mut dyn Observer,
    report: &mut Report,
) -> Result<(
    Mesh,
    Option<vector_adding::Decisions>,
    Option<&'u UnmovedAtOrder>,
)> {
    if inverted > 0 {
        report.order = 1;
        report.notes.push(format!(
            "the mover inverted {inverted} linear cells: the moved linear mesh is written, not curved"
        ));
        return Ok((moved_layered.mesh.clone(), None, None));
    }
    let baseline = unmoved.baseline(case, (order, triangles))?;
    if order == 1 {
        let mesh = mesh2d::linear_at_order(moved_layered, triangles, report);
        return Ok((mesh, None, Some(baseline)));
    }
    let curved = curve_keeping(
        moved,
        &unmoved.nodes,
        (moved_layered, &baseline.0),
        (order, triangles),
        observer,
        report,
    )?;
    Ok((curved.mesh, Some(curved.decisions), Some(baseline)))
}

/// The moved layered mesh curved as the original one is (`vector_adding::curve_mesh_keeping`
/// with the original curving's decisions): a small motion flips no decision; the decisions
/// that had to change (a cell the kept decision would leave invalid) are counted in the
/// report and the first ones named in its notes.
fn curve_keeping(
    moved: &MovedGeometry,
    nodes: &[BoundaryNodes],
    (layered, decisions): (&LayeredMesh, &Option<vector_adding::Decisions>),
    (order, triangles): (u8, bool),
    observer: &mut dyn Observer,
    report: &mut Report,
) -> Result<vector_adding::Curved> {
    let what = "curving (Vector-Adding, the original's decisions kept)";
    let (curved, seconds) = stage(observer, what, || {
        let decisions = decisions
            .as_ref()
            .ok_or_else(|| input_error!("curving: no decisions of the unmoved mesh"))?;
        vector_adding::curve_mesh_keeping(
            layered,
            &pipeline::loop_curves(&moved.curves, nodes),
            &pipeline::curving_params(&moved.case, order, triangles),
            decisions,
        )
        .map_err(|e| input_error!("curving: {e}"))
    });
    let (curved, changes) = curved?;
    report.timings_s.insert("curving", seconds);
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

/// The boundary nodes and the layered linear mesh of `snapshot`, checked to be this case's:
/// every boundary node on its curve. `origin` names the snapshot in messages.
fn from_snapshot(
    case: &Case,
    snapshot: Snapshot,
    origin: &str,
    report: &mut Report,
) -> Result<(Vec<BoundaryNodes>, LayeredMesh)> {
    ensure!(
        snapshot.case == case.name,
        "{origin}: made from case '{}', not '{}'",
        snapshot.case,
        case.name
    );
    let curves = pipeline::curves(case)?;
    ensure!(
        snapshot.boundary.len() == curves.len(),
        "{origin}: {} boundary loops, the case has {}",
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
            "{origin}: its boundary nodes of loop '{}' are not on the case's curve (made from \
             another version of the case?)",
            input.name
        );
    }
    report.layers = (snapshot.layered.layering.node_layer.iter())
        .filter(|&&l| l != mesh_model::NONE)
        .max()
        .copied();
    Ok((snapshot.boundary, snapshot.layered))
}
