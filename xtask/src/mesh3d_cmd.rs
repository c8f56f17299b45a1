//! `cargo xtask mesh` on a 3D case (`dimension = 3`): reserve every output, then the stages —
//! the wall surface, its check, the layers, the cut into standard cells, the validation and
//! measures (at order 2 after the curving, each wall onto its true surface, and the certified
//! check of every cell) — then the meshes (`.msh` with the physical groups `fluid`, `wall`
//! and `farfield`, the final front; `.vtu`), the pictures (a plane cut through the linear
//! cells) and the report, all put in place together. Bad input (a surface that is open, inverted, self-intersecting; a
//! flag that does not apply in 3D) leaves every output as it was and exits 1; a mesh that
//! fails validation is written and exits 2.

use std::time::Instant;

use anyhow::{Result, bail};
use mesh_io::Format;

use crate::case3d::{Case3d, check_order};
use crate::cli::MeshArgs;
use crate::mesh_cmd::{OutputFlags, Run, commit, plan_with, write_and_record};
use crate::progress::timed;
use crate::report::Report;
use crate::{Finished, pictures, pipeline3d};

/// Runs a 3D case; `total` is when the run started.
pub fn run(args: &MeshArgs, case: &Case3d, total: Instant) -> Result<Finished> {
    let order = args.output.order.unwrap_or(case.order);
    check_order(order, &format!("--order {order}"))?;
    refuse_2d_flags(args)?;
    let flags = OutputFlags {
        outs: &args.output.outs,
        report: args.output.report.as_deref(),
        snapshot: None,
        pictures: &args.pictures,
    };
    let mut plane = None;
    let mut plan = plan_with(&flags, &crate::outputs::file_stem_of(&case.name), || {
        let (pictures, p) = pictures::parse_3d(&args.pictures)?;
        plane = p;
        Ok(pictures)
    })?;
    plan.binary = args.binary;

    let mut report = Report::new(&case.name, order);
    report.dimension = 3;
    report
        .timings_s
        .insert("setup", total.elapsed().as_secs_f64());
    let quiet = args.quiet;
    let r = &mut report;
    let (surface, shape) = timed(r, quiet, ("surface", "wall surface"), |_| {
        pipeline3d::surface(case)
    })?;
    timed(r, quiet, ("check", "surface check"), |_| {
        pipeline3d::check_surface(case, &surface)
    })?;
    let grown = timed(r, quiet, ("grow", "layers (AFSF 3D)"), |_| {
        pipeline3d::grow(case, &surface)
    })?;
    // (the fronts' measures are taken once: the mixed cut's leaning test reads them too)
    let (mesh, cut_anyway, front) = timed(r, quiet, ("cut", "cut into standard cells"), |_| {
        let front = pipeline3d::front_measures(&surface, &grown);
        let (mesh, flagged) = pipeline3d::cut(case, &grown, &front)?;
        anyhow::Ok((mesh, flagged, front))
    })?;
    let mut measures = timed(r, quiet, ("measure", "measures"), |_| {
        pipeline3d::measure(&surface, &grown, &front, &mesh, case.layers.layers)
    });
    let curved = if order == 2 {
        let curved = timed(r, quiet, ("curving", "curving to P2"), |_| {
            pipeline3d::curve(case, &shape, &grown, &mesh)
        })?;
        timed(r, quiet, ("volume", "curved volumes"), |_| {
            pipeline3d::curved_volumes(&curved.mesh, &mut measures)
        })?;
        Some(curved)
    } else {
        None
    };
    let out = curved.as_ref().map_or(&mesh, |c| &c.mesh);
    timed(r, quiet, ("validate", "validation"), |r| {
        r.describe_3d(out, &measures);
        match &curved {
            Some(c) => r.certify_3d(c, &shape),
            None => Ok(()),
        }
    })?;
    report.layers = Some(case.layers.layers as u32);
    push_notes(&mut report, curved.is_none(), grown.stats.converged);
    push_height_note(&mut report, &case.layers, &grown);
    push_cut_note(&mut report, case, cut_anyway);
    timed(&mut report, quiet, ("write", "writing"), |r| {
        write_and_record(&mut plan, out, r)
    })?;
    if !plan.pictures.is_empty() {
        timed(&mut report, quiet, ("pictures", "pictures"), |_| {
            let (pictures, outputs) = (&plan.pictures, &mut plan.outputs);
            pictures::draw_slices(&mesh, pictures, &args.pictures, plane, &case.name, outputs)
        })?;
    }
    let run = Run {
        pictures: &args.pictures,
        name: &case.name,
        quiet,
        total,
    };
    let report_path = commit(plan, &run, &mut report)?;
    Ok(report.finish(report_path.as_deref(), quiet, "the mesh was written but"))
}

