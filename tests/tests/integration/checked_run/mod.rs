//! One run of `cargo xtask mesh` (in-process) and the checks of what it wrote, shared by the
//! tests that run many geometries.
#![allow(dead_code)]

use std::path::Path;

use clap::Parser;
use curvemesh_cli::{Outcome, cli::Cli, execute};

/// What one run came to.
pub enum Verdict {
    /// Written, and every check passed; the largest angle of its triangles (quads cut).
    Valid(f64),
    /// Refused with this one-line message, nothing written.
    Refused(String),
}

/// Runs the case at `order` and checks what it wrote independently of the report: read back,
/// structurally valid, every cell certified, the cells' area equal to the area the boundary
/// encloses, no triangle (quads cut on the shorter diagonal) of `angle_bound` degrees or more.
/// `Err` describes a failure.
pub fn run_and_check(
    dir: &Path,
    case: &Path,
    order: u8,
    angle_bound: f64,
) -> Result<Verdict, String> {
    let msh = dir.join(format!("p{order}.msh"));
    let _ = std::fs::remove_file(&msh);
    let args = [
        "cargo xtask",
        "mesh",
        case.to_str().unwrap(),
        "--quiet",
        "--order",
        &order.to_string(),
        "--out",
        msh.to_str().unwrap(),
    ];
    let cli = Cli::try_parse_from(args).map_err(|e| e.to_string())?;
    let outcome = std::panic::catch_unwind(|| execute(cli)).map_err(|_| "panicked".to_string())?;
    match outcome {
        Err(e) => {
            let msg = format!("{e:#}");
            if msg.contains('\n') {
                return Err(format!("refusal of more than one line: {msg}"));
            }
            if msh.exists() {
                return Err(format!("refused ({msg}) but wrote {}", msh.display()));
            }
            return Ok(Verdict::Refused(msg));
        }
        Ok(Outcome::Invalid) => return Err("a mesh that failed validation (exit 2)".into()),
        Ok(Outcome::Valid) => {}
    }
    let mesh = mesh_io::read_msh(&msh).map_err(|e| format!("reading back: {e}"))?;
    let problems = mesh_model::validate(&mesh);
    if let Some(p) = problems.first() {
        return Err(format!(
            "{} structural problems, first: {p}",
            problems.len()
        ));
    }
    let v = jacobian_check::check_mesh(&mesh, &jacobian_check::CertifyParams::default())
        .map_err(|e| format!("certifying: {e}"))?;
    if !v.invalid_cells.is_empty() || !v.undecided.is_empty() {
        return Err(format!(
            "{} invalid and {} undecided cells",
            v.invalid_cells.len(),
            v.undecided.len()
        ));
    }
    let cells = jacobian_check::integrate_area(&mesh).map_err(|e| e.to_string())?;
    let enclosed = jacobian_check::enclosed_area(&mesh).map_err(|e| e.to_string())?;
    if (cells - enclosed).abs() > 1e-9 * enclosed.abs() {
        return Err(format!("cell area {cells:e} != enclosed area {enclosed:e}"));
    }
    let angle = afsf2d::max_angle_histogram(&mesh).max_angle_deg;
    if angle >= angle_bound {
        return Err(format!("a triangle of {angle:.2}° (bound {angle_bound}°)"));
    }
    Ok(Verdict::Valid(angle))
}
