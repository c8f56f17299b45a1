//! A 3D case meshed (`dimension = 3`): the wall surface, its check, the layers, the cut into
//! standard cells, the validation and measures (at orders 2 and 3 after the curving, each wall onto
//! its true surface, and the certified check of every cell), then the meshes written into the
//! caller's reserved outputs. Bad input (a surface that is open, inverted,
//! self-intersecting; an option that does not apply in 3D) is an error before any output.

use crate::case3d::{Case3d, CutCells, check_order};
use crate::error::{Result, bail};
use crate::meshed::{Meshed, Options};
use crate::observer::{Observer, stage};
use crate::outputs::Plan;
use crate::pipeline3d;
use crate::report::Report;

/// Meshes the 3D `case` with `options`, telling `observer` of each stage; the meshes are
/// written into `plan`'s reserved outputs.
pub(crate) fn mesh(
    case: &Case3d,
    options: &Options,
    observer: &mut dyn Observer,
    plan: Option<&mut Plan>,
) -> Result<Meshed> {
    let order = options.order.unwrap_or(case.order);
    check_order(order, &format!("--order {order}"))?;
    if options.snapshot || options.triangles {
        let what = if options.snapshot {
            "--snapshot"
        } else {
            "--triangles"
        };
        bail!("{what} applies to 2D cases (this case has dimension = 3)");
    }
    let mut report = Report::new(&case.name, order);
    report.dimension = 3;
    report.inputs = Some(crate::report::Inputs {
        first_height: case.layers.first_height,
        growth: case.layers.growth,
        max_layers: u32::try_from(case.layers.layers).unwrap_or(u32::MAX),
        placement: crate::placement::Placement::default(),
    });
    let o = &mut *observer;
    let r = &mut report;
    let (surface, shape) = timed(r, o, ("surface", "wall surface"), |_| {
        pipeline3d::surface(case)
    })?;
    timed(r, o, ("check", "surface check"), |_| {
        pipeline3d::check_surface(case, &surface)
    })?;
    // with a far field, the layers stop where they turn isotropic or near it
    let far = case
        .farfield
        .as_ref()
        .map(|f| crate::fill3d::farfield_for(case, f, &surface))
        .transpose()?;
    let with_far;
    let case = match &far {
        Some((_, max_thickness)) => {
            with_far = crate::fill3d::layers_before_fill(case, *max_thickness);
            &with_far
        }
        None => case,
    };
    let mut layered = grow_and_cut(case, &surface, far.is_some(), r, o)?;
    if prism_cut_kept_none(case, &layered) {
        // the fronts are reshaped for the prisms a cut keeps, and cost the tetrahedra of a
        // fill between close fronts: with none kept, the layers grow as the tetrahedral cut's
        layered = grow_unreshaped_and_cut(case, &surface, far.is_some(), r, o)?;
        r.notes.push(
            "the prism cut kept no prism (every layer has a cell to cut): the layers grown \
             again without reshaping their fronts' facets, as for the tetrahedral cut"
                .into(),
        );
    }
    let mut filled = match &far {
        Some((far, _)) => {
            let options = crate::fill3d::options(case);
            let fill = |l: &Layered, r: &mut Report, o: &mut dyn Observer| {
                timed(r, o, ("fill", "volume fill"), |_| {
                    crate::fill3d::fill(&l.mesh, &surface, far, &options)
                })
            };
            Some(fill_or_regrow(case, &surface, &mut layered, (r, o), fill)?)
        }
        None => None,
    };
    let Layered {
        grown,
        columns,
        mesh,
        cut_anyway,
        front,
    } = layered;
    let grown_layers = grown.layer_heights.len();
    let mut layers_mesh = mesh;
    let mut mesh = layers_mesh.clone();
    if let Some(f) = &filled {
        crate::fill3d::apply_linear(&mut mesh, f);
    }
    // the tetrahedra no cut mends (steps down to stopped columns, fronts facing each other)
    // mended by moving their free nodes, in the layers and the fill alike
    let smoothed = timed(r, o, ("smooth", "worst tetrahedra"), |_| {
        Ok::<_, crate::error::Error>(pipeline3d::smooth(
            &mut mesh,
            &grown,
            &mut layers_mesh,
            filled.as_mut(),
        ))
    })?;
    let mut measures = timed(r, o, ("measure", "measures"), |_| {
        pipeline3d::measure(&surface, &grown, &front, &mesh, grown_layers)
    });
    let curved = if order >= 2 {
        let curved = timed(r, o, ("curving", &format!("curving to P{order}")), |_| {
            let mut c = pipeline3d::curve(case, &shape, &grown, &layers_mesh, order)?;
            let mended = match &filled {
                Some(f) => Some(crate::fill3d::apply_curved(&mut c.mesh, f)?),
                None => None,
            };
            Ok::<_, crate::error::Error>((c, mended))
        })?;
        let (curved, mended) = curved;
        if let Some(m) = mended.filter(|m| m.invalid_fill_cells > 0) {
            r.notes.push(format!(
                "{} of the fill's straight cells on the curved last front were invalid: {} front \
                 edges and faces straightened in part or whole to mend them ({} cells not mended)",
                m.invalid_fill_cells, m.straightened, m.still_invalid
            ));
        }
        timed(r, o, ("volume", "curved volumes"), |_| {
            pipeline3d::curved_volumes(&curved.mesh, &mut measures)
        })?;
        Some(curved)
    } else {
        None
    };
    let out = curved.as_ref().map_or(&mesh, |c| &c.mesh);
    timed(r, o, ("validate", "validation"), |r| {
        r.describe_3d(out, &measures);
        match &curved {
            Some(c) => r.certify_3d(c, &shape),
            None => Ok(()),
        }
    })?;
    report.layers = Some(grown_layers as u32);
    report.fill = filled.as_ref().map(|f| f.stats);
    push_notes(
        &mut report,
        curved.is_none(),
        grown.stats.converged,
        filled.is_some(),
    );
    report.notes.extend(columns.note());
    report.columns = Some(columns);
    push_height_note(&mut report, &case.layers, &grown);
    push_cut_note(&mut report, case, cut_anyway);
    push_smooth_note(&mut report, &smoothed);
    if let Some(plan) = plan {
        timed(&mut report, observer, ("write", "writing"), |r| {
            for (path, format) in plan.write_meshes(out)? {
                r.wrote_mesh(&path, format, out.order);
            }
            Ok::<_, crate::error::Error>(())
        })?;
    }
    let (mesh, linear) = match curved {
        Some(c) => (c.mesh, Some(mesh)),
        None => (mesh, None),
    };
    Ok(Meshed {
        mesh,
        report,
        scaled_jacobian: Vec::new(),
        snapshot: None,
        linear,
        fill_cells: 0,
    })
}

