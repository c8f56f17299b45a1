//! Test and bench fixture code only — not part of the pipeline. The built-in cases of
//! `curvemesh mesh` as the tool reads them (`fixtures/cases/*.toml` through the library's case
//! loader, [`curvemesh::load()`]) and run through the tool's own stages ([`curvemesh::pipeline`]):
//! curves, boundary nodes, the layered linear mesh and its curving. Domains made in code
//! (random bodies, ellipses) become a [`Case`] by [`case_of`] and run through the same
//! stages, so that the tests and benches of `afsf2d` and `vector-adding` mesh what the tool
//! meshes, with the same spacing rules and parameters.
//!
//! Dev-only: a `[dev-dependencies]` entry of this workspace's crates, never a normal
//! dependency, never published, and with no usage example of its own; no crate needs it to
//! be used (see `examples/standalone/`).

use afsf2d::{AfsfOutput, AfsfParams, FrontLoop};
use boundary1d::BoundaryNodes;
pub use curvemesh::case::{Case, LoopInput};
use curvemesh::pipeline;
use geom_curve::ClosedCurve;
use mesh_model::Role;
use vector_adding::{Curved, CurvingError, CurvingParams};

/// The names of the built-in cases (`cargo xtask mesh --list`).
pub fn real_cases() -> Vec<&'static str> {
    curvemesh::builtin::names()
}

/// A built-in case by name, read from its case file as `cargo xtask mesh NAME` reads it.
///
/// # Panics
/// When `name` is not a built-in case.
pub fn real_case(name: &str) -> Case {
    curvemesh::load::load_2d(name).unwrap_or_else(|e| panic!("built-in case {name}: {e:#}"))
}

/// A case made in code from its loops — (name, role, points) each, in any orientation — with
/// every parameter at the case file's default. `inside` meshes the inside of the single wall
/// loop.
pub fn case_of(name: &str, loops: Vec<(String, Role, Vec<[f64; 2]>)>, inside: bool) -> Case {
    let loops = loops
        .into_iter()
        .map(|(loop_name, role, points)| LoopInput {
            origin: format!("loop {loop_name}"),
            name: loop_name,
            role,
            points,
            group: String::new(),
            max_spacing: None,
        })
        .collect();
    Case::new(name, loops, inside, false)
}

/// `case` with layers of first height `first_height` growing by `growth` (the boundary nodes
/// follow the first height, as in the tool).
pub fn with_layers(case: &Case, first_height: f64, growth: f64) -> Case {
    let mut case = case.clone();
    case.layers.first_height = first_height;
    case.layers.growth = growth;
    case
}

/// The loops' curves and boundary nodes, as the tool makes them.
///
/// # Panics
/// When a stage fails (a loop the curve checks refuse, say).
pub fn boundary(case: &Case) -> (Vec<ClosedCurve>, Vec<BoundaryNodes>) {
    let curves = pipeline::curves(case).unwrap_or_else(|e| panic!("{}: curves: {e:#}", case.name));
    let nodes =
        pipeline::boundary_nodes(case, &curves).unwrap_or_else(|e| panic!("{}: {e:#}", case.name));
    (curves, nodes)
}

/// The mesher's loops of a case: its boundary nodes, as the tool hands them to `afsf2d`.
///
/// # Panics
/// As [`boundary`].
pub fn front_loops(case: &Case) -> Vec<FrontLoop> {
    pipeline::front_loops(case, &boundary(case).1)
}

/// The mesher's loops and parameters of a case, as the tool hands them to `afsf2d`.
///
/// # Panics
/// As [`boundary`].
pub fn mesher_input(case: &Case) -> (Vec<FrontLoop>, AfsfParams) {
    (front_loops(case), pipeline::afsf_params(case))
}

/// The layered linear mesh of a case and what it was grown from: all the curving needs.
#[derive(Debug, Clone)]
pub struct Grown {
    /// The case.
    pub case: Case,
    /// The loops' curves, counter-clockwise, in the case's loop order (= patch order).
    pub curves: Vec<ClosedCurve>,
    /// The boundary nodes of every loop, with their curve parameters `t`.
    pub nodes: Vec<BoundaryNodes>,
    /// The mesher's output: the layered mesh and the run's figures.
    pub output: AfsfOutput,
}

/// Curves, boundary nodes and the layered linear mesh of a case, by the tool's stages.
///
/// # Panics
/// When a stage fails.
pub fn grow(case: &Case) -> Grown {
    let (curves, nodes) = boundary(case);
    let output =
        pipeline::linear_mesh(case, &nodes).unwrap_or_else(|e| panic!("{}: {e:#}", case.name));
    Grown {
        case: case.clone(),
        curves,
        nodes,
        output,
    }
}

impl Grown {
    /// The layered mesh curved with `params`, its boundary's high-order nodes on the curves.
    ///
    /// # Errors
    /// The curving's own errors (bad parameters, say).
    pub fn curve(&self, params: &CurvingParams) -> Result<Curved, CurvingError> {
        let loops = pipeline::loop_curves(&self.curves, &self.nodes);
        vector_adding::curve_mesh(&self.output.layered, &loops, params)
    }

    /// The curving parameters of the case at `order`, as `cargo xtask mesh --order` takes
    /// them.
    pub fn curving_params(&self, order: u8, triangles: bool) -> CurvingParams {
        pipeline::curving_params(&self.case, order, triangles)
    }
}
