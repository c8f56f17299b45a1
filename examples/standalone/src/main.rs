//! The curvemesh crates used from another project, both ways:
//!
//! 1. the whole pipeline by the `curvemesh` library: a case written as TOML text (a NACA 0012
//!    in a far-field circle) meshed at P3 with the tool's own policies and certified, the
//!    very mesh `curvemesh mesh` makes of it;
//! 2. pick-and-mix, the stage crates chained by hand: a NACA 0012 section (`geom_curve::naca`)
//!    and a far-field circle become C2 curves, get boundary nodes (`boundary1d`), a layered
//!    linear mesh (`afsf2d`), are curved to P3 (`vector_adding`), every cell is certified
//!    (`jacobian_check`), and the mesh is written as Gmsh MSH 4.1 and read back (`mesh_io`).
//!
//! Usage: `cargo run --release -- [OUT.msh]` (default: a file in the system's temporary
//! folder; the library's mesh goes beside it, `OUT-library.msh`). Exits 1 with one line on
//! stderr when a stage fails or a cell is not certified.

use std::path::PathBuf;
use std::process::ExitCode;

use afsf2d::{AfsfParams, FrontLoop};
use boundary1d::SpacingParams;
use geom_curve::{ClosedCurve, CurveParams, Point2};
use jacobian_check::CertifyParams;
use mesh_model::Role;
use vector_adding::{CurvingParams, LoopCurve};

type Error = Box<dyn std::error::Error>;

fn main() -> ExitCode {
    let out = std::env::args_os()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(|| std::env::temp_dir().join("curvemesh-standalone-naca0012.msh"));
    let library = out.with_file_name(format!(
        "{}-library.msh",
        out.file_stem().and_then(|s| s.to_str()).unwrap_or("mesh")
    ));
    match whole(&library).and_then(|()| run(&out)) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}

/// The case of the library path: a NACA 0012 in a circle of radius 10, first layer 1e-4.
const CASE: &str = r#"
name = "naca0012-standalone"
[[loop]]
role = "wall"
naca = "0012"
[[loop]]
role = "farfield"
circle = { center = [0.5, 0.0], radius = 10.0, points = 128 }
[layers]
first_height = 1e-4
"#;

/// The whole pipeline by the `curvemesh` library: the case meshed at P3, every cell
/// certified, written to `out`.
fn whole(out: &std::path::Path) -> Result<(), Error> {
    let case = curvemesh::load::parse_str(CASE)?;
    let options = curvemesh::Options {
        order: Some(3),
        ..Default::default()
    };
    let meshed = curvemesh::mesh(&case, &options, &mut curvemesh::Silent)?;
    if let Some(problem) = meshed.report.problems.first() {
        return Err(format!("the library's mesh failed validation: {problem}").into());
    }
    mesh_io::write(out, &meshed.mesh)?;
    println!(
        "library: {} cells at P3, all certified (min scaled Jacobian {:.3}); written to {}",
        meshed.mesh.cells.len(),
        meshed.scaled_jacobian.iter().copied().fold(f64::INFINITY, f64::min),
        out.display()
    );
    Ok(())
}

/// The pick-and-mix path: the stage crates chained by hand.
fn run(out: &std::path::Path) -> Result<(), Error> {
    // 1. geometry: the section (unit chord, closed trailing edge) and a far field of radius 10
    let wall = geom_curve::naca::naca4("0012", 81, true)?;
    let far = geom_curve::circle_points(Point2::new(0.5, 0.0), 10.0, 128)?;
    let fit = |mut p: Vec<Point2<f64>>| -> Result<ClosedCurve, Error> {
        geom_curve::loops::make_counter_clockwise(&mut p);
        Ok(ClosedCurve::new(&p, &CurveParams::default())?)
    };
    let curves = [fit(wall)?, fit(far)?];
    let roles = [(Role::Wall, "naca0012"), (Role::Farfield, "farfield")];

    // 2. boundary nodes, spaced by curvature and graded from the trailing edge
    let first_height = 1e-4;
    let spacing = SpacingParams {
        first_height,
        max_spacing: 1.0,
        ..SpacingParams::default()
    };
    let nodes = boundary1d::mesh_loops(&curves, &spacing)?;

    // 3. the layered linear mesh (quads and triangles), grown from both loops
    let loops: Vec<FrontLoop> = nodes
        .iter()
        .zip(roles)
        .map(|(bn, (role, name))| FrontLoop {
            points: bn.points.iter().map(|p| [p.x, p.y]).collect(),
            is_corner: bn.is_corner.clone(),
            role,
            name: name.to_string(),
        })
        .collect();
    let params = AfsfParams {
        first_height,
        growth: 1.3,
        max_layers: 30,
        ..AfsfParams::default()
    };
    let linear = afsf2d::grow_mesh(&loops, &params)?;

    // 4. curved to P3: the wall's high-order nodes on its curve, carried up the layers
    let on_curves: Vec<LoopCurve<'_>> = curves
        .iter()
        .zip(&nodes)
        .map(|(curve, bn)| LoopCurve { curve, t: &bn.t })
        .collect();
    let curving = CurvingParams {
        order: 3,
        ..CurvingParams::default()
    };
    let curved = vector_adding::curve_mesh(&linear.layered, &on_curves, &curving)?;
    let mesh = curved.mesh;

    // 5. every cell certified: a proof that the Jacobian determinant is positive everywhere
    let validity = jacobian_check::check_mesh(&mesh, &CertifyParams::default())?;
    if let Some(&cell) = validity
        .invalid_cells
        .iter()
        .chain(&validity.undecided)
        .next()
    {
        return Err(format!("cell {cell} of the P3 mesh is not certified valid").into());
    }
    // the curved cells cover exactly the region the curved boundary encloses
    let area = jacobian_check::integrate_area(&mesh)?;
    let enclosed = jacobian_check::enclosed_area(&mesh)?;
    if (area - enclosed).abs() > 1e-9 * enclosed.abs() {
        return Err(format!("cells cover {area}, the boundary encloses {enclosed}").into());
    }

    // 6. written as Gmsh MSH 4.1 (atomically) and read back
    mesh_io::write(out, &mesh)?;
    let back = mesh_io::read_msh(out)?;
    if back.cells != mesh.cells || back.nodes.len() != mesh.nodes.len() {
        return Err(format!("{} does not read back as written", out.display()).into());
    }
    println!(
        "NACA 0012: {} boundary nodes, {} linear cells in {} layers, P3 with {:.1} % of the \
         edges curved; all {} cells certified (min scaled Jacobian {:.3}), area {:.6}; \
         written to {}",
        nodes.iter().map(|n| n.len()).sum::<usize>(),
        linear.layered.mesh.cells.len(),
        linear.stats.layers,
        100.0 * curved.stats.curved_edge_fraction,
        mesh.cells.len(),
        validity.min_scaled_jacobian,
        area,
        out.display()
    );
    Ok(())
}
