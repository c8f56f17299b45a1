//! The built-in cases of the pipeline (`fixtures/cases/*.toml`), with their boundary nodes made
//! the way `cargo xtask mesh` makes them: `geom-curve` curves through the loop points, then
//! `boundary1d::mesh_loops` (curvature-driven spacing, corners at the first height).
#![allow(dead_code)]

use afsf2d::{AfsfParams, FrontLoop};
use boundary1d::SpacingParams;
use geom_curve::{ClosedCurve, CurveParams, Point2, loops};
use mesh_model::Role;

/// One built-in case: its loops (before boundary meshing) and parameters.
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

/// The names of the built-in cases.
pub const REAL_CASES: [&str; 5] = ["naca0012", "two-element", "bat", "lshape", "30p30n"];

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

fn circle(c: [f64; 2], r: f64) -> Vec<[f64; 2]> {
    geom_curve::circle_points(Point2::new(c[0], c[1]), r, 256)
        .unwrap()
        .iter()
        .map(|p| [p.x, p.y])
        .collect()
}

fn naca(digits: &str, scale: f64, rotate_deg: f64, translate: [f64; 2]) -> Vec<[f64; 2]> {
    let (s, c) = rotate_deg.to_radians().sin_cos();
    geom_curve::naca::naca4(digits, 101, true)
        .unwrap()
        .iter()
        .map(|p| {
            let (x, y) = (p.x * scale, p.y * scale);
            [x * c - y * s + translate[0], x * s + y * c + translate[1]]
        })
        .collect()
}

/// A built-in case by name.
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
    /// The boundary loops, meshed as the pipeline does (first height `first_height`).
    pub fn front_loops(&self, first_height: f64) -> Vec<FrontLoop> {
        let params = CurveParams::default();
        let curves: Vec<ClosedCurve> = self
            .loops
            .iter()
            .map(|(_, _, pts)| {
                let mut p: Vec<Point2<f64>> = pts.iter().map(|q| Point2::new(q[0], q[1])).collect();
                loops::make_counter_clockwise(&mut p);
                ClosedCurve::new(&p, &params).unwrap()
            })
            .collect();
        let spacing = SpacingParams {
            growth: 1.3,
            refine_angle_deg: 165.0,
            max_spacing: self.max_spacing,
            first_height,
            medial_axis: true,
            ..SpacingParams::default()
        };
        let nodes = boundary1d::mesh_loops(&curves, &spacing).unwrap();
        self.loops
            .iter()
            .zip(nodes)
            .map(|((name, role, _), bn)| FrontLoop {
                points: bn.points.iter().map(|p| [p.x, p.y]).collect(),
                is_corner: bn.is_corner.clone(),
                role: *role,
                name: name.clone(),
            })
            .collect()
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
}