/// The layers grown and cut, with what the report needs of them.
struct Layered {
    grown: afsf3d::Grown3d,
    columns: crate::columns3d::Columns,
    mesh: mesh_model::Mesh,
    cut_anyway: pipeline3d::CutAnyway,
    front: pipeline3d::FrontMeasures,
}

/// Grows `case`'s layers over `surface` (`filled`: a far field's fill follows) and cuts them
/// into standard cells; too few full columns fail here, before any output.
fn grow_and_cut(
    case: &Case3d,
    surface: &geom_surface::Surface,
    filled: bool,
    r: &mut Report,
    o: &mut dyn Observer,
) -> Result<Layered> {
    let grown = timed(r, o, ("grow", "layers (AFSF 3D)"), |_| {
        pipeline3d::grow(case, surface)
    })?;
    let columns = crate::columns3d::columns(surface, &grown, case.min_coverage, filled);
    columns.check(&case.origin)?;
    // (the fronts' measures are taken once: the mixed cut's leaning test reads them too)
    let (mesh, cut_anyway, front) = timed(r, o, ("cut", "cut into standard cells"), |_| {
        let front = pipeline3d::front_measures(surface, &grown);
        let (mut mesh, flagged) = pipeline3d::cut(case, &grown, &front)?;
        // the wall's facets in their surface patches' groups (the wing's tips apart)
        crate::groups3d::wall_groups(surface, &mut mesh)?;
        Ok::<_, crate::error::Error>((mesh, flagged, front))
    })?;
    Ok(Layered {
        grown,
        columns,
        mesh,
        cut_anyway,
        front,
    })
}

/// [`grow_and_cut`] with the fronts' facets not reshaped (`afsf3d`'s `shape`), whatever the
/// case asks: the second growth when the reshaped fronts served no prism or no fill.
fn grow_unreshaped_and_cut(
    case: &Case3d,
    surface: &geom_surface::Surface,
    filled: bool,
    r: &mut Report,
    o: &mut dyn Observer,
) -> Result<Layered> {
    let mut unshaped = case.clone();
    unshaped.layers.reshape = false;
    grow_and_cut(&unshaped, surface, filled, r, o)
}

/// Whether `layered` is a prism cut ([`CutCells::Prisms`]) of reshaped layers that kept no
/// prism: its layers are better grown unreshaped.
fn prism_cut_kept_none(case: &Case3d, layered: &Layered) -> bool {
    case.cells == CutCells::Prisms
        && case.layers.reshape
        && layered.grown.stats.reshaped > 0
        && layered.mesh.count(mesh_model::Shape::Prism) == 0
}

