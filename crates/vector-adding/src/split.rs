//! Cutting curved quadrilaterals into two triangles along the shorter diagonal. The diagonal
//! stays straight where both triangles are valid with it and at least as good as the stop
//! threshold asks of a pipe's last cell; otherwise it follows the
//! quadrilateral's map (two-vector: where the top edge carries the bottom's deviation that map
//! is a polynomial of degree p on each half, so the triangles reproduce it exactly) or its
//! lower triangle's map (one-vector).

use jacobian_check::{Certificate, CertifyParams, JacobianError, certify_cell};
use mesh_model::{CellType, Mesh, NONE, Shape};

use crate::cellmap::{Interiors, coons, lagrange_1d};
use crate::decisions::Diagonal;
use crate::edges::{EdgeTable, lerp};
use crate::error::CurvingError;
use crate::params::{CurvingParams, Strategy};
use crate::quality::quality;
use crate::roles::NO_EDGE;
use crate::scratch::Scratch;

/// A cell of the output: corners and the edge of each local edge (Gmsh order).
#[derive(Debug, Clone, Copy)]
pub(crate) struct OutCell {
    pub shape: Shape,
    pub corners: [u32; 4],
    pub edges: [u32; 4],
    /// The linear cell it comes from.
    pub source: u32,
    /// The interior node of a cubic triangle cut from a quadrilateral with a curved
    /// diagonal, placed on the quadrilateral's map; None: from the triangle's own edges.
    pub interior: Option<[f64; 2]>,
}

impl OutCell {
    pub fn len(&self) -> usize {
        if self.shape == Shape::Quad { 4 } else { 3 }
    }
}

/// The output cells without cutting: one per linear cell, made as they are read (no array of
/// them: the assembly walks them without holding a copy of the cells) from the edge table
/// alone, so that the linear cells can be let go before: `cell_edges` are each cell's edges
/// in Gmsh order (NONE in a triangle's fourth slot), `ends` each edge's ends, and corner `j`
/// of a cell is where its edges `j − 1` and `j` meet.
pub(crate) fn keep<'a>(
    cell_edges: &'a [[u32; 4]],
    ends: &'a [[u32; 2]],
) -> impl Iterator<Item = OutCell> + Clone + 'a {
    (0..cell_edges.len()).map(move |i| keep_at(cell_edges, ends, i))
}

/// Output cell `i` of [`keep`], on its own (the assembly takes the cells by index, from
/// every thread).
pub(crate) fn keep_at(cell_edges: &[[u32; 4]], ends: &[[u32; 2]], i: usize) -> OutCell {
    let edges = cell_edges[i];
    let (shape, n) = if edges[3] == NONE {
        (Shape::Tri, 3)
    } else {
        (Shape::Quad, 4)
    };
    let mut corners = [0; 4];
    for (j, corner) in corners.iter_mut().enumerate().take(n) {
        let [a, b] = ends[edges[(j + n - 1) % n] as usize];
        *corner = if ends[edges[j] as usize].contains(&a) {
            a
        } else {
            b
        };
    }
    OutCell {
        shape,
        corners,
        edges,
        source: i as u32,
        interior: None,
    }
}

/// The two triangles of a quadrilateral cut along its shorter diagonal, and the verdict on
/// them.
#[derive(Debug, Clone)]
pub(crate) struct Halves {
    /// The diagonal runs from local corner `from` to local corner `from + 2`.
    pub from: usize,
    /// Whether the diagonal had to be curved (its points are in `Scratch::diag`).
    pub curved: bool,
    /// The interior nodes of the two triangles when they are cubic and the diagonal curved.
    pub interiors: [Option<[f64; 2]>; 2],
    /// Valid when both triangles are (with the lower scaled-Jacobian bound of the two);
    /// otherwise the first failing triangle's certificate.
    pub certificate: Certificate,
}

/// The local corners of the two triangles of a cut quadrilateral, and for each triangle edge
/// the quadrilateral edge it is (None: the diagonal).
fn triangles_of(from: usize) -> [([usize; 3], [Option<usize>; 3]); 2] {
    if from == 0 {
        [
            ([0, 1, 2], [Some(0), Some(1), None]),
            ([0, 2, 3], [None, Some(2), Some(3)]),
        ]
    } else {
        [
            ([0, 1, 3], [Some(0), None, Some(3)]),
            ([1, 2, 3], [Some(1), Some(2), None]),
        ]
    }
}

