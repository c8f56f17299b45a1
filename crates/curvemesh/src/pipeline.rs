//! The stages of the pipeline as plain functions, shared by `mesh` and `bench`: checked loops
//! → curves → boundary nodes → the layered linear mesh. No file is touched here.

use std::borrow::Cow;

use crate::error::{Result, bail, input_error};
use afsf2d::AfsfParams;
use boundary1d::{BoundaryNodes, SpacingParams};
use geom_curve::{ClosedCurve, CurveParams, Point2, loops};
use mesh_model::Role;
use vector_adding::CurvingParams;

use crate::case::Case;
pub use crate::policy::{curving_of, spacing_of};

/// The loops of a case as curves, each counter-clockwise, in the case's order. Every loop
/// check (each loop, crossings between loops, nesting) runs before any curve is fitted.
pub fn curves(case: &Case) -> Result<Vec<ClosedCurve>> {
    let params = CurveParams::default();
    let at = |l: &crate::case::LoopInput| format!("loop '{}' ({})", l.name, l.origin);
    let mut polygons = Vec::with_capacity(case.loops.len());
    for l in &case.loops {
        let mut points: Vec<Point2<f64>> =
            l.points.iter().map(|p| Point2::new(p[0], p[1])).collect();
        loops::validate_loop(&points, &params.loop_checks)
            .map_err(|e| input_error!("{}: {e}", at(l)))?;
        loops::make_counter_clockwise(&mut points);
        polygons.push(points);
    }
    if let Err(e) = loops::check_loops_disjoint(&polygons) {
        let name = |i: usize| format!("'{}'", case.loops[i].name);
        if let geom_curve::CurveError::LoopsCross {
            loop_a,
            loop_b,
            x,
            y,
            ..
        } = e
        {
            bail!(
                "loops {} and {} cross at ({x}, {y}): move or scale one of them",
                name(loop_a),
                name(loop_b)
            );
        }
        bail!("{e}");
    }
    check_nesting(case, &polygons)?;
    case.loops
        .iter()
        .zip(&polygons)
        .map(|(l, points)| {
            ClosedCurve::new(points, &params).map_err(|e| input_error!("{}: {e}", at(l)))
        })
        .collect()
}

/// Walls must lie inside the far field and outside each other.
fn check_nesting(case: &Case, polygons: &[Vec<Point2<f64>>]) -> Result<()> {
    let walls: Vec<usize> = (0..case.loops.len())
        .filter(|&i| case.loops[i].role == Role::Wall)
        .collect();
    if let Some(ff) = case.loops.iter().position(|l| l.role == Role::Farfield) {
        for &w in &walls {
            if !loops::loop_inside_loop(&polygons[w], &polygons[ff]) {
                bail!(
                    "wall loop '{}' is not inside the farfield loop '{}'",
                    case.loops[w].name,
                    case.loops[ff].name
                );
            }
        }
    }
    for &a in &walls {
        for &b in &walls {
            if a != b && loops::loop_inside_loop(&polygons[a], &polygons[b]) {
                bail!(
                    "wall loop '{}' lies inside wall loop '{}': bodies must not overlap",
                    case.loops[a].name,
                    case.loops[b].name
                );
            }
        }
    }
    Ok(())
}

/// The spacing parameters of a case.
pub fn spacing_params(case: &Case) -> SpacingParams {
    spacing_of(&case.boundary, &case.layers)
}

/// The 1D boundary mesh of every loop.
pub fn boundary_nodes(case: &Case, curves: &[ClosedCurve]) -> Result<Vec<BoundaryNodes>> {
    let caps: Vec<f64> = case
        .loops
        .iter()
        .map(|l| l.max_spacing.unwrap_or(case.boundary.max_spacing))
        .collect();
    boundary1d::mesh_loops_with_caps(curves, &spacing_params(case), &caps)
        .map_err(|e| input_error!("boundary mesh: {e}"))
}

/// The mesher's parameters for a case.
pub fn afsf_params(case: &Case) -> AfsfParams {
    case.layers
}

/// The mesher's loops: the boundary nodes of every loop, with its role and boundary group.
pub fn front_loops(case: &Case, nodes: &[BoundaryNodes]) -> Vec<afsf2d::FrontLoop> {
    case.loops
        .iter()
        .zip(nodes)
        .map(|(input, bn)| afsf2d::FrontLoop {
            points: bn.points.iter().map(|p| [p.x, p.y]).collect(),
            is_corner: bn.is_corner.clone(),
            role: input.role,
            // the patch name is the loop's boundary group in the mesh files
            name: input.group.clone(),
        })
        .collect()
}

