//! A 2D case meshed: curves, boundary mesh (refused above the cell limit), the layered linear
//! mesh, the curving at P2/P3, then the report's description and the certified check of every
//! cell — with the mesh files written beside the check when the caller reserved them (the
//! files do not depend on it, and two threads do both at once).

use std::time::Instant;

use boundary1d::BoundaryNodes;
use geom_curve::ClosedCurve;
use mesh_model::{LayeredMesh, Mesh};

use crate::case::{Case, LoopInput};
use crate::error::Result;
use crate::meshed::{Meshed, Options};
use crate::observer::{Observer, stage};
use crate::outputs::Plan;
use crate::report::{Inputs, LinearAngles, LoopReport, Report};
use crate::stages::Snapshot;
use crate::{estimate, pipeline};

/// Meshes the 2D `case` with `options`, telling `observer` of each stage; the meshes (and the
/// snapshot, when asked for) are written into `plan`'s reserved outputs beside the check.
pub(crate) fn mesh(
    case: &Case,
    options: &Options,
    observer: &mut dyn Observer,
    plan: Option<&mut Plan>,
) -> Result<Meshed> {
    let order = case.order_of(options.order)?;
    estimate::check_loops(case, options.max_cells, observer)?;
    let mut report = Report::new(&case.name, order);
    report.inputs = Some(inputs_of(case));
    let (mesh, snapshot, angles, fill_cells) = make(case, options, order, observer, &mut report)?;
    let scaled_jacobian = certify_and_write(
        (&mesh, angles),
        plan.map(|p| (p, snapshot.as_ref())),
        observer,
        &mut report,
    )?;
    Ok(Meshed {
        mesh,
        report,
        scaled_jacobian,
        snapshot,
        linear: None,
        fill_cells,
    })
}

