//! The cut mesh: every cell cut (or kept), then the boundary facets with their patches.

use mesh_model::poly::PolyMesh;
use mesh_model::{CellType, Dim, Mesh, NONE, Patch, Role, Shape};

use crate::CutError;
use crate::cone::{CellFaces, Piece, UNRANKED, split_face};
use crate::refine::Cut;

/// Cuts every cell of `poly` as `cut` says (or keeps it when it has no apex) and adds the
/// boundary facets.
pub fn cut(poly: &PolyMesh, cut: &Cut) -> Result<Mesh, CutError> {
    let mut mesh = Mesh::new(Dim::Three, 1);
    mesh.nodes = poly.nodes.clone();
    let mut faces = CellFaces::default();
    let mut pieces: Vec<Piece> = Vec::new();
    for c in 0..poly.cell_count() {
        crate::load_checked(&mut faces, poly, c)?;
        pieces.clear();
        match cut.apex[c] {
            UNRANKED => {
                let piece = faces.standard().ok_or(CutError::NotStandard { cell: c })?;
                crate::prisms::kept_pieces(&faces, piece, &cut.split, c, &mut pieces)?;
            }
            _ => cut.pieces(&faces, c, &mut pieces),
        }
        let layer = poly.cell_layer.get(c).copied().unwrap_or(NONE);
        let pipe = poly.cell_pipe.get(c).copied().unwrap_or(NONE);
        for (shape, corners) in &pieces {
            mesh.cells
                .push(CellType::new(*shape, 1), &corners[..shape.corners()]);
            mesh.cell_layer.push(layer);
            mesh.cell_pipe.push(pipe);
        }
    }
    boundary(poly, &cut.split, &mut mesh);
    Ok(mesh)
}

/// The faces of one cell: the bottoms of layer-0 cells are the wall, the others the far
/// field; split as the cells split them, turned out of the domain. When the wall's pipes are
/// `0..n`, one each, the first part of pipe `p`'s wall facet is facet `p`.
fn boundary(poly: &PolyMesh, split: &[u32], mesh: &mut Mesh) {
    let mut uses = vec![0u8; poly.face_count()];
    for c in 0..poly.cell_count() {
        for cf in poly.cell(c) {
            let u = &mut uses[cf.face as usize];
            *u = u.saturating_add(1);
        }
    }
    let mut faces = CellFaces::default();
    let mut parts = Vec::new();
    // (pipe of a wall facet or NONE, role, polygon)
    let mut facets: Vec<(u32, Role, Vec<u32>)> = Vec::new();
    for c in 0..poly.cell_count() {
        let layer = poly.cell_layer.get(c).copied().unwrap_or(NONE);
        let pipe = poly.cell_pipe.get(c).copied().unwrap_or(NONE);
        faces.load(poly, c);
        for (i, cf) in poly.cell(c).iter().enumerate() {
            if uses[cf.face as usize] != 1 {
                continue;
            }
            let wall = i == 0 && layer == 0;
            parts.clear();
            let w = Some(split[cf.face as usize]).filter(|&s| s != UNRANKED);
            split_face(faces.face(i), w, &mut parts);
            for (j, k) in parts.drain(..).enumerate() {
                match (wall, j) {
                    (true, 0) => facets.push((pipe, Role::Wall, k)),
                    (true, _) => facets.push((NONE, Role::Wall, k)),
                    (false, _) => facets.push((NONE, Role::Farfield, k)),
                }
            }
        }
    }
    order_by_pipe(&mut facets);
    for (_, role, k) in facets {
        let shape = if k.len() == 3 {
            Shape::Tri
        } else {
            Shape::Quad
        };
        mesh.boundary.push(CellType::new(shape, 1), &k);
        mesh.boundary_patch.push(match role {
            Role::Wall => 0,
            Role::Farfield => 1,
        });
    }
    for role in [Role::Wall, Role::Farfield] {
        mesh.patches.push(Patch {
            name: role.name().into(),
            role,
        });
    }
}

/// Puts the wall facet of pipe `p` at index `p` when the pipes of the wall facets are
/// exactly `0..n`; otherwise leaves the order (wall facets first, stable).
fn order_by_pipe(facets: &mut [(u32, Role, Vec<u32>)]) {
    let piped: Vec<u32> = facets.iter().map(|f| f.0).filter(|&p| p != NONE).collect();
    let n = piped.len();
    let mut seen = vec![false; n];
    let dense = piped.iter().all(|&p| {
        let fresh = (p as usize) < n && !seen[p as usize];
        if fresh {
            seen[p as usize] = true;
        }
        fresh
    });
    let key = |f: &(u32, Role, Vec<u32>)| match (f.0, f.1) {
        (p, _) if p != NONE && dense => (0, p),
        (_, Role::Wall) => (1, 0),
        _ => (2, 0),
    };
    facets.sort_by_key(key);
}
