//! Test and bench fixture code only — not part of the pipeline. The built-in cases of
//! `cargo xtask mesh` (`fixtures/cases/*.toml`) made the way the pipeline makes them: the
//! loops' points (Selig files read from the workspace's `fixtures/geometry`, NACA sections,
//! far-field circles), `geom-curve` curves through them (counter-clockwise), the boundary
//! nodes of `boundary1d::mesh_loops` (curvature-driven spacing, corners at the first height),
//! the front loops and parameters of `afsf2d`, and the grown layered mesh with everything the
//! curving stage needs. Shared by the tests and benches of `afsf2d` and `vector-adding` so
//! that they mesh the same cases.
//!
//! Dev-only: a `[dev-dependencies]` entry of this workspace's crates, never a normal
//! dependency, never published, and with no usage example of its own; no crate needs it to
//! be used (see `examples/standalone/`).

use afsf2d::{AfsfOutput, AfsfParams, FrontLoop};
use boundary1d::{BoundaryNodes, SpacingParams};
use geom_curve::{ClosedCurve, CurveParams, Point2, loops};
use mesh_model::Role;

/// One built-in case: its loops (before boundary meshing) and parameters.
#[derive(Debug, Clone)]
pub struct RealCase {
    /// Case name as in `xtask mesh --list`.
    pub name: &'static str,
    /// (name, role, points) of every loop.
    pub loops: Vec<(String, Role, Vec<[f64; 2]>)>,
    /// First layer height.
    pub first_height: f64,
    /// Boundary max spacing.
    pub max_spacing: f64,
    /// Layer budget.
    pub max_layers: u32,
    /// Mesh inside the single wall loop.
    pub inside: bool,
}

/// The layered linear mesh of a case and what it was grown from: all the curving stage needs.
#[derive(Debug, Clone)]
pub struct Grown {
    /// The loops' curves, counter-clockwise, in the case's loop order (= patch order).
    pub curves: Vec<ClosedCurve>,
    /// The boundary nodes of every loop, with their curve parameters `t`.
    pub nodes: Vec<BoundaryNodes>,
    /// The mesher's output.
    pub output: AfsfOutput,
}

/// The names of the built-in cases.
pub const REAL_CASES: [&str; 5] = ["naca0012", "two-element", "bat", "lshape", "30p30n"];

/// Reads a Selig `.dat` file under the workspace's `fixtures/geometry`.
fn selig(rel: &str) -> Vec<[f64; 2]> {
    let path = format!(
        "{}/../../fixtures/geometry/{rel}",
        env!("CARGO_MANIFEST_DIR")
    );
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    geom_curve::selig::parse(&text)
        .unwrap_or_else(|e| panic!("{path}: {e}"))
        .iter()
        .map(|p| [p.x, p.y])
        .collect()
}

/// A far-field circle as the case files define it (256 points, the case key's default).
fn circle(c: [f64; 2], r: f64) -> Vec<[f64; 2]> {
    geom_curve::circle_points(Point2::new(c[0], c[1]), r, 256)
        .expect("a positive radius")
        .iter()
        .map(|p| [p.x, p.y])
        .collect()
}

/// A NACA 4-digit section (101 points, closed trailing edge), scaled, rotated about the
/// origin, then translated, as the case keys do.
fn naca(digits: &str, scale: f64, rotate_deg: f64, translate: [f64; 2]) -> Vec<[f64; 2]> {
    let (s, c) = rotate_deg.to_radians().sin_cos();
    geom_curve::naca::naca4(digits, 101, true)
        .expect("a valid NACA section")
        .iter()
        .map(|p| {
            let (x, y) = (p.x * scale, p.y * scale);
            [x * c - y * s + translate[0], x * s + y * c + translate[1]]
        })
        .collect()
}

/// A built-in case by name.
///
/// # Panics
/// When `name` is not one of [`REAL_CASES`] or a fixture file cannot be read.
pub fn real_case(name: &str) -> RealCase {
    let wall = |n: &str, p: Vec<[f64; 2]>| (n.to_string(), Role::Wall, p);
    let far = |c: [f64; 2], r: f64| ("farfield".to_string(), Role::Farfield, circle(c, r));
    let base = |name, loops, first_height, max_layers| RealCase {
        name,
        loops,
        first_height,
        max_spacing: 1.0,
        max_layers,
        inside: false,
    };
    match name {
        "naca0012" => base(
            "naca0012",
            vec![
                wall("naca0012", selig("naca0012.dat")),
                far([0.5, 0.0], 20.0),
            ],
            5e-5,
            60,
        ),
        "two-element" => base(
            "two-element",
            vec![
                wall("main", naca("2412", 1.0, 0.0, [0.0, 0.0])),
                wall("flap", naca("4412", 0.3, -25.0, [0.93, -0.045])),
                far([0.5, 0.0], 20.0),
            ],
            5e-5,
            60,
        ),
        "bat" => RealCase {
            max_spacing: 2.0,
            inside: true,
            ..base("bat", vec![wall("bat", selig("bat.dat"))], 5e-4, 51)
        },
        "lshape" => base(
            "lshape",
            vec![
                wall(
                    "lshape",
                    vec![
                        [0.0, 0.0],
                        [1.0, 0.0],
                        [1.0, 0.3],
                        [0.3, 0.3],
                        [0.3, 1.0],
                        [0.0, 1.0],
                    ],
                ),
                far([0.5, 0.5], 15.0),
            ],
            1e-3,
            40,
        ),
        "30p30n" => base(
            "30p30n",
            vec![
                wall("slat", selig("30p30n/slat.dat")),
                wall("main", selig("30p30n/main.dat")),
                wall("flap", selig("30p30n/flap.dat")),
                far([0.5, 0.0], 20.0),
            ],
            5e-6,
            60,
        ),
        other => panic!("no built-in case {other}"),
    }
}