/// Scratch buffers of one cut triangle's nodes.
pub(crate) struct TriScratch<'a> {
    pub corners: &'a mut Vec<[f64; 2]>,
    pub pts: &'a mut Vec<[f64; 2]>,
    pub nodes: &'a mut Vec<[f64; 2]>,
}

/// The centre, on the map of the quadrilateral with corners `x` and edge points `quad_pts`,
/// of its cut triangle with local corners `tc`.
fn centre(p: usize, x: &[[f64; 2]], quad_pts: &[[f64; 2]], tc: &[usize; 3]) -> [f64; 2] {
    // a cut triangle's corners in the quadrilateral's (u, v)
    const UV: [[f64; 2]; 4] = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    let u = (UV[tc[0]][0] + UV[tc[1]][0] + UV[tc[2]][0]) / 3.0;
    let v = (UV[tc[0]][1] + UV[tc[1]][1] + UV[tc[2]][1]) / 3.0;
    coons(p, x, quad_pts, u, v)
}

/// The interior nodes of the two triangles of the cut from `from`: on the quadrilateral's
/// map when they are cubic and the diagonal curved, else from their own edges (None).
fn cut_interiors(
    p: usize,
    x: &[[f64; 2]],
    quad_pts: &[[f64; 2]],
    from: usize,
    curved: bool,
) -> [Option<[f64; 2]>; 2] {
    if !curved || p != 3 {
        return [None; 2];
    }
    let tris = triangles_of(from);
    [
        Some(centre(p, x, quad_pts, &tris[0].0)),
        Some(centre(p, x, quad_pts, &tris[1].0)),
    ]
}

/// Certifies the two triangles of the quadrilateral (corners `x`, edge points `quad_pts`)
/// cut from local corner `from` along the diagonal with inner points `diag`, their cubic
/// centres on the quadrilateral's map when `on_map`: valid with the lower bound of the two,
/// or the first failing triangle's certificate.
#[allow(clippy::too_many_arguments)]
pub(crate) fn judge_halves(
    p: usize,
    x: &[[f64; 2]],
    quad_pts: &[[f64; 2]],
    from: usize,
    diag: &[[f64; 2]],
    on_map: bool,
    interiors: &Interiors,
    certify: &CertifyParams,
    s: &mut TriScratch<'_>,
) -> Result<Certificate, JacobianError> {
    let q = p - 1;
    let tri = CellType::new(Shape::Tri, p as u8);
    let mut worst: Option<Certificate> = None;
    for (tc, te) in &triangles_of(from) {
        s.corners.clear();
        s.corners.extend(tc.iter().map(|&l| x[l]));
        s.pts.clear();
        for (m, edge) in te.iter().enumerate() {
            let a = tc[m];
            match edge {
                Some(j) => s.pts.extend_from_slice(&quad_pts[j * q..(j + 1) * q]),
                None if a == from => s.pts.extend_from_slice(diag),
                None => s.pts.extend(diag.iter().rev()),
            }
        }
        crate::cellmap::cell_nodes(p, s.corners, s.pts, interiors, s.nodes);
        if on_map && p == 3 {
            s.nodes[9] = centre(p, x, quad_pts, tc);
        }
        let c = certify_cell(tri, s.nodes, certify)?;
        if !c.is_valid() {
            return Ok(c);
        }
        if worst.as_ref().is_none_or(|w| quality(&c) < quality(w)) {
            worst = Some(c);
        }
    }
    Ok(worst.expect("two triangles"))
}

/// The cut `d` of a quadrilateral replayed: its diagonal's inner points into `diag`, and the
/// triangles' interior nodes.
pub(crate) fn diagonal_as(
    p: usize,
    x: &[[f64; 2]],
    quad_pts: &[[f64; 2]],
    bottom: u8,
    strategy: Strategy,
    d: Diagonal,
    diag: &mut Vec<[f64; 2]>,
) -> [Option<[f64; 2]>; 2] {
    let from = d.from as usize;
    diag.clear();
    diag.extend((0..p - 1).map(|j| lerp(x[from], x[from + 2], (j + 1) as f64 / p as f64)));
    if d.curved {
        curved_diagonal(p, x, quad_pts, from, bottom, strategy, diag);
    }
    cut_interiors(p, x, quad_pts, from, d.curved)
}

