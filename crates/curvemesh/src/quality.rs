//! Any 2D mesh checked as a run checks its own: counts, structural problems (conformity,
//! orientation), the largest angles of the linear cells, and the certified least scaled
//! Jacobian of every cell — for a `.msh` file read back, whoever wrote it.

use mesh_model::{Dim, Mesh};

use crate::error::{Result, bail};
use crate::report::Report;

/// `mesh` described and certified in a report named `name`; `origin` names it in messages.
/// Returns the report (its [`Report::is_valid`] tells the verdict) and each cell's least
/// scaled Jacobian.
pub fn check(mesh: &Mesh, name: &str, origin: &str) -> Result<(Report, Vec<f64>)> {
    if mesh.dim != Dim::Two || mesh.cells.is_empty() {
        bail!("{origin}: has no 2D cells to check (a surface or boundary-only mesh)");
    }
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