impl RealCase {
    /// The loops' curves, each counter-clockwise, in the case's loop order.
    ///
    /// # Panics
    /// When a loop cannot be fitted (the built-in loops always can).
    pub fn curves(&self) -> Vec<ClosedCurve> {
        let params = CurveParams::default();
        self.loops
            .iter()
            .map(|(name, _, pts)| {
                let mut p: Vec<Point2<f64>> = pts.iter().map(|q| Point2::new(q[0], q[1])).collect();
                loops::make_counter_clockwise(&mut p);
                ClosedCurve::new(&p, &params).unwrap_or_else(|e| panic!("{name}: {e}"))
            })
            .collect()
    }

    /// The spacing parameters of the boundary mesh at first height `first_height`.
    pub fn spacing(&self, first_height: f64) -> SpacingParams {
        SpacingParams {
            growth: 1.3,
            refine_angle_deg: 165.0,
            max_spacing: self.max_spacing,
            first_height,
            medial_axis: true,
            ..SpacingParams::default()
        }
    }

    /// The boundary nodes of every loop on `curves` (from [`Self::curves`]), as the pipeline
    /// places them at first height `first_height`.
    ///
    /// # Panics
    /// When the boundary mesher fails.
    pub fn boundary_nodes(&self, curves: &[ClosedCurve], first_height: f64) -> Vec<BoundaryNodes> {
        boundary1d::mesh_loops(curves, &self.spacing(first_height))
            .unwrap_or_else(|e| panic!("{}: boundary mesh: {e}", self.name))
    }

    /// The mesher's loops made from boundary nodes `nodes` (one per loop, in order).
    pub fn front_loops_of(&self, nodes: &[BoundaryNodes]) -> Vec<FrontLoop> {
        self.loops
            .iter()
            .zip(nodes)
            .map(|((name, role, _), bn)| front_loop(bn, *role, name))
            .collect()
    }

    /// The boundary loops, meshed as the pipeline does (first height `first_height`).
    pub fn front_loops(&self, first_height: f64) -> Vec<FrontLoop> {
        let curves = self.curves();
        self.front_loops_of(&self.boundary_nodes(&curves, first_height))
    }

    /// The mesher's parameters for this case at growth `growth` and first height
    /// `first_height`.
    pub fn params(&self, first_height: f64, growth: f64) -> AfsfParams {
        AfsfParams {
            first_height,
            growth,
            max_layers: self.max_layers,
            inside: self.inside,
            ..AfsfParams::default()
        }
    }

    /// The mesher's parameters of the case file (its first height, growth 1.3).
    pub fn afsf_params(&self) -> AfsfParams {
        self.params(self.first_height, 1.3)
    }

    /// Curves, boundary nodes and the layered linear mesh at the case's own parameters, as
    /// `cargo xtask mesh` makes them.
    ///
    /// # Panics
    /// When a stage fails.
    pub fn grow(&self) -> Grown {
        self.grow_with(&self.afsf_params())
    }

    /// [`Self::grow`] with other mesher parameters (the boundary nodes are placed at
    /// `params.first_height`).
    ///
    /// # Panics
    /// When a stage fails.
    pub fn grow_with(&self, params: &AfsfParams) -> Grown {
        let curves = self.curves();
        let nodes = self.boundary_nodes(&curves, params.first_height);
        let output = afsf2d::grow_mesh(&self.front_loops_of(&nodes), params)
            .unwrap_or_else(|e| panic!("{}: linear mesh: {e}", self.name));
        Grown {
            curves,
            nodes,
            output,
        }
    }
}

/// The mesher's loop made from one loop's boundary nodes.
pub fn front_loop(nodes: &BoundaryNodes, role: Role, name: &str) -> FrontLoop {
    FrontLoop {
        points: nodes.points.iter().map(|p| [p.x, p.y]).collect(),
        is_corner: nodes.is_corner.clone(),
        role,
        name: name.to_string(),
    }
}