/// Cuts the quadrilateral with corners `x` and edge points `quad_pts` (in its edge
/// directions) along its shorter diagonal: straight if both triangles are valid so with a
/// scaled Jacobian of at least `good_enough`, else curved by `strategy` if that is better;
/// leaves the diagonal's inner points in `diag`.
#[allow(clippy::too_many_arguments)]
pub(crate) fn best_halves(
    p: usize,
    x: &[[f64; 2]],
    quad_pts: &[[f64; 2]],
    bottom: u8,
    strategy: Strategy,
    interiors: &Interiors,
    certify: &CertifyParams,
    good_enough: f64,
    corners: &mut Vec<[f64; 2]>,
    pts: &mut Vec<[f64; 2]>,
    nodes: &mut Vec<[f64; 2]>,
    diag: &mut Vec<[f64; 2]>,
) -> Result<Halves, JacobianError> {
    let d02 = (x[2][0] - x[0][0]).hypot(x[2][1] - x[0][1]);
    let d13 = (x[3][0] - x[1][0]).hypot(x[3][1] - x[1][1]);
    let from = if d02 <= d13 { 0 } else { 1 };
    let mut s = TriScratch {
        corners,
        pts,
        nodes,
    };
    let mut judge = |diag: &[[f64; 2]], on_map: bool| {
        judge_halves(
            p, x, quad_pts, from, diag, on_map, interiors, certify, &mut s,
        )
    };
    let straight_cut = Diagonal {
        from: from as u8,
        curved: false,
    };
    diagonal_as(p, x, quad_pts, bottom, strategy, straight_cut, diag);
    let straight = judge(diag, false)?;
    if quality(&straight) >= good_enough {
        return Ok(Halves {
            from,
            curved: false,
            interiors: [None; 2],
            certificate: straight,
        });
    }
    let chord = diag.clone();
    curved_diagonal(p, x, quad_pts, from, bottom, strategy, diag);
    let certificate = judge(diag, true)?;
    if straight.is_valid() && quality(&straight) >= quality(&certificate) {
        // valid but poor either way: the straight one is no worse
        diag.clone_from(&chord);
        return Ok(Halves {
            from,
            curved: false,
            interiors: [None; 2],
            certificate: straight,
        });
    }
    Ok(Halves {
        from,
        curved: true,
        interiors: cut_interiors(p, x, quad_pts, from, true),
        certificate,
    })
}

/// Figures of the cutting.
#[derive(Debug, Clone, Default)]
pub(crate) struct CutOutcome {
    pub curved_diagonals: usize,
    /// Triangles found invalid (none are judged when the cuts are replayed).
    pub invalid: usize,
    /// The cut of every linear cell (None for a triangle).
    pub diagonals: Vec<Option<Diagonal>>,
}