/// Fills the space between `layered`'s last fronts and the far field by `fill`. Where the
/// fill cannot recover a front the growth reshaped (`afsf3d`'s `shape`: on the extruded
/// 30P30N, its cells reshaped from 0.9 of their bars, the boundary recovery met an edge it
/// could not flip clear), the layers are grown again unreshaped and filled (a note says so);
/// a second failure is the run's error.
fn fill_or_regrow<T>(
    case: &Case3d,
    surface: &geom_surface::Surface,
    layered: &mut Layered,
    (r, o): (&mut Report, &mut dyn Observer),
    fill: impl Fn(&Layered, &mut Report, &mut dyn Observer) -> Result<T>,
) -> Result<T> {
    match fill(layered, r, o) {
        Err(e) if case.layers.reshape && layered.grown.stats.reshaped > 0 => {
            *layered = grow_unreshaped_and_cut(case, surface, true, r, o)?;
            r.notes.push(format!(
                "the layers grown again without reshaping their fronts' facets: the fill \
                 could not recover the reshaped fronts ({e})"
            ));
            fill(layered, r, o)
        }
        other => other,
    }
}

/// The report's note on the tetrahedra mended by moving nodes, when any was.
fn push_smooth_note(report: &mut Report, s: &topo_cut::smooth::Smoothed) {
    if s.moves > 0 {
        report.notes.push(format!(
            "{} node moves took the tetrahedra's largest dihedral angle from {:.1}° to {:.1}° \
             ({} over {}° before, {} after; walls and far field fixed, the first layer sliding across its extrusion edges)",
            s.moves,
            s.before_deg,
            s.after_deg,
            s.over_before,
            pipeline3d::SMOOTH_TARGET_DEG,
            s.over_after
        ));
    }
}

/// Runs `work` on `report` as the stage `what` and records its seconds in the report's
/// timings under `key`.
fn timed<T>(
    report: &mut Report,
    observer: &mut dyn Observer,
    (key, what): (&'static str, &str),
    work: impl FnOnce(&mut Report) -> T,
) -> T {
    let (out, seconds) = stage(observer, what, || work(report));
    report.timings_s.insert(key, seconds);
    out
}

/// The report's notes on what the mesh is: near-body, how validity was judged, balances that
/// ran out of iterations.
fn push_notes(report: &mut Report, linear: bool, converged: bool, filled: bool) {
    if !filled {
        report.notes.push(
            "a near-body mesh: the domain is the region the layers cover, its outer boundary \
             (the group outer) the final front; a [farfield] fills the space to a far field"
                .into(),
        );
    }
    if linear {
        report.notes.push(crate::report::P1_VALIDITY.into());
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::observer::Silent;

    /// A fill that refuses reshaped fronts gets the layers grown again unreshaped, with a
    /// note; one that takes them keeps them.
    #[test]
    fn a_fill_that_cannot_recover_reshaped_fronts_gets_them_grown_again_unreshaped() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../fixtures/cases3d/torus.toml"
        );
        let crate::load::AnyCase::Three(case) = crate::load::load(path).unwrap() else {
            panic!("a 3D case")
        };
        assert!(case.layers.reshape, "the mixed cut reshapes");
        let surface = pipeline3d::surface(&case).unwrap().0;
        let (mut r, mut o) = (Report::new("torus", 1), Silent);
        let mut layered = grow_and_cut(&case, &surface, true, &mut r, &mut o).unwrap();
        let reshaped = layered.grown.stats.reshaped;
        assert!(reshaped > 0);
        let refuse = |l: &Layered, _: &mut Report, _: &mut dyn Observer| {
            if l.grown.stats.reshaped > 0 {
                bail!("the volume fill: facet 0 cannot be recovered")
            }
            Ok(l.mesh.cells.len())
        };
        let cells = fill_or_regrow(&case, &surface, &mut layered, (&mut r, &mut o), refuse);
        assert_eq!(cells.unwrap(), layered.mesh.cells.len());
        assert_eq!(layered.grown.stats.reshaped, 0);
        assert!(
            r.notes
                .iter()
                .any(|n| n.contains("grown again without reshaping"))
        );
        // a fill that takes them: the reshaped layers stay, no note
        let mut r = Report::new("torus", 1);
        let mut layered = grow_and_cut(&case, &surface, true, &mut r, &mut o).unwrap();
        let take = |l: &Layered, _: &mut Report, _: &mut dyn Observer| Ok(l.grown.stats.reshaped);
        let kept = fill_or_regrow(&case, &surface, &mut layered, (&mut r, &mut o), take);
        assert_eq!(kept.unwrap(), reshaped);
        assert!(r.notes.is_empty());
    }
}
