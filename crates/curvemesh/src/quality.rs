//! Any mesh checked as a run checks its own, for a `.msh` file read back, whoever wrote it.
//!
//! 2D: counts, structural problems (conformity, orientation), the largest angles of the
//! linear cells, and the certified least scaled Jacobian of every cell.
//!
//! 3D: what `mesh` checks of its 3D meshes — counts by type, structural problems
//! (conformity, every corner Jacobian positive by the exact `orient3d`), the largest dihedral
//! angle of the tetrahedra (table 7), the smallest corner scaled Jacobian of the prisms and
//! hexahedra, the smallest cell volume and the cell volumes against the volume the boundary
//! facets enclose ([`crate::pipeline3d::mesh_measures`], [`Report::describe_3d`]), and at
//! order 2 the curved volumes and the certified Jacobian check of every cell
//! ([`Report::certify_cells_3d`]). What needs the growth (coverage, layers, tables 5 and 6)
//! is left out.

use mesh_model::{Dim, Mesh};

use crate::error::{Result, bail};
use crate::pipeline3d;
use crate::report::{P1_VALIDITY, P2_VALIDITY, Report};

/// `mesh` described and certified in a report named `name`; `origin` names it in messages.
/// Returns the report (its [`Report::is_valid`] tells the verdict) and, in 2D, each cell's
/// least scaled Jacobian (empty in 3D).
pub fn check(mesh: &Mesh, name: &str, origin: &str) -> Result<(Report, Vec<f64>)> {
    if mesh.cells.is_empty() {
        bail!("{origin}: has no 2D or 3D cells to check (a surface or boundary-only mesh)");
    }
    match mesh.dim {
        Dim::Two => check_2d(mesh, name),
        Dim::Three => Ok((check_3d(mesh, name)?, Vec::new())),
    }
}

fn check_2d(mesh: &Mesh, name: &str) -> Result<(Report, Vec<f64>)> {
    let mut report = Report::new(name, mesh.order);
    if mesh.order > 1 {
        report
            .notes
            .push("angles are those of the linear cells under the curved ones".to_string());
    }
    report.describe(mesh);
    let t = std::time::Instant::now();
    let scaled_jacobian = report.certify(mesh)?;
    report
        .timings_s
        .insert("validity", t.elapsed().as_secs_f64());
    report.curved_edge_fraction = Some(jacobian_check::curved_edge_fraction(mesh));
    Ok((report, scaled_jacobian))
}

fn check_3d(mesh: &Mesh, name: &str) -> Result<Report> {
    let mut report = Report::new(name, mesh.order);
    report.dimension = 3;
    if mesh_model::first_structural_problem(mesh).is_some() {
        // nothing can be measured on indices that are out of range or coordinates that are
        // not finite: the counts and the problems
        report.describe_3d_structure(mesh);
        return Ok(report);
    }
    let t = std::time::Instant::now();
    let mut measures = pipeline3d::mesh_measures(mesh);
    report
        .timings_s
        .insert("measure", t.elapsed().as_secs_f64());
    if mesh.order > 1 {
        let t = std::time::Instant::now();
        pipeline3d::curved_volumes(mesh, &mut measures)?;
        report.timings_s.insert("volume", t.elapsed().as_secs_f64());
    }
    let t = std::time::Instant::now();
    report.describe_3d(mesh, &measures);
    report.notes.push(
        if mesh.order > 1 {
            P2_VALIDITY
        } else {
            P1_VALIDITY
        }
        .to_string(),
    );
    if mesh.order > 1 && report.certify_cells_3d(mesh)? {
        report.curved_edge_fraction = Some(jacobian_check::curved_edge_fraction(mesh));
    }
    report
        .timings_s
        .insert("validity", t.elapsed().as_secs_f64());
    report.notes.push(
        "a mesh read back: the volume check is against the volume its boundary facets \
         enclose; what measures the growth (coverage, layers, the front tables 5 and 6) is \
         not known"
            .to_string(),
    );
    Ok(report)
}