/// The layered linear mesh grown from the boundary nodes of every loop.
pub fn linear_mesh(case: &Case, nodes: &[BoundaryNodes]) -> Result<afsf2d::AfsfOutput> {
    linear_mesh_ahead(case, nodes, false).map(|(out, _)| out)
}

/// The edge table of a linear mesh's layered cells, made while its fill was, and the
/// positions among those cells of the ones the fill peeled back: for the curving
/// ([`curved_mesh_with`]), which finishes it rather than building the whole table.
pub type Ahead = (vector_adding::PartEdges, Vec<u32>);

/// [`linear_mesh`]; with `ahead`, the layered cells' edge table is made beside the fill.
pub fn linear_mesh_ahead(
    case: &Case,
    nodes: &[BoundaryNodes],
    ahead: bool,
) -> Result<(afsf2d::AfsfOutput, Option<Ahead>)> {
    let part_edges = |cells: &mesh_model::Cells, n: usize| {
        ahead.then(|| vector_adding::PartEdges::new(cells, n))
    };
    let (out, beside) =
        afsf2d::grow_mesh_with(&front_loops(case, nodes), &afsf_params(case), part_edges)
            .map_err(|e| input_error!("linear mesh: {e}"))?;
    Ok((out, beside.made.map(|part| (part, beside.left_out))))
}

/// The curving parameters of a case at an order.
pub fn curving_params(case: &Case, order: u8, triangles: bool) -> CurvingParams {
    curving_of(&case.curving, order, triangles)
}

/// The curved mesh of order 2 or 3 made from the layered linear mesh by Vector-Adding, with
/// the boundary's high-order nodes on `curves` (the case's, or its moved curves) at the
/// parameters `t` of the boundary `nodes`. A `layered` given to keep is let go piece by piece
/// as the curving no longer needs it (`vector_adding::curve_mesh_owned`): the same mesh with
/// less memory at the peak.
pub fn curved_mesh(
    case: &Case,
    curves: &[ClosedCurve],
    nodes: &[BoundaryNodes],
    layered: Cow<'_, mesh_model::LayeredMesh>,
    order: u8,
    triangles: bool,
) -> Result<vector_adding::Curved> {
    let (loops, params) = (
        loop_curves(curves, nodes),
        curving_params(case, order, triangles),
    );
    match layered {
        Cow::Borrowed(layered) => vector_adding::curve_mesh(layered, &loops, &params),
        Cow::Owned(layered) => vector_adding::curve_mesh_owned(layered, &loops, &params),
    }
    .map_err(|e| input_error!("curving: {e}"))
}

/// [`curved_mesh`] of a linear mesh given to keep, with `beside` run on the linear mesh while
/// the curving takes its decisions (`vector_adding::curve_mesh_owned_with`: on another thread
/// when there is one). Returns the curved mesh and what `beside` gave.
pub fn curved_mesh_with<R: Send>(
    case: &Case,
    (curves, nodes): (&[ClosedCurve], &[BoundaryNodes]),
    (layered, ahead): (mesh_model::LayeredMesh, Option<Ahead>),
    (order, triangles): (u8, bool),
    beside: impl FnOnce(&mesh_model::Mesh) -> R + Send,
) -> Result<(vector_adding::Curved, R)> {
    let (loops, params) = (
        loop_curves(curves, nodes),
        curving_params(case, order, triangles),
    );
    let (part, left_out) = ahead.map_or((None, Vec::new()), |(p, l)| (Some(p), l));
    let ahead = part.map(|part| (part, &left_out[..]));
    vector_adding::curve_mesh_owned_with(layered, &loops, &params, ahead, beside)
        .map_err(|e| input_error!("curving: {e}"))
}

/// Where the boundary nodes of every loop sit on its curve, for the curving.
pub fn loop_curves<'a>(
    curves: &'a [ClosedCurve],
    nodes: &'a [BoundaryNodes],
) -> Vec<vector_adding::LoopCurve<'a>> {
    curves
        .iter()
        .zip(nodes)
        .map(|(curve, bn)| vector_adding::LoopCurve { curve, t: &bn.t })
        .collect()
}
