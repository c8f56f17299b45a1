//! The parameters of the movers: the inverse-distance weighting and the radial basis
//! functions of [`crate::movers`], and the spring mover of [`crate::springs`] with its
//! strategy and fill. Plain data with their defaults; the movers themselves are elsewhere.

use springfield::{NewtonParams, ShapeLaw, SolverParams, SpringParams};

/// Parameters of the inverse-distance weighting.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IdwParams {
    /// Exponent `p` of the weights `A_i / r^p` (> 0; larger is more local). Default 3.
    pub exponent: f64,
}

impl Default for IdwParams {
    fn default() -> Self {
        IdwParams { exponent: 3.0 }
    }
}

/// The radial basis function.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kernel {
    /// Wendland's C2 function `(1 − r/R)⁴ (4r/R + 1)`, zero beyond the support radius `R`.
    WendlandC2,
    /// The thin-plate spline `r² ln r` (global).
    ThinPlateSpline,
}

/// Parameters of the radial-basis-function mover.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RbfParams {
    /// The kernel. Default Wendland C2.
    pub kernel: Kernel,
    /// Support radius `R` of the Wendland kernel; `None` (the default): the bounding-box
    /// diagonal of the mesh, so that every boundary node acts everywhere. Ignored by the
    /// thin-plate spline.
    pub support_radius: Option<f64>,
}

impl Default for RbfParams {
    fn default() -> Self {
        RbfParams {
            kernel: Kernel::WendlandC2,
            support_radius: None,
        }
    }
}

/// In what order the layer nodes are balanced.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Strategy {
    /// Every layer node in one solve.
    #[default]
    AllTogether,
    /// One solve per layer from the wall up (the layers below held), then one solve of all.
    LayerByLayer,
}

/// How the nodes outside the kept layers are placed before the shape balance: the fill
/// chosen, then, only while the start inverts a cell, the screw, RBF and IDW fills in turn —
/// never a choice among candidates by their quality (which would make the start, and so the
/// balance's basin, jump with the motion). The balance does not depend on where its start
/// is inside its basin, so the fill matters only for large motions, where a start must not
/// invert a cell.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Fill {
    /// Rotation-aware IDW from the region's bounding nodes (blends each node's linear map:
    /// a half turn blends to a collapse).
    Idw,
    /// The screw fill (the default): the bounding nodes' local similarities as logarithms
    /// (scale, turn, translation), blended by inverse-distance weights, then exponentiated; each rotation
    /// angle is read on the branch of its body's turn, so a half turn is a twist, as is
    /// 179.999°.
    #[default]
    Screw,
    /// As-rigid-as-possible iterations from the screw fill.
    Arap,
    /// The global Wendland C2 RBF of the bounding nodes' displacements (the screw fill when
    /// its system is singular).
    Rbf,
}

/// Parameters of the spring mover.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpringMoveParams {
    /// The spring coefficients: the dissertation's, except a ten times stiffer extrusion
    /// spring (the layer heights are given, not grown) and no angle reaction on the parent
    /// (`c_percent` 0: the layers below are already in place). With the dissertation's own
    /// the angle springs' pull shortens the first-layer edges of a bumped wall by up to 6 %
    /// before the solve stops.
    pub springs: SpringParams,
    /// The explicit solver (tolerance relative to each node's original extrusion length).
    pub solver: SolverParams,
    /// All layer nodes together, or layer by layer.
    pub strategy: Strategy,
    /// Where the filled region starts.
    pub fill: Fill,
    /// The IDW of the filled region.
    pub idw: IdwParams,
    /// The exponent of the screw fill's inverse-distance weights (> 0). Default 2.5.
    ///
    /// The fill is only the balance's start (inside its basin the balance does not depend
    /// on it), so this is a matter of Newton steps. Measured over the fourteen motions of
    /// `tests/movement/measures.sh` and `cases.sh` (Cholesky factorisations, 2 → 2.5 → 3):
    /// the 30P30N flap 9 → 4 → 4 (a weight falling as the square leaves a tenth of the
    /// flap's motion in the main element's trailing-edge fan, whose cells are 10⁻⁵ wide),
    /// the slat 14 → 4 → 4, the NACA0012 turned 30° 11 → 20 → 18 and 180° 23 → 17 → 50 (a
    /// whole body's turn spreads far out, which a steeper weight confines), all fourteen
    /// 461 → 363 → 445.
    pub screw_exponent: f64,
    /// Most as-rigid-as-possible iterations.
    pub arap_iterations: usize,
    /// A layer node keeps its original layer geometry (predictor and springs) while its
    /// cell below is at least this anisotropic (front spacing over extrusion length) and
    /// its parents do; the nodes above join the filled region. Default 16.
    pub core_aspect: f64,
    /// The last phase: the shape balance ([`crate::balance`]) by Newton's method, which
    /// makes the moved mesh a smooth function of the boundary, the base of the
    /// sensitivities.
    pub newton: NewtonParams,
    /// The energy density of the shape balance.
    pub shape: ShapeLaw,
}

impl Default for SpringMoveParams {
    fn default() -> Self {
        SpringMoveParams {
            springs: SpringParams {
                k_extrusion: 10.0,
                c_percent: 0.0,
                ..SpringParams::default()
            },
            solver: SolverParams {
                max_iterations: 500,
                tolerance: 1e-4,
                // the two groups of §4.1 with their own move limits: the extrusion springs
                // move a node along its extrusion edge, the neighbour and angle springs
                // across it (their forces are at right angles to the edge)
                lateral_max_move: Some(LATERAL_MAX_MOVE),
                ..SolverParams::default()
            },
            strategy: Strategy::AllTogether,
            fill: Fill::Screw,
            idw: IdwParams::default(),
            screw_exponent: 2.5,
            arap_iterations: 30,
            core_aspect: 16.0,
            newton: NewtonParams::default(),
            shape: ShapeLaw::default(),
        }
    }
}

/// The move limit across a node's extrusion edge per iteration (fraction of its length
/// scale), against 0.25 along it: the sideways pull of the neighbour and angle springs is
/// taken in smaller steps than the extrusion spring's, so a column is set to its height
/// before it swings.
const LATERAL_MAX_MOVE: f64 = 0.1;