/// Cuts every quadrilateral into two triangles, adding the diagonals to `edges`: deciding
/// each cut, or replaying `fixed` (one per linear cell) without judging it.
pub(crate) fn cut(
    mesh: &Mesh,
    roles: &[[u8; 2]],
    edges: &mut EdgeTable,
    interiors: &Interiors,
    params: &CurvingParams,
    fixed: Option<&[Option<Diagonal>]>,
) -> Result<(Vec<OutCell>, CutOutcome), CurvingError> {
    let p = edges.p;
    let q = p - 1;
    let mut out = Vec::with_capacity(mesh.cells.len() * 2);
    let mut outcome = CutOutcome {
        diagonals: vec![None; mesh.cells.len()],
        ..CutOutcome::default()
    };
    let mut s = Scratch::default();
    let mut quad_pts = vec![[0.0; 2]; 4 * q];
    for (i, c) in mesh.cells.iter().enumerate() {
        let k = c.corners();
        let ce = edges.cell_edges[i];
        if c.ty.shape != Shape::Quad {
            let mut corners = [0; 4];
            corners[..3].copy_from_slice(k);
            out.push(OutCell {
                shape: c.ty.shape,
                corners,
                edges: ce,
                source: i as u32,
                interior: None,
            });
            continue;
        }
        let x: Vec<[f64; 2]> = k.iter().map(|&v| mesh.xy(v)).collect();
        for j in 0..4 {
            edges.points_from(ce[j], k[j], &mut quad_pts[j * q..(j + 1) * q]);
        }
        let (from, curved, halves_interiors) = match fixed {
            Some(fixed) => {
                let d = fixed[i].ok_or_else(|| {
                    CurvingError::NotTheSameMesh(format!("cell {i} is a quadrilateral now"))
                })?;
                let strategy = params.strategy;
                let inner = diagonal_as(p, &x, &quad_pts, roles[i][0], strategy, d, &mut s.diag);
                (d.from as usize, d.curved, inner)
            }
            None => {
                let halves = best_halves(
                    p,
                    &x,
                    &quad_pts,
                    roles[i][0],
                    params.strategy,
                    interiors,
                    &params.certify,
                    params.stop_min_scaled_jacobian,
                    &mut s.tri,
                    &mut s.tri_pts,
                    &mut s.nodes,
                    &mut s.diag,
                )
                .map_err(|source| CurvingError::Check { cell: i, source })?;
                if !halves.certificate.is_valid() {
                    outcome.invalid += 1;
                }
                (halves.from, halves.curved, halves.interiors)
            }
        };
        if curved {
            outcome.curved_diagonals += 1;
        }
        outcome.diagonals[i] = Some(Diagonal {
            from: from as u8,
            curved,
        });
        let de = edges.push(k[from], k[from + 2], &s.diag, curved);
        for ((tc, te), interior) in triangles_of(from).iter().zip(halves_interiors) {
            let mut corners = [0; 4];
            let mut es = [mesh_model::NONE; 4];
            for m in 0..3 {
                corners[m] = k[tc[m]];
                es[m] = te[m].map_or(de, |j| ce[j]);
            }
            out.push(OutCell {
                shape: Shape::Tri,
                corners,
                edges: es,
                source: i as u32,
                interior,
            });
        }
    }
    Ok((out, outcome))
}

/// The inner points of the diagonal from local corner `from` (0 or 1) of a quadrilateral with
/// corners `x` and edge points `quad_pts` (in its edge directions), by `strategy`.
fn curved_diagonal(
    p: usize,
    x: &[[f64; 2]],
    quad_pts: &[[f64; 2]],
    from: usize,
    bottom: u8,
    strategy: Strategy,
    diag: &mut [[f64; 2]],
) {
    let q = p - 1;
    let at = |j: usize| (j + 1) as f64 / p as f64;
    if strategy == Strategy::OneVector && bottom != NO_EDGE {
        // the lower triangle's map: the bottom curve plus one extrusion vector
        let kb = bottom as usize;
        let (a, b) = (kb, (kb + 1) % 4);
        let (cb, ca) = ((kb + 2) % 4, (kb + 3) % 4);
        let bottom_curve = |s: f64| lagrange_1d(p, x[a], &quad_pts[kb * q..(kb + 1) * q], x[b], s);
        let v = |top: usize, base: usize| [x[top][0] - x[base][0], x[top][1] - x[base][1]];
        for (j, d) in diag.iter_mut().enumerate() {
            let s = at(j);
            // the diagonal runs a → cb or b → ca; walk it from `from`
            *d = if from == a || from == cb {
                let sigma = if from == a { s } else { 1.0 - s };
                let (bc, vb) = (bottom_curve(sigma), v(cb, b));
                [bc[0] + sigma * vb[0], bc[1] + sigma * vb[1]]
            } else {
                let sigma = if from == b { s } else { 1.0 - s };
                let (bc, va) = (bottom_curve(1.0 - sigma), v(ca, a));
                [bc[0] + sigma * va[0], bc[1] + sigma * va[1]]
            };
        }
        return;
    }
    for (j, d) in diag.iter_mut().enumerate() {
        let s = at(j);
        let (u, v) = if from == 0 { (s, s) } else { (1.0 - s, s) };
        *d = coons(p, x, quad_pts, u, v);
    }
}
