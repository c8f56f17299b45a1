//! Certifying one cell of the mesh being curved, built from the edge table with some of its
//! edges replaced by candidate points: the test behind every decision of the marching and the
//! repair. When the output is to be cut into triangles, a quadrilateral is judged by its two
//! triangles (see [`crate::split::best_halves`]), so that every decision holds for the cells
//! actually written.

use jacobian_check::{Certificate, certify_cell};
use mesh_model::{CellType, Mesh, Shape};

use crate::cellmap::{Interiors, cell_nodes};
use crate::decisions::Diagonal;
use crate::edges::EdgeTable;
use crate::error::CurvingError;
use crate::params::CurvingParams;
use crate::scratch::Scratch;
use crate::split::{TriScratch, best_halves, diagonal_as, judge_halves};

/// A candidate for one local edge of a cell: (local edge, node the points start from, the
/// `p − 1` inner points).
pub(crate) type Candidate<'a> = (u8, u32, &'a [[f64; 2]]);

/// What every check needs besides the edge table.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Ctx<'a> {
    pub mesh: &'a Mesh,
    pub interiors: &'a Interiors,
    pub params: &'a CurvingParams,
    /// Bottom and top local edge of every cell (see `roles::classify`).
    pub roles: &'a [[u8; 2]],
}

/// Certifies cell `ci` built from the edge table, with the edges in `replaced` taking their
/// candidate points.
pub(crate) fn check(
    ctx: &Ctx<'_>,
    edges: &EdgeTable,
    ci: usize,
    replaced: &[Candidate<'_>],
    s: &mut Scratch,
) -> Result<Certificate, CurvingError> {
    let p = edges.p;
    gather(ctx.mesh, ci, edges, replaced, s);
    let shape = ctx.mesh.cells.get(ci).ty.shape;
    let err = |source| CurvingError::Check { cell: ci, source };
    if shape == Shape::Quad && ctx.params.triangles {
        let halves = best_halves(
            p,
            &s.corners,
            &s.edge_pts,
            ctx.roles[ci][0],
            ctx.params.strategy,
            ctx.interiors,
            &ctx.params.certify,
            ctx.params.stop_min_scaled_jacobian,
            &mut s.tri,
            &mut s.tri_pts,
            &mut s.nodes,
            &mut s.diag,
        )
        .map_err(err)?;
        return Ok(halves.certificate);
    }
    cell_nodes(p, &s.corners, &s.edge_pts, ctx.interiors, &mut s.nodes);
    certify_cell(CellType::new(shape, p as u8), &s.nodes, &ctx.params.certify).map_err(err)
}

/// Certifies cell `ci` built from the edge table as it will be written: a quadrilateral cut
/// by `cut` is judged by its two triangles.
pub(crate) fn check_as_cut(
    ctx: &Ctx<'_>,
    edges: &EdgeTable,
    ci: usize,
    cut: Option<Diagonal>,
    s: &mut Scratch,
) -> Result<Certificate, CurvingError> {
    let Some(d) = cut else {
        let mut plain = *ctx.params;
        plain.triangles = false;
        return check(
            &Ctx {
                params: &plain,
                ..*ctx
            },
            edges,
            ci,
            &[],
            s,
        );
    };
    let p = edges.p;
    gather(ctx.mesh, ci, edges, &[], s);
    let (x, quad_pts, bottom) = (&s.corners, &s.edge_pts, ctx.roles[ci][0]);
    diagonal_as(p, x, quad_pts, bottom, ctx.params.strategy, d, &mut s.diag);
    let mut t = TriScratch {
        corners: &mut s.tri,
        pts: &mut s.tri_pts,
        nodes: &mut s.nodes,
    };
    let (from, on_map) = (d.from as usize, d.curved);
    let (interiors, certify) = (ctx.interiors, &ctx.params.certify);
    judge_halves(
        p, x, quad_pts, from, &s.diag, on_map, interiors, certify, &mut t,
    )
    .map_err(|source| CurvingError::Check { cell: ci, source })
}

/// The corners and edge points of cell `ci` (edge points in the cell's edge directions).
fn gather(mesh: &Mesh, ci: usize, edges: &EdgeTable, replaced: &[Candidate<'_>], s: &mut Scratch) {
    let q = edges.p - 1;
    let cell = mesh.cells.get(ci);
    let k = cell.corners();
    s.corners.clear();
    s.corners.extend(k.iter().map(|&v| mesh.xy(v)));
    s.edge_pts.clear();
    s.edge_pts.resize(k.len() * q, [0.0; 2]);
    for (j, e) in cell.ty.shape.edges().iter().enumerate() {
        let dst = &mut s.edge_pts[j * q..(j + 1) * q];
        let from = k[e[0]];
        match replaced.iter().find(|r| r.0 as usize == j) {
            Some(&(_, start, pts)) => {
                if start == from {
                    dst.copy_from_slice(pts);
                } else {
                    for (o, v) in dst.iter_mut().zip(pts.iter().rev()) {
                        *o = *v;
                    }
                }
            }
            None => edges.points_from(edges.cell_edges[ci][j], from, dst),
        }
    }
}
