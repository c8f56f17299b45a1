//! High-order nodes of the boundary edges, on the C2 curves: the inner nodes of a facet are
//! spaced equally in arc length between its two ends.

use geom_curve::ClosedCurve;
use mesh_model::Mesh;

use crate::decisions::EdgeRule;
use crate::edges::EdgeTable;
use crate::error::CurvingError;
use crate::loop_curve::LoopCurve;

/// Puts the inner points of every boundary facet on its loop's curve. The boundary nodes of
/// loop `l` are mesh nodes `first_l .. first_l + t.len()`, loops numbered as the patches.
pub(crate) fn place_on_curves(
    mesh: &Mesh,
    loops: &[LoopCurve<'_>],
    edges: &mut EdgeTable,
) -> Result<(), CurvingError> {
    let p = edges.p;
    let mut first = Vec::with_capacity(loops.len());
    let mut next = 0u32;
    for l in loops {
        first.push(next);
        next += l.t.len() as u32;
    }
    // every boundary node must sit on its curve, or the caller mixed up loops and patches
    for (l, lc) in loops.iter().enumerate() {
        let scale = lc.curve.total_length();
        for (k, &t) in lc.t.iter().enumerate() {
            let node = first[l] + k as u32;
            let Some(v) = mesh.nodes.get(node as usize) else {
                return Err(CurvingError::BoundaryMismatch {
                    facet: 0,
                    patch: l as u32,
                    what: format!("node {node} of the loop is not in the mesh"),
                });
            };
            let c = lc.curve.point(t);
            let off = ((v[0] - c.x).powi(2) + (v[1] - c.y).powi(2)).sqrt();
            if off > 1e-9 * scale {
                return Err(CurvingError::BoundaryMismatch {
                    facet: 0,
                    patch: l as u32,
                    what: format!("node {node} lies {off:e} off its curve at t = {t}"),
                });
            }
        }
    }
    let mut pts = vec![[0.0; 2]; p - 1];
    for (f, cell) in mesh.boundary.iter().enumerate() {
        let patch = mesh.boundary_patch[f];
        let Some(lc) = loops.get(patch as usize) else {
            return Err(CurvingError::BoundaryMismatch {
                facet: f,
                patch,
                what: format!("no curve given for it ({} curves)", loops.len()),
            });
        };
        let [a, b] = [cell.nodes[0], cell.nodes[1]];
        let n = lc.t.len() as u32;
        let local = |g: u32| g.checked_sub(first[patch as usize]).filter(|&k| k < n);
        let (Some(ka), Some(kb)) = (local(a), local(b)) else {
            return Err(CurvingError::BoundaryMismatch {
                facet: f,
                patch,
                what: format!("its nodes {a}, {b} are not nodes of the loop"),
            });
        };
        let forward = kb == (ka + 1) % n;
        if !forward && ka != (kb + 1) % n {
            return Err(CurvingError::BoundaryMismatch {
                facet: f,
                patch,
                what: format!("its nodes {a}, {b} are not neighbours on the loop"),
            });
        }
        let (lo, hi) = if forward { (ka, kb) } else { (kb, ka) };
        arc_points(lc.curve, lc.t[lo as usize], lc.t[hi as usize], p, &mut pts);
        if !forward {
            pts.reverse();
        }
        let e = edge_of(edges, a, b).ok_or_else(|| CurvingError::BoundaryMismatch {
            facet: f,
            patch,
            what: format!("no cell has the edge {a}–{b}"),
        })?;
        let [ax, bx] = [mesh.nodes[a as usize], mesh.nodes[b as usize]];
        let chord = ((bx[0] - ax[0]).powi(2) + (bx[1] - ax[1]).powi(2)).sqrt();
        let curved = pts.iter().enumerate().any(|(i, q)| {
            let s = (i + 1) as f64 / p as f64;
            let l = [ax[0] + s * (bx[0] - ax[0]), ax[1] + s * (bx[1] - ax[1])];
            (q[0] - l[0]).hypot(q[1] - l[1]) > 1e-9 * chord
        });
        edges.set_points_from(e, a, &pts, curved);
        edges.rules.set(e as usize, EdgeRule::OnCurve);
    }
    Ok(())
}

/// The inner points of every boundary facet, `p − 1` per facet in the mesh's facet order,
/// each listed from the facet's first node to its second.
pub(crate) fn facet_points(mesh: &Mesh, edges: &EdgeTable) -> Vec<[f64; 2]> {
    let q = edges.p - 1;
    let mut out = vec![[0.0; 2]; mesh.boundary.len() * q];
    for (f, cell) in mesh.boundary.iter().enumerate() {
        let [a, b] = [cell.nodes[0], cell.nodes[1]];
        let e = edge_of(edges, a, b).expect("every boundary facet is an edge of a cell");
        edges.points_from(e, a, &mut out[f * q..(f + 1) * q]);
    }
    out
}

/// Gives every boundary facet the inner points `pts` (laid out as [`facet_points`] makes
/// them).
///
/// # Errors
/// [`CurvingError::BoundaryMismatch`] when `pts` has the wrong length or a facet is no edge.
pub(crate) fn place_given(
    mesh: &Mesh,
    pts: &[[f64; 2]],
    edges: &mut EdgeTable,
) -> Result<(), CurvingError> {
    let q = edges.p - 1;
    if pts.len() != mesh.boundary.len() * q {
        return Err(CurvingError::BoundaryMismatch {
            facet: 0,
            patch: 0,
            what: format!(
                "{} boundary high-order points given, {} facets need {}",
                pts.len(),
                mesh.boundary.len(),
                mesh.boundary.len() * q
            ),
        });
    }
    for (f, cell) in mesh.boundary.iter().enumerate() {
        let [a, b] = [cell.nodes[0], cell.nodes[1]];
        let e = edge_of(edges, a, b).ok_or_else(|| CurvingError::BoundaryMismatch {
            facet: f,
            patch: mesh.boundary_patch[f],
            what: format!("no cell has the edge {a}–{b}"),
        })?;
        edges.set_points_from(e, a, &pts[f * q..(f + 1) * q], true);
        edges.rules.set(e as usize, EdgeRule::OnCurve);
    }
    Ok(())
}

/// The `p − 1` points equally spaced in arc length strictly between parameters `t0` and `t1`
/// (going forward in `t`, through the seam when `t1 ≤ t0`).
fn arc_points(curve: &ClosedCurve, t0: f64, t1: f64, p: usize, out: &mut [[f64; 2]]) {
    let period = curve.segment_count() as f64;
    let t1 = if t1 <= t0 { t1 + period } else { t1 };
    let s0 = curve.arc_length(0.0, t0);
    let length = curve.arc_length(t0, t1);
    for (i, o) in out.iter_mut().enumerate().take(p - 1) {
        let s = s0 + length * (i + 1) as f64 / p as f64;
        let c = curve.point(curve.t_at_arc_length(s));
        *o = [c.x, c.y];
    }
}

/// The edge joining `a` and `b`, by binary search in the (sorted) edges of the linear cells.
fn edge_of(edges: &EdgeTable, a: u32, b: u32) -> Option<u32> {
    let key = [a.min(b), a.max(b)];
    edges.ends.binary_search(&key).ok().map(|e| e as u32)
}
