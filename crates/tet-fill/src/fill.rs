//! The fill's driver: the input checked, the input points tetrahedralised inside a box well
//! outside them (so that every facet is interior and every flip near it is between real tets),
//! the facets recovered, the region classified, refined and cleared of slivers; then the
//! region's tets returned with the box's corners dropped.

use crate::build::{check_points, collinear, tetrahedralise};
use crate::error::FillError;
use crate::insert::FaceSet;
use crate::mesh::{GHOST, Mesh, face_key};
use crate::quality::max_dihedral_deg;
use crate::recover::Recovery;
use crate::region::{Side, classify};
use crate::{Fill, FillInput, FillOptions};

/// Refuses facets naming missing points and degenerate facets.
fn check_facets(input: &FillInput) -> Result<(), FillError> {
    let n = input.points.len();
    for (facet, f) in input.facets.iter().enumerate() {
        if let Some(&index) = f.iter().find(|&&v| v as usize >= n) {
            return Err(FillError::FacetIndexOutOfRange {
                facet,
                index,
                points: n,
            });
        }
        let [a, b, c] = f.map(|v| input.points[v as usize]);
        let degenerate = f[0] == f[1] || f[1] == f[2] || f[0] == f[2] || collinear(a, b, c);
        if degenerate {
            return Err(FillError::DegenerateFacet {
                facet,
                corners: [a, b, c],
            });
        }
    }
    Ok(())
}

/// The eight corners of a box around `points` with a margin of their extent on every side.
fn box_corners(points: &[[f64; 3]]) -> Vec<[f64; 3]> {
    let Some(geom_predicates::Aabb { lo, hi }) = geom_predicates::Aabb::of_points(points) else {
        return Vec::new();
    };
    let extent = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max).max(1.0);
    // each corner pushed out by its own odd amount: no box face parallel to an input plane,
    // no box corner co-spherical with input points (degeneracies that recovery would pay for)
    (0..8)
        .map(|i| {
            [0, 1, 2].map(|k| {
                let m = extent * (1.0 + 0.0371 * ((3 * i + k) % 7) as f64);
                if (i >> k) & 1 == 0 {
                    lo[k] - m
                } else {
                    hi[k] + m
                }
            })
        })
        .collect()
}

/// The fill (see [`crate::fill`]).
pub(crate) fn run(input: &FillInput, options: &FillOptions) -> Result<Fill, FillError> {
    check_points(input.points)?;
    check_facets(input)?;
    crate::intersect::check_disjoint(input)?;
    let n = input.points.len();
    if n + 8 > options.max_points {
        return Err(FillError::TooManyPoints {
            limit: options.max_points,
        });
    }
    let mut points = input.points.to_vec();
    points.extend(box_corners(input.points));
    let mut mesh = Mesh::new(points);
    let all: Vec<u32> = (0..(n + 8) as u32).collect();
    tetrahedralise(&mut mesh, &all)?;
    let (faces, steiner) = recover_all(&mut mesh, input, options.max_points)?;
    let mut side = classify(&mesh, input.facets, &faces)?;
    let facets = crate::refine::Facets::new(input);
    // (the points the refinement and the sliver removal add are counted by `output` among
    // those the region's tets use)
    crate::refine::refine(&mut mesh, &mut side, &faces, input, &facets, options)?;
    let encroached = |q: [f64; 3]| facets.encroached(q);
    crate::sliver::improve(&mut mesh, &mut side, &faces, n + 8, options, &encroached);
    Ok(output(&mesh, &side, n, steiner))
}

/// The first edge of facet `f` missing from the tetrahedralisation, if one is.
fn missing_edge(rec: &mut Recovery, f: [u32; 3]) -> Option<[u32; 2]> {
    (0..3)
        .map(|i| [f[i], f[(i + 1) % 3]])
        .find(|&[a, b]| rec.find_edge(a, b).is_none())
}

