//! Which tets are in the region to fill: the tet on each input facet's positive side (its
//! normal's side) is inside, the one on its negative side outside, and the labels flood across
//! every face that is not an input facet. A tet reached by both labels, or a facet with both
//! sides alike, means the surfaces are inconsistently oriented (or not closed).

use crate::error::FillError;
use crate::insert::FaceSet;
use crate::mesh::{GHOST, Mesh, face_key, face_of};
use geom_predicates::orient3d;

/// A tet's label.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Side {
    /// Not reached (yet).
    Unknown,
    /// In the region to fill.
    Inside,
    /// Not in it.
    Outside,
}

impl Side {
    fn name(self) -> &'static str {
        match self {
            Side::Inside => "inside",
            _ => "outside",
        }
    }
}

/// The side of every tet slot; `faces` holds the input facets (all present), `facets` them in
/// input order, `corners` looks up coordinates for the errors.
pub(crate) fn classify(
    mesh: &Mesh,
    facets: &[[u32; 3]],
    faces: &FaceSet,
) -> Result<Vec<Side>, FillError> {
    let mut side = vec![Side::Unknown; mesh.tets.len()];
    let mut source = vec![u32::MAX; mesh.tets.len()];
    let mut stack = Vec::new();
    let lookup = face_lookup(mesh, faces);
    for (k, f) in facets.iter().enumerate() {
        let err = |s: Side| FillError::InconsistentOrientation {
            facet: k,
            corners: f.map(|v| mesh.p(v)),
            side: s.name(),
        };
        let &(t, i) = lookup.get(&face_key(*f)).expect("every facet is a face");
        let u = mesh.neighbour(t, i);
        let apex = mesh.tets[t as usize][i];
        let [a, b, c] = f.map(|v| mesh.p(v));
        // the fill is where the facet turns counter-clockwise: orient3d < 0
        let t_in = apex != GHOST && orient3d(a, b, c, mesh.p(apex)) < 0.0;
        let (inside, outside) = if t_in { (t, u) } else { (u, t) };
        for (tet, s) in [(inside, Side::Inside), (outside, Side::Outside)] {
            if mesh.is_ghost(tet) && s == Side::Inside {
                return Err(err(Side::Outside));
            }
            match side[tet as usize] {
                Side::Unknown => {
                    side[tet as usize] = s;
                    source[tet as usize] = k as u32;
                    stack.push(tet);
                }
                x if x != s => return Err(err(x)),
                _ => {}
            }
        }
    }
    flood(mesh, faces, facets, &mut side, &mut source, stack)?;
    Ok(side)
}

/// The (tet, face) of every kept face.
fn face_lookup(mesh: &Mesh, faces: &FaceSet) -> std::collections::HashMap<[u32; 3], (u32, usize)> {
    let mut map = std::collections::HashMap::with_capacity(faces.len());
    for t in 0..mesh.tets.len() as u32 {
        if mesh.is_dead(t) {
            continue;
        }
        for i in 0..4 {
            let f = face_of(mesh.tets[t as usize], i);
            if !f.contains(&GHOST) {
                let key = face_key(f);
                if faces.contains(&key) {
                    map.entry(key).or_insert((t, i));
                }
            }
        }
    }
    map
}

/// Spreads the labels across non-facet faces; a tet labelled both ways is an error naming the
/// facet whose label arrived second.
fn flood(
    mesh: &Mesh,
    faces: &FaceSet,
    facets: &[[u32; 3]],
    side: &mut [Side],
    source: &mut [u32],
    mut stack: Vec<u32>,
) -> Result<(), FillError> {
    while let Some(t) = stack.pop() {
        for i in 0..4 {
            let f = face_of(mesh.tets[t as usize], i);
            if !f.contains(&GHOST) && faces.contains(&face_key(f)) {
                continue;
            }
            let n = mesh.neighbour(t, i) as usize;
            let s = side[t as usize];
            if side[n] == Side::Unknown {
                if s == Side::Inside && mesh.is_ghost(n as u32) {
                    let k = source[t as usize] as usize;
                    return Err(FillError::InconsistentOrientation {
                        facet: k,
                        corners: facets[k].map(|v| mesh.p(v)),
                        side: "inside",
                    });
                }
                side[n] = s;
                source[n] = source[t as usize];
                stack.push(n as u32);
            } else if side[n] != s {
                let k = source[t as usize] as usize;
                return Err(FillError::InconsistentOrientation {
                    facet: k,
                    corners: facets[k].map(|v| mesh.p(v)),
                    side: s.name(),
                });
            }
        }
    }
    Ok(())
}
