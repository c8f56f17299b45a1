//! The prism cut: the mixed cut without pyramids or hexahedra, for solvers that take only
//! tetrahedra and prisms (PyFR, for one, refuses a pyramid whose base is not an exact
//! parallelogram, which a curved front's quadrilaterals never are).
//!
//! A pyramid of the mixed cut sits on a quadrilateral kept whole beside a cut cell, so no
//! cell may be cut while a cell across one of its quadrilaterals is kept. The cells joined
//! by quadrilaterals make *groups* ([`cut_groups`]): the prisms of a layer with their side
//! faces, a column of hexahedra with their tops and bottoms and its neighbours across its
//! sides. A group is cut whole into tetrahedra — by the tetrahedral cut's sweep (each cell the
//! cone from its first node, each quadrilateral split through its first node: conforming by
//! construction), then refined as the tetrahedral cut is — when a cell of it has to be cut (a
//! merged cell, a pyramid, a cell the caller flags) or would leave a quadrilateral that no
//! prism can take (a prism's or a hexahedron's side on the boundary, where a fill beyond the
//! layers would cap it with a pyramid; a hexahedron's top on another kind of cell). In the
//! other groups the prisms are kept and each hexahedron is halved into two prisms
//! ([`kept_pieces`]) across its top and bottom, by one diagonal up each column. Nothing joins
//! through a triangle, so the layers under the first stop keep their prisms and the layers
//! above are tetrahedra: the only pyramid-free mesh with prisms kept.

use mesh_model::Shape;
use mesh_model::poly::PolyMesh;

use crate::CutError;
use crate::cone::{CellFaces, Piece, UNRANKED, first_ranked};
use crate::improve::{INVERTED, piece_quality};
use crate::order::{cells_by_layer, child};
use crate::refine::{Cut, face_cells, normal_split, through};

/// The cut of `poly` without pyramids or hexahedra, from the sweep's ranks of every node
/// `sweep`, the cells `cut_anyway` flags (one flag per cell, or none) cut as well: the groups
/// that must be cut ([`cut_groups`]) cut whole by the sweep, the others kept, their hexahedra
/// halved up each column (the splits [`kept_pieces`] reads) by the diagonal of its wall's
/// quadrilateral that keeps the triangles best.
pub fn prism_cut(poly: &PolyMesh, cut_anyway: &[bool], sweep: &[u32]) -> Cut {
    let cut_cells = cut_groups(poly, cut_anyway);
    let mut faces = CellFaces::default();
    let mut cut = Cut {
        apex: vec![UNRANKED; poly.cell_count()],
        split: vec![UNRANKED; poly.face_count()],
    };
    for c in cells_by_layer(poly) {
        let c = c as usize;
        faces.load(poly, c);
        if !cut_cells[c] {
            if is_hex(&faces) {
                halve(poly, &faces, &mut cut.split);
            }
            continue;
        }
        cut.apex[c] = faces.first_ranked(sweep).unwrap_or(UNRANKED);
        for i in 0..faces.len() {
            let f = faces.id(i) as usize;
            let k = poly.face(f);
            if let (4, Some(w)) = (k.len(), first_ranked(k, sweep)) {
                cut.split[f] = normal_split(k, w);
            }
        }
    }
    cut
}

/// Splits the bottom (face 0) and top (face 1) of the hexahedron in `faces` by parallel
/// diagonals: the bottom's as the hexahedron under it split its top, or else the one whose
/// triangles' smallest angle, with the top's above them, is largest.
fn halve(poly: &PolyMesh, faces: &CellFaces, split: &mut [u32]) {
    let (f0, f1) = (faces.id(0) as usize, faces.id(1) as usize);
    let bottom = faces.face(0);
    let Some(above) = bottom
        .iter()
        .map(|&v| child(faces, v))
        .collect::<Option<Vec<u32>>>()
    else {
        return; // no hexahedron of the layers: every bottom node has a child
    };
    let s = match split[f0] {
        UNRANKED => {
            let x = |v: u32| poly.nodes[v as usize];
            let sine = |q: &[u32], i: usize| {
                let t =
                    |a: usize, b: usize, d: usize| min_sine(x(q[a % 4]), x(q[b % 4]), x(q[d % 4]));
                t(i, i + 1, i + 2).min(t(i, i + 2, i + 3))
            };
            let best =
                if sine(bottom, 1).min(sine(&above, 1)) > sine(bottom, 0).min(sine(&above, 0)) {
                    1
                } else {
                    0
                };
            split[f0] = normal_split(poly.face(f0), bottom[best]);
            bottom[best]
        }
        s => s,
    };
    let at = bottom.iter().position(|&v| v == s).unwrap_or(0);
    split[f1] = normal_split(poly.face(f1), above[at]);
}

