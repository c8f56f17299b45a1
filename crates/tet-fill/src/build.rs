//! The unconstrained Delaunay tetrahedralisation of a point set: input checks (finite,
//! distinct), a first tet on four non-coplanar points, then every other point inserted in BRIO
//! order.

use crate::error::FillError;
use crate::insert::{Located, Scratch};
use crate::mesh::Mesh;
use crate::order::brio;
use geom_predicates::{orient2d, orient3d};

/// Refuses non-finite and repeated points.
pub(crate) fn check_points(points: &[[f64; 3]]) -> Result<(), FillError> {
    if let Some(index) = points.iter().position(|p| p.iter().any(|x| !x.is_finite())) {
        return Err(FillError::NonFinitePoint {
            index,
            point: points[index],
        });
    }
    let mut order: Vec<u32> = (0..points.len() as u32).collect();
    let cmp = |a: &u32, b: &u32| {
        let (p, q) = (points[*a as usize], points[*b as usize]);
        (p[0].total_cmp(&q[0]))
            .then(p[1].total_cmp(&q[1]))
            .then(p[2].total_cmp(&q[2]))
            .then(a.cmp(b))
    };
    order.sort_unstable_by(cmp);
    for w in order.windows(2) {
        let (a, b) = (w[0] as usize, w[1] as usize);
        // -0.0 and 0.0 are one point
        if points[a] == points[b] {
            return Err(FillError::DuplicatePoint {
                first: a.min(b),
                second: a.max(b),
                point: points[a],
            });
        }
    }
    Ok(())
}

/// Whether three points lie on one line (exact: all three axis projections collinear).
pub(crate) fn collinear(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> bool {
    let xy = |p: [f64; 3]| [p[0], p[1]];
    let yz = |p: [f64; 3]| [p[1], p[2]];
    let zx = |p: [f64; 3]| [p[2], p[0]];
    orient2d(xy(a), xy(b), xy(c)) == 0.0
        && orient2d(yz(a), yz(b), yz(c)) == 0.0
        && orient2d(zx(a), zx(b), zx(c)) == 0.0
}

/// Four points of `order` spanning a tet, the first ones that do; `None` when all are coplanar.
fn first_tet(points: &[[f64; 3]], order: &[u32]) -> Option<[u32; 4]> {
    let p = |v: u32| points[v as usize];
    let a = *order.first()?;
    let b = *order.get(1)?;
    let c = *order.iter().find(|&&c| !collinear(p(a), p(b), p(c)))?;
    let d = *order
        .iter()
        .find(|&&d| orient3d(p(a), p(b), p(c), p(d)) != 0.0)?;
    Some([a, b, c, d])
}

/// The Delaunay tetrahedralisation of `mesh.points[..]` listed in `vertices` (inserted in
/// BRIO order of their own); `Flat` when they are coplanar. The points must be checked.
pub(crate) fn tetrahedralise(mesh: &mut Mesh, vertices: &[u32]) -> Result<(), FillError> {
    let coords: Vec<[f64; 3]> = vertices.iter().map(|&v| mesh.p(v)).collect();
    let order: Vec<u32> = brio(&coords)
        .into_iter()
        .map(|k| vertices[k as usize])
        .collect();
    let corners = first_tet(&mesh.points, &order).ok_or(FillError::Flat {
        points: vertices.len(),
    })?;
    mesh.start(corners);
    let mut scratch = Scratch::default();
    let mut new = Vec::new();
    for &v in &order {
        if corners.contains(&v) {
            continue;
        }
        let p = mesh.p(v);
        match mesh.locate(p) {
            Located::Vertex(w) => {
                return Err(FillError::DuplicatePoint {
                    first: w.min(v) as usize,
                    second: w.max(v) as usize,
                    point: p,
                });
            }
            Located::Tet(t) => {
                if !mesh.insert(v, t, None, &mut scratch, &mut new) {
                    return Err(FillError::PointNotInserted {
                        index: v as usize,
                        point: p,
                    });
                }
            }
        }
    }
    Ok(())
}

/// The Delaunay tetrahedralisation of `points`: the tets of their convex hull, each positive
/// (`orient3d > 0`), none with a point strictly inside its circumsphere. Co-spherical points
/// are tetrahedralised in one of the valid ways. Fewer than four points, or all coplanar: no
/// tet.
pub fn delaunay(points: &[[f64; 3]]) -> Result<Vec<[u32; 4]>, FillError> {
    check_points(points)?;
    let mut mesh = Mesh::new(points.to_vec());
    let all: Vec<u32> = (0..points.len() as u32).collect();
    match tetrahedralise(&mut mesh, &all) {
        Ok(()) => Ok(mesh.real_tets().map(|t| mesh.tets[t as usize]).collect()),
        Err(FillError::Flat { .. }) => Ok(Vec::new()),
        Err(e) => Err(e),
    }
}
