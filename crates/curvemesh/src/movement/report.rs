//! The `movement` block of the report of a move: the motion, the mover, and the linear
//! meshes' quality before and after, cell by cell.

use mesh_move::{LoopMotion, Surface};
use serde::Serialize;

/// The `movement` block of the report of `move`.
#[derive(Debug, Clone, Serialize)]
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
    /// The four measures cell by cell against the unmoved mesh of the same order (lin, sj,
    /// sicn, edge; absent when the mover inverted a cell).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub measures: Option<super::measures::Measures>,
}

/// The spring mover's solves in the report.
#[derive(Debug, Clone, Serialize)]
pub struct SpringsReport {
    /// Explicit spring solves (1, or one per layer plus one).
    pub solves: usize,
    /// Their iterations, summed.
    pub iterations: usize,
    /// True when every explicit solve reached its tolerance.
    pub converged: bool,
    /// The last solve's largest node move over the node's extrusion length.
    pub residual: f64,
    /// The shape balance by Newton's method (absent when the fill inverted a cell).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub newton: Option<NewtonReport>,
}

/// The Newton solve of the shape balance in the report.
#[derive(Debug, Clone, Serialize)]
pub struct NewtonReport {
    /// Newton steps.
    pub iterations: usize,
    /// True when the last full step was within the tolerance (10⁻¹⁰ of a node's scale).
    pub converged: bool,
    /// The last step over the node's length scale.
    pub residual: f64,
    /// Steps whose matrix needed a diagonal shift (not positive definite).
    pub shifted: usize,
    /// Steps that took the springs' convex Hessian (not positive definite after 20 steps).
    pub convex: usize,
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
        newton: s.newton.map(|n| NewtonReport {
            iterations: n.iterations,
            converged: n.converged,
            residual: n.residual,
            shifted: n.shifted,
            convex: n.convex,
            factorisations: n.factorisations,
            energy_evaluations: n.energy_evaluations,
        }),
    }
}

/// One loop's motion in the report.
#[derive(Debug, Clone, Serialize)]
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
#[derive(Debug, Clone, Serialize)]
pub struct RigidReport {
    scale: f64,
    rotate_deg: f64,
    about: [f64; 2],
    translate: [f64; 2],
}

/// Quality of one linear mesh.
#[derive(Debug, Clone, Serialize)]
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
    /// The block of a move by `method` (with `kernel` for RBF) of `motions`, with the
    /// mover's `stats` and the comparison `c` of the linear meshes `before` and `after`.
    pub fn new(
        motions: &[LoopMotion],
        (method, kernel): (&str, Option<&str>),
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
        let rbf = kernel.is_some();
        MovementReport {
            motion: motions.iter().map(loop_motion_report).collect(),
            method: method.to_string(),
            kernel: kernel.map(str::to_string),
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
            measures: None,
        }
    }

    /// The line printed after the summary table.
    pub fn summary(&self) -> String {
        let mut out = format!(
            "moved by {}: largest displacement {:.4e}, worst-cell ratio {:.3}, min scaled \
             Jacobian (linear) {:.3} -> {:.3}, max angle {:.1} -> {:.1} deg\n",
            self.method,
            self.largest_displacement,
            self.worst_cell_ratio,
            self.before.min_scaled_jacobian,
            self.after.min_scaled_jacobian,
            self.before.max_angle_deg,
            self.after.max_angle_deg,
        );
        if let Some(m) = &self.measures {
            out += &format!(
                "worst ratios after / before, cell by cell: lin {:.3}, sj {:.3}, sicn {:.3}, \
                 edge {:.3}\n",
                m.lin.ratio, m.sj.ratio, m.sicn.ratio, m.edge.ratio
            );
        }
        out
    }
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