/// The smallest sine of the triangle (a, b, c)'s angles.
fn min_sine(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> f64 {
    use geom_predicates::vector::{cross3, dist, dot, sub};
    let n = cross3(sub(b, a), sub(c, a));
    let area2 = dot(n, n).sqrt();
    let (ab, bc, ca) = (dist(a, b), dist(b, c), dist(c, a));
    // a corner's sine is twice the area over its two sides; the smallest angle is opposite
    // the shortest side, between the two longest
    let shortest = ab.min(bc).min(ca);
    if shortest > 0.0 {
        area2 * shortest / (ab * bc * ca)
    } else {
        0.0
    }
}

/// Which cells lie in a group of cells joined by quadrilaterals that the prism cut cuts into
/// tetrahedra: a group with a cell `cut_anyway` flags, a cell no standard one (or with a corner
/// not positive, as the mixed cut judges them), a pyramid, or a cell [`fits_prisms`] refuses.
pub fn cut_groups(poly: &PolyMesh, cut_anyway: &[bool]) -> Vec<bool> {
    let across = face_cells(poly);
    let mut group: Vec<u32> = (0..poly.cell_count() as u32).collect();
    for (f, &[a, b]) in across.iter().enumerate() {
        if b != UNRANKED && poly.face(f).len() == 4 {
            union(&mut group, a, b);
        }
    }
    let mut faces = CellFaces::default();
    let hexes: Vec<bool> = (0..poly.cell_count())
        .map(|c| {
            faces.load(poly, c);
            is_hex(&faces)
        })
        .collect();
    let mut must = vec![false; poly.cell_count()];
    for c in 0..poly.cell_count() {
        faces.load(poly, c);
        let root = find(&mut group, c as u32) as usize;
        let flagged = cut_anyway.get(c).copied().unwrap_or(false);
        if flagged || !fits_prisms(poly, &faces, &across, &hexes) {
            must[root] = true;
        }
    }
    (0..poly.cell_count())
        .map(|c| must[find(&mut group, c as u32) as usize])
        .collect()
}

/// Whether the kept cell in `faces` can stay (a prism or tetrahedron) or be halved (a
/// hexahedron whose top and bottom are on hexahedra, `hexes` flagging them, or on the
/// boundary) and leaves no quadrilateral whole on the boundary.
fn fits_prisms(poly: &PolyMesh, faces: &CellFaces, across: &[[u32; 2]], hexes: &[bool]) -> bool {
    let Some(piece) = faces.standard() else {
        return false;
    };
    if piece_quality(&poly.nodes, &piece) >= INVERTED {
        return false;
    }
    let shape = piece.0;
    let hex = is_hex(faces);
    let on_boundary = |i: usize| across[faces.id(i) as usize][1] == UNRANKED;
    match shape {
        Shape::Tet => true,
        Shape::Prism => (0..faces.len()).all(|i| faces.face(i).len() == 3 || !on_boundary(i)),
        Shape::Hex if hex => {
            let sides_inside = (2..6).all(|i| !on_boundary(i));
            let ends_on_hexes = (0..2).all(|i| {
                let [a, b] = across[faces.id(i) as usize];
                [a, b]
                    .into_iter()
                    .filter(|&d| d != UNRANKED)
                    .all(|d| hexes[d as usize])
            });
            sides_inside && ends_on_hexes
        }
        _ => false,
    }
}

/// Whether the cell in `faces` has six quadrilaterals, its bottom (face 0) opposite its top
/// (face 1), as the layers' hexahedra do.
fn is_hex(faces: &CellFaces) -> bool {
    faces.len() == 6
        && faces.faces().all(|k| k.len() == 4)
        && faces.face(0).iter().all(|v| !faces.face(1).contains(v))
}

fn find(group: &mut [u32], mut c: u32) -> u32 {
    while group[c as usize] != c {
        let up = group[group[c as usize] as usize];
        group[c as usize] = up;
        c = up;
    }
    c
}

fn union(group: &mut [u32], a: u32, b: u32) {
    let (ra, rb) = (find(group, a), find(group, b));
    if ra != rb {
        group[ra.max(rb) as usize] = ra.min(rb);
    }
}

/// The kept cell loaded in `faces` (its standard piece `piece`, in Gmsh's order: a layer
/// hexahedron's bottom is its corners 0–3, corner `j + 4` above corner `j`) as it goes into the
/// mesh: itself, or a hexahedron [`prism_cut`] halved across its bottom and top, its two prisms.
pub fn kept_pieces(
    faces: &CellFaces,
    piece: Piece,
    split: &[u32],
    c: usize,
    out: &mut Vec<Piece>,
) -> Result<(), CutError> {
    let split_of = |i: usize| split[faces.id(i) as usize];
    let split_faces: Vec<usize> = (0..faces.len())
        .filter(|&i| split_of(i) != UNRANKED)
        .collect();
    if split_faces.is_empty() {
        out.push(piece);
        return Ok(());
    }
    let h = piece.1;
    let face_of = |nodes: &[u32]| {
        (0..faces.len()).find(|&i| {
            let k = faces.face(i);
            k.len() == 4 && nodes.iter().all(|v| k.contains(v))
        })
    };
    let (Some(a), Some(b)) = (face_of(&h[..4]), face_of(&h[4..8])) else {
        return Err(CutError::NotStandard { cell: c });
    };
    let on_first = through(faces.face(a), split_of(a), h[0]);
    let parallel = through(faces.face(b), split_of(b), h[if on_first { 4 } else { 5 }]);
    if piece.0 != Shape::Hex || split_faces != [a.min(b), a.max(b)] || !parallel {
        return Err(CutError::NotStandard { cell: c });
    }
    let prism = |k: [usize; 6]| {
        let mut p = [0u32; 8];
        (0..6).for_each(|j| p[j] = h[k[j]]);
        (Shape::Prism, p)
    };
    if on_first {
        out.push(prism([0, 1, 2, 4, 5, 6]));
        out.push(prism([0, 2, 3, 4, 6, 7]));
    } else {
        out.push(prism([1, 2, 3, 5, 6, 7]));
        out.push(prism([1, 3, 0, 5, 7, 4]));
    }
    Ok(())
}