/// Describes `mesh` in the report, with the angle figures of `linear` (of the linear mesh
/// under it, the same at every order and with triangles), and certifies every cell, while
/// the meshes and the snapshot are written into `plan` (both at once, on two threads when
/// there are two). Returns each cell's least scaled Jacobian.
pub(crate) fn certify_and_write(
    (mesh, linear): (&Mesh, LinearAngles<'_>),
    plan: Option<(&mut Plan, Option<&Snapshot>)>,
    observer: &mut dyn Observer,
    report: &mut Report,
) -> Result<Vec<f64>> {
    let what = match plan {
        Some(_) => "certified validity, writing",
        None => "certified validity",
    };
    let t = Instant::now();
    observer.stage_begun(what);
    let (checked, written) = rayon::join(
        || -> Result<Vec<f64>> {
            report.describe_over(mesh, linear);
            let t = Instant::now();
            let scaled_jacobian = report.certify(mesh)?;
            report
                .timings_s
                .insert("validity", t.elapsed().as_secs_f64());
            Ok(scaled_jacobian)
        },
        || match plan {
            Some((plan, snapshot)) => plan.write_meshes_and_snapshot(mesh, snapshot).map(Some),
            None => Ok(None),
        },
    );
    observer.stage_ended(what, t.elapsed().as_secs_f64());
    // (a failed check is told before a failed write, as when they ran one after the other)
    let scaled_jacobian = checked?;
    if let Some((wrote, seconds)) = written? {
        for (path, format) in wrote {
            report.wrote_mesh(&path, format, mesh.order);
        }
        report.timings_s.insert("write", seconds);
    }
    Ok(scaled_jacobian)
}

/// Runs the stages: curves, boundary mesh (then the cell estimate), the layered linear mesh,
/// and the curving when `order` > 1. Returns the final mesh, the stages to save when asked
/// for, the angle figures of the linear layered mesh (its quads uncut), computed beside
/// the curving's decisions, before the curving lets go of the linear mesh (which it does
/// before it builds the curved mesh, the peak of the run's memory), and the number of its
/// fill cells ([`Meshed::fill_cells`]).
fn make(
    case: &Case,
    options: &Options,
    order: u8,
    observer: &mut dyn Observer,
    report: &mut Report,
) -> Result<(Mesh, Option<Snapshot>, LinearAngles<'static>, usize)> {
    // the layered part's edge table is made beside the fill when the curving will want it
    // and there is a second thread to make it
    let ahead = order > 1 && rayon::current_num_threads() > 1;
    let (curves, nodes, (grown, ahead)) =
        grow_ahead(case, options.max_cells, ahead, observer, report)?;
    let snapshot = options.snapshot.then(|| Snapshot {
        case: case.name.clone(),
        boundary: nodes.clone(),
        layered: grown.layered.clone(),
    });
    let fill_cells = crate::meshed::fill_cells(&grown.layered);
    let (mesh, angles) = at_order(
        case,
        (&curves, &nodes),
        (grown.layered, ahead),
        (order, options.triangles),
        observer,
        report,
    )?;
    Ok((mesh, snapshot, angles, fill_cells))
}

/// The first stages: curves, boundary mesh (then the cell estimate, refused above
/// `max_cells`), the layered linear mesh; their timings, loops and notes go to `report`.
pub(crate) fn grow(
    case: &Case,
    max_cells: u64,
    observer: &mut dyn Observer,
    report: &mut Report,
) -> Result<(Vec<ClosedCurve>, Vec<BoundaryNodes>, afsf2d::AfsfOutput)> {
    grow_ahead(case, max_cells, false, observer, report)
        .map(|(curves, nodes, (grown, _))| (curves, nodes, grown))
}

/// What [`grow_ahead`] makes: the curves, the boundary nodes, the linear mesh and, when
/// asked for, its layered part's edge table made beside its fill.
type Grown = (
    Vec<ClosedCurve>,
    Vec<BoundaryNodes>,
    (afsf2d::AfsfOutput, Option<pipeline::Ahead>),
);

/// [`grow`]; with `ahead`, the layered part's edge table is made beside the fill, for the
/// curving.
fn grow_ahead(
    case: &Case,
    max_cells: u64,
    ahead: bool,
    observer: &mut dyn Observer,
    report: &mut Report,
) -> Result<Grown> {
    let (boundary, seconds) = stage(observer, "boundary curves and 1D mesh", || {
        let curves = pipeline::curves(case)?;
        let nodes = pipeline::boundary_nodes(case, &curves)?;
        Ok::<_, crate::error::Error>((curves, nodes))
    });
    let (curves, nodes) = boundary?;
    report.timings_s.insert("boundary", seconds);
    for (input, curve_nodes) in case.loops.iter().zip(&nodes) {
        report.loops.push(loop_report(input, curve_nodes));
    }
    let expected = estimate::cells(case, &nodes);
    report.estimated_cells = Some(expected);
    let boundary_nodes = nodes.iter().map(|n| n.points.len()).sum();
    estimate::check_cells(expected, boundary_nodes, max_cells, observer)?;

    let (grown, seconds) = stage(observer, "linear layered mesh (AFSF)", || {
        pipeline::linear_mesh_ahead(case, &nodes, ahead)
    });
    let (grown, made_ahead) = grown?;
    report.timings_s.insert("linear", seconds);
    report.layers = Some(grown.stats.layers);
    report.notes.extend(growth_notes(&grown.stats));
    Ok((curves, nodes, (grown, made_ahead)))
}

/// The notes on the growth that tell where and what to do: the layers whose spring balance
/// stopped at its iteration limit, and the wall facets left without layers.
fn growth_notes(stats: &afsf2d::AfsfStats) -> Vec<String> {
    let mut notes = Vec::new();
    let open: Vec<String> = (stats.layer_stats.iter())
        .filter(|s| !s.converged)
        .map(|s| s.layer.to_string())
        .collect();
    if !open.is_empty() {
        notes.push(format!(
            "the spring balance of layer{} {} stopped at its iteration limit: those layers keep \
             the last iterate, and the mesh passed its checks (nothing to do unless the quality \
             figures show poor cells there)",
            if open.len() == 1 { "" } else { "s" },
            open.join(", ")
        ));
    }
    if let Some(first) = stats.bare_wall_facets_at.first() {
        let more = match stats.bare_wall_facets {
            1 => String::new(),
            n => format!(" and {} more", n - 1),
        };
        notes.push(format!(
            "{} wall facets have no layers (at ({:.6}, {:.6}){more}): the filled region meets \
             the wall directly, in a gap narrower than the first layer or a tight concave \
             corner; a lower [layers] first_height, or finer boundary spacing there (the \
             loop's max_spacing), lets the layers in",
            stats.bare_wall_facets, first[0], first[1]
        ));
    }
    notes
}

/// The mesh of the run at `order` (quads cut when `triangles`): `layered` curved by
/// Vector-Adding with its boundary nodes on `curves` at the `t` of `nodes` (the curving
/// takes it, to let go of what it no longer needs; `ahead`: its layered part's edge table,
/// made beside its fill), or itself at order 1; with the angle figures of `layered`: taken
/// beside the curving's decisions (within its time, so none of their own), or before the
/// copy at order 1 (with their time, which goes to `describe`).
fn at_order(
    case: &Case,
    (curves, nodes): (&[ClosedCurve], &[BoundaryNodes]),
    (layered, ahead): (LayeredMesh, Option<pipeline::Ahead>),
    (order, triangles): (u8, bool),
    observer: &mut dyn Observer,
    report: &mut Report,
) -> Result<(Mesh, LinearAngles<'static>)> {
    if order == 1 {
        let t = Instant::now();
        let angles = angles_of(&layered.mesh);
        let seconds = t.elapsed().as_secs_f64();
        return Ok((
            if triangles {
                linear_at_order(&layered, triangles, report)
            } else {
                report.curved_edge_fraction = Some(0.0);
                layered.mesh
            },
            LinearAngles::Given { angles, seconds },
        ));
    }
    let (curved, seconds) = stage(observer, "curving (Vector-Adding)", || {
        pipeline::curved_mesh_with(
            case,
            (curves, nodes),
            (layered, ahead),
            (order, triangles),
            angles_of,
        )
    });
    let (curved, angles) = curved?;
    report.timings_s.insert("curving", seconds);
    report.curved_edge_fraction = Some(curved.stats.curved_edge_fraction);
    report.curving = Some(curved.stats);
    let seconds = 0.0;
    Ok((curved.mesh, LinearAngles::Given { angles, seconds }))
}

/// The angle figures of the linear mesh `linear`.
fn angles_of(linear: &Mesh) -> afsf2d::AngleStats {
    afsf2d::max_angle_histogram(linear)
}

/// The mesh of a run at order 1: `layered`'s own (a copy), its quads cut when `triangles`.
pub(crate) fn linear_at_order(layered: &LayeredMesh, triangles: bool, report: &mut Report) -> Mesh {
    // a linear mesh has no curved edge
    report.curved_edge_fraction = Some(0.0);
    if triangles {
        afsf2d::cut_quads_shorter_diagonal(&layered.mesh)
    } else {
        layered.mesh.clone()
    }
}

/// The inputs of a 2D case as the run uses them.
pub(crate) fn inputs_of(case: &Case) -> Inputs {
    Inputs {
        first_height: case.layers.first_height,
        growth: case.layers.growth,
        max_layers: case.layers.max_layers,
        placement: case.placement.clone(),
    }
}

fn loop_report(input: &LoopInput, nodes: &BoundaryNodes) -> LoopReport {
    let n = nodes.points.len();
    let lengths = (0..n).map(|i| (nodes.points[(i + 1) % n] - nodes.points[i]).norm());
    let (min, max) = lengths.fold((f64::INFINITY, 0.0f64), |(lo, hi), l| {
        (lo.min(l), hi.max(l))
    });
    LoopReport {
        name: input.name.clone(),
        role: input.role.name(),
        nodes: n,
        corners: nodes.is_corner.iter().filter(|&&c| c).count(),
        spacing_min: min,
        spacing_max: max,
    }
}

#[cfg(test)]
mod tests {
    use super::growth_notes;
    use afsf2d::{AfsfStats, LayerStats};

    /// The layers whose balance stopped at its limit are named, and the first bare wall
    /// facet is located, with what to change.
    #[test]
    fn growth_notes_name_the_layers_and_the_place() {
        let layer = |layer, converged| LayerStats {
            layer,
            converged,
            ..LayerStats::default()
        };
        let stats = AfsfStats {
            layer_stats: vec![layer(1, true), layer(2, false), layer(5, false)],
            bare_wall_facets: 3,
            bare_wall_facets_at: vec![[0.7, 0.032094], [0.8, 0.0]],
            ..AfsfStats::default()
        };
        let notes = growth_notes(&stats);
        assert_eq!(notes.len(), 2, "{notes:?}");
        assert!(notes[0].contains("layers 2, 5 stopped"), "{}", notes[0]);
        assert!(
            notes[1].contains("3 wall facets have no layers (at (0.700000, 0.032094) and 2 more)"),
            "{}",
            notes[1]
        );
        assert!(growth_notes(&AfsfStats::default()).is_empty());
    }
}