/// The report's notes on what the mesh is: near-body, how validity was judged, balances that
/// ran out of iterations.
fn push_notes(report: &mut Report, linear: bool, converged: bool) {
    report.notes.push(
        "a near-body mesh: the domain is the region the layers cover, its outer boundary \
         (farfield) the final front"
            .into(),
    );
    if linear {
        report.notes.push(
            "linear cells: validity is every corner Jacobian positive by the exact orient3d \
             (mesh_model::validate)"
                .into(),
        );
    }
    if !converged {
        report.notes.push(
            "some layers' spring balances ran out of iterations (the layers passed their checks)"
                .into(),
        );
    }
}

/// The report's note on layers whose height [`afsf3d::LayerParams::max_aspect`] held below
/// `first_height × growth^k`: from which layer, and the stack's thickness with and without.
fn push_height_note(report: &mut Report, params: &afsf3d::LayerParams, grown: &afsf3d::Grown3d) {
    let Some(first) = grown.stats.first_capped else {
        return;
    };
    let grown_to: f64 = grown.layer_heights.iter().sum();
    let geometric: f64 = (0..grown.layer_heights.len())
        .map(|k| params.first_height * params.growth.powi(k as i32))
        .sum();
    report.notes.push(format!(
        "layer heights held to {} × the front's mean edge from layer {first} on ({} layers): \
         the layers' heights sum to {grown_to:.4} (geometric first_height × growth^k: {geometric:.4})",
        params.max_aspect, grown.stats.capped_layers
    ));
}

/// The report's note on the standard layer cells the mixed cut cut into tetrahedra and
/// pyramids rather than keep ([`pipeline3d::cut_anyway`]), when there are any.
fn push_cut_note(report: &mut Report, case: &Case3d, cut: pipeline3d::CutAnyway) {
    let mut why = Vec::new();
    if cut.leaning > 0 {
        why.push(format!(
            "{} over an extrusion edge leaning more than {}° off the front's normal",
            cut.leaning, case.max_lean_deg
        ));
    }
    if cut.low_corner > 0 {
        why.push(format!(
            "{} with a corner scaled Jacobian below {}",
            cut.low_corner, case.min_corner_sj
        ));
    }
    if !why.is_empty() {
        report.notes.push(format!(
            "layer cells cut into tetrahedra and pyramids rather than kept as prisms or \
             hexahedra: {}",
            why.join(", ")
        ));
    }
}

/// Refuses the flags of 2D runs that mean nothing in 3D, and the linear-only `.su2` output,
/// before any work.
fn refuse_2d_flags(args: &MeshArgs) -> Result<()> {
    let given = [
        ("--snapshot", args.snapshot.is_some()),
        ("--triangles", args.output.triangles),
    ];
    if let Some((flag, _)) = given.into_iter().find(|f| f.1) {
        bail!("{flag} applies to 2D cases (this case has dimension = 3)");
    }
    for out in &args.output.outs {
        if Format::from_path(out) == Some(Format::Su2) {
            bail!(
                "--out {}: 3D meshes are written as .msh or .vtu",
                out.display()
            );
        }
    }
    Ok(())
}