/// The error for input facet `k`, given up on for `why`: its missing edge, and every input
/// edge missing at this point.
fn unrecoverable(rec: &mut Recovery, input: &FillInput, k: usize, why: String) -> FillError {
    let f = input.facets[k];
    let edge = missing_edge(rec, f);
    let mut missing_edges: Vec<[u32; 2]> = Vec::new();
    for &g in input.facets {
        if rec.has_face(g) {
            continue;
        }
        for i in 0..3 {
            let (a, b) = (g[i], g[(i + 1) % 3]);
            if rec.find_edge(a, b).is_none() {
                missing_edges.push([a.min(b), a.max(b)]);
            }
        }
    }
    missing_edges.sort_unstable();
    missing_edges.dedup();
    FillError::Unrecoverable {
        facet: k,
        corners: Box::new(f.map(|v| rec.mesh.p(v))),
        why,
        edge,
        missing_edges,
    }
}

/// Recovers every facet; the kept faces and the Steiner points added.
fn recover_all(
    mesh: &mut Mesh,
    input: &FillInput,
    max_points: usize,
) -> Result<(FaceSet, usize), FillError> {
    let mut rec = Recovery::new(mesh, max_points);
    rec.keep_present(input.facets);
    // every edge first: facets kept early would wall in the edges' cavities
    for &f in input.facets {
        rec.recover_edges(f);
    }
    // a Steiner point may take back an earlier facet's edges: a few passes
    for pass in 0..4 {
        let mut missing = 0;
        for (k, &f) in input.facets.iter().enumerate() {
            if rec.faces.contains(&face_key(f)) && rec.has_face(f) {
                continue;
            }
            missing += 1;
            // a failure may clear on a later pass, after other facets' flips and points
            match rec.recover_facet(f) {
                Err(why) if pass == 3 || why.contains("cap of") => {
                    return Err(unrecoverable(&mut rec, input, k, why));
                }
                _ => {}
            }
        }
        if missing == 0 {
            break;
        }
    }
    for (k, &f) in input.facets.iter().enumerate() {
        if !rec.has_face(f) {
            let why = "lost again while recovering others".to_string();
            return Err(unrecoverable(&mut rec, input, k, why));
        }
    }
    let steiner = rec.steiner;
    Ok((rec.faces, steiner))
}

/// The inside tets, with the box's corners dropped from the numbering and so are the added
/// points no inside tet uses (Steiner points that fell outside the region); the first
/// `steiner` added points are the recovery's, the others the refinement's and the sliver
/// removal's.
fn output(mesh: &Mesh, side: &[Side], n: usize, steiner: usize) -> Fill {
    let inside: Vec<[u32; 4]> = (0..mesh.tets.len())
        .filter(|&t| side.get(t) == Some(&Side::Inside) && !mesh.is_dead(t as u32))
        .map(|t| mesh.tets[t])
        .collect();
    debug_assert!(inside.iter().all(|t| !t.contains(&GHOST)));
    let mut remap = vec![u32::MAX; mesh.points.len()];
    for (v, r) in remap.iter_mut().enumerate().take(n) {
        *r = v as u32;
    }
    for t in &inside {
        for &v in t {
            if v as usize >= n {
                remap[v as usize] = 0;
            }
        }
    }
    let mut points = mesh.points[..n].to_vec();
    let (mut steiner_points, mut refinement_points) = (0, 0);
    for (v, r) in remap.iter_mut().enumerate().skip(n + 8) {
        if *r == 0 {
            *r = points.len() as u32;
            points.push(mesh.points[v]);
            if v < n + 8 + steiner {
                steiner_points += 1;
            } else {
                refinement_points += 1;
            }
        }
    }
    // (every added point is counted by the stage that made it, or is one of the cavities'
    // kernel points: at most all the points past the box's corners are used)
    debug_assert!(steiner_points + refinement_points <= mesh.points.len() - n - 8);
    let tets: Vec<[u32; 4]> = inside
        .iter()
        .map(|t| t.map(|v| remap[v as usize]))
        .collect();
    let max_dihedral_deg = tets
        .iter()
        .map(|t| max_dihedral_deg(t.map(|v| points[v as usize])))
        .fold(0.0, f64::max);
    Fill {
        points,
        tets,
        steiner_points,
        refinement_points,
        max_dihedral_deg,
    }
}
